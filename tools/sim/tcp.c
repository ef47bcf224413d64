/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — RTU over TCP (--tcp [ADDR:]PORT): a source of the line for masters that
 * carry RTU frames in a TCP stream, as serial device servers and "RTU over TCP" masters
 * do (diagslave -m enc, pymodbus's TCP client with the RTU framer).
 *
 * One client at a time (the next is accepted when it leaves): what it sends goes onto the
 * line through the line's pty, as a master on the pty would write it (the slaves' t3.5
 * cuts the frames, as on the pty), and what the line carries back to the master goes to
 * the client. A client that disconnects mid-frame leaves that frame unfinished on the line
 * (the slave drops it at t3.5, as any cut frame); the next client starts on a clean
 * line: what was still to come for the one before is discarded when it is accepted.
 * While a client is connected, what the line carries back goes to it (a master on the
 * pty then misses it: one master at a time); between clients the pty is a master's alone. */
#define _GNU_SOURCE
#include "tcp.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

bool sim_tcp_listen(sim_tcp_t *t, const char *spec, char *err, size_t cap)
{
    memset(t, 0, sizeof *t);
    t->fd = -1;
    char host[64] = "127.0.0.1";
    const char *colon = strrchr(spec, ':');
    const char *port_s = spec;
    if (colon != NULL) {
        size_t hl = (size_t)(colon - spec);
        if (hl == 0u || hl >= sizeof host) {
            snprintf(err, cap, "expected [ADDR:]PORT");
            return false;
        }
        memcpy(host, spec, hl);
        host[hl] = '\0';
        port_s = colon + 1;
    }
    char *end = NULL;
    long port = strtol(port_s, &end, 10);
    struct sockaddr_in sa;
    memset(&sa, 0, sizeof sa);
    sa.sin_family = AF_INET;
    if (*port_s == '\0' || *end != '\0' || port < 1 || port > 65535 ||
        inet_pton(AF_INET, host, &sa.sin_addr) != 1) {
        snprintf(err, cap, "expected [ADDR:]PORT with an IPv4 address and a port 1..65535");
        return false;
    }
    sa.sin_port = htons((uint16_t)port);
    t->fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    int one = 1;
    if (t->fd < 0 || setsockopt(t->fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
        bind(t->fd, (struct sockaddr *)&sa, sizeof sa) != 0 || listen(t->fd, 4) != 0) {
        snprintf(err, cap, "%s:%ld: %s", host, port, strerror(errno));
        if (t->fd >= 0) {
            close(t->fd);
        }
        t->fd = -1;
        return false;
    }
    snprintf(t->where, sizeof t->where, "%s:%ld", host, port);
    return true;
}

/* Copies what is readable on from to to; false when from is closed. */
static bool pump(int from, int to)
{
    uint8_t buf[1024];
    ssize_t n = read(from, buf, sizeof buf);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
        return false;
    }
    for (ssize_t off = 0; n > 0 && off < n;) {
        ssize_t w = write(to, buf + off, (size_t)(n - off));
        if (w < 0 && errno != EAGAIN && errno != EINTR) {
            break;
        }
        off += w > 0 ? w : 0;
    }
    return true;
}

/* One client until it leaves or *stop. */
static void serve(sim_tcp_t *t, int cfd, int line, const atomic_bool *stop)
{
    int one = 1;
    (void)setsockopt(cfd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    (void)tcflush(line, TCIFLUSH); /* what was still to come for the client before */
    t->clients++;
    while (!atomic_load(stop)) {
        struct pollfd pf[2] = {{cfd, POLLIN, 0}, {line, POLLIN, 0}};
        if (poll(pf, 2, 200) <= 0) {
            continue;
        }
        if ((pf[0].revents & (POLLIN | POLLHUP | POLLERR)) != 0 && !pump(cfd, line)) {
            break;
        }
        if ((pf[1].revents & POLLIN) != 0) {
            (void)pump(line, cfd);
        }
    }
    close(cfd);
}

void sim_tcp_run(sim_tcp_t *t, const char *line_path, const atomic_bool *stop)
{
    int line = open(line_path, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (line < 0) {
        return;
    }
    struct termios tio;
    if (tcgetattr(line, &tio) == 0) {
        cfmakeraw(&tio);
        (void)tcsetattr(line, TCSANOW, &tio);
    }
    while (!atomic_load(stop)) {
        struct pollfd pf = {t->fd, POLLIN, 0};
        if (poll(&pf, 1, 200) <= 0) {
            continue; /* no client: the line is the pty's alone */
        }
        int cfd = accept4(t->fd, NULL, NULL, SOCK_CLOEXEC | SOCK_NONBLOCK);
        if (cfd >= 0) {
            serve(t, cfd, line, stop);
        }
    }
    close(line);
}

void sim_tcp_close(sim_tcp_t *t)
{
    if (t->fd >= 0) {
        close(t->fd);
        t->fd = -1;
    }
}
