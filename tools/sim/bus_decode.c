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
    return s->low_us > 0.0 ? s->t0 + s->low_us : s->t0 + (double)s->len * b->c_us;
}

/* Level of bit i of s's character k, with the transmission's serial faults. */
static int sender_bit(const sim_bus_t *b, const sender_t *s, size_t k, unsigned i)
{
    unsigned db = b->line.data_bits;
    unsigned par = b->line.parity != 0u ? 1u : 0u;
    if (s->cut_bits != 0u && k + 1u == s->len && i >= b->nbits - s->cut_bits) {
        return 1; /* the driver is off: the line idles (fail-safe bias) */
    }
    int v = frame_bit(b, s->b[k], i);
    if (par != 0u && i == db + 1u && k + 1u == s->parity_k) {
        v ^= 1;
    }
    if (i == db + 1u + par && k + 1u == s->framing_k) {
        v = 0;
    }
    return v;
}

static int sender_level(const sim_bus_t *b, const sender_t *s, double tau)
{
    double r = tau - s->t0;
    if (r < 0.0 || tau >= end_of(b, s)) {
        return 1;
    }
    if (s->low_us > 0.0) {
        return 0; /* a BREAK */
    }
    size_t gb = (size_t)(r / b->bit_us);
    size_t k = gb / b->nbits;
    if (k >= s->len) {
        return 1;
    }
    return sender_bit(b, s, k, (unsigned)(gb % b->nbits));
}

static int line_level(const sim_bus_t *b, double tau)
{
    for (size_t i = 0; i < b->s_hi; i++) {
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
    if (s->low_us > 0.0) {
        *at = s->t0 + r;
        return true;
    }
    size_t total = (size_t)s->len * b->nbits;
    for (size_t gb = (size_t)(r / b->bit_us); gb < total; gb++) {
        if (sender_bit(b, s, gb / b->nbits, (unsigned)(gb % b->nbits)) == 0) {
            double start = (double)gb * b->bit_us;
            *at = s->t0 + (start > r ? start : r);
            return true;
        }
    }
    return false;
}

/* The earliest start bit from `from` on (false: none). */
static bool next_start(const sim_bus_t *b, double from, double *ts)
{
    bool found = false;
    for (size_t i = 0; i < b->s_hi; i++) {
        double at;
        if (b->s[i].used && sender_first_low(b, &b->s[i], from, &at) && (!found || at < *ts)) {
            *ts = at;
            found = true;
        }
    }
    return found;
}

/* The character at ts as a UART samples it: data, parity check, stop bit; a character
 * of 0 bits with a 0 stop bit is a BREAK, which lasts until the line is 1 again. */
static void sample(const sim_bus_t *b, double ts, rxchar_t *out)
{
    unsigned db = b->line.data_bits;
    unsigned par = b->line.parity != 0u ? 1u : 0u;
    uint8_t v = 0;
    unsigned ones = 0;
    for (unsigned i = 1; i <= db; i++) {
        if (line_level(b, ts + ((double)i + 0.5) * b->bit_us) != 0) {
            v = (uint8_t)(v | (1u << (i - 1u)));
            ones++;
        }
    }
    int pbit = par != 0u ? line_level(b, ts + ((double)db + 1.5) * b->bit_us) : 0;
    int stop = line_level(b, ts + ((double)(db + par) + 1.5) * b->bit_us);
    out->byte = v;
    out->errors = 0;
    out->len_us = b->c_us;
    if (par != 0u && pbit != (b->line.parity == 2u ? (int)(ones & 1u) : (int)((ones & 1u) ^ 1u))) {
        out->errors |= MODCP_LINE_PARITY;
    }
    if (stop == 0 && v == 0u && pbit == 0) {
        double t = ts + b->c_us;
        while (line_level(b, t) == 0 && t < ts + 60e6) {
            t += 0.5 * b->bit_us;
        }
        out->errors = MODCP_LINE_BREAK;
        out->len_us = t - ts;
    } else if (stop == 0) {
        out->errors |= MODCP_LINE_FRAMING;
    }
}

/* The receiver's next character from b->from on (not consumed). */
bool decode_next(const sim_bus_t *b, rxchar_t *out)
{
    double from = b->from;
    for (int tries = 0; tries < 64; tries++) {
        double ts = 0.0;
        if (!next_start(b, from, &ts)) {
            return false;
        }
        if (line_level(b, ts + 0.5 * b->bit_us) != 0) {
            from = ts + 0.5 * b->bit_us; /* a glitch, not a start bit */
            continue;
        }
        sample(b, ts, out);
        out->start = ts;
        memset(&out->mask, 0, sizeof out->mask);
        out->senders = 0;
        for (size_t i = 0; i < b->s_hi; i++) {
            const sender_t *s = &b->s[i];
            if (s->used && s->t0 < ts + out->len_us && end_of(b, s) > ts) {
                out->senders++;
                if (s->who >= 0) {
                    mset_add(&out->mask, (size_t)s->who);
                }
            }
        }
        return true;
    }
    return false;
}
