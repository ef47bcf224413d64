/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the parameter record's binary form, from the rows of params_fields.h.
 *
 * Little-endian, fixed widths, fields in the order of the rows:
 *   "MCPR" | u16 version | u16 payload length | payload | u16 CRC-16 (low byte first)
 * A group (windows, 32-bit ranges, limits, scanner entries) is encoded struct by
 * struct. ID strings occupy 16 bytes each (the characters up to the NUL, zero padded;
 * the decoder always terminates them). The payload length is the sum of the rows'
 * widths (308 bytes in version 2, record 318); decode accepts trailing bytes after the
 * record (it may sit in a padded block). The rows' columns (params.c's table) are checked
 * at compile time here too. */
#include <stdbool.h>
#include <string.h>

#include "modcp/crc.h"
#include "modcp/params.h"
#include "params_fields.h"

#define SZ_S(member, width, ...) +(unsigned)(width)
#define SZ_G(...)
#define SZ_M(type, member, width, count) +((unsigned)(width) * (unsigned)(count))
#define PAYLOAD_BYTES (0u MODCP_PARAM_ROWS(SZ_S, SZ_G, SZ_M))
#define HEADER_BYTES 8u /* magic, version, length */
#define CRC_BYTES 2u
#define RECORD_BYTES (HEADER_BYTES + PAYLOAD_BYTES + CRC_BYTES)

_Static_assert(RECORD_BYTES <= MODCP_PARAMS_RECORD_MAX, "parameter record too large");
_Static_assert(PAYLOAD_BYTES <= 0xFFFFu, "payload length must fit u16");

/* A group's structs lie in the record member after member (params_fields.h). */
#define FIRST_W(type) ((size_t)MODCP_PARAM_FIRST_WIDTH_##type)
#define OFF_IN(type, member) ((size_t)offsetof(type, member))
#define SLOT_OF(type) ((size_t)MODCP_PARAM_SLOT(MODCP_PARAM_FIRST_WIDTH_##type))
#define LAYOUT_G(member, count, type, members, field)                                           \
    _Static_assert((sizeof(type) == (SLOT_OF(type) + (2u * ((size_t)(members) - 1u)))) &&      \
                       ((size_t)MODCP_PARAM_OFF(member) <= MODCP_PARAM_ABSENT),                 \
                   #member ": members without a gap");
#define LAYOUT_M(type, member, width, count)                                                    \
    _Static_assert(((OFF_IN(type, member) == 0u) ||                                             \
                    (((OFF_IN(type, member) - SLOT_OF(type)) % 2u) == 0u)) &&                   \
                       ((size_t)(width) == ((OFF_IN(type, member) == 0u) ? FIRST_W(type) : 2u)), \
                   #type "." #member ": place");
/* A scalar row names a member of its width, aligned to it (params.c's param_get reads it
 * through a pointer of that width). */
#define LAYOUT_S(member, width, ...)                                                            \
    _Static_assert(((unsigned)(width) == MODCP_PW_STR) ||                                       \
                       ((MODCP_PARAM_SIZE(member) == (size_t)(width)) &&                        \
                        (((size_t)MODCP_PARAM_OFF(member) % (size_t)(width)) == 0u)),           \
                   #member ": a scalar of its row's width, aligned to it");
MODCP_PARAM_ROWS(LAYOUT_S, LAYOUT_G, LAYOUT_M)
_Static_assert(OFF_IN(modcp_params_t, lim_q) ==
                   (OFF_IN(modcp_params_t, lim_db) + (2u * sizeof(modcp_limit_t))),
               "lim_db, lim_m, lim_q are one group of three");

/* Every event of a row is a parameter event of class 0EH; the ranges and defaults of the
 * rows up to 16 bits fit the table (a 32-bit row, the baud rate, is checked by its own
 * rule); the issue index of a row is the one params.c's run_checks derives (row_index). */
#define CHECK_S(member, width, field, index, min, max, def, ev, flags, ...)                    \
    _Static_assert(((unsigned)(ev) >> 8u) == 0x0Eu, #member ": event class 0EH");            \
    _Static_assert((((unsigned)(width) > 2u) &&                                               \
                    (((uint8_t)(flags) & MODCP_PF_CUSTOM) != 0u)) ||                          \
                       (((unsigned)(max) <= 0xFFFFu) && ((unsigned)(min) <= 0xFFu)),          \
                   #member ": range fits the row");                                           \
    _Static_assert((MODCP_PARAM_CODE(def) <= 0xFFu) && (MODCP_PARAM_CODE(max) <= 0xFFu) &&    \
                       ((uint8_t)(flags) < 8u),                                               \
                   #member ": default and maximum");                                                      \
    _Static_assert((size_t)MODCP_PARAM_OFF(member) <= MODCP_PARAM_ABSENT, #member ": offset"); \
    _Static_assert((((unsigned)(field) != (unsigned)MODCP_PF_SCANNER) ||                     \
                    ((unsigned)(index) == 0xFFu)) &&                                           \
                       (((unsigned)(field) == (unsigned)MODCP_PF_SCANNER) ||                  \
                        ((unsigned)(field) == (unsigned)MODCP_PF_ID_STRING) ||                \
                        ((unsigned)(index) == 0u)),                                           \
                   #member ": index");
#define CHECK_G(member, count, type, members, field)                                          \
    _Static_assert((unsigned)(count) <= 0xFFu, #member ": the count fits a row's byte");
#define CHECK_M(...)
MODCP_PARAM_ROWS(CHECK_S, CHECK_G, CHECK_M)
#if MODCP_WITH_EXTENDED
#define CHECK_ID_S(member, width, field, index, ...)                                          \
    _Static_assert(((field) != MODCP_PF_ID_STRING) ||                                          \
                       ((size_t)(index) ==                                                      \
                        (((size_t)MODCP_PARAM_OFF(member) - (size_t)offsetof(modcp_params_t, vendor)) / \
                         ((size_t)MODCP_ID_STRING_MAX + 1u))),                                  \
                   #member ": index of an ID string");
MODCP_PARAM_ROWS(CHECK_ID_S, CHECK_G, CHECK_M)
_Static_assert(((size_t)offsetof(modcp_params_t, scan) < MODCP_PARAM_ABSENT) &&
                   ((size_t)offsetof(modcp_params_t, app_name) <
                    (size_t)offsetof(modcp_params_t, scan)),
               "the last row's member starts below MODCP_PARAM_ABSENT");
#endif

/* "MCPR", read and written as one little-endian word (no memcmp: in the manual's core the
 * record was its only caller) */
#define RECORD_MAGIC                                                                              \
    ((uint32_t)'M' | ((uint32_t)'C' << 8u) | ((uint32_t)'P' << 16u) | ((uint32_t)'R' << 24u))

/* encode: dst = the payload, src = the parameters; decode: the other way round */
typedef struct {
    uint8_t *dst;
    const uint8_t *src;
} codec_t;

/* On a little-endian machine (every target so far) a field's bytes are its record bytes;
 * with packed structs (modcp/params.h) a group's structs are too, each row is one run of
 * bytes in both (RECORD_AS_BYTES). */
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) &&                            \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
#define RECORD_LE 1
#else
#define RECORD_LE 0
#endif
#define RECORD_AS_BYTES (RECORD_LE && MODCP_PARAMS_PACKED_LAYOUT)

/* One field of width bytes (1, 2, 4, little-endian in the record; an ID string, str; with
 * RECORD_AS_BYTES a whole row): at its place in the payload (at) and in modcp_params_t (off). */
typedef void field_fn(const codec_t *c, size_t at, size_t off, size_t width, bool str);

/* The byte of a field in modcp_params_t that is its record byte i (of width). */
static size_t field_byte(size_t i, size_t width, bool str)
{
    return (RECORD_LE || str) ? i : (width - 1u - i);
}

static void enc_field(const codec_t *c, size_t at, size_t off, size_t width, bool str)
{
    uint8_t *r = &c->dst[at];
    const uint8_t *f = &c->src[off];
    bool end = false; /* an ID string: up to the NUL, zero padded */
    for (size_t i = 0u; i < width; i++) {
        const uint8_t b = f[field_byte(i, width, str)];
        end = end || (str && (b == 0u));
        r[i] = end ? 0u : b;
    }
}

static void dec_field(const codec_t *c, size_t at, size_t off, size_t width, bool str)
{
    const uint8_t *r = &c->src[at];
    uint8_t *f = &c->dst[off];
#if RECORD_LE
    (void)memcpy(f, r, width); /* the same bytes: one call, shared with the rest of the core */
#else
    for (size_t i = 0u; i < width; i++) {
        f[field_byte(i, width, str)] = r[i];
    }
#endif
    if (str) {
        f[MODCP_PW_STR] = 0u; /* terminated whatever the record holds */
    }
}

/* Every field in record order. A row this build does not keep (off MODCP_PARAM_ABSENT)
 * has only its place in the record (encode leaves the zeros there). A group's structs'
 * members lie one after the other as in the record (params_fields.h), 2 bytes wide except
 * a struct's first member, which may be one byte (in a 2-byte slot unless packed). */
static void walk(const codec_t *c, field_fn *fn)
{
    size_t at = 0u;
    for (uint8_t i = 0u; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        const bool str = MODCP_PARAM_WIDTH(r) == MODCP_PW_STR;
        uint8_t first = MODCP_PARAM_WIDTH(r);
        uint8_t members = 1u;
        size_t count = 1u;
        if (first == 0u) { /* a group: count structs */
            first = r->def;
            members = r->event;
            count = r->max;
        }
#if RECORD_AS_BYTES
        const size_t n = count * ((size_t)first + (2u * ((size_t)members - 1u)));
        if (r->off != MODCP_PARAM_ABSENT) {
            fn(c, at, r->off, n, str);
        }
        at += n;
#else
        size_t off = r->off;
        uint8_t j = 0u; /* the member of the struct */
        for (size_t k = 0u; k < (count * members); k++) {
            const uint8_t w = (j == 0u) ? first : 2u;
            j++;
            if (j == members) {
                j = 0u;
            }
            if (r->off != MODCP_PARAM_ABSENT) {
                /* unpacked: every member of a group in a 2-byte slot */
                fn(c, at, MODCP_PARAMS_PACKED_LAYOUT ? off : ((size_t)r->off + (2u * k)), w, str);
            }
            at += w;
            off += w;
        }
#endif
    }
}

static void put16(uint8_t *b, uint16_t v)
{
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)(v >> 8u);
}

static uint16_t get16(const uint8_t *b)
{
    return (uint16_t)((uint32_t)b[0] | ((uint32_t)b[1] << 8u));
}

static uint32_t get32(const uint8_t *b)
{
    return (uint32_t)get16(b) | ((uint32_t)get16(&b[2]) << 16u);
}

size_t modcp_params_encode(const modcp_params_t *p, uint8_t *buf, size_t cap)
{
    if ((buf == NULL) || (cap < RECORD_BYTES)) {
        return 0u;
    }
    (void)memset(buf, 0, RECORD_BYTES); /* the bytes of members this build does not keep */
    put16(buf, (uint16_t)RECORD_MAGIC);
    put16(&buf[2], (uint16_t)(RECORD_MAGIC >> 16u));
    put16(&buf[4], (uint16_t)MODCP_PARAMS_VERSION);
    put16(&buf[6], (uint16_t)PAYLOAD_BYTES);
    const codec_t c = {&buf[HEADER_BYTES], (const uint8_t *)p};
    walk(&c, enc_field);
    put16(&buf[HEADER_BYTES + PAYLOAD_BYTES], modcp_crc16(buf, HEADER_BYTES + PAYLOAD_BYTES));
    return RECORD_BYTES;
}

modcp_event_t modcp_params_decode(const uint8_t *buf, size_t len, modcp_params_t *p)
{
    if ((buf == NULL) || (p == NULL) || (len < RECORD_BYTES) || (get32(buf) != RECORD_MAGIC) ||
        (get16(&buf[4]) != MODCP_PARAMS_VERSION) || (get16(&buf[6]) != PAYLOAD_BYTES) ||
        (modcp_crc16(buf, HEADER_BYTES + PAYLOAD_BYTES) !=
         get16(&buf[HEADER_BYTES + PAYLOAD_BYTES]))) {
        return (modcp_event_t)MODCP_EV_PARAM_RECORD;
    }
    /* The record is sound: from here on nothing can fail, decode straight into p. */
    (void)memset(p, 0, sizeof *p);
    const codec_t c = {(uint8_t *)p, &buf[HEADER_BYTES]};
    walk(&c, dec_field);
    return (modcp_event_t)MODCP_EV_NONE;
}
