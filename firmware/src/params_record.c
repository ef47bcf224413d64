/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the parameter record's binary form, from the rows of params_fields.h.
 *
 * Little-endian, fixed widths, fields in the order of the rows:
 *   "MCPR" | u16 version | u16 payload length | payload | u16 CRC-16 (low byte first)
 * A group (windows, 32-bit ranges, limits, scanner entries) is encoded struct by
 * struct. ID strings occupy 16 bytes each (the characters up to the NUL, zero padded;
 * the decoder always terminates them). The payload length is the sum of the rows'
 * widths (308 bytes in version 2, record 318); decode accepts trailing bytes after the
 * record (it may sit in a padded block). */
#include <stdbool.h>
#include <string.h>

#include "modcp/crc.h"
#include "modcp/params.h"
#include "params_fields.h"

#define SZ_S(member, width, ...) +(width)
#define SZ_G(...)
#define SZ_M(type, member, width, count) +(width) * (count)
#define PAYLOAD_BYTES (0u MODCP_PARAM_ROWS(SZ_S, SZ_G, SZ_M))
#define HEADER_BYTES 8u /* magic, version, length */
#define CRC_BYTES 2u
#define RECORD_BYTES (HEADER_BYTES + PAYLOAD_BYTES + CRC_BYTES)

_Static_assert(RECORD_BYTES <= MODCP_PARAMS_RECORD_MAX, "parameter record too large");
_Static_assert(PAYLOAD_BYTES <= 0xFFFFu, "payload length must fit u16");

/* A group's structs lie in the record member after member (params_fields.h). */
#define FIRST_W(type) MODCP_PARAM_FIRST_WIDTH_##type
#define LAYOUT_G(member, count, type, members, field)                                           \
    _Static_assert((sizeof(type) == (MODCP_PARAM_SLOT(FIRST_W(type)) + (2u * ((members) - 1u)))) && \
                       (MODCP_PARAM_OFF(member) <= MODCP_PARAM_ABSENT),                         \
                   #member ": members without a gap");
#define LAYOUT_M(type, member, width, count)                                                    \
    _Static_assert(((offsetof(type, member) == 0u) ||                                           \
                    (((offsetof(type, member) - MODCP_PARAM_SLOT(FIRST_W(type))) % 2u) == 0u)) && \
                       ((width) == ((offsetof(type, member) == 0u) ? FIRST_W(type) : 2u)),     \
                   #type "." #member ": place");
#define LAYOUT_S(...)
MODCP_PARAM_ROWS(LAYOUT_S, LAYOUT_G, LAYOUT_M)
_Static_assert(offsetof(modcp_params_t, lim_q) ==
                   offsetof(modcp_params_t, lim_db) + 2u * sizeof(modcp_limit_t),
               "lim_db, lim_m, lim_q are one group of three");

/* "MCPR", read and written as one little-endian word (no memcmp: in the manual's core the
 * record was its only caller) */
#define RECORD_MAGIC                                                                              \
    ((uint32_t)'M' | (uint32_t)'C' << 8 | (uint32_t)'P' << 16 | (uint32_t)'R' << 24)

/* encode: dst = the payload, src = the parameters; decode: the other way round */
typedef struct {
    uint8_t *dst;
    const uint8_t *src;
} codec_t;

/* One field of width 1, 2, 4 (little-endian) or MODCP_PW_STR: at its place in the
 * payload (at) and in modcp_params_t (off). */
typedef void field_fn(const codec_t *c, size_t at, size_t off, uint8_t width);

/* On a little-endian machine (every target so far) a field's bytes are its record bytes. */
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) &&                            \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define RECORD_LE 1
#else
#define RECORD_LE 0
#endif

static void enc_field(const codec_t *c, size_t at, size_t off, uint8_t width)
{
    uint8_t *r = c->dst + at;
    const uint8_t *f = c->src + off;
    if (width == MODCP_PW_STR) { /* up to the NUL, zero padded */
        bool end = false;
        for (size_t i = 0; i < MODCP_PW_STR; i++) {
            end = end || f[i] == 0u;
            r[i] = end ? 0u : f[i];
        }
        return;
    }
#if RECORD_LE
    memcpy(r, f, width);
#else
    uint32_t v = width == 1u ? *f : 0u;
    if (width == 2u) {
        uint16_t x;
        memcpy(&x, f, sizeof x);
        v = x;
    } else if (width == 4u) {
        memcpy(&v, f, sizeof v);
    }
    for (uint8_t i = 0; i < width; i++) {
        r[i] = (uint8_t)(v >> (8u * i));
    }
#endif
}

static void dec_field(const codec_t *c, size_t at, size_t off, uint8_t width)
{
    const uint8_t *r = c->src + at;
    uint8_t *f = c->dst + off;
#if RECORD_LE
    memcpy(f, r, width);
    if (width == MODCP_PW_STR) {
        f[MODCP_PW_STR] = 0u;
    }
#else
    if (width == MODCP_PW_STR) {
        memcpy(f, r, MODCP_PW_STR);
        f[MODCP_PW_STR] = 0u;
        return;
    }
    uint32_t v = 0;
    for (uint8_t i = 0; i < width; i++) {
        v |= (uint32_t)r[i] << (8u * i);
    }
    if (width == 1u) {
        *f = (uint8_t)v;
    } else if (width == 2u) {
        uint16_t x = (uint16_t)v;
        memcpy(f, &x, sizeof x);
    } else {
        memcpy(f, &v, sizeof v);
    }
#endif
}

/* Every field in record order. A row this build does not keep (off MODCP_PARAM_ABSENT)
 * has only its place in the record (encode leaves the zeros there). A group's structs'
 * members lie one after the other as in the record (params_fields.h), 2 bytes wide except
 * a struct's first member, which may be one byte (in a 2-byte slot unless packed). */
static void walk(const codec_t *c, field_fn *fn)
{
    size_t at = 0;
    for (uint8_t i = 0; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        uint8_t first = MODCP_PARAM_WIDTH(r);
        uint8_t members = 1;
        size_t fields = 1;
        size_t off = r->off;
        if (first == 0u) { /* a group: count structs */
            first = r->def;
            members = r->event;
            fields = (size_t)r->max * members;
        }
        for (size_t k = 0, j = 0; k < fields; k++) {
            uint8_t w = j == 0u ? first : 2u;
            if (++j == members) {
                j = 0;
            }
            if (r->off != MODCP_PARAM_ABSENT) {
                /* unpacked: every member of a group in a 2-byte slot */
                fn(c, at, MODCP_PARAMS_PACKED_LAYOUT ? off : r->off + 2u * k, w);
            }
            at += w;
            off += w;
        }
    }
}

static void put16(uint8_t *b, uint16_t v)
{
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)(v >> 8);
}

static uint16_t get16(const uint8_t *b)
{
    return (uint16_t)(b[0] | (uint16_t)(b[1] << 8));
}

static uint32_t get32(const uint8_t *b)
{
    return (uint32_t)get16(b) | (uint32_t)get16(b + 2) << 16;
}

size_t modcp_params_encode(const modcp_params_t *p, uint8_t *buf, size_t cap)
{
    if (buf == NULL || cap < RECORD_BYTES) {
        return 0u;
    }
    memset(buf, 0, RECORD_BYTES); /* the bytes of members this build does not keep */
    put16(buf, (uint16_t)RECORD_MAGIC);
    put16(buf + 2, (uint16_t)(RECORD_MAGIC >> 16));
    put16(buf + 4, (uint16_t)MODCP_PARAMS_VERSION);
    put16(buf + 6, (uint16_t)PAYLOAD_BYTES);
    codec_t c = {buf + HEADER_BYTES, (const uint8_t *)p};
    walk(&c, enc_field);
    put16(buf + HEADER_BYTES + PAYLOAD_BYTES, modcp_crc16(buf, HEADER_BYTES + PAYLOAD_BYTES));
    return RECORD_BYTES;
}

modcp_event_t modcp_params_decode(const uint8_t *buf, size_t len, modcp_params_t *p)
{
    if (buf == NULL || p == NULL || len < RECORD_BYTES ||
        get32(buf) != RECORD_MAGIC ||
        get16(buf + 4) != MODCP_PARAMS_VERSION || get16(buf + 6) != PAYLOAD_BYTES ||
        modcp_crc16(buf, HEADER_BYTES + PAYLOAD_BYTES) !=
            get16(buf + HEADER_BYTES + PAYLOAD_BYTES)) {
        return MODCP_EV_PARAM_RECORD;
    }
    /* The record is sound: from here on nothing can fail, decode straight into p. */
    memset(p, 0, sizeof *p);
    codec_t c = {(uint8_t *)p, buf + HEADER_BYTES};
    walk(&c, dec_field);
    return MODCP_EV_NONE;
}
