/* SPDX-License-Identifier: Apache-2.0 */
/* The requests both benchmarks serve (slave 5). Frames are built at start-up with
 * their CRC (bench_frame): holding registers in one DB (DB 800), coils in M. */
#ifndef BENCH_REQUESTS_H
#define BENCH_REQUESTS_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BENCH_FRAME_MAX 256u

typedef struct {
    const char *name;
    uint8_t fc;
    uint16_t addr;
    uint16_t qty;       /* coils / registers (FC05: 0xFF00 = ON, FC06: the value) */
    uint16_t reply_len; /* reply ADU bytes, CRC included */
} bench_request_t;

static const bench_request_t bench_requests[] = {
    {"fc03x10", 0x03, 0x0000, 10, 25},    /* 10 holding registers at 0 */
    {"fc16x4", 0x10, 0x0032, 4, 8},       /* 4 registers at 0x32, data 1..8 */
    {"fc01x32", 0x01, 0x0040, 32, 9},     /* 32 coils at 0x40 ([RTU-2003] §6.1 example) */
    /* issue 12 item 7: the six requests of tools/bench --summary */
    {"fc01x2000", 0x01, 0x0000, 2000, 255}, /* 2000 coils (M) */
    {"fc03x125", 0x03, 0x0000, 125, 255},   /* 125 holding registers (DB 800) */
    {"fc05", 0x05, 0x0013, 0xFF00, 8},      /* coil 0x13 ON */
    {"fc06", 0x06, 0x0001, 0x0003, 8},      /* register 1 := 3 */
    {"fc15x1968", 0x0F, 0x0000, 1968, 8},   /* 1968 coils */
    {"fc16x123", 0x10, 0x0000, 123, 8},     /* 123 registers */
};

#define BENCH_SUMMARY_SET "fc01x2000 fc03x125 fc05 fc06 fc15x1968 fc16x123"

static inline uint16_t bench_crc(const uint8_t *p, size_t n)
{
    uint16_t crc = 0xFFFFu;
    for (size_t k = 0; k < n; k++) {
        crc = (uint16_t)(crc ^ p[k]);
        for (int b = 0; b < 8; b++) {
            crc = (crc & 1u) ? (uint16_t)((crc >> 1) ^ 0xA001u) : (uint16_t)(crc >> 1);
        }
    }
    return crc;
}

/* The request frame (CRC included) into out[BENCH_FRAME_MAX]; returns its length. */
static inline size_t bench_frame(const bench_request_t *r, uint8_t *out)
{
    size_t n = 0;
    out[n++] = 5;
    out[n++] = r->fc;
    out[n++] = (uint8_t)(r->addr >> 8);
    out[n++] = (uint8_t)(r->addr & 0xFFu);
    out[n++] = (uint8_t)(r->qty >> 8);
    out[n++] = (uint8_t)(r->qty & 0xFFu);
    if (r->fc == 0x0F || r->fc == 0x10) {
        size_t bytes = r->fc == 0x0F ? (r->qty + 7u) / 8u : 2u * r->qty;
        out[n++] = (uint8_t)bytes;
        for (size_t k = 0; k < bytes; k++) {
            out[n++] = r->fc == 0x10 ? (uint8_t)(k + 1u) : (uint8_t)(0xA5u ^ (k * 7u));
        }
    }
    uint16_t crc = bench_crc(out, n);
    out[n++] = (uint8_t)(crc & 0xFFu);
    out[n++] = (uint8_t)(crc >> 8);
    return n;
}

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
