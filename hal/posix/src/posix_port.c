/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: pty / serial UART, monotonic clock, one-shot timer, threads. */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#ifdef __linux__
#include <linux/serial.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#endif

#include "posix_baud.h"

/* ---- clock -------------------------------------------------------------------- */

uint64_t modcp_posix_now_us64(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

uint32_t modcp_posix_now_us(void)
{
    return (uint32_t)(modcp_posix_now_us64() & 0xFFFFFFFFu);
}

uint32_t modcp_posix_now_ms(void)
{
    return (uint32_t)((modcp_posix_now_us64() / 1000u) & 0xFFFFFFFFu);
}

void modcp_posix_sleep_until_us64(uint64_t t_us)
{
    struct timespec ts;
    ts.tv_sec = (time_t)(t_us / 1000000u);
    ts.tv_nsec = (long)((t_us % 1000000u) * 1000u);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
    }
}

void modcp_posix_spin_until_us64(uint64_t t_us)
{
    while (modcp_posix_now_us64() < t_us) {
    }
}

/* ---- events (a pipe) ----------------------------------------------------------------- */

static int pipe_nonblock(int fds[2])
{
    if (pipe(fds) != 0) {
        return -errno;
    }
    for (int i = 0; i < 2; i++) {
        int fl = fcntl(fds[i], F_GETFL);
        (void)fcntl(fds[i], F_SETFL, fl | O_NONBLOCK);
        (void)fcntl(fds[i], F_SETFD, FD_CLOEXEC);
    }
    return 0;
}

static void pipe_drain(int fd)
{
    char drain[64];
    while (read(fd, drain, sizeof drain) > 0) {
    }
}

static void pipe_poke(int fd)
{
    if (fd >= 0) {
        char c = 1;
        ssize_t r = write(fd, &c, 1); /* EAGAIN: a wake-up is pending already */
        (void)r;
    }
}

int modcp_posix_event_open(modcp_posix_event_t *e)
{
    int fds[2];
    e->rd = -1;
    e->wr = -1;
    int rc = pipe_nonblock(fds);
    if (rc == 0) {
        e->rd = fds[0];
        e->wr = fds[1];
    }
    return rc;
}

void modcp_posix_event_close(modcp_posix_event_t *e)
{
    if (e->rd >= 0) {
        close(e->rd);
    }
    if (e->wr >= 0) {
        close(e->wr);
    }
    e->rd = -1;
    e->wr = -1;
}

void modcp_posix_event_signal(modcp_posix_event_t *e)
{
    pipe_poke(e->wr);
}

void modcp_posix_event_clear(modcp_posix_event_t *e)
{
    pipe_drain(e->rd);
}

bool modcp_posix_event_wait_until(modcp_posix_event_t *e, uint64_t t_us)
{
    uint64_t now = modcp_posix_now_us64();
    uint64_t d = t_us > now ? t_us - now : 0u;
    struct timespec ts = {(time_t)(d / 1000000u), (long)(d % 1000000u) * 1000L};
    struct pollfd pf = {e->rd, POLLIN, 0};
    int pr = ppoll(&pf, 1, &ts, NULL);
    if (pr > 0) {
        modcp_posix_event_clear(e);
        return true;
    }
    return false;
}

/* ---- threads -------------------------------------------------------------------- */

/* The threads run a few microseconds at a time and must run when they wake: ask the
 * scheduler (Linux 6.12+, EEVDF) for a short time slice, 100 us instead of the default
 * (0.7 ms x (1 + log2 CPUs): 1.4 ms on two). A task's virtual deadline is its slice
 * ahead, so a woken thread with a short slice has the earlier deadline and preempts a
 * compiler that is running instead of waiting for its slice to end; its share of the
 * processor is unchanged. Policy and nice value stay as they are; an older kernel
 * ignores the request. */
static void short_slice(void)
{
#if defined(__linux__) && defined(SYS_sched_setattr) && defined(SYS_sched_getattr)
    struct {
        uint32_t size, policy;
        uint64_t flags;
        int32_t nice;
        uint32_t prio;
        uint64_t runtime, deadline, period;
    } sa;
    memset(&sa, 0, sizeof sa);
    if (syscall(SYS_sched_getattr, 0, &sa, (unsigned)sizeof sa, 0u) == 0 &&
        sa.policy == 0u /* SCHED_OTHER */) {
        sa.size = (uint32_t)sizeof sa;
        sa.runtime = 100000u; /* ns */
        (void)syscall(SYS_sched_setattr, 0, &sa, 0u);
    }
#endif
}

/* Every thread of the port's owner waits for deadlines of a few hundred microseconds
 * (t3.5, a character time, the CPU cycle): ask the kernel not to add its default timer
 * slack (50 us on Linux) to those waits. */
static void *thread_entry(void *arg)
{
    modcp_posix_thread_t *t = arg;
#ifdef PR_SET_TIMERSLACK
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL); /* 1 ns: as exact as the clock */
#endif
    short_slice();
    return t->fn(t->arg);
}

int modcp_posix_thread_start(modcp_posix_thread_t *t, void *(*fn)(void *), void *arg)
{
    t->fn = fn;
    t->arg = arg;
    int rc = pthread_create(&t->handle, NULL, thread_entry, t);
    return rc == 0 ? 0 : -rc;
}

void modcp_posix_thread_join(modcp_posix_thread_t *t)
{
    (void)pthread_join(t->handle, NULL);
}

/* ---- opening ---------------------------------------------------------------------- */

static void port_reset(modcp_posix_port_t *p, uint32_t char_us)
{
    memset(p, 0, sizeof *p);
    p->fd = -1;
    p->slave_fd = -1;
    p->wake.rd = -1;
    p->wake.wr = -1;
    p->char_us = char_us != 0u ? char_us : 1u;
}

void modcp_posix_wake(modcp_posix_port_t *p)
{
    modcp_posix_event_signal(&p->wake);
}

int modcp_posix_open_pty(modcp_posix_port_t *p, const char *link, uint32_t char_us)
{
    port_reset(p, char_us);
    int wrc = modcp_posix_event_open(&p->wake);
    if (wrc != 0) {
        return wrc;
    }
    int fd = posix_openpt(O_RDWR | O_NOCTTY);
    if (fd < 0) {
        int e = errno;
        modcp_posix_close(p);
        return -e;
    }
    if (grantpt(fd) != 0 || unlockpt(fd) != 0 || ptsname_r(fd, p->path, sizeof p->path) != 0) {
        int e = errno;
        close(fd);
        modcp_posix_close(p);
        return -e;
    }
    int sfd = open(p->path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (sfd < 0) {
        int e = errno;
        close(fd);
        modcp_posix_close(p);
        return -e;
    }
    struct termios tio;
    if (tcgetattr(sfd, &tio) == 0) {
        cfmakeraw(&tio);
        tio.c_cflag |= CLOCAL | CREAD;
        tio.c_cc[VMIN] = 1;
        tio.c_cc[VTIME] = 0;
        (void)tcsetattr(sfd, TCSANOW, &tio);
    }
    int fl = fcntl(fd, F_GETFL);
    (void)fcntl(fd, F_SETFL, fl | O_NONBLOCK);
    p->fd = fd;
    p->slave_fd = sfd;
    p->is_pty = true;
    p->paced = true;
    if (link != NULL && link[0] != '\0') {
        struct stat st;
        if (lstat(link, &st) == 0) {
            if (!S_ISLNK(st.st_mode)) {
                modcp_posix_close(p);
                return -EEXIST; /* never replace a regular file */
            }
            struct stat tst, own;
            if (stat(link, &tst) == 0 &&
                !(stat(p->path, &own) == 0 && own.st_rdev == tst.st_rdev)) {
                modcp_posix_close(p);
                return -EBUSY; /* points at a device that exists: maybe a live instance's */
            }
            /* a stale link left by an instance that was killed (its pty is gone, or is
             * the one we were just given) */
            (void)unlink(link);
        }
        if (symlink(p->path, link) != 0) {
            int e = errno;
            modcp_posix_close(p);
            return -e;
        }
        snprintf(p->link, sizeof p->link, "%s", link);
    }
    return 0;
}

static speed_t speed_of(uint32_t baud)
{
    switch (baud) {
    case 300u: return B300;
    case 600u: return B600;
    case 1200u: return B1200;
    case 2400u: return B2400;
    case 4800u: return B4800;
    case 9600u: return B9600;
    case 19200u: return B19200;
    case 38400u: return B38400;
    case 57600u: return B57600;
    case 115200u: return B115200;
    default: return B0;
    }
}

int modcp_posix_open_device(modcp_posix_port_t *p, const char *path, uint32_t baud,
                            uint8_t data_bits, uint8_t parity, uint8_t stop_bits, uint32_t char_us)
{
    port_reset(p, char_us);
    p->parity = parity;
    int wrc = modcp_posix_event_open(&p->wake);
    if (wrc != 0) {
        return wrc;
    }
    int fd = open(path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        int e = errno;
        modcp_posix_close(p);
        return -e;
    }
    struct termios tio;
    if (tcgetattr(fd, &tio) != 0) {
        int e = errno;
        close(fd);
        modcp_posix_close(p);
        return -e;
    }
    cfmakeraw(&tio);
    tio.c_cflag &= (tcflag_t) ~(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
    tio.c_cflag |= CLOCAL | CREAD | (data_bits == 7u ? CS7 : CS8);
    if (parity != 0u) {
        tio.c_cflag |= PARENB;
        if (parity == 1u) {
            tio.c_cflag |= PARODD;
        }
    }
    if (stop_bits == 2u) {
        tio.c_cflag |= CSTOPB;
    }
    /* mark parity / framing errors and BREAK in the stream: FF 00 x, FF 00 00, FF FF */
    tio.c_iflag &= (tcflag_t) ~(IGNBRK | BRKINT | IGNPAR | ISTRIP | IXON | IXOFF | IXANY);
    tio.c_iflag |= INPCK | PARMRK;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    speed_t sp = speed_of(baud);
    if (sp != B0) {
        cfsetispeed(&tio, sp);
        cfsetospeed(&tio, sp);
    }
    if (tcsetattr(fd, TCSANOW, &tio) != 0) {
        int e = errno;
        close(fd);
        modcp_posix_close(p);
        return -e;
    }
    if (sp == B0) {
        int rc = modcp_posix_custom_baud(fd, baud);
        if (rc != 0) {
            close(fd);
            modcp_posix_close(p);
            return rc;
        }
    }
    (void)tcflush(fd, TCIOFLUSH);
    p->fd = fd;
    p->is_pty = false;
    snprintf(p->path, sizeof p->path, "%s", path);
    char real[PATH_MAX];
    const char *tn = ttyname(fd);
    p->paced = (tn != NULL && strncmp(tn, "/dev/pts/", 9) == 0) ||
               (realpath(path, real) != NULL && strncmp(real, "/dev/pts/", 9) == 0);
#ifdef TIOCGICOUNT
    struct serial_icounter_struct ic;
    if (ioctl(fd, TIOCGICOUNT, &ic) == 0) {
        p->overruns = (uint32_t)(ic.overrun + ic.buf_overrun);
    }
#endif
    return 0;
}

void modcp_posix_close(modcp_posix_port_t *p)
{
    if (p->link[0] != '\0') {
        char target[256];
        ssize_t n = readlink(p->link, target, sizeof target - 1u);
        if (n >= 0) {
            target[n] = '\0';
            if (strcmp(target, p->path) == 0) {
                (void)unlink(p->link);
            }
        }
        p->link[0] = '\0';
    }
    if (p->slave_fd >= 0) {
        close(p->slave_fd);
        p->slave_fd = -1;
    }
    if (p->fd >= 0) {
        close(p->fd);
        p->fd = -1;
    }
    modcp_posix_event_close(&p->wake);
}

/* ---- HAL callbacks ------------------------------------------------------------------- */

static void modem_bit(int fd, int bit, bool on)
{
    if (fd >= 0) {
        (void)ioctl(fd, on ? TIOCMBIS : TIOCMBIC, &bit);
    }
}

static void hal_uart_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    modcp_posix_port_t *p = ctx;
    if (len > MODCP_POSIX_TX_MAX) {
        len = MODCP_POSIX_TX_MAX;
    }
    memcpy(p->tx_buf, buf, len);
    p->tx_len = len;
    p->tx_pos = 0;
    p->tx_t0_us = p->now_us;
    p->tx_active = true;
    if (p->on_tx != NULL) {
        p->on_tx(p->on_tx_user, buf, len, p->now_us);
    }
    if (!p->paced && p->fd >= 0) {
        /* the UART paces; write it all now */
        size_t off = 0;
        while (off < len) {
            ssize_t n = write(p->fd, p->tx_buf + off, len - off);
            if (n < 0) {
                if (errno == EINTR) {
                    continue;
                }
                if (errno == EAGAIN) {
                    struct pollfd pf = {p->fd, POLLOUT, 0};
                    (void)poll(&pf, 1, 100);
                    continue;
                }
                break;
            }
            off += (size_t)n;
        }
        p->tx_pos = len;
    }
}

/* RS232 automatic signals: CTS or DSR went OFF while sending. */
static void hal_uart_tx_abort(void *ctx)
{
    modcp_posix_port_t *p = ctx;
    if (p->tx_active && !p->paced && p->fd >= 0) {
        (void)tcflush(p->fd, TCOFLUSH);
    }
    p->tx_active = false; /* no transmission-complete for an aborted frame */
}

static void hal_timer_arm(void *ctx, uint32_t us)
{
    modcp_posix_port_t *p = ctx;
    if (us == 0u) {
        p->timer_armed = false;
        return;
    }
    p->timer_armed = true;
    p->timer_deadline_us = p->now_us + us;
}

static void hal_set_de(void *ctx, bool on)
{
    modcp_posix_port_t *p = ctx;
    p->de = on;
    if (!p->is_pty) {
        modem_bit(p->fd, TIOCM_RTS, on); /* RTS as the transceiver's DE, as common adapters do */
    }
}

static void hal_set_led(void *ctx, modcp_led_t led, bool on)
{
    modcp_posix_port_t *p = ctx;
    if ((unsigned)led < 3u) {
        p->led[led] = on;
    }
}

static void hal_set_signal(void *ctx, modcp_signal_t sig, bool on)
{
    modcp_posix_port_t *p = ctx;
    if (sig == MODCP_SIG_RTS) {
        p->rts = on;
        if (!p->is_pty) {
            modem_bit(p->fd, TIOCM_RTS, on);
        }
    } else {
        p->dtr = on;
        if (!p->is_pty) {
            modem_bit(p->fd, TIOCM_DTR, on);
        }
    }
}

/* The line as the preset makes it (000 Table 5-8): R(A) 0 V / R(B) 5 V holds a broken
 * or undriven line at idle, so a BREAK on it is not received (decode_rx drops it). */
static void hal_set_rx_preset(void *ctx, uint8_t preset)
{
    ((modcp_posix_port_t *)ctx)->rx_preset = preset;
}

void modcp_posix_hal(modcp_posix_port_t *p, modcp_hal_t *hal)
{
    memset(hal, 0, sizeof *hal);
    hal->ctx = p;
    hal->uart_tx = hal_uart_tx;
    hal->timer_arm = hal_timer_arm;
    hal->set_de = hal_set_de;
    hal->set_led = hal_set_led;
    hal->set_signal = hal_set_signal;
    hal->uart_tx_abort = hal_uart_tx_abort;
    hal->set_rx_preset = hal_set_rx_preset;
}

bool modcp_posix_modem_inputs(modcp_posix_port_t *p, bool *cts, bool *dsr)
{
    bool c = true;
    bool d = true;
    if (!p->is_pty && p->fd >= 0) {
        int bits = 0;
        if (ioctl(p->fd, TIOCMGET, &bits) == 0) {
            c = (bits & TIOCM_CTS) != 0;
            d = (bits & TIOCM_DSR) != 0;
        }
    }
    bool changed = !p->inputs_known || c != p->cts || d != p->dsr;
    p->inputs_known = true;
    p->cts = c;
    p->dsr = d;
    *cts = c;
    *dsr = d;
    return changed;
}

/* ---- waiting ---------------------------------------------------------------------------- */

static bool due(uint32_t now, uint32_t at)
{
    return (int32_t)(now - at) >= 0;
}

/* Microseconds from now until at (0 if due). */
static uint32_t until(uint32_t now, uint32_t at)
{
    return due(now, at) ? 0u : at - now;
}

/* pty: write the bytes whose time has come; report completion with the last one. */
static bool tx_progress(modcp_posix_port_t *p, uint32_t now)
{
    if (!p->tx_active) {
        return false;
    }
    if (p->paced) {
        uint32_t elapsed = now - p->tx_t0_us;
        uint32_t n_due = elapsed / p->char_us;
        if (n_due > p->tx_len) {
            n_due = p->tx_len;
        }
        while (p->tx_pos < n_due) {
            ssize_t n = write(p->fd, p->tx_buf + p->tx_pos, (size_t)(n_due - p->tx_pos));
            if (n < 0) {
                if (errno == EINTR) {
                    continue;
                }
                /* EAGAIN: nobody reads the pty; drop, like a line without a listener */
                p->tx_pos = (uint16_t)n_due;
                break;
            }
            p->tx_pos = (uint16_t)(p->tx_pos + (uint16_t)n);
        }
        if (p->tx_pos >= p->tx_len) {
            p->tx_active = false;
            return true;
        }
        return false;
    }
    if (!due(now, p->tx_t0_us + (uint32_t)p->tx_len * p->char_us)) {
        return false;
    }
    int queued = 0;
    if (ioctl(p->fd, TIOCOUTQ, &queued) == 0 && queued > 0) {
        return false; /* the driver still has bytes: check again */
    }
    p->tx_active = false;
    return true;
}

static uint32_t tx_next_us(const modcp_posix_port_t *p, uint32_t now)
{
    if (!p->tx_active) {
        return UINT32_MAX;
    }
    if (p->paced) {
        return until(now, p->tx_t0_us + (uint32_t)(p->tx_pos + 1u) * p->char_us);
    }
    uint32_t u = until(now, p->tx_t0_us + (uint32_t)p->tx_len * p->char_us);
    return u == 0u ? 500u : u;
}

/* Decode a PARMRK stream (device only). */
static size_t decode(modcp_posix_port_t *p, const uint8_t *in, size_t n, modcp_posix_rx_t *rx,
                     size_t cap)
{
    size_t k = 0;
    uint8_t err = p->parity != 0u ? MODCP_LINE_PARITY : MODCP_LINE_FRAMING;
    for (size_t i = 0; i < n && k < cap; i++) {
        uint8_t b = in[i];
        switch (p->mark_state) {
        case 0:
            if (b == 0xFFu) {
                p->mark_state = 1;
            } else {
                rx[k].byte = b;
                rx[k].errors = 0;
                k++;
            }
            break;
        case 1:
            if (b == 0xFFu) {
                rx[k].byte = 0xFFu;
                rx[k].errors = 0;
                k++;
                p->mark_state = 0;
            } else {
                p->mark_state = 2; /* FF 00: a marked character follows */
            }
            break;
        default:
            p->mark_state = 0;
            if (b == 0u && p->rx_preset == MODCP_RXP_HIGH) {
                break; /* BREAK on a line held HIGH by the preset: never seen */
            }
            rx[k].byte = b;
            rx[k].errors = b == 0u ? MODCP_LINE_BREAK : err;
            k++;
            break;
        }
    }
    return k;
}

/* A sleeping thread wakes some ten microseconds after its deadline, more on a loaded
 * host. The deadlines a master sees — the one-shot timer (end of frame t3.5, t1.5,
 * turnaround, RTS delays) and a reply's first byte — are therefore not slept up to:
 * the wait sleeps until SPIN_US before them and watches the clock (and the
 * descriptors) for the rest. Later reply bytes just sleep (their times are absolute,
 * a late one does not delay the next). An expected wake-up (expect_us) is watched for
 * from EXPECT_BEFORE_US before until EXPECT_AFTER_US after it; later it is slept for
 * like any other. */
#define SPIN_US 50u
#define EXPECT_BEFORE_US SPIN_US
#define EXPECT_AFTER_US 50u

int modcp_posix_wait(modcp_posix_port_t *p, uint32_t max_us, modcp_posix_rx_t *rx, size_t cap,
                     bool *tx_done, bool *timer_fired, uint32_t *now_us)
{
    uint32_t now = modcp_posix_now_us();
    uint32_t wait = max_us;
    uint32_t exact = UINT32_MAX; /* until a deadline that must not be late */
    if (p->timer_armed) {
        exact = until(now, p->timer_deadline_us);
    }
    uint32_t t = tx_next_us(p, now);
    if (p->tx_active && p->paced && p->tx_pos == 0u && t < exact) {
        exact = t;
    }
    wait = t < wait ? t : wait;
    wait = exact < wait ? exact : wait;

    /* sleep for sleep_us, then (spin) watch until spin_us, all from now */
    bool spin = exact <= wait;
    uint32_t sleep_us = spin ? (exact > SPIN_US ? exact - SPIN_US : 0u) : wait;
    uint32_t spin_us = wait;
    if (p->expect_armed) {
        int32_t rel = (int32_t)(p->expect_us - now);
        if (rel > -(int32_t)EXPECT_AFTER_US) {
            uint32_t start =
                rel > (int32_t)EXPECT_BEFORE_US ? (uint32_t)rel - EXPECT_BEFORE_US : 0u;
            uint32_t end = (uint32_t)rel + EXPECT_AFTER_US; /* rel > -EXPECT_AFTER_US */
            if (start < sleep_us) {
                sleep_us = start;
                spin_us = end < wait ? end : wait;
                spin = true;
            }
        }
    }

    struct pollfd pfs[2] = {{p->fd, POLLIN, 0}, {p->wake.rd, POLLIN, 0}};
    nfds_t nfds = p->wake.rd >= 0 ? 2u : 1u;
    struct timespec ts = {(time_t)(sleep_us / 1000000u), (long)(sleep_us % 1000000u) * 1000L};
    int pr = ppoll(pfs, nfds, &ts, NULL);
    if (pr == 0 && spin) {
        const struct timespec zero = {0, 0};
        const uint32_t at = now + spin_us;
        while (pr == 0 && !due(modcp_posix_now_us(), at)) {
            pr = ppoll(pfs, nfds, &zero, NULL);
        }
    }
    if (pr < 0 && errno != EINTR) {
        return -errno;
    }
    if (pr > 0 && nfds == 2u && (pfs[1].revents & POLLIN) != 0) {
        modcp_posix_event_clear(&p->wake);
    }
    const struct pollfd pf = pfs[0];
    now = modcp_posix_now_us();
    *now_us = now;
    *tx_done = tx_progress(p, now);
    *timer_fired = false;
    if (p->timer_armed && due(now, p->timer_deadline_us)) {
        p->timer_armed = false;
        *timer_fired = true;
    }
    size_t k = 0;
    if (pr > 0 && (pf.revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        uint8_t buf[512];
        size_t want = cap < sizeof buf ? cap : sizeof buf;
        ssize_t n = read(p->fd, buf, want);
        if (n > 0) {
            if (p->is_pty) {
                for (ssize_t i = 0; i < n; i++) {
                    rx[i].byte = buf[i];
                    rx[i].errors = 0;
                }
                k = (size_t)n;
            } else {
                k = decode(p, buf, (size_t)n, rx, cap);
#ifdef TIOCGICOUNT
                struct serial_icounter_struct ic;
                if (ioctl(p->fd, TIOCGICOUNT, &ic) == 0) {
                    uint32_t ov = (uint32_t)(ic.overrun + ic.buf_overrun);
                    if (ov != p->overruns && k > 0u) {
                        rx[k - 1u].errors |= MODCP_LINE_OVERRUN;
                    }
                    p->overruns = ov;
                }
#endif
            }
        } else if (n < 0 && errno != EAGAIN && errno != EINTR && errno != EIO) {
            return -errno;
        } else if (n < 0 && errno == EIO) {
            /* pty without a slave: cannot happen while slave_fd is open; avoid a busy loop */
            struct timespec s = {0, 1000000L};
            nanosleep(&s, NULL);
        }
    }
    return (int)k;
}
