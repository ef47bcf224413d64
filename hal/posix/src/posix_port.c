/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: the port — modcp_hal_t's callbacks (transmission, one-shot timer,
 * DE, LEDs, RS232 outputs), the RS232 inputs, paced transmission on a pty, and the wait
 * that ends on whatever the owner must hand to the core next. The line's end itself
 * (opening, reading) is posix_serial.c; clock, events and threads have their own files. */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <errno.h>
#include <poll.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "posix_internal.h"

void modcp_posix_wake(modcp_posix_port_t *p)
{
    modcp_posix_event_signal(&p->wake);
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

/* The line as the preset makes it ([RTU-2009] Table 5-8): R(A) 0 V / R(B) 5 V holds a broken
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

/* One wait: asleep for sleep_us, then (spin) watching the clock and the descriptors
 * until spin_us, both counted from the wait's start. */
typedef struct {
    uint32_t sleep_us;
    uint32_t spin_us;
    bool spin;
} wait_plan_t;

/* An expected wake-up: watch for it from EXPECT_BEFORE_US before until EXPECT_AFTER_US
 * after it, when that starts before the planned sleep ends. */
static void plan_expect(const modcp_posix_port_t *p, uint32_t now, uint32_t wait, wait_plan_t *w)
{
    int32_t rel = (int32_t)(p->expect_us - now);
    if (rel <= -(int32_t)EXPECT_AFTER_US) {
        return;
    }
    uint32_t start = rel > (int32_t)EXPECT_BEFORE_US ? (uint32_t)rel - EXPECT_BEFORE_US : 0u;
    uint32_t end = (uint32_t)rel + EXPECT_AFTER_US; /* rel > -EXPECT_AFTER_US */
    if (start < w->sleep_us) {
        w->sleep_us = start;
        w->spin_us = end < wait ? end : wait;
        w->spin = true;
    }
}

static wait_plan_t plan_wait(const modcp_posix_port_t *p, uint32_t now, uint32_t max_us)
{
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
    wait_plan_t w;
    w.spin = exact <= wait;
    w.sleep_us = w.spin ? (exact > SPIN_US ? exact - SPIN_US : 0u) : wait;
    w.spin_us = wait;
    if (p->expect_armed) {
        plan_expect(p, now, wait, &w);
    }
    return w;
}

/* ppoll as planned; returns ppoll's result (revents set in pfs). */
static int poll_planned(struct pollfd *pfs, nfds_t nfds, uint32_t now, const wait_plan_t *w)
{
    struct timespec ts = {(time_t)(w->sleep_us / 1000000u), (long)(w->sleep_us % 1000000u) * 1000L};
    int pr = ppoll(pfs, nfds, &ts, NULL);
    if (pr == 0 && w->spin) {
        const struct timespec zero = {0, 0};
        const uint32_t at = now + w->spin_us;
        while (pr == 0 && !due(modcp_posix_now_us(), at)) {
            pr = ppoll(pfs, nfds, &zero, NULL);
        }
    }
    return pr;
}

int modcp_posix_wait(modcp_posix_port_t *p, uint32_t max_us, modcp_posix_rx_t *rx, size_t cap,
                     bool *tx_done, bool *timer_fired, uint32_t *now_us)
{
    uint32_t now = modcp_posix_now_us();
    const wait_plan_t w = plan_wait(p, now, max_us);
    struct pollfd pfs[2] = {{p->fd, POLLIN, 0}, {p->wake.rd, POLLIN, 0}};
    nfds_t nfds = p->wake.rd >= 0 ? 2u : 1u;
    int pr = poll_planned(pfs, nfds, now, &w);
    if (pr < 0 && errno != EINTR) {
        return -errno;
    }
    if (pr > 0 && nfds == 2u && (pfs[1].revents & POLLIN) != 0) {
        modcp_posix_event_clear(&p->wake);
    }
    now = modcp_posix_now_us();
    *now_us = now;
    *tx_done = tx_progress(p, now);
    *timer_fired = false;
    if (p->timer_armed && due(now, p->timer_deadline_us)) {
        p->timer_armed = false;
        *timer_fired = true;
    }
    if (pr > 0 && (pfs[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        return modcp_posix_serial_read(p, rx, cap);
    }
    return 0;
}
