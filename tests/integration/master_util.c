/* SPDX-License-Identifier: Apache-2.0 */
#define _POSIX_C_SOURCE 200809L
#include "master_util.h"

#include <errno.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

int passed, failed;
bool verbose;

void ok(bool cond, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (cond) {
        passed++;
        if (verbose) {
            printf("ok - ");
            vprintf(fmt, ap);
            printf("\n");
        }
    } else {
        failed++;
        printf("FAIL - ");
        vprintf(fmt, ap);
        printf("\n");
    }
    va_end(ap);
    fflush(stdout);
}

double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

size_t hex(const char *s, uint8_t *out, size_t cap)
{
    size_t n = 0;
    while (*s != '\0' && n < cap) {
        while (*s == ' ') {
            s++;
        }
        if (*s == '\0') {
            break;
        }
        unsigned v;
        if (sscanf(s, "%2x", &v) != 1) {
            fprintf(stderr, "bad hex '%s'\n", s);
            exit(3);
        }
        out[n++] = (uint8_t)v;
        s += 2;
    }
    return n;
}

void fmt_hex(const uint8_t *b, size_t n, char *out, size_t cap)
{
    size_t pos = 0;
    out[0] = '\0';
    for (size_t i = 0; i < n && pos + 4 < cap; i++) {
        pos += (size_t)snprintf(out + pos, cap - pos, "%s%02X", i ? " " : "", b[i]);
    }
}

uint16_t crc16(const uint8_t *p, size_t n)
{
    uint16_t crc = 0xFFFF;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int b = 0; b < 8; b++) {
            crc = (crc & 1u) ? (uint16_t)((crc >> 1) ^ 0xA001u) : (uint16_t)(crc >> 1);
        }
    }
    return crc;
}

size_t add_crc(uint8_t *b, size_t n)
{
    uint16_t c = crc16(b, n);
    b[n] = (uint8_t)(c & 0xFF);
    b[n + 1] = (uint8_t)(c >> 8);
    return n + 2;
}

int read_want(int fd, uint8_t *rsp, size_t want, int wait_ms)
{
    size_t got = 0;
    double end = now_s() + wait_ms / 1000.0;
    while (got < want) {
        int left = (int)((end - now_s()) * 1000.0);
        if (left <= 0) {
            break;
        }
        struct pollfd pf = {fd, POLLIN, 0};
        if (poll(&pf, 1, left) <= 0) {
            break;
        }
        ssize_t r = read(fd, rsp + got, want - got);
        if (r > 0) {
            got += (size_t)r;
        } else if (r < 0 && errno != EAGAIN && errno != EINTR) {
            break;
        }
    }
    return (int)got;
}
