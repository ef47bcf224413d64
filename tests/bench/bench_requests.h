/* The requests both benchmarks serve (slave 5, CRC included). */
#ifndef BENCH_REQUESTS_H
#define BENCH_REQUESTS_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *name;
    uint8_t frame[32];
    size_t len;
    uint16_t reply_len;
} bench_request_t;

static const bench_request_t bench_requests[] = {
    /* FC03: 10 holding registers at 0 */
    {"fc03x10", {0x05, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC4, 0x49}, 8, 25},
    /* FC16: 4 registers at 0x32 */
    {"fc16x4", {0x05, 0x10, 0x00, 0x32, 0x00, 0x04, 0x08, 1, 2, 3, 4, 5, 6, 7, 8, 0xFB, 0x3A}, 17, 8},
    /* FC01: 32 coils at 0x40 (004 §6.1 example) */
    {"fc01x32", {0x05, 0x01, 0x00, 0x40, 0x00, 0x20, 0x3D, 0x82}, 8, 9},
};

static inline const bench_request_t *bench_find(const char *name)
{
    for (size_t k = 0; k < sizeof bench_requests / sizeof bench_requests[0]; k++) {
        if (strcmp(bench_requests[k].name, name) == 0) {
            return &bench_requests[k];
        }
    }
    fprintf(stderr, "unknown request %s\n", name);
    exit(2);
}

#endif
