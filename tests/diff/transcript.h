/* SPDX-License-Identifier: Apache-2.0 */
/* The differential harness's input side (tools/diffcore, transcript.c): a seeded
 * generator and the Modbus requests it builds. Nothing here reads the core's state, so
 * two cores given the same seed get the same input as long as they behave alike. */
#ifndef DIFF_TRANSCRIPT_H
#define DIFF_TRANSCRIPT_H

#include <stddef.h>
#include <stdint.h>

#include "modcp/params.h"

/* splitmix64: one stream per (seed, input number). */
typedef struct {
    uint64_t s;
} drng_t;

void drng_seed(drng_t *r, uint64_t seed, uint64_t input);
uint32_t drng_next(drng_t *r);
/* 0 .. n - 1 (n >= 1). */
uint32_t drng_below(drng_t *r, uint32_t n);

/* A request ADU without its check (address byte, function code, data), aimed at the
 * set p's windows, ranges and limits and their edges; sometimes malformed. Returns its
 * length (<= cap, cap >= 260). */
size_t diff_request(drng_t *r, const modcp_params_t *p, uint8_t *out, size_t cap);

/* The ADU as it goes on the line: RTU with its CRC, ASCII ':' + hex + LRC + CR LF.
 * Returns the frame length (cap >= 2 * n + 5). */
size_t diff_encode(const modcp_params_t *p, const uint8_t *adu, size_t n, uint8_t *out,
                   size_t cap);

/* Sometimes (about one frame in seven) a corrupted frame: a bit flipped, a character
 * dropped, one added, or the check broken. Returns the new length (<= cap). */
size_t diff_corrupt(drng_t *r, uint8_t *fr, size_t n, size_t cap);

#endif
