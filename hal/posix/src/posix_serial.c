/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: the serial line's end — opening a pseudo-terminal or a serial
 * device (termios), closing it, and reading its characters (PARMRK decoding and the
 * overrun count of a device). */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
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
#endif

#include "posix_baud.h"
#include "posix_internal.h"

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

/* Close p and return rc (for the error paths of the openers). */
static int fail(modcp_posix_port_t *p, int rc)
{
    modcp_posix_close(p);
    return rc;
}

/* Make link a symlink to the pty slave p->path; 0 or -errno (see open_pty). */
static int pty_link(modcp_posix_port_t *p, const char *link)
{
    struct stat st;
    if (lstat(link, &st) == 0) {
        if (!S_ISLNK(st.st_mode)) {
            return -EEXIST; /* never replace a regular file */
        }
        struct stat tst, own;
        if (stat(link, &tst) == 0 && !(stat(p->path, &own) == 0 && own.st_rdev == tst.st_rdev)) {
            return -EBUSY; /* points at a device that exists: maybe a live instance's */
        }
        /* a stale link left by an instance that was killed (its pty is gone, or is
         * the one we were just given) */
        (void)unlink(link);
    }
    if (symlink(p->path, link) != 0) {
        return -errno;
    }
    snprintf(p->link, sizeof p->link, "%s", link);
    return 0;
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
        return fail(p, -errno);
    }
    if (grantpt(fd) != 0 || unlockpt(fd) != 0 || ptsname_r(fd, p->path, sizeof p->path) != 0) {
        int e = errno;
        close(fd);
        return fail(p, -e);
    }
    int sfd = open(p->path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (sfd < 0) {
        int e = errno;
        close(fd);
        return fail(p, -e);
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
        int rc = pty_link(p, link);
        if (rc != 0) {
            return fail(p, rc);
        }
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

/* Raw mode with the character format; parity / framing errors and BREAK marked in the
 * stream (PARMRK: FF 00 x, FF 00 00, FF FF). */
static void device_termios(struct termios *tio, uint8_t data_bits, uint8_t parity,
                           uint8_t stop_bits)
{
    cfmakeraw(tio);
    tio->c_cflag &= (tcflag_t) ~(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
    tio->c_cflag |= CLOCAL | CREAD | (data_bits == 7u ? CS7 : CS8);
    if (parity != 0u) {
        tio->c_cflag |= PARENB;
        if (parity == 1u) {
            tio->c_cflag |= PARODD;
        }
    }
    if (stop_bits == 2u) {
        tio->c_cflag |= CSTOPB;
    }
    tio->c_iflag &= (tcflag_t) ~(IGNBRK | BRKINT | IGNPAR | ISTRIP | IXON | IXOFF | IXANY);
    tio->c_iflag |= INPCK | PARMRK;
    tio->c_cc[VMIN] = 1;
    tio->c_cc[VTIME] = 0;
}

/* The device's overrun count so far (TIOCGICOUNT), or 0 where it cannot be read. */
static bool overrun_count(int fd, uint32_t *count)
{
#ifdef TIOCGICOUNT
    struct serial_icounter_struct ic;
    if (ioctl(fd, TIOCGICOUNT, &ic) == 0) {
        *count = (uint32_t)(ic.overrun + ic.buf_overrun);
        return true;
    }
#else
    (void)fd;
    (void)count;
#endif
    return false;
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
        return fail(p, -errno);
    }
    struct termios tio;
    if (tcgetattr(fd, &tio) != 0) {
        int e = errno;
        close(fd);
        return fail(p, -e);
    }
    device_termios(&tio, data_bits, parity, stop_bits);
    speed_t sp = speed_of(baud);
    if (sp != B0) {
        cfsetispeed(&tio, sp);
        cfsetospeed(&tio, sp);
    }
    if (tcsetattr(fd, TCSANOW, &tio) != 0) {
        int e = errno;
        close(fd);
        return fail(p, -e);
    }
    if (sp == B0) {
        int rc = modcp_posix_custom_baud(fd, baud);
        if (rc != 0) {
            close(fd);
            return fail(p, rc);
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
    (void)overrun_count(fd, &p->overruns);
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

/* ---- reading ----------------------------------------------------------------------- */

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
                break; /* BREAK on a line held HIGH by the preset ([RTU-2009] Table 5-8): never seen */
            }
            rx[k].byte = b;
            rx[k].errors = b == 0u ? MODCP_LINE_BREAK : err;
            k++;
            break;
        }
    }
    return k;
}

int modcp_posix_serial_read(modcp_posix_port_t *p, modcp_posix_rx_t *rx, size_t cap)
{
    uint8_t buf[512];
    size_t want = cap < sizeof buf ? cap : sizeof buf;
    ssize_t n = read(p->fd, buf, want);
    if (n < 0 && errno == EIO) {
        /* pty without a slave: cannot happen while slave_fd is open; avoid a busy loop */
        struct timespec s = {0, 1000000L};
        nanosleep(&s, NULL);
        return 0;
    }
    if (n < 0) {
        return errno == EAGAIN || errno == EINTR ? 0 : -errno;
    }
    if (n == 0) {
        return 0;
    }
    if (p->is_pty) {
        for (ssize_t i = 0; i < n; i++) {
            rx[i].byte = buf[i];
            rx[i].errors = 0;
        }
        return (int)n;
    }
    size_t k = decode(p, buf, (size_t)n, rx, cap);
    uint32_t ov;
    if (overrun_count(p->fd, &ov)) {
        if (ov != p->overruns && k > 0u) {
            rx[k - 1u].errors |= MODCP_LINE_OVERRUN;
        }
        p->overruns = ov;
    }
    return (int)k;
}
