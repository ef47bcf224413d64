/* SPDX-License-Identifier: Apache-2.0 */
/* The differential harness's requests (transcript.h): every function code of the
 * extended set and some that do not exist, addresses at and around the set's windows,
 * 32-bit ranges and scanner, quantities at and around the limits of [MB-APP] and the
 * manuals, byte counts that sometimes disagree with the quantity. */
#include "transcript.h"

#include <string.h>

#include "modcp/crc.h"

void drng_seed(drng_t *r, uint64_t seed, uint64_t input)
{
    r->s = seed * 0x9E3779B97F4A7C15ull + input * 0xD1B54A32D192ED03ull + 1u;
}

uint32_t drng_next(drng_t *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (uint32_t)((z ^ (z >> 31)) >> 32);
}

uint32_t drng_below(drng_t *r, uint32_t n)
{
    return drng_next(r) % n;
}

static size_t put16(uint8_t *o, uint32_t v)
{
    o[0] = (uint8_t)(v >> 8);
    o[1] = (uint8_t)v;
    return 2;
}

/* A window of the set (one that is on, when there is one). */
static const modcp_bitwin_t *pick_window(drng_t *r, const modcp_params_t *p, int coils)
{
    const modcp_bitwin_t *ws = coils ? p->coils : p->inputs;
    uint32_t n = coils ? MODCP_COIL_WINDOWS : MODCP_INPUT_WINDOWS;
    uint32_t k = drng_below(r, n);
    for (uint32_t tries = 0; tries < n && ws[k].area == MODCP_AREA_NONE; tries++) {
        k = (k + 1u) % n;
    }
    return &ws[k];
}

static uint16_t pick_bit_addr(drng_t *r, const modcp_params_t *p, int coils)
{
    const modcp_bitwin_t *w = pick_window(r, p, coils);
    switch (drng_below(r, 10)) {
    case 0: return w->from;
    case 1: return w->to;
    case 2: return (uint16_t)(w->to - drng_below(r, 80));
    case 3: return (uint16_t)(w->from - 1u);
    case 4: return (uint16_t)(w->to + 1u);
    case 5: return (uint16_t)drng_next(r);
    default: return (uint16_t)(w->from + drng_below(r, (uint32_t)(uint16_t)(w->to - w->from) + 1u));
    }
}

/* A holding register in a DB the write limits allow (DB hr_base_db + register / 512,
 * docs/mapping.md), when there is one. */
static uint16_t writable_reg(drng_t *r, const modcp_params_t *p)
{
    uint32_t db = p->lim_db.min > p->hr_base_db ? p->lim_db.min : p->hr_base_db;
    db += drng_below(r, 2);
    if (p->lim_db.max == 0u || db > p->lim_db.max || (db - p->hr_base_db) >= 128u) {
        return (uint16_t)drng_below(r, 512);
    }
    return (uint16_t)((db - p->hr_base_db) * 512u + drng_below(r, 512));
}

static uint16_t pick_reg(drng_t *r, const modcp_params_t *p)
{
    static const uint16_t edges[] = {0, 1, 100, 510, 511, 512, 1000, 32767, 65535, 65534};
    const modcp_r32range_t *g = &p->r32[drng_below(r, 3)];
    switch (drng_below(r, 11)) {
    case 0: return (uint16_t)(g->from + drng_below(r, 3) - 1u);
    case 1: return (uint16_t)(g->to - drng_below(r, 3) + 1u);
    case 2: return (uint16_t)(g->from + drng_below(r, 64));
#if MODCP_WITH_EXTENDED
    case 3: return (uint16_t)(p->scan_start + drng_below(r, 20) - 2u);
#endif
    case 4: return edges[drng_below(r, sizeof edges / sizeof edges[0])];
    case 5: return (uint16_t)drng_next(r);
    case 6: case 7: return writable_reg(r, p);
    default: return (uint16_t)drng_below(r, 600);
    }
}

static uint16_t pick_qty(drng_t *r)
{
    static const uint16_t q[] = {0,   1,   2,   3,   7,   8,    9,    16,   17,   100,  120, 121,
                                 122, 123, 124, 125, 126, 127,  128,  1968, 1969, 2000, 2001,
                                 2040, 2041, 65535};
    switch (drng_below(r, 4)) {
    case 0: return q[drng_below(r, sizeof q / sizeof q[0])];
    case 1: return (uint16_t)(1u + drng_below(r, 130));
    default: return (uint16_t)(1u + drng_below(r, 16));
    }
}

static size_t random_bytes(drng_t *r, uint8_t *o, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        o[k] = (uint8_t)drng_next(r);
    }
    return n;
}

/* FC15 / FC16 / FC23's write part: quantity, byte count (sometimes off by one), data. */
static size_t write_multi(drng_t *r, int bits, uint8_t *o)
{
    uint16_t qty = pick_qty(r);
    uint32_t bytes = bits ? (qty + 7u) / 8u : 2u * qty;
    if (bytes > 240u) {
        bytes = drng_below(r, 241);
    }
    size_t n = put16(o, qty);
    uint32_t count = bytes;
    if (drng_below(r, 12) == 0) {
        count = (uint8_t)(bytes + drng_below(r, 3) - 1u);
    }
    o[n++] = (uint8_t)count;
    return n + random_bytes(r, o + n, bytes);
}

static size_t fc08(drng_t *r, uint8_t *o)
{
    static const uint16_t subs[] = {0, 1, 2, 3, 4, 10, 11, 12, 13, 14, 15, 16, 17, 18, 20, 5, 21};
    uint16_t sub = drng_below(r, 8) == 0 ? (uint16_t)drng_next(r)
                                         : subs[drng_below(r, sizeof subs / sizeof subs[0])];
    static const uint16_t data[] = {0x0000, 0xFF00, 0x0A00, 0x0D00, 0x3A00, 0x4100, 0x1234};
    size_t n = put16(o, sub);
    n += put16(o + n, data[drng_below(r, sizeof data / sizeof data[0])]);
    if (drng_below(r, 10) == 0) {
        n += random_bytes(r, o + n, drng_below(r, 4));
    }
    return n;
}

static size_t fc43(drng_t *r, uint8_t *o)
{
    static const uint8_t objs[] = {0, 1, 2, 3, 4, 5, 6, 7, 0x80, 0x81, 0xFF};
    o[0] = drng_below(r, 10) == 0 ? (uint8_t)drng_next(r) : 0x0E;
    o[1] = (uint8_t)drng_below(r, 6);
    o[2] = drng_below(r, 5) == 0 ? (uint8_t)drng_next(r) : objs[drng_below(r, sizeof objs)];
    return 3;
}

/* The PDU's data after the function code. */
static size_t pdu_data(drng_t *r, const modcp_params_t *p, uint8_t fc, uint8_t *o)
{
    size_t n = 0;
    switch (fc) {
    case 1: case 2:
        n = put16(o, pick_bit_addr(r, p, fc == 1));
        return n + put16(o + n, pick_qty(r));
    case 3: case 4:
        n = put16(o, pick_reg(r, p));
        return n + put16(o + n, pick_qty(r));
    case 5:
        n = put16(o, pick_bit_addr(r, p, 1));
        return n + put16(o + n, drng_below(r, 8) == 0 ? drng_next(r) : 0xFF00u * drng_below(r, 2));
    case 6:
        n = put16(o, pick_reg(r, p));
        return n + put16(o + n, drng_next(r));
    case 15:
        n = put16(o, pick_bit_addr(r, p, 1));
        return n + write_multi(r, 1, o + n);
    case 16:
        n = put16(o, pick_reg(r, p));
        return n + write_multi(r, 0, o + n);
    case 8: return fc08(r, o);
    case 11: case 12: case 17: return random_bytes(r, o, drng_below(r, 8) == 0 ? 1u : 0u);
    case 22:
        n = put16(o, pick_reg(r, p));
        return n + random_bytes(r, o + n, 4);
    case 23:
        n = put16(o, pick_reg(r, p));
        n += put16(o + n, pick_qty(r));
        n += put16(o + n, pick_reg(r, p));
        return n + write_multi(r, 0, o + n);
    case 43: return fc43(r, o);
    default: return random_bytes(r, o, drng_below(r, 9));
    }
}

size_t diff_request(drng_t *r, const modcp_params_t *p, uint8_t *out, size_t cap)
{
    static const uint8_t fcs[] = {1, 1, 2, 3, 3, 4, 5, 6, 15, 16, 16, 8, 8, 11, 12,
                                  12, 17, 22, 23, 43, 1, 3, 16, 5, 6, 15, 2, 4, 12};
    uint32_t a = drng_below(r, 100);
    out[0] = a < 80u ? p->slave_addr : (a < 88u ? 0u : (uint8_t)drng_next(r));
    uint32_t k = drng_below(r, sizeof fcs + 2u);
    out[1] = k < sizeof fcs ? fcs[k] : (uint8_t)drng_next(r);
    uint8_t data[256];
    size_t n = pdu_data(r, p, out[1], data);
    n = n > cap - 2u ? cap - 2u : n;
    memcpy(out + 2, data, n);
    return n + 2u;
}

size_t diff_encode(const modcp_params_t *p, const uint8_t *adu, size_t n, uint8_t *out,
                   size_t cap)
{
    if (p->framing != MODCP_FRAMING_ASCII) {
        uint16_t crc = modcp_crc16(adu, n);
        memcpy(out, adu, n);
        out[n] = (uint8_t)crc;
        out[n + 1] = (uint8_t)(crc >> 8);
        return n + 2u;
    }
    static const char hx[] = "0123456789ABCDEF";
    size_t m = 0;
    out[m++] = ':';
    uint8_t lrc = modcp_lrc(adu, n);
    for (size_t k = 0; k <= n && m + 4u <= cap; k++) {
        uint8_t v = k < n ? adu[k] : lrc;
        out[m++] = (uint8_t)hx[v >> 4];
        out[m++] = (uint8_t)hx[v & 15u];
    }
    out[m++] = '\r';
    out[m++] = '\n';
    return m;
}

size_t diff_corrupt(drng_t *r, uint8_t *fr, size_t n, size_t cap)
{
    if (n < 2u || drng_below(r, 7) != 0) {
        return n;
    }
    size_t at = drng_below(r, (uint32_t)n);
    switch (drng_below(r, 4)) {
    case 0: fr[at] ^= (uint8_t)(1u << drng_below(r, 8)); return n;
    case 1: memmove(fr + at, fr + at + 1, n - at - 1u); return n - 1u;
    case 2:
        if (n < cap) {
            memmove(fr + at + 1, fr + at, n - at);
            fr[at] = (uint8_t)drng_next(r);
            return n + 1u;
        }
        return n;
    default: fr[n - 1u] = (uint8_t)(fr[n - 1u] + 1u); return n;
    }
}
