/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the master's direction: its characters through its serial faults
 * (@master: parity, framing, break, gap, de_cut, early) to the members, each at its time.
 *
 * Without a fault, a request read from the master's pty reaches the members at once (a
 * pty delivers it in one piece), every character at the time of the read (bus.c). With
 * one, the request is put on the line as a UART sends it: from the read on, one
 * character after the other, with a character with a parity or framing error, a BREAK
 * after the first character (the rest after it), a pause after byte k, the last
 * character cut short by DE (its last bits read as 1), or, with early=US, a request
 * that follows a reply put US after the reply's last stop bit. The characters are
 * handed to the members at once, each with its time (the end of its stop bit): a member
 * takes a character when its time has come and wakes for it (sim_bus_next_time), so the
 * t1.5 / t3.5 gaps are exact however late a thread runs. */
#define _GNU_SOURCE
#include "bus_internal.h"

static void mq_push(sim_bus_t *b, uint8_t byte, uint8_t errors, double t)
{
    if (b->mq_n < MQ_MAX) {
        b->mq[b->mq_n++] = (mchar_t){byte, errors, t};
    }
}

/* The last character with its last `cut` bits idle (1): *errors gets a parity error
 * when the idle parity bit does not match what is left of the data. */
static uint8_t cut_byte(const sim_bus_t *b, uint8_t v, unsigned cut, uint8_t *errors)
{
    unsigned keep = b->nbits - cut; /* bits still driven, the start bit included */
    unsigned db = b->line.data_bits;
    unsigned ones = 0;
    for (unsigned i = 1; i <= db; i++) {
        if (i >= keep) {
            v = (uint8_t)(v | (1u << (i - 1u)));
        }
        ones += ((unsigned)v >> (i - 1u)) & 1u;
    }
    if (b->line.parity != 0u && db + 1u >= keep) {
        unsigned want = b->line.parity == 2u ? (ones & 1u) : ((ones & 1u) ^ 1u);
        if (want != 1u) {
            *errors |= MODCP_LINE_PARITY;
        }
    }
    return v;
}

/* To the line model: the master's characters with their flags (a BREAK apart). */
static void line_put(sim_bus_t *b, uint8_t byte, uint8_t flags, double end, uint32_t len_us)
{
    double t0 = end - (double)len_us;
    sim_char_t c = {(uint64_t)(t0 < 0.0 ? 0.0 : t0), len_us, 0, SIM_SRC_MASTER, byte, flags};
    sim_line_put(b->wire, &c);
}

/* The first character's end: the request goes onto the line when the master wrote it
 * (read at t), one character after the other; with early=US, a request read within
 * 100 ms of a reply's end starts US after that end (once per reply). */
static double first_end(sim_bus_t *b, double t)
{
    sim_fault_t *f = &b->mfault;
    double end = t + b->c_us;
    if (f->early_us != 0u && b->reply_end > 0.0 && t - b->reply_end < 100000.0) {
        end = b->reply_end + (double)f->early_us + b->c_us;
        b->reply_end = 0.0;
        f->early_sent++;
    }
    return end;
}

void master_faults(sim_bus_t *b, const uint8_t *buf, size_t n, double t)
{
    sim_fault_t *f = &b->mfault;
    f->replies++;
    double end = first_end(b, t);
    for (size_t k = 0; k < n; k++) {
        uint8_t v = buf[k], e = 0, fl = 0;
        if (k + 1u == f->parity_k && b->line.parity != 0u) {
            e |= MODCP_LINE_PARITY;
            fl |= SIM_CH_PARITY;
            f->parity_errs++;
        }
        if (k + 1u == f->framing_k) {
            e |= MODCP_LINE_FRAMING;
            fl |= SIM_CH_FRAMING;
            f->framing_errs++;
        }
        if (k + 1u == n && f->de_cut_bits != 0u) {
            unsigned cut = f->de_cut_bits < b->nbits ? f->de_cut_bits : b->nbits - 1u;
            v = cut_byte(b, v, cut, &e);
            fl |= SIM_CH_DE_CUT;
            f->de_cuts++;
        }
        mq_push(b, v, e, end);
        sim_char_t c = {0, b->line.char_us, 0, SIM_SRC_MASTER, v, fl};
        if ((fl & SIM_CH_DE_CUT) != 0u) {
            c.de_off_us = (uint32_t)((double)(b->nbits - f->de_cut_bits) * b->bit_us);
        }
        line_put(b, c.byte, c.flags, end, b->line.char_us);
        if (k == 0u && f->break_ms != 0u) {
            double len = (double)f->break_ms * 1000.0;
            end += len;
            mq_push(b, 0, MODCP_LINE_BREAK, end);
            line_put(b, 0, SIM_CH_BREAK, end, f->break_ms * 1000u);
            f->breaks_sent++;
            end += b->bit_us; /* a bit of idle before the next start bit */
        }
        if (k + 1u == f->gap_k && k + 1u < n) {
            end += (double)f->gap_us;
            f->gaps_made++;
        }
        end += b->c_us;
    }
}

double master_due(sim_bus_t *b, double now)
{
    /* all at once, each with its time: a member takes a character when its time has
     * come and wakes for it (sim_bus_next_time), so a late bus thread cannot let the
     * member's t3.5 expire before a character that ends earlier */
    (void)now;
    size_t k = b->mq_n;
    if (k > 0u) {
        uint8_t bytes[MQ_MAX], errs[MQ_MAX];
        double t[MQ_MAX];
        for (size_t i = 0; i < k; i++) {
            bytes[i] = b->mq[i].byte;
            errs[i] = b->mq[i].errors;
            t[i] = b->mq[i].t;
        }
        for (size_t m = 0; m < b->n; m++) {
            deliver(b, m, bytes, errs, t, k);
        }
        memmove(&b->mq[0], &b->mq[k], (b->mq_n - k) * sizeof b->mq[0]);
        b->mq_n -= k;
    }
    return b->mq_n > 0u ? b->mq[0].t : -1.0;
}
