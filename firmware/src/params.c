/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the parameter record: defaults, validation, effective copy, binary form.
 *
 * Validation rules and the events they raise ([RTU-2003] §2, §3, §7.5; [ASCII-32] §3, §4.5, §8.6).
 * One issue per bad field (per window / range / scanner entry / ID string); for a
 * field with several problems only the first one found is reported.
 *
 *   data_bits      RTU: 8; ASCII: 7 or 8 (8: modcp extension, docs/parameters.md) (0E)20H fatal
 *   stop_bits      ASCII: not 1 with parity even/odd, not 2 with parity none ([ASCII-32]
 *                  §3.1 "with even or odd parity 1 stop bit is pre-defined; none
 *                  parity effects two stop bits": 7E1, 7O1, 7N2; the same for the
 *                  8-bit extension) ... (0E)2EH fatal (the manual gives no event)
 *   slave_addr     0 ................................................ (0E)23H fatal
 *   opmode         not 0/1; normal on RS485 (two-wire) while rs485_sel is 0
 *                  ([RTU-2009] Table 5-2: without "enable operating-mode selection for
 *                  RS485" two-wire RS485 runs in modem = interference suppression
 *                  mode only; event (0E)22H "selected operating mode not allowed")
 *                  .................................................. (0E)22H fatal
 *   f_mul          outside 1..10 ................. (0E)21H NOT fatal, runs with 1
 *   ascii_timeout  outside 1..6500 ms ............ (0E)21H NOT fatal, runs with 1000
 *                  ([ASCII-32] §8.6 prints this as the second parameter event, at the
 *                  position of 21H; checked whatever the framing, the value is
 *                  corrected in either case)
 *   lim_db/m/q     max != 0 && min > max; lim_db: max != 0 && min == 0 (0E)24H fatal
 *                  value = min << 16 | max
 *   coils[i]       area not M/Q/T/C/DB, from > to, DB window with db 0, T/C window
 *                  size (to-from+1) not a multiple of 16, last byte / element
 *                  beyond 65535 .................................... (0E)25H fatal
 *                  two enabled windows overlapping ................. (0E)27H fatal
 *   inputs[i]      as coils with areas M/I/DB ....... (0E)26H / (0E)28H fatal
 *   r32[k]         (only when regs32 != 0) from > to, db 0, range larger than one
 *                  DB (2 bytes per int16 register, 4 per int32/float register,
 *                  65536 bytes), two ranges overlapping, two ranges on the same DB
 *                  .................................................. (0E)2EH fatal
 *                  [ASCII-32] §8.6 lists these four errors between "overlap FC02" (28H)
 *                  and "error reading the parameter file" (2EH), but their event
 *                  numbers are illegible in the OCR. We do not invent numbers and
 *                  report them as (0E)2EH. An all-zero entry (from = to = db = 0)
 *                  is an unused range (modcp extension: fewer than three ranges).
 *   everything else that has no event of its own (0E)2EH fatal ("error reading the
 *                  parameter file"): baud not in the table, parity > 2, stop bits
 *                  not 1/2, framing > 1, eof_timing > 1, t15_check > 1, iface > 2,
 *                  turnaround > 100 ms, rs232_auto > 1 or with an interface other
 *                  than RS232, regs32 > 1, r32_lim_db > 1, fset > 1, rs485_sel > 1, cpu_model > 1,
 *                  job_limit not 0
 *                  and not 32..model limit, cpu_timeout 0, start_time 0, commloss
 *                  not 0 and not 100..30000, scanner count > 16 or first + count
 *                  beyond 65535 (index 0xFF), an enabled scanner entry (index <
 *                  scan_count, area != NONE) that is not a word operand (M, I, Q,
 *                  DB with db != 0 with byte offset <= 65534, T, C), an ID string
 *                  not NUL-terminated within 17 bytes (index 0 vendor, 1 product,
 *                  2 revision, 3 app_name), diag_irq > 1.
 *   a feature compiled out of this image (modcp/features.h) .... (0E)2EH fatal
 *                  framing ascii without MODCP_WITH_ASCII; rs232_auto on without
 *                  MODCP_WITH_RS232_SIGNALS; without MODCP_WITH_EXTENDED: fset
 *                  extended, commloss not 0, scan_count not 0 (index 0xFF). The
 *                  CP stays "not ready" with that reason, never half-working.
 *
 * Values of issues: the offending field value; for from/to problems of a window
 * from << 16 | to; for a bad area the area; for db 0 the db (0); for a T/C size
 * the size; for an extent the last byte / element; for an overlap (windows and
 * 32-bit ranges) the index of the earlier window / range it collides with; for
 * a 32-bit same-DB the DB number; for a scanner entry the area (db 0: the db,
 * offset: the offset); for the scanner start/count (index 0xFF) scan_count.
 *
 * The fields, their order in the record, widths, defaults, ranges, events and INI keys
 * are the rows of params_fields.h; this file expands them into modcp_param_rows[] and
 * adds the rules a range cannot say (marked MODCP_PF_CUSTOM there, and the groups:
 * windows, 32-bit ranges, limits, scanner entries). The binary record: params_record.c. */
#include "modcp/params.h"

#include <string.h>

#include "params_fields.h"
#include "params_internal.h"

/* ---- the rows ------------------------------------------------------------------ */

#define ROW_S(member, width, field, index, min, max, def, ev, flags, ...)                      \
    {(uint16_t)((max) > 0xFFFF ? 0xFFFF : (max)), (uint8_t)MODCP_PARAM_OFF(member),           \
     (uint8_t)((width) | ((flags) << 5)), (uint8_t)(field), MODCP_EVENT_NUMBER(ev),           \
     (uint8_t)((min) > 0xFF ? 0 : (min)), (uint8_t)MODCP_PARAM_DEF_CODE(def)},
#define ROW_G(member, count, type, members, field)                                           \
    {(uint16_t)(count), (uint8_t)MODCP_PARAM_OFF(member), 0u, (uint8_t)(field),              \
     (uint8_t)(members), (uint8_t)sizeof(type), (uint8_t)FIRST_WIDTH_##type},
#define ROW_M(...)

/* A group's structs (packed): 2-byte members one after the other, the first possibly 1 byte
 * (FIRST_WIDTH_<type>); test_params checks that the rows list the members in this order. */
#define FIRST_WIDTH_modcp_bitwin_t 1u
#define FIRST_WIDTH_modcp_r32range_t 2u
#define FIRST_WIDTH_modcp_limit_t 2u
#define FIRST_WIDTH_modcp_operand_ref_t 1u

const modcp_param_row_t modcp_param_rows[MODCP_PARAM_ROW_COUNT] = {
    MODCP_PARAM_ROWS(ROW_S, ROW_G, ROW_M)};

/* Every event of a row is a parameter event of class 0EH; the ranges and defaults of the
 * rows up to 16 bits fit the table (a 32-bit row, the baud rate, is checked by its own
 * rule); the issue index of a row is the one run_checks derives (row_index). */
#define CHECK_S(member, width, field, index, min, max, def, ev, flags, ...)                    \
    _Static_assert(MODCP_EVENT_CLASS(ev) == 0x0Eu, #member ": event class 0EH");             \
    _Static_assert(((width) > 2 && ((flags) & MODCP_PF_CUSTOM) != 0) ||                       \
                       ((max) <= 0xFFFF && (min) <= 0xFF),                                    \
                   #member ": range fits the row");                                           \
    _Static_assert(MODCP_PARAM_DEF_CODE(def) <= 0xFFu && (flags) < 8, #member ": default");   \
    _Static_assert(MODCP_PARAM_OFF(member) <= MODCP_PARAM_ABSENT, #member ": offset");        \
    _Static_assert((field) == MODCP_PF_SCANNER ? (index) == 0xFF                              \
                                               : (field) == MODCP_PF_ID_STRING || (index) == 0, \
                   #member ": index");
#define CHECK_G(member, count, type, members, field)                                         \
    _Static_assert(sizeof(type) == MODCP_PARAM_SLOT(FIRST_WIDTH_##type) + 2u * ((members) - 1u) && \
                       MODCP_PARAM_OFF(member) <= MODCP_PARAM_ABSENT,                         \
                   #member ": members without a gap");
#define CHECK_M(type, member, width, count)                                                  \
    _Static_assert((offsetof(type, member) == 0u ||                                           \
                    (offsetof(type, member) - MODCP_PARAM_SLOT(FIRST_WIDTH_##type)) % 2u == 0u) && \
                       (width) == (offsetof(type, member) == 0u ? FIRST_WIDTH_##type : 2u),   \
                   #type "." #member ": place");
MODCP_PARAM_ROWS(CHECK_S, CHECK_G, CHECK_M)
#if MODCP_WITH_EXTENDED
#define CHECK_ID_S(member, width, field, index, ...)                                          \
    _Static_assert((field) != MODCP_PF_ID_STRING ||                                            \
                       (index) == (MODCP_PARAM_OFF(member) - offsetof(modcp_params_t, vendor)) / \
                                      (MODCP_ID_STRING_MAX + 1u),                             \
                   #member ": index of an ID string");
#define CHECK_ID_G(...)
#define CHECK_ID_M(...)
MODCP_PARAM_ROWS(CHECK_ID_S, CHECK_ID_G, CHECK_ID_M)
_Static_assert(offsetof(modcp_params_t, scan) < MODCP_PARAM_ABSENT &&
                   offsetof(modcp_params_t, app_name) < offsetof(modcp_params_t, scan),
               "the last row's member starts below MODCP_PARAM_ABSENT");
#endif
_Static_assert(offsetof(modcp_params_t, lim_q) ==
                   offsetof(modcp_params_t, lim_db) + 2u * sizeof(modcp_limit_t),
               "lim_db, lim_m, lim_q are one group of three");

static const uint16_t big_defaults[] = {MODCP_PARAM_BIG_DEFAULTS};

static uint32_t row_def(const modcp_param_row_t *r)
{
    return r->def < 240u ? r->def : big_defaults[r->def - 240u];
}

static uint32_t param_get(const modcp_params_t *p, const modcp_param_row_t *r)
{
    const uint8_t *b = (const uint8_t *)p + r->off;
    if (MODCP_PARAM_WIDTH(r) == 1u) {
        return *b;
    }
    if (MODCP_PARAM_WIDTH(r) == 2u) {
        uint16_t v;
        memcpy(&v, b, sizeof v);
        return v;
    }
    uint32_t v;
    memcpy(&v, b, sizeof v);
    return v;
}

static void param_put(modcp_params_t *p, const modcp_param_row_t *r, uint32_t v)
{
    uint8_t *b = (uint8_t *)p + r->off;
    if (MODCP_PARAM_WIDTH(r) == 1u) {
        *b = (uint8_t)v;
    } else if (MODCP_PARAM_WIDTH(r) == 2u) {
        uint16_t x = (uint16_t)v;
        memcpy(b, &x, sizeof x);
    } else {
        memcpy(b, &v, sizeof v);
    }
}

/* The row's default into p (modcp_params_defaults, and a corrected field in apply). */
static void put_default(modcp_params_t *p, const modcp_param_row_t *r)
{
    param_put(p, r, row_def(r));
}

/* ---- defaults ----------------------------------------------------------------- */

/* An ID string's default into the zeroed member (a literal that fits, NUL included). */
#define SET_ID(dst, lit)                                                                          \
    do {                                                                                          \
        _Static_assert(sizeof(lit) <= MODCP_ID_STRING_MAX + 1u, "ID string default too long");    \
        memcpy((dst), (lit), sizeof(lit));                                                        \
    } while (0)

void modcp_params_defaults(modcp_params_t *p)
{
    /* everything not in a row is 0: no windows, no ranges, writes disabled */
    memset(p, 0, sizeof *p);
    for (uint8_t i = 0; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        uint8_t w = MODCP_PARAM_WIDTH(r);
        if (w != 0u && w != MODCP_PW_STR) {
            put_default(p, r);
        }
    }
#if MODCP_WITH_EXTENDED
    SET_ID(p->vendor, "modcp");
    SET_ID(p->product, "modcp-cp");
    /* revision empty: FC17 / FC43 report modcp's version (devid.c) */
#endif
}

/* ---- validation ----------------------------------------------------------------- */

/* Every function below has one caller and is inlined into it, and run_checks into
 * modcp_params_validate and modcp_params_apply: in apply's copy, the one the firmware
 * links, the sink has no issue array and the compiler drops what only the issues need
 * (their field, index and value), the tools' validate keeps it. */
#define CHECK_INLINE inline __attribute__((always_inline))

typedef struct {
    modcp_param_issue_t *out;
    size_t max;
    size_t n;
    modcp_event_t first_fatal;
    modcp_event_t first_warning;
} issue_sink_t;

/* field and index of an issue in one argument */
#define FI(field, index) ((uint16_t)(((unsigned)(field) << 8) | (uint8_t)(index)))

static CHECK_INLINE void add_issue(issue_sink_t *s, uint16_t fi, modcp_event_t ev, bool fatal,
                                   uint32_t value)
{
    if (s->out != NULL && s->n < s->max) {
        modcp_param_issue_t *it = &s->out[s->n];
        it->field = (uint8_t)(fi >> 8);
        it->index = (uint8_t)fi;
        it->event = ev;
        it->fatal = fatal;
        it->value = value;
    }
    s->n++;
    if (fatal) {
        if (s->first_fatal == MODCP_EV_NONE) {
            s->first_fatal = ev;
        }
    } else if (s->first_warning == MODCP_EV_NONE) {
        s->first_warning = ev;
    }
}

static CHECK_INLINE void add_fatal(issue_sink_t *s, uint16_t fi, modcp_event_t ev, uint32_t value)
{
    add_issue(s, fi, ev, true, value);
}

/* 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 76800 (300 x 2^k), 57600, 115200 */
static CHECK_INLINE bool baud_ok(uint32_t baud)
{
    uint32_t k = baud / 300u;
    return baud % 300u == 0u && ((k <= 256u && (k & (k - 1u)) == 0u) || k == 192u || k == 384u);
}

static uint16_t model_limit(uint8_t cpu_model)
{
    return cpu_model == MODCP_CPU_CP441 ? 450u : 1024u;
}

/* scan_count's range is its row (0 .. 16, 0 without the extended set); the entries must
 * also fit the register space. */
static CHECK_INLINE bool scan_count_ok(const modcp_params_t *p)
{
    return p->scan_count <= (MODCP_WITH_EXTENDED ? MODCP_SCANNER_MAX : 0u) &&
           (uint32_t)p->scan_start + (uint32_t)p->scan_count <= 0x10000u;
}

/* A 2-byte member of a group struct: at any address when packed, else 2-byte aligned. */
static CHECK_INLINE uint16_t get16(const uint8_t *b)
{
#if MODCP_PARAMS_PACKED_LAYOUT
    uint16_t v;
    memcpy(&v, b, sizeof v);
    return v;
#else
    return *(const uint16_t *)(const void *)b;
#endif
}

static CHECK_INLINE uint32_t pair(uint16_t hi, uint16_t lo)
{
    return ((uint32_t)hi << 16) | (uint32_t)lo;
}

/* The areas a bit window may map (bit n = modcp_area_t n). */
#define AREA_BIT(a) (1u << (unsigned)(a))
#define AREAS_COILS                                                                               \
    (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_Q) | AREA_BIT(MODCP_AREA_T) |                  \
     AREA_BIT(MODCP_AREA_C) | AREA_BIT(MODCP_AREA_DB))
#define AREAS_INPUTS (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_I) | AREA_BIT(MODCP_AREA_DB))

#define WIN_FROM offsetof(modcp_bitwin_t, from) /* 1 packed, 2 otherwise */
_Static_assert(offsetof(modcp_bitwin_t, area) == 0u && WIN_FROM == MODCP_PARAM_SLOT(1u) &&
                   offsetof(modcp_bitwin_t, to) == WIN_FROM + 2u &&
                   offsetof(modcp_bitwin_t, start) == WIN_FROM + 4u &&
                   offsetof(modcp_bitwin_t, db) == WIN_FROM + 6u,
               "area, from, to, start, db");
_Static_assert(offsetof(modcp_r32range_t, from) == 0u && offsetof(modcp_r32range_t, to) == 2u &&
                   offsetof(modcp_r32range_t, db) == 4u,
               "from, to, db");
_Static_assert(MODCP_EV_INPUT_FROMTO == MODCP_EV_COIL_FROMTO + 1 &&
                   MODCP_PF_INPUTS == MODCP_PF_COILS + 1 &&
                   MODCP_EV_COIL_OVERLAP == MODCP_EV_COIL_FROMTO + 2 &&
                   MODCP_EV_INPUT_OVERLAP == MODCP_EV_INPUT_FROMTO + 2,
               "the overlap event follows the from/to event by 2");

/* The bit windows (coils, inputs) and the 32-bit ranges (only when regs32 != 0): each
 * entry on its own, then every usable entry against the earlier usable ones. A 32-bit
 * range is checked as a DB window from byte 0 of 16 (int16) or 32 bits per register; it
 * is unused when from, to and db are all 0, and its extent is reported in bytes. An
 * overlap is reported once per entry, with the earlier entry's index as the value; two
 * 32-bit ranges on the same DB with that DB number. */
static CHECK_INLINE void check_ranges(issue_sink_t *s, const modcp_params_t *p,
                                      const modcp_param_row_t *r)
{
    const bool r32 = r->field == MODCP_PF_R32;
    const bool coils = r->field == MODCP_PF_COILS;
    const modcp_event_t ev = r32 ? MODCP_EV_PARAM_RECORD
                                 : (modcp_event_t)(MODCP_EV_COIL_FROMTO + (r->field - MODCP_PF_COILS));
    const unsigned areas = r32 ? AREA_BIT(MODCP_AREA_DB) : coils ? AREAS_COILS : AREAS_INPUTS;
    const uint8_t *base = (const uint8_t *)p + r->off;
    const size_t ft = r32 ? 0u : WIN_FROM; /* from, to, then start, db (window) or db (range) */
    const unsigned count = r->max;
    uint32_t ok = 0;
    if (r32 && p->regs32 == 0u) {
        return;
    }
    for (unsigned k = 0; k < count; k++) {
        const uint8_t *e = base + (size_t)k * r->min;
        const uint8_t *f = e + ft;
        const uint16_t from = get16(f);
        const uint16_t to = get16(f + 2);
        const uint16_t db = get16(f + (r32 ? 4 : 6));
        const uint8_t area = !r32                        ? e[0]
                             : (from | to | db) != 0u ? (uint8_t)MODCP_AREA_DB
                                                      : (uint8_t)MODCP_AREA_NONE;
        uint32_t bad;
        if (area == MODCP_AREA_NONE) {
            continue;
        }
        if (area > MODCP_AREA_DB || (areas & AREA_BIT(area)) == 0u) {
            bad = area;
        } else if (from > to) {
            bad = pair(from, to);
        } else if (area == MODCP_AREA_DB && db == 0u) {
            bad = db;
        } else {
            bool tc = area == MODCP_AREA_T || area == MODCP_AREA_C; /* 16 bits per element */
            uint32_t bits = (uint32_t)to - (uint32_t)from + 1u;
            if (r32) {
                bits <<= k == MODCP_R32_INT16 ? 4u : 5u;
            }
            uint32_t last = (r32 ? 0u : get16(f + 4)) + (tc ? bits / 16u - 1u : (bits - 1u) / 8u);
            if (tc && bits % 16u != 0u) {
                bad = bits;
            } else if (last > 0xFFFFu) {
                bad = last + (r32 ? 1u : 0u);
            } else {
                ok |= 1u << k;
                continue;
            }
        }
        add_fatal(s, FI(r->field, k), ev, bad);
    }
    for (unsigned j = 1; j < count; j++) {
        const uint8_t *b = base + (size_t)j * r->min + ft;
        if ((ok & (1u << j)) == 0u) {
            continue;
        }
        for (unsigned i = 0; i < j; i++) {
            const uint8_t *a = base + (size_t)i * r->min + ft;
            uint32_t bad;
            if ((ok & (1u << i)) == 0u) {
                continue;
            }
            if (get16(a) <= get16(b + 2) && get16(b) <= get16(a + 2)) {
                bad = i;
            } else if (r32 && get16(a + 4) == get16(b + 4)) {
                bad = get16(b + 4);
            } else {
                continue;
            }
            add_fatal(s, FI(r->field, j), r32 ? ev : (modcp_event_t)(ev + 2u), bad);
            break;
        }
    }
}

/* lim_db, lim_m, lim_q (one group of three): max 0 = not writable, any min is fine */
static CHECK_INLINE void check_limits(issue_sink_t *s, const modcp_params_t *p)
{
    for (unsigned k = 0; k < 3u; k++) {
        const modcp_limit_t *l = (const modcp_limit_t *)(const void *)((const uint8_t *)p +
            offsetof(modcp_params_t, lim_db) + k * sizeof(modcp_limit_t));
        if (l->max != 0u && (l->min > l->max || (k == 0u && l->min == 0u))) {
            add_fatal(s, FI(MODCP_PF_LIM_DB + k, 0u), MODCP_EV_WRITE_LIMITS, pair(l->min, l->max));
        }
    }
}
_Static_assert(offsetof(modcp_params_t, lim_m) ==
                   offsetof(modcp_params_t, lim_db) + sizeof(modcp_limit_t) &&
                   MODCP_PF_LIM_M == MODCP_PF_LIM_DB + 1 && MODCP_PF_LIM_Q == MODCP_PF_LIM_DB + 2,
               "lim_db, lim_m, lim_q in a row");

#if MODCP_WITH_EXTENDED
static CHECK_INLINE bool id_terminated(const char *str)
{
    for (size_t i = 0; i <= MODCP_ID_STRING_MAX; i++) {
        if (str[i] == '\0') {
            return true;
        }
    }
    return false;
}

/* The entries, when the count is usable (its own row reports it otherwise). */
static CHECK_INLINE void check_scanner(issue_sink_t *s, const modcp_params_t *p)
{
    if (!scan_count_ok(p)) {
        return;
    }
    for (uint8_t i = 0; i < p->scan_count; i++) {
        const modcp_operand_ref_t *e = &p->scan[i];
        uint32_t bad;
        if (e->area == MODCP_AREA_NONE || e->area == MODCP_AREA_T || e->area == MODCP_AREA_C) {
            continue; /* unused entry, or an element number */
        }
        if (e->area > MODCP_AREA_DB) {
            bad = e->area;
        } else if (e->area == MODCP_AREA_DB && e->db == 0u) {
            bad = e->db;
        } else if (e->offset > 0xFFFEu) { /* the word's second byte must exist */
            bad = e->offset;
        } else {
            continue;
        }
        add_fatal(s, FI(MODCP_PF_SCANNER, i), MODCP_EV_PARAM_RECORD, bad);
    }
}
#endif

/* The rules a row's range cannot say (MODCP_PF_CUSTOM); *v: the value to report. */
static CHECK_INLINE bool custom_ok(const modcp_params_t *p, const modcp_param_row_t *r,
                                   uint32_t *v)
{
    /* The ASCII character frame ([ASCII-32] §3.1) and the RS485 operating mode ([RTU-2009] Table 5-2);
     * tested before the switch, which then stays a compare chain (no jump table). */
    if (r->field == MODCP_PF_STOP_BITS) {
        return p->framing != MODCP_FRAMING_ASCII ||
               *v == (p->parity == MODCP_PARITY_NONE ? 2u : 1u);
    }
    if (r->field == MODCP_PF_OPMODE) {
        return *v != MODCP_OPMODE_NORMAL || p->iface != MODCP_IFACE_RS485 || p->rs485_sel != 0u;
    }
    switch (r->field) {
    case MODCP_PF_BAUD: return baud_ok(*v);
    case MODCP_PF_DATA_BITS: return p->framing == MODCP_FRAMING_ASCII || *v == 8u;
    case MODCP_PF_RS232_AUTO: return *v == 0u || p->iface == MODCP_IFACE_RS232;
    case MODCP_PF_RTS_ON_DELAY:
    case MODCP_PF_RTS_OFF_DELAY: return *v % 10u == 0u; /* [VIPA-341] §1.6: steps of 10 ms */
    case MODCP_PF_RX_PRESET: return *v != MODCP_RXP_BREAK || p->iface != MODCP_IFACE_RS485;
    case MODCP_PF_JOB_LIMIT: return *v <= model_limit(p->cpu_model);
    case MODCP_PF_SCANNER: return MODCP_PARAM_WIDTH(r) != 1u || scan_count_ok(p);
#if MODCP_WITH_EXTENDED
    case MODCP_PF_ID_STRING: {
        const char *str = (const char *)p + r->off;
        *v = (uint8_t)str[MODCP_ID_STRING_MAX];
        return id_terminated(str);
    }
#endif
    default: return true;
    }
}

/* The index of a row's issue: 0xFF for the scanner's start and count, the string's number
 * for an ID string (the rows' index column, checked at compile time above). */
static CHECK_INLINE uint8_t row_index(const modcp_param_row_t *r)
{
    if (r->field == MODCP_PF_SCANNER) {
        return 0xFFu;
    }
#if MODCP_WITH_EXTENDED
    if (r->field == MODCP_PF_ID_STRING) {
        return (uint8_t)((r->off - offsetof(modcp_params_t, vendor)) / (MODCP_ID_STRING_MAX + 1u));
    }
#endif
    return 0u;
}

static CHECK_INLINE void check_group(const modcp_params_t *p, issue_sink_t *s,
                                     const modcp_param_row_t *r)
{
    if (r->field == MODCP_PF_LIM_DB) {
        check_limits(s, p);
    } else if (r->field != MODCP_PF_SCANNER) {
        check_ranges(s, p, r);
    } else {
#if MODCP_WITH_EXTENDED
        check_scanner(s, p); /* without the extended set scan_count is 0 (its row) */
#endif
    }
}

/* Every row in record order; fix != NULL: a bad MODCP_PF_WARN field gets its default. */
static CHECK_INLINE void run_checks(const modcp_params_t *p, issue_sink_t *s, modcp_params_t *fix)
{
    for (uint8_t i = 0; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        uint8_t w = MODCP_PARAM_WIDTH(r);
        uint8_t flags = MODCP_PARAM_FLAGS(r);
        if (w == 0u) {
            check_group(p, s, r);
            continue;
        }
        uint32_t v = w == MODCP_PW_STR ? 0u : param_get(p, r);
        bool ok = w > 2u || (v >= r->min && v <= r->max) ||
                  ((flags & MODCP_PF_ZERO_OK) != 0u && v == 0u);
        if (ok && (flags & MODCP_PF_CUSTOM) != 0u) {
            ok = custom_ok(p, r, &v);
        }
        if (!ok) {
            bool warn = (flags & MODCP_PF_WARN) != 0u;
            add_issue(s, FI(r->field, row_index(r)), (modcp_event_t)(0x0E00u | r->event), !warn,
                      v);
            if (warn && fix != NULL) {
                put_default(fix, r);
            }
        }
    }
}

size_t modcp_params_validate(const modcp_params_t *p, modcp_param_issue_t *out, size_t max)
{
    issue_sink_t s = {out, max, 0u, MODCP_EV_NONE, MODCP_EV_NONE};
    run_checks(p, &s, NULL);
    return s.n;
}

modcp_event_t modcp_params_apply(const modcp_params_t *in, modcp_params_t *out,
                                 modcp_event_t *first_warning)
{
    issue_sink_t s = {NULL, 0u, 0u, MODCP_EV_NONE, MODCP_EV_NONE};
    if (out != in) {
        memcpy(out, in, sizeof *out);
    }
    run_checks(out, &s, out);
    if (first_warning != NULL) {
        *first_warning = s.first_warning;
    }
    return s.first_fatal;
}

uint16_t modcp_params_job_limit(const modcp_params_t *p)
{
    return p->job_limit != 0u ? p->job_limit : model_limit(p->cpu_model);
}
