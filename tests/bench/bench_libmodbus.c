/* SPDX-License-Identifier: Apache-2.0 */
#define _POSIX_C_SOURCE 200809L
/* Benchmark: the same requests served by libmodbus's slave side (modbus_receive +
 * modbus_reply over a socketpair, RTU backend, CRC checked by libmodbus) for
 * comparison under callgrind. tools/bench counts only modbus_receive and modbus_reply
 * (--toggle-collect): this harness's write of the request and read of the reply play
 * the master and are not the slave's cost. libmodbus is only ever linked into tests
 * and tools. */
#include <errno.h>
#include <modbus.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "bench_requests.h"

static modbus_t *ctx;
static modbus_mapping_t *map;
static int sv[2];

static ssize_t last_reply;

static void one(const uint8_t *req, size_t len)
{
    uint8_t buf[MODBUS_RTU_MAX_ADU_LENGTH];
    if (write(sv[1], req, len) != (ssize_t)len) {
        perror("write");
        exit(1);
    }
    int rc = modbus_receive(ctx, buf);
    if (rc <= 0 || modbus_reply(ctx, buf, rc, map) < 0) {
        fprintf(stderr, "libmodbus: %s\n", modbus_strerror(errno));
        exit(1);
    }
    uint8_t reply[300];
    last_reply = read(sv[1], reply, sizeof reply);
    if (last_reply <= 0) {
        perror("read");
        exit(1);
    }
}

void bench_loop(const uint8_t *req, size_t len, unsigned n);
__attribute__((noinline)) void bench_loop(const uint8_t *req, size_t len, unsigned n)
{
    for (unsigned k = 0; k < n; k++) {
        one(req, len);
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench_libmodbus NAME COUNT\n");
        return 2;
    }
    const bench_request_t *r = bench_find(argv[1]);
    unsigned n = (unsigned)strtoul(argv[2], NULL, 0);
    uint8_t frame[BENCH_FRAME_MAX];
    size_t len = bench_frame(r, frame);
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, sv) != 0) {
        perror("socketpair");
        return 1;
    }
    ctx = modbus_new_rtu("/dev/null", 9600, 'E', 8, 1);
    modbus_set_slave(ctx, 5);
    modbus_set_socket(ctx, sv[0]);
    map = modbus_mapping_new(4096, 0, 1024, 1024);
    one(frame, len);
    if (last_reply != (ssize_t)r->reply_len) {
        fprintf(stderr, "bench_libmodbus: %s: reply length %zd, expected %u\n", r->name,
                last_reply, r->reply_len);
        return 1;
    }
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    bench_loop(frame, len, n);
    clock_gettime(CLOCK_MONOTONIC, &b);
    double us = ((double)(b.tv_sec - a.tv_sec) * 1e6 + (double)(b.tv_nsec - a.tv_nsec) / 1e3) / n;
    printf("libmodbus %s: %.2f us per request (wall, %u requests)\n", r->name, us, n);
    modbus_mapping_free(map);
    modbus_free(ctx);
    return 0;
}
