/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: events another thread can signal (a non-blocking pipe). */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <time.h>
#include <unistd.h>

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
