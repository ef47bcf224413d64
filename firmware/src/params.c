/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the parameter record: the rows of params_fields.h as modcp_param_rows[], defaults,
 * validation, effective copy (the binary record: params_record.c).
 *
 * Validation ([RTU-2003] §2, §3, §7.5; [ASCII-32] §3, §4.5, §8.6) walks the rows of
 * params_fields.h in record order: a scalar row is checked against its range (min .. max,
 * 0 too with MODCP_PF_ZERO_OK), then, marked MODCP_PF_CUSTOM, against its further rule
 * (custom_ok: the baud table, RTU 8 data bits, the ASCII frame 7E1 / 7O1 / 7N2 on the stop
 * bits, normal mode on two-wire RS485 only with rs485_sel ([RTU-2009] Table 5-2), rs232_auto
 * on RS232 only, RTS delays in steps of 10 ms, receive preset break not on RS485, the job
 * limit of the CPU model, the scanner's start + count, ID strings terminated). A group row
 * has its own function: the bit windows and 32-bit ranges (check_ranges: area, from <= to,
 * DB not 0, whole T/C elements, extent, then overlaps and, for the 32-bit ranges, the same
 * DB twice), the write limits (check_limits), the scanner entries (check_scanner).
 *
 * Each bad field (window, range, limit, scanner entry, ID string) is one issue: its field,
 * index, the row's event (class 0EH), fatal or not, the rule it breaks (modcp_param_rule_t,
 * whose comments say what the value is) and the offending value; a field with several
 * problems reports the first one found. Not fatal are only f_mul and ascii_timeout
 * (MODCP_PF_WARN, (0E)21H): the effective copy runs with their defaults. The 32-bit range
 * errors, whose event numbers are illegible in [ASCII-32] §8.6, and every field without an
 * event of its own are (0E)2EH; so is a feature compiled out of this image
 * (modcp/features.h: framing ascii, rs232_auto on, fset extended, commloss, scanner): the
 * rows' ranges end at 0 there, and the CP stays "not ready", never half-working. */
#include "modcp/params.h"

#include <string.h>

#include "params_fields.h"
#include "params_internal.h"

/* ---- the rows ------------------------------------------------------------------ */

#define ROW_S(member, ...) MODCP_PARAM_IF_PRESENT(member, ROW_NONE, ROW_S_)(member, __VA_ARGS__)
#define ROW_NONE(...)
#define ROW_S_(member, width, field, index, min, max, def, ev, flags, ...)                     \
    {(uint8_t)MODCP_PARAM_OFF(member),                                                          \
     (uint8_t)((unsigned)(width) | ((unsigned)(uint8_t)(flags) << 5u)),                         \
     (uint8_t)(field), (uint8_t)((unsigned)(ev) & 0xFFu),                                       \
     (uint8_t)(((unsigned)(min) > 0xFFu) ? 0u : (unsigned)(min)),                               \
     (uint8_t)MODCP_PARAM_CODE(max), (uint8_t)MODCP_PARAM_CODE(def)},
#define ROW_G(member, ...) MODCP_PARAM_IF_PRESENT(member, ROW_SKIP, ROW_G_)(member, __VA_ARGS__)
#define ROW_G_(member, count, type, members, field)                                          \
    {(uint8_t)MODCP_PARAM_OFF(member), 0u, (uint8_t)(field), (uint8_t)(members),             \
     (uint8_t)sizeof(type), (uint8_t)(count), (uint8_t)MODCP_PARAM_FIRST_WIDTH_##type},
/* the run of absent members (params_fields.h): one field of MODCP_PARAM_ABSENT_BYTES */
#define ROW_SKIP(member, count, type, members, field)                                        \
    {MODCP_PARAM_ABSENT, 0u, (uint8_t)(field), 1u, 0u, 1u, (uint8_t)ABSENT_BYTES},
enum { ABSENT_BYTES = MODCP_PARAM_ABSENT_BYTES }; /* (not expandable inside the rows) */
_Static_assert(ABSENT_BYTES <= 0xFFu, "the absent run fits a row's width");
#define ROW_M(...)

const modcp_param_row_t modcp_param_rows[MODCP_PARAM_ROW_COUNT] = {
    MODCP_PARAM_ROWS(ROW_S, ROW_G, ROW_M)};

static const uint16_t big_values[] = {MODCP_PARAM_BIG};

/* A row's max or def column (MODCP_PARAM_CODE). */
static uint32_t row_value(uint8_t code)
{
    return (code < 240u) ? (uint32_t)code : (uint32_t)big_values[code - 240u];
}

/* A scalar row's value (width 1, 2 or 4) and its store; a scalar member has its row's
 * width and is aligned to it (asserted in params_record.c). */
static uint32_t param_get(const modcp_params_t *p, const modcp_param_row_t *r)
{
    const void *b = (const uint8_t *)p + r->off;
    uint32_t v = *(const uint8_t *)b;
    if (MODCP_PARAM_WIDTH(r) == 2u) {
        v = *(const uint16_t *)b;
    } else if (MODCP_PARAM_WIDTH(r) == 4u) {
        v = *(const uint32_t *)b;
    } else {
        /* one byte */
    }
    return v;
}

static void param_put(modcp_params_t *p, const modcp_param_row_t *r, uint32_t v)
{
    void *b = (uint8_t *)p + r->off;
    if (MODCP_PARAM_WIDTH(r) == 1u) {
        *(uint8_t *)b = (uint8_t)v;
    } else if (MODCP_PARAM_WIDTH(r) == 2u) {
        *(uint16_t *)b = (uint16_t)v;
    } else {
        *(uint32_t *)b = v;
    }
}

/* The row's default into p (modcp_params_defaults, and a corrected field in apply). */
static void put_default(modcp_params_t *p, const modcp_param_row_t *r)
{
    param_put(p, r, row_value(r->def));
}

/* ---- defaults ----------------------------------------------------------------- */

/* An ID string's default into the zeroed member (a literal that fits, NUL included). */
#define SET_ID(dst, lit)                                                                          \
    do {                                                                                          \
        _Static_assert(sizeof(lit) <= ((size_t)MODCP_ID_STRING_MAX + 1u), "ID string too long"); \
        (void)memcpy((dst), (lit), sizeof(lit));                                                  \
    } while (false)

void modcp_params_defaults(modcp_params_t *p)
{
    /* everything not in a row is 0: no windows, no ranges, writes disabled */
    (void)memset(p, 0, sizeof *p);
    for (uint8_t i = 0u; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        const uint8_t w = MODCP_PARAM_WIDTH(r);
        if ((w != 0u) && (w != MODCP_PW_STR)) {
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

/* Every function below is inlined into run_checks and run_checks into modcp_params_validate
 * and modcp_params_apply: in apply's copy, the one the firmware links, the sink has no issue
 * array and the compiler drops what only the issues need (field, index, rule, value). Without
 * it params.c's code in the firmware (Cortex-M3 -Os, validate not linked) grows from 1,316 to
 * 1,614 bytes (manual set), from 1,576 to 1,928 (every feature). */
#define CHECK_INLINE inline __attribute__((always_inline))

typedef struct {
    modcp_param_issue_t *out;
    size_t max;
    size_t n;
    modcp_event_t first_fatal;
    modcp_event_t first_warning;
} issue_sink_t;

#define EV_NONE ((modcp_event_t)MODCP_EV_NONE)
#define NO_OTHER 0xFFu /* modcp_param_issue_t.other when no other entry is involved */

/* One issue: into out while there is room, counted always; the first fatal event and the
 * first warning are what modcp_params_apply returns. */
static CHECK_INLINE void report(issue_sink_t *s, const modcp_param_issue_t *is)
{
    if ((s->out != NULL) && (s->n < s->max)) {
        s->out[s->n] = *is;
    }
    s->n++;
    if (is->fatal) {
        if (s->first_fatal == EV_NONE) {
            s->first_fatal = is->event;
        }
    } else if (s->first_warning == EV_NONE) {
        s->first_warning = is->event;
    } else {
        /* an earlier warning stands */
    }
}

/* A fatal issue of entry index of field (a window, range, limit or scanner entry). */
static CHECK_INLINE void report_fatal(issue_sink_t *s, uint8_t field, uint8_t index,
                                      modcp_event_t ev, uint8_t rule, uint32_t value,
                                      uint8_t other)
{
    const modcp_param_issue_t is = {field, index, ev, true, rule, other, value};
    report(s, &is);
}

/* 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 76800 (300 x 2^k), 57600, 115200 */
static CHECK_INLINE bool baud_ok(uint32_t baud)
{
    const uint32_t k = baud / 300u;
    return ((baud % 300u) == 0u) && (k != 0u) &&
           (((k <= 256u) && ((k & (k - 1u)) == 0u)) || (k == 192u) || (k == 384u));
}

static CHECK_INLINE uint16_t model_limit(uint8_t cpu_model)
{
    return (cpu_model == (uint8_t)MODCP_CPU_CP441) ? 450u : 1024u;
}

/* scan_count's range is its row (0 .. 16, 0 without the extended set); the entries must
 * also fit the register space. */
static CHECK_INLINE bool scan_count_ok(const modcp_params_t *p)
{
    return (p->scan_count <= (MODCP_WITH_EXTENDED ? (uint8_t)MODCP_SCANNER_MAX : 0u)) &&
           (((uint32_t)p->scan_start + (uint32_t)p->scan_count) <= 0x10000u);
}

/* ---- windows and 32-bit ranges ---- */

/* A bit window, or a 32-bit range seen as a DB window from byte 0 (area DB; NONE when
 * from, to and db are all 0: an unused range). */
typedef struct {
    uint8_t area;
    uint16_t from;
    uint16_t to;
    uint16_t start;
    uint16_t db;
} span_t;

/* Entry k of the group row r (coils, inputs: a window; r32: a range). */
static CHECK_INLINE void span_get(const modcp_params_t *p, const modcp_param_row_t *r, unsigned k,
                                  span_t *sp)
{
    const void *e = (const uint8_t *)p + r->off + ((size_t)k * r->min);
    if (r->field == (uint8_t)MODCP_PF_R32) {
        const modcp_r32range_t *g = (const modcp_r32range_t *)e;
        sp->area = (((unsigned)g->from | g->to | g->db) != 0u) ? (uint8_t)MODCP_AREA_DB
                                                                : (uint8_t)MODCP_AREA_NONE;
        sp->from = g->from;
        sp->to = g->to;
        sp->start = 0u;
        sp->db = g->db;
    } else {
        const modcp_bitwin_t *w = (const modcp_bitwin_t *)e;
        sp->area = w->area;
        sp->from = w->from;
        sp->to = w->to;
        sp->start = w->start;
        sp->db = w->db;
    }
}

/* The areas a bit window may map (bit n = modcp_area_t n). */
#define AREA_BIT(a) (1u << (unsigned)(a))
#define AREAS_COILS                                                                               \
    (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_Q) | AREA_BIT(MODCP_AREA_T) |                  \
     AREA_BIT(MODCP_AREA_C) | AREA_BIT(MODCP_AREA_DB))
#define AREAS_INPUTS (AREA_BIT(MODCP_AREA_M) | AREA_BIT(MODCP_AREA_I) | AREA_BIT(MODCP_AREA_DB))

/* The rule an entry in use breaks (MODCP_PR_NONE: none); *value: what its issue reports.
 * shift: 0 for a bit window; a 32-bit range of 16 (int16) or 32 bits per register is 4 or
 * 5, and its extent is reported in bytes. */
static CHECK_INLINE uint8_t span_rule(const span_t *sp, unsigned areas, uint8_t shift,
                                      uint32_t *value)
{
    uint8_t rule = (uint8_t)MODCP_PR_NONE;
    if ((sp->area > (uint8_t)MODCP_AREA_DB) || ((areas & AREA_BIT(sp->area)) == 0u)) {
        rule = (uint8_t)MODCP_PR_AREA;
        *value = sp->area;
    } else if (sp->from > sp->to) {
        rule = (uint8_t)MODCP_PR_FROM_TO;
        *value = ((uint32_t)sp->from << 16u) | sp->to;
    } else if ((sp->area == (uint8_t)MODCP_AREA_DB) && (sp->db == 0u)) {
        rule = (uint8_t)MODCP_PR_DB_ZERO;
        *value = sp->db;
    } else {
        /* 16 bits per T / C element, 8 per byte */
        const bool tc = (sp->area == (uint8_t)MODCP_AREA_T) || (sp->area == (uint8_t)MODCP_AREA_C);
        const uint32_t bits = (((uint32_t)sp->to - (uint32_t)sp->from) + 1u) << shift;
        const uint32_t last = (uint32_t)sp->start + (tc ? ((bits / 16u) - 1u) : ((bits - 1u) / 8u));
        if (tc && ((bits % 16u) != 0u)) {
            rule = (uint8_t)MODCP_PR_TC_SIZE;
            *value = bits;
        } else if (last > 0xFFFFu) {
            rule = (uint8_t)MODCP_PR_EXTENT;
            *value = (shift != 0u) ? (last + 1u) : last;
        } else {
            /* a usable entry */
        }
    }
    return rule;
}

_Static_assert(((unsigned)MODCP_EV_INPUT_FROMTO == ((unsigned)MODCP_EV_COIL_FROMTO + 1u)) &&
                   ((unsigned)MODCP_PF_INPUTS == ((unsigned)MODCP_PF_COILS + 1u)) &&
                   ((unsigned)MODCP_EV_COIL_OVERLAP == ((unsigned)MODCP_EV_COIL_FROMTO + 2u)) &&
                   ((unsigned)MODCP_EV_INPUT_OVERLAP == ((unsigned)MODCP_EV_INPUT_FROMTO + 2u)),
               "the overlap event follows the from/to event by 2");

typedef struct { /* the usable entries of a group (bit k of ok), as check_ranges read them */
    uint32_t ok;
    uint16_t from[MODCP_COIL_WINDOWS];
    uint16_t to[MODCP_COIL_WINDOWS];
    uint16_t db[MODCP_COIL_WINDOWS];
} spans_t;
_Static_assert((MODCP_INPUT_WINDOWS <= MODCP_COIL_WINDOWS) && (3 <= MODCP_COIL_WINDOWS),
               "spans_t holds every group of windows or ranges");

/* Every usable entry against the earlier usable ones: an overlap is reported once per
 * entry, with the earlier entry's index as the value; two 32-bit ranges on the same DB
 * with that DB number. ev: the group's overlap event. */
static CHECK_INLINE void check_overlaps(issue_sink_t *s, const modcp_param_row_t *r,
                                        const spans_t *u, modcp_event_t ev)
{
    const bool r32 = r->field == (uint8_t)MODCP_PF_R32;
    for (unsigned j = 1u; j < r->max; j++) {
        for (unsigned i = 0u; (((u->ok >> j) & 1u) != 0u) && (i < j); i++) {
            uint8_t rule = (uint8_t)MODCP_PR_NONE;
            uint32_t value = i;
            if (((u->ok >> i) & 1u) == 0u) {
                /* not usable: reported on its own */
            } else if ((u->from[i] <= u->to[j]) && (u->from[j] <= u->to[i])) {
                rule = (uint8_t)MODCP_PR_OVERLAP;
            } else if (r32 && (u->db[i] == u->db[j])) {
                rule = (uint8_t)MODCP_PR_SAME_DB;
                value = u->db[j];
            } else {
                /* disjoint */
            }
            if (rule != (uint8_t)MODCP_PR_NONE) {
                report_fatal(s, r->field, (uint8_t)j, ev, rule, value, (uint8_t)i);
                break;
            }
        }
    }
}

/* The bit windows (coils, inputs) and the 32-bit ranges (only when regs32 != 0): each
 * entry in use on its own (span_rule), then against the earlier ones (check_overlaps). */
static CHECK_INLINE void check_ranges(issue_sink_t *s, const modcp_params_t *p,
                                      const modcp_param_row_t *r)
{
    const bool r32 = r->field == (uint8_t)MODCP_PF_R32;
    const bool coils = r->field == (uint8_t)MODCP_PF_COILS;
    const modcp_event_t ev =
        r32 ? (modcp_event_t)MODCP_EV_PARAM_RECORD
            : (modcp_event_t)((uint32_t)MODCP_EV_COIL_FROMTO +
                              ((uint32_t)r->field - (uint32_t)MODCP_PF_COILS));
    const unsigned areas = r32 ? AREA_BIT(MODCP_AREA_DB) : (coils ? AREAS_COILS : AREAS_INPUTS);
    spans_t u;
    u.ok = 0u;
    if (!r32 || (p->regs32 != 0u)) {
        for (unsigned k = 0u; k < r->max; k++) {
            span_t sp;
            uint32_t value = 0u;
            span_get(p, r, k, &sp);
            uint8_t shift = 0u; /* a bit window */
            if (r32) {
                shift = (k == (unsigned)MODCP_R32_INT16) ? 4u : 5u;
            }
            const uint8_t rule = (sp.area == (uint8_t)MODCP_AREA_NONE)
                                     ? (uint8_t)MODCP_PR_NONE
                                     : span_rule(&sp, areas, shift, &value);
            if (rule != (uint8_t)MODCP_PR_NONE) {
                report_fatal(s, r->field, (uint8_t)k, ev, rule, value, NO_OTHER);
            } else if (sp.area != (uint8_t)MODCP_AREA_NONE) {
                u.ok |= (uint32_t)1u << k;
                u.from[k] = sp.from;
                u.to[k] = sp.to;
                u.db[k] = sp.db;
            } else {
                /* unused */
            }
        }
        check_overlaps(s, r, &u, r32 ? ev : (modcp_event_t)(ev + 2u));
    }
}

/* lim_db, lim_m, lim_q: max 0 = not writable, any min is fine; the DB limit's min >= 1 */
static CHECK_INLINE void check_limits(issue_sink_t *s, const modcp_params_t *p)
{
    for (uint8_t k = 0u; k < 3u; k++) {
        const void *at = (const uint8_t *)p + (size_t)offsetof(modcp_params_t, lim_db) +
                         ((size_t)k * sizeof(modcp_limit_t));
        const modcp_limit_t *l = (const modcp_limit_t *)at;
        uint8_t rule = (uint8_t)MODCP_PR_NONE;
        if (l->max == 0u) {
            /* not writable: any min */
        } else if (l->min > l->max) {
            rule = (uint8_t)MODCP_PR_FROM_TO;
        } else if ((k == 0u) && (l->min == 0u)) {
            rule = (uint8_t)MODCP_PR_DB_ZERO;
        } else {
            /* a range */
        }
        if (rule != (uint8_t)MODCP_PR_NONE) {
            report_fatal(s, (uint8_t)((uint8_t)MODCP_PF_LIM_DB + k), 0u,
                         (modcp_event_t)MODCP_EV_WRITE_LIMITS, rule,
                         ((uint32_t)l->min << 16u) | l->max, NO_OTHER);
        }
    }
}
_Static_assert(((unsigned)MODCP_PF_LIM_M == ((unsigned)MODCP_PF_LIM_DB + 1u)) &&
                   ((unsigned)MODCP_PF_LIM_Q == ((unsigned)MODCP_PF_LIM_DB + 2u)),
               "lim_db, lim_m, lim_q in a row");

#if MODCP_WITH_EXTENDED
static CHECK_INLINE bool id_terminated(const char *str)
{
    for (size_t i = 0u; i <= (size_t)MODCP_ID_STRING_MAX; i++) {
        if (str[i] == '\0') {
            return true;
        }
    }
    return false;
}

/* The entries in use (area not NONE) up to scan_count, when the count is usable (its own
 * row reports it otherwise): a word operand, T and C by element number. */
static CHECK_INLINE void check_scanner(issue_sink_t *s, const modcp_params_t *p)
{
    if (!scan_count_ok(p)) {
        return;
    }
    for (unsigned i = 0u; i < p->scan_count; i++) {
        const modcp_operand_ref_t *e = &p->scan[i];
        uint8_t rule = (uint8_t)MODCP_PR_NONE;
        uint32_t value = 0u;
        if ((e->area == (uint8_t)MODCP_AREA_NONE) || (e->area == (uint8_t)MODCP_AREA_T) ||
            (e->area == (uint8_t)MODCP_AREA_C)) {
            /* unused, or an element number */
        } else if (e->area > (uint8_t)MODCP_AREA_DB) {
            rule = (uint8_t)MODCP_PR_AREA;
            value = e->area;
        } else if ((e->area == (uint8_t)MODCP_AREA_DB) && (e->db == 0u)) {
            rule = (uint8_t)MODCP_PR_DB_ZERO;
            value = e->db;
        } else if (e->offset > 0xFFFEu) { /* the word's second byte must exist */
            rule = (uint8_t)MODCP_PR_EXTENT;
            value = e->offset;
        } else {
            /* a word operand */
        }
        if (rule != (uint8_t)MODCP_PR_NONE) {
            report_fatal(s, (uint8_t)MODCP_PF_SCANNER, (uint8_t)i,
                         (modcp_event_t)MODCP_EV_PARAM_RECORD, rule, value, NO_OTHER);
        }
    }
}
#endif

/* ---- one row ---- */

/* The rules a row's range cannot say (MODCP_PF_CUSTOM); *v: the value to report. The ASCII
 * character frame ([ASCII-32] §3.1) and the RS485 operating mode ([RTU-2009] Table 5-2) are
 * tested before the switch, which then stays a compare chain (no jump table). */
static CHECK_INLINE bool custom_ok(const modcp_params_t *p, const modcp_param_row_t *r,
                                   uint32_t *v)
{
    bool ok = true;
    if (r->field == (uint8_t)MODCP_PF_STOP_BITS) {
        ok = (p->framing != (uint8_t)MODCP_FRAMING_ASCII) ||
             (*v == ((p->parity == (uint8_t)MODCP_PARITY_NONE) ? 2u : 1u));
    } else if (r->field == (uint8_t)MODCP_PF_OPMODE) {
        ok = (*v != (uint32_t)MODCP_OPMODE_NORMAL) || (p->iface != (uint8_t)MODCP_IFACE_RS485) ||
             (p->rs485_sel != 0u);
    } else {
        switch (r->field) {
        case (uint8_t)MODCP_PF_BAUD: ok = baud_ok(*v); break;
        case (uint8_t)MODCP_PF_DATA_BITS:
            ok = (p->framing == (uint8_t)MODCP_FRAMING_ASCII) || (*v == 8u);
            break;
#if MODCP_WITH_RS232_SIGNALS /* (without them the row's range is 0 .. 0: nothing to add) */
        case (uint8_t)MODCP_PF_RS232_AUTO:
            ok = (*v == 0u) || (p->iface == (uint8_t)MODCP_IFACE_RS232);
            break;
#endif
        case (uint8_t)MODCP_PF_RTS_ON_DELAY: /* [VIPA-341] §1.6: steps of 10 ms */
        case (uint8_t)MODCP_PF_RTS_OFF_DELAY: ok = (*v % 10u) == 0u; break;
        case (uint8_t)MODCP_PF_RX_PRESET:
            ok = (*v != (uint32_t)MODCP_RXP_BREAK) || (p->iface != (uint8_t)MODCP_IFACE_RS485);
            break;
        case (uint8_t)MODCP_PF_JOB_LIMIT: ok = *v <= model_limit(p->cpu_model); break;
        case (uint8_t)MODCP_PF_SCANNER:
            ok = (MODCP_PARAM_WIDTH(r) != 1u) || scan_count_ok(p);
            break;
#if MODCP_WITH_EXTENDED
        case (uint8_t)MODCP_PF_ID_STRING: {
            const char *str = (const char *)p + r->off;
            *v = (uint8_t)str[MODCP_ID_STRING_MAX];
            ok = id_terminated(str);
            break;
        }
#endif
        default: break;
        }
    }
    return ok;
}

/* The index of a row's issue: 0xFF for the scanner's start and count, the string's number
 * for an ID string (the rows' index column, checked at compile time above). */
static CHECK_INLINE uint8_t row_index(const modcp_param_row_t *r)
{
    uint8_t index = 0u;
    if (r->field == (uint8_t)MODCP_PF_SCANNER) {
        index = 0xFFu;
    }
#if MODCP_WITH_EXTENDED
    if (r->field == (uint8_t)MODCP_PF_ID_STRING) {
        index = (uint8_t)(((size_t)r->off - (size_t)offsetof(modcp_params_t, vendor)) /
                          ((size_t)MODCP_ID_STRING_MAX + 1u));
    }
#endif
    return index;
}

static CHECK_INLINE void check_group(issue_sink_t *s, const modcp_params_t *p,
                                     const modcp_param_row_t *r)
{
    if (r->field == (uint8_t)MODCP_PF_LIM_DB) {
        check_limits(s, p);
    } else if (r->field != (uint8_t)MODCP_PF_SCANNER) {
        check_ranges(s, p, r);
    } else {
#if MODCP_WITH_EXTENDED
        check_scanner(s, p); /* without the extended set scan_count is 0 (its row) */
#endif
    }
}

/* A scalar row (or an ID string): its range, then its further rule. fix != NULL: a bad
 * MODCP_PF_WARN field gets its default there. */
static CHECK_INLINE void check_row(issue_sink_t *s, const modcp_params_t *p,
                                   const modcp_param_row_t *r, modcp_params_t *fix)
{
    const uint8_t w = MODCP_PARAM_WIDTH(r);
    const uint8_t flags = MODCP_PARAM_FLAGS(r);
    uint32_t v = (w == MODCP_PW_STR) ? 0u : param_get(p, r);
    uint8_t rule = (uint8_t)MODCP_PR_NONE;
    if ((w <= 2u) && ((v < r->min) || (v > row_value(r->max))) &&
        (((flags & MODCP_PF_ZERO_OK) == 0u) || (v != 0u))) {
        rule = (uint8_t)MODCP_PR_RANGE;
    } else if (((flags & MODCP_PF_CUSTOM) != 0u) && !custom_ok(p, r, &v)) {
        rule = (uint8_t)MODCP_PR_RULE;
    } else {
        /* legal */
    }
    if (rule != (uint8_t)MODCP_PR_NONE) {
        const bool warn = (flags & MODCP_PF_WARN) != 0u;
        const modcp_param_issue_t is = {r->field, row_index(r),
                                        (modcp_event_t)(0x0E00u | (uint32_t)r->event), !warn,
                                        rule, NO_OTHER, v};
        report(s, &is);
        if (warn && (fix != NULL)) {
            put_default(fix, r);
        }
    }
}

/* Every row in record order. */
static CHECK_INLINE void run_checks(const modcp_params_t *p, issue_sink_t *s, modcp_params_t *fix)
{
    for (uint8_t i = 0u; i < MODCP_PARAM_ROW_COUNT; i++) {
        const modcp_param_row_t *r = &modcp_param_rows[i];
        if (MODCP_PARAM_WIDTH(r) == 0u) {
            check_group(s, p, r);
        } else {
            check_row(s, p, r, fix);
        }
    }
}

size_t modcp_params_validate(const modcp_params_t *p, modcp_param_issue_t *out, size_t max)
{
    issue_sink_t s = {out, max, 0u, EV_NONE, EV_NONE};
    run_checks(p, &s, NULL);
    return s.n;
}

modcp_event_t modcp_params_apply(const modcp_params_t *in, modcp_params_t *out,
                                 modcp_event_t *first_warning)
{
    issue_sink_t s = {NULL, 0u, 0u, EV_NONE, EV_NONE};
    if (out != in) {
        (void)memcpy(out, in, sizeof *out);
    }
    run_checks(out, &s, out);
    if (first_warning != NULL) {
        *first_warning = s.first_warning;
    }
    return s.first_fatal;
}

uint16_t modcp_params_job_limit(const modcp_params_t *p)
{
    return (p->job_limit != 0u) ? p->job_limit : model_limit(p->cpu_model);
}
