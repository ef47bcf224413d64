/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the bus's line levels (the wired AND of every sender) and its UART receiver (falling edge, sampled mid-bit). */
#define _GNU_SOURCE
#include "bus_internal.h"

/* ---- the line's levels ---------------------------------------------------------- */

/* Level of bit i (0 = start) of the character v. */
static int frame_bit(const sim_bus_t *b, uint8_t v, unsigned i)
{
    unsigned db = b->line.data_bits;
    if (i == 0u) {
        return 0;
    }
    if (i <= db) {
        return (v >> (i - 1u)) & 1;
    }
    if (b->line.parity != 0u && i == db + 1u) {
        unsigned ones = 0;
        for (unsigned k = 0; k < db; k++) {
            ones += ((unsigned)v >> k) & 1u;
        }
        return b->line.parity == 2u ? (int)(ones & 1u) : (int)((ones & 1u) ^ 1u);
    }
    return 1; /* stop bits, idle */
}

double end_of(const sim_bus_t *b, const sender_t *s)
{
    return s->t0 + (double)s->len * b->c_us;
}

static int sender_level(const sim_bus_t *b, const sender_t *s, double tau)
{
    double r = tau - s->t0;
    if (r < 0.0 || tau >= end_of(b, s)) {
        return 1;
    }
    size_t gb = (size_t)(r / b->bit_us);
    size_t k = gb / b->nbits;
    if (k >= s->len) {
        return 1;
    }
    return frame_bit(b, s->b[k], (unsigned)(gb % b->nbits));
}

static int line_level(const sim_bus_t *b, double tau)
{
    for (size_t i = 0; i < MAX_SENDERS; i++) {
        if (b->s[i].used && sender_level(b, &b->s[i], tau) == 0) {
            return 0;
        }
    }
    return 1;
}

/* Earliest time >= from at which s drives a 0. */
static bool sender_first_low(const sim_bus_t *b, const sender_t *s, double from, double *at)
{
    double r = from - s->t0;
    if (from >= end_of(b, s)) {
        return false;
    }
    if (r < 0.0) {
        r = 0.0;
    }
    size_t total = (size_t)s->len * b->nbits;
    for (size_t gb = (size_t)(r / b->bit_us); gb < total; gb++) {
        if (frame_bit(b, s->b[gb / b->nbits], (unsigned)(gb % b->nbits)) == 0) {
            double start = (double)gb * b->bit_us;
            *at = s->t0 + (start > r ? start : r);
            return true;
        }
    }
    return false;
}


/* The receiver's next character from b->from on (not consumed). */
bool decode_next(const sim_bus_t *b, rxchar_t *out)
{
    double from = b->from;
    for (int tries = 0; tries < 64; tries++) {
        bool found = false;
        double ts = 0.0;
        for (size_t i = 0; i < MAX_SENDERS; i++) {
            double at;
            if (b->s[i].used && sender_first_low(b, &b->s[i], from, &at) && (!found || at < ts)) {
                ts = at;
                found = true;
            }
        }
        if (!found) {
            return false;
        }
        if (line_level(b, ts + 0.5 * b->bit_us) != 0) {
            from = ts + 0.5 * b->bit_us; /* a glitch, not a start bit */
            continue;
        }
        uint8_t v = 0;
        for (unsigned i = 1; i <= b->line.data_bits; i++) {
            if (line_level(b, ts + ((double)i + 0.5) * b->bit_us) != 0) {
                v = (uint8_t)(v | (1u << (i - 1u)));
            }
        }
        out->start = ts;
        out->byte = v;
        out->mask = 0;
        out->senders = 0;
        for (size_t i = 0; i < MAX_SENDERS; i++) {
            const sender_t *s = &b->s[i];
            if (s->used && s->t0 < ts + b->c_us && end_of(b, s) > ts) {
                out->senders++;
                if (s->who >= 0) {
                    out->mask |= 1u << (unsigned)s->who;
                }
            }
        }
        return true;
    }
    return false;
}
