/* modcp — the parameter record: defaults, validation, effective copy, binary form.
 *
 * Validation rules and the events they raise (004 §2, §3, §7.5; 003 §3, §4.5, §8.6).
 * One issue per bad field (per window / range / scanner entry / ID string); for a
 * field with several problems only the first one found is reported.
 *
 *   data_bits      RTU: 8; ASCII: 7 or 8 (8: modcp extension, SPEC §2) (0E)20H fatal
 *   stop_bits      ASCII: not 1 with parity even/odd, not 2 with parity none (003
 *                  §3.1 "with even or odd parity 1 stop bit is pre-defined; none
 *                  parity effects two stop bits": 7E1, 7O1, 7N2; the same for the
 *                  8-bit extension) ... (0E)2EH fatal (the manual gives no event)
 *   slave_addr     0 ................................................ (0E)23H fatal
 *   opmode         not 0/1; normal on RS485 (two-wire) while rs485_sel is 0
 *                  (000 Table 5-2: without "enable operating-mode selection for
 *                  RS485" two-wire RS485 runs in modem = interference suppression
 *                  mode only; event (0E)22H "selected operating mode not allowed")
 *                  .................................................. (0E)22H fatal
 *   f_mul          outside 1..10 ................. (0E)21H NOT fatal, runs with 1
 *   ascii_timeout  outside 1..6500 ms ............ (0E)21H NOT fatal, runs with 1000
 *                  (003 §8.6 prints this as the second parameter event, at the
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
 *                  003 §8.6 lists these four errors between "overlap FC02" (28H)
 *                  and "error reading the parameter file" (2EH), but their event
 *                  numbers are illegible in the OCR. We do not invent numbers and
 *                  report them as (0E)2EH. An all-zero entry (from = to = db = 0)
 *                  is an unused range (modcp extension: fewer than three ranges).
 *   everything else that has no event of its own (0E)2EH fatal ("error reading the
 *                  parameter file"): baud not in the table, parity > 2, stop bits
 *                  not 1/2, framing > 1, eof_timing > 1, t15_check > 1, iface > 2,
 *                  turnaround > 100 ms, rs232_auto > 1 or with an interface other
 *                  than RS232, regs32 > 1, fset > 1, rs485_sel > 1, cpu_model > 1, job_limit not 0
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
    {(uint16_t)MODCP_PARAM_OFF(member), (uint16_t)((min) > 0xFFFF ? 0 : (min)),               \
     (uint16_t)((max) > 0xFFFF ? 0xFFFF : (max)), (uint16_t)(def), (uint8_t)(field),          \
     MODCP_EVENT_NUMBER(ev), (uint8_t)((width) | ((flags) << 5)), (uint8_t)(index)},
#define ROW_G(member, count, type, members, field)                                           \
    {(uint16_t)MODCP_PARAM_OFF(member), (uint16_t)sizeof(type), 0u, 0u,                     \
     (uint8_t)(field), (uint8_t)(members), 0u, (uint8_t)(count)},
#define ROW_M(...)
#define MEMBER_S(...)
#define MEMBER_G(...)
#define MEMBER_M(type, member, width, count) {(uint8_t)offsetof(type, member), (uint8_t)(width)},

const modcp_param_row_t modcp_param_rows[] = {MODCP_PARAM_ROWS(ROW_S, ROW_G, ROW_M)};
const uint8_t modcp_param_row_count = (uint8_t)(sizeof modcp_param_rows / sizeof modcp_param_rows[0]);
const modcp_param_member_t modcp_param_members[] = {MODCP_PARAM_ROWS(MEMBER_S, MEMBER_G, MEMBER_M)};

/* every event of a row is a parameter event of class 0EH; ranges and defaults of rows up to
 * 16 bits fit the table's u16 (a 32-bit row, the baud rate, is checked by its own rule) */
#define EV_CLASS_S(member, width, field, index, min, max, def, ev, flags, ...)                 \
    _Static_assert(MODCP_EVENT_CLASS(ev) == 0x0Eu, #member ": event class 0EH");             \
    _Static_assert(((width) > 2 && ((flags) & MODCP_PF_CUSTOM) != 0) || (max) <= 0xFFFF,      \
                   #member ": range fits u16");                                               \
    _Static_assert((def) <= 0xFFFF && (flags) < 8, #member ": default fits u16");
#define EV_CLASS_G(...)
#define EV_CLASS_M(...)
MODCP_PARAM_ROWS(EV_CLASS_S, EV_CLASS_G, EV_CLASS_M)
_Static_assert(offsetof(modcp_params_t, lim_q) ==
                   offsetof(modcp_params_t, lim_db) + 2u * sizeof(modcp_limit_t),
               "lim_db, lim_m, lim_q are one group of three");

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

/* ---- defaults ----------------------------------------------------------------- */

#if MODCP_WITH_EXTENDED
static void set_id(char *dst, const char *src)
{
    size_t n = strlen(src);
    memset(dst, 0, MODCP_ID_STRING_MAX + 1u);
    memcpy(dst, src, n <= MODCP_ID_STRING_MAX ? n : MODCP_ID_STRING_MAX);
}
#endif

void modcp_params_defaults(modcp_params_t *p)
{
    /* everything not in a row is 0: no windows, no ranges, writes disabled */
    memset(p, 0, sizeof *p);
    for (uint8_t i = 0; i < modcp_param_row_count; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        uint8_t w = MODCP_PARAM_WIDTH(r);
        if (w != 0u && w != MODCP_PW_STR) {
            param_put(p, r, r->def);
        }
    }
#if MODCP_WITH_EXTENDED
    set_id(p->vendor, "modcp");
    set_id(p->product, "modcp-cp");
    set_id(p->revision, "0.1");
#endif
}

/* ---- validation ----------------------------------------------------------------- */

typedef struct {
    modcp_param_issue_t *out;
    size_t max;
    size_t n;
    modcp_event_t first_fatal;
    modcp_event_t first_warning;
} issue_sink_t;

/* field and index of an issue in one argument (fewer arguments at every call) */
#define FI(field, index) ((uint16_t)(((unsigned)(field) << 8) | (uint8_t)(index)))

static void add_issue(issue_sink_t *s, uint16_t fi, modcp_event_t ev, bool fatal, uint32_t value)
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

static void add_fatal(issue_sink_t *s, uint16_t fi, modcp_event_t ev, uint32_t value)
{
    add_issue(s, fi, ev, true, value);
}

/* 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 76800 (300 x 2^k), 57600, 115200 */
static bool baud_ok(uint32_t baud)
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
static bool scan_count_ok(const modcp_params_t *p)
{
    return p->scan_count <= (MODCP_WITH_EXTENDED ? MODCP_SCANNER_MAX : 0u) &&
           (uint32_t)p->scan_start + (uint32_t)p->scan_count <= 0x10000u;
}

static uint32_t pair(uint16_t hi, uint16_t lo)
{
    return ((uint32_t)hi << 16) | (uint32_t)lo;
}

/* The areas a bit window may map (bit n = modcp_area_t n). */
#define AREA_BIT(a) (1u << (unsigned)(a))
#define AREAS_COILS                                                                               \
    (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_Q) | AREA_BIT(MODCP_AREA_T) |                  \
     AREA_BIT(MODCP_AREA_C) | AREA_BIT(MODCP_AREA_DB))
#define AREAS_INPUTS (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_I) | AREA_BIT(MODCP_AREA_DB))

/* Checks one bit window on its own; returns true when it is usable for the
 * overlap check (enabled and without a problem of its own). */
static bool check_window(issue_sink_t *s, uint16_t fi, modcp_event_t ev, const modcp_bitwin_t *w,
                         unsigned areas)
{
    uint32_t bad;
    if (w->area == MODCP_AREA_NONE) {
        return false;
    }
    if (w->area > MODCP_AREA_DB || (areas & AREA_BIT(w->area)) == 0u) {
        bad = w->area;
    } else if (w->from > w->to) {
        bad = pair(w->from, w->to);
    } else if (w->area == MODCP_AREA_DB && w->db == 0u) {
        bad = w->db;
    } else {
        uint32_t bits = (uint32_t)w->to - (uint32_t)w->from + 1u;
        bool tc = w->area == MODCP_AREA_T || w->area == MODCP_AREA_C; /* 16 bits per element */
        uint32_t last = (uint32_t)w->start + (tc ? bits / 16u - 1u : (bits - 1u) / 8u);
        if (tc && bits % 16u != 0u) {
            bad = bits;
        } else if (last > 0xFFFFu) {
            bad = last;
        } else {
            return true;
        }
    }
    add_fatal(s, fi, ev, bad);
    return false;
}

/* The usable entries (bit k of ok) of count structs, stride bytes apart, whose from and
 * to are the u16 at f[0], f[1] and (same_db) the DB number at f[2]: an entry overlapping
 * an earlier one is reported once, with the earlier one's index as the value; with
 * same_db, one on the same DB as an earlier one with that DB number. */
static void check_overlaps(issue_sink_t *s, uint8_t field, modcp_event_t ev, const uint8_t *base,
                           uint8_t stride, uint8_t count, uint32_t ok, bool same_db)
{
    for (uint8_t j = 1; j < count; j++) {
        const uint16_t *b = (const uint16_t *)(const void *)(base + (size_t)j * stride);
        if ((ok & (1u << j)) == 0u) {
            continue;
        }
        for (uint8_t i = 0; i < j; i++) {
            const uint16_t *a = (const uint16_t *)(const void *)(base + (size_t)i * stride);
            uint32_t bad;
            if ((ok & (1u << i)) == 0u) {
                continue;
            }
            if (a[0] <= b[1] && b[0] <= a[1]) {
                bad = i;
            } else if (same_db && a[2] == b[2]) {
                bad = b[2];
            } else {
                continue;
            }
            add_fatal(s, FI(field, j), ev, bad);
            break;
        }
    }
}
_Static_assert(offsetof(modcp_bitwin_t, to) == offsetof(modcp_bitwin_t, from) + 2u, "from, to");
_Static_assert(offsetof(modcp_r32range_t, from) == 0u && offsetof(modcp_r32range_t, to) == 2u &&
                   offsetof(modcp_r32range_t, db) == 4u,
               "from, to, db");
_Static_assert(MODCP_EV_COIL_OVERLAP == MODCP_EV_COIL_FROMTO + 2 &&
                   MODCP_EV_INPUT_OVERLAP == MODCP_EV_INPUT_FROMTO + 2,
               "the overlap event follows the from/to event by 2");

static void check_windows(issue_sink_t *s, const modcp_bitwin_t *w, uint8_t count, uint8_t field,
                          modcp_event_t ev, unsigned areas)
{
    uint32_t ok = 0;
    for (uint8_t i = 0; i < count; i++) {
        if (check_window(s, FI(field, i), ev, &w[i], areas)) {
            ok |= 1u << i;
        }
    }
    check_overlaps(s, field, (modcp_event_t)(ev + 2u), (const uint8_t *)&w->from,
                   (uint8_t)sizeof *w, count, ok, false);
}

static void check_r32(issue_sink_t *s, const modcp_params_t *p)
{
    uint32_t ok = 0;
    for (uint8_t k = 0; k < 3u; k++) {
        const modcp_r32range_t *r = &p->r32[k];
        uint32_t bad;
        if (r->from == 0u && r->to == 0u && r->db == 0u) {
            continue; /* unused */
        }
        if (r->from > r->to) {
            bad = pair(r->from, r->to);
        } else if (r->db == 0u) {
            bad = 0u;
        } else {
            bad = ((uint32_t)r->to - (uint32_t)r->from + 1u) * (k == MODCP_R32_INT16 ? 2u : 4u);
            if (bad <= 65536u) { /* bytes: one DB */
                ok |= 1u << k;
                continue;
            }
        }
        add_fatal(s, FI(MODCP_PF_R32, k), MODCP_EV_PARAM_RECORD, bad);
    }
    check_overlaps(s, MODCP_PF_R32, MODCP_EV_PARAM_RECORD, (const uint8_t *)p->r32,
                   (uint8_t)sizeof p->r32[0], 3u, ok, true);
}

/* lim_db, lim_m, lim_q (one group of three): max 0 = not writable, any min is fine */
static void check_limits(issue_sink_t *s, const modcp_params_t *p)
{
    for (uint8_t k = 0; k < 3u; k++) {
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
static bool id_terminated(const char *str)
{
    for (size_t i = 0; i <= MODCP_ID_STRING_MAX; i++) {
        if (str[i] == '\0') {
            return true;
        }
    }
    return false;
}

/* The entries, when the count is usable (its own row reports it otherwise). */
static void check_scanner(issue_sink_t *s, const modcp_params_t *p)
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
static bool custom_ok(const modcp_params_t *p, const modcp_param_row_t *r, uint32_t *v)
{
    /* The ASCII character frame (003 §3.1) and the RS485 operating mode (000 Table 5-2);
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

static void check_group(const modcp_params_t *p, issue_sink_t *s, uint8_t field)
{
    switch (field) {
    case MODCP_PF_COILS:
        check_windows(s, p->coils, MODCP_COIL_WINDOWS, MODCP_PF_COILS, MODCP_EV_COIL_FROMTO,
                      AREAS_COILS);
        break;
    case MODCP_PF_INPUTS:
        check_windows(s, p->inputs, MODCP_INPUT_WINDOWS, MODCP_PF_INPUTS, MODCP_EV_INPUT_FROMTO,
                      AREAS_INPUTS);
        break;
    case MODCP_PF_R32:
        if (p->regs32 != 0u) {
            check_r32(s, p);
        }
        break;
    case MODCP_PF_LIM_DB: check_limits(s, p); break;
    default:
#if MODCP_WITH_EXTENDED
        check_scanner(s, p); /* without the extended set scan_count is 0 (its row) */
#endif
        break;
    }
}

/* Every row in record order; fix != NULL: a bad MODCP_PF_WARN field gets its default. */
static void run_checks(const modcp_params_t *p, issue_sink_t *s, modcp_params_t *fix)
{
    for (uint8_t i = 0; i < modcp_param_row_count; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        uint8_t w = MODCP_PARAM_WIDTH(r);
        uint8_t flags = MODCP_PARAM_FLAGS(r);
        if (w == 0u) {
            check_group(p, s, r->field);
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
            add_issue(s, FI(r->field, r->index), (modcp_event_t)(0x0E00u | r->event), !warn, v);
            if (warn && fix != NULL) {
                param_put(fix, r, r->def);
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
