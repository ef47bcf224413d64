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

static void add_issue(issue_sink_t *s, modcp_param_field_t field, uint8_t index,
                      modcp_event_t ev, bool fatal, uint32_t value)
{
    if (s->out != NULL && s->n < s->max) {
        modcp_param_issue_t *it = &s->out[s->n];
        it->field = (uint8_t)field;
        it->index = index;
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

static void add_fatal(issue_sink_t *s, modcp_param_field_t field, uint8_t index,
                      modcp_event_t ev, uint32_t value)
{
    add_issue(s, field, index, ev, true, value);
}

static bool baud_ok(uint32_t baud)
{
    static const uint32_t rates[] = {300u,   600u,   1200u,  2400u,  4800u,  9600u,
                                     19200u, 38400u, 57600u, 76800u, 115200u};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; i++) {
        if (rates[i] == baud) {
            return true;
        }
    }
    return false;
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

static bool is_tc(uint8_t area)
{
    return area == MODCP_AREA_T || area == MODCP_AREA_C;
}

static uint32_t pair(uint16_t hi, uint16_t lo)
{
    return ((uint32_t)hi << 16) | (uint32_t)lo;
}

/* Checks one bit window on its own; returns true when it is usable for the
 * overlap check (enabled and without a problem of its own). */
static bool check_window(issue_sink_t *s, modcp_param_field_t field, uint8_t idx,
                         const modcp_bitwin_t *w, bool coils, modcp_event_t ev)
{
    bool area_ok;
    if (w->area == MODCP_AREA_NONE) {
        return false;
    }
    if (coils) {
        area_ok = w->area == MODCP_AREA_M || w->area == MODCP_AREA_Q ||
                  w->area == MODCP_AREA_T || w->area == MODCP_AREA_C ||
                  w->area == MODCP_AREA_DB;
    } else {
        area_ok = w->area == MODCP_AREA_M || w->area == MODCP_AREA_I ||
                  w->area == MODCP_AREA_DB;
    }
    if (!area_ok) {
        add_fatal(s, field, idx, ev, w->area);
        return false;
    }
    if (w->from > w->to) {
        add_fatal(s, field, idx, ev, pair(w->from, w->to));
        return false;
    }
    if (w->area == MODCP_AREA_DB && w->db == 0u) {
        add_fatal(s, field, idx, ev, w->db);
        return false;
    }
    uint32_t bits = (uint32_t)w->to - (uint32_t)w->from + 1u;
    uint32_t last;
    if (is_tc(w->area)) {
        if (bits % 16u != 0u) {
            add_fatal(s, field, idx, ev, bits);
            return false;
        }
        last = (uint32_t)w->start + bits / 16u - 1u;
    } else {
        last = (uint32_t)w->start + (bits - 1u) / 8u;
    }
    if (last > 0xFFFFu) {
        add_fatal(s, field, idx, ev, last);
        return false;
    }
    return true;
}

static void check_windows(issue_sink_t *s, const modcp_bitwin_t *w, size_t count, bool coils)
{
    modcp_param_field_t field = coils ? MODCP_PF_COILS : MODCP_PF_INPUTS;
    modcp_event_t ev_bad = coils ? MODCP_EV_COIL_FROMTO : MODCP_EV_INPUT_FROMTO;
    modcp_event_t ev_ovl = coils ? MODCP_EV_COIL_OVERLAP : MODCP_EV_INPUT_OVERLAP;
    bool ok[MODCP_COIL_WINDOWS];
    for (size_t i = 0; i < count; i++) {
        ok[i] = check_window(s, field, (uint8_t)i, &w[i], coils, ev_bad);
    }
    for (size_t j = 1; j < count; j++) {
        if (!ok[j]) {
            continue;
        }
        for (size_t i = 0; i < j; i++) {
            if (ok[i] && w[i].from <= w[j].to && w[j].from <= w[i].to) {
                add_fatal(s, field, (uint8_t)j, ev_ovl, (uint32_t)i);
                break;
            }
        }
    }
}

static bool r32_unused(const modcp_r32range_t *r)
{
    return r->from == 0u && r->to == 0u && r->db == 0u;
}

static void check_r32(issue_sink_t *s, const modcp_params_t *p)
{
    bool ok[3];
    for (uint8_t k = 0; k < 3u; k++) {
        const modcp_r32range_t *r = &p->r32[k];
        ok[k] = false;
        if (r32_unused(r)) {
            continue;
        }
        if (r->from > r->to) {
            add_fatal(s, MODCP_PF_R32, k, MODCP_EV_PARAM_RECORD, pair(r->from, r->to));
            continue;
        }
        if (r->db == 0u) {
            add_fatal(s, MODCP_PF_R32, k, MODCP_EV_PARAM_RECORD, 0u);
            continue;
        }
        uint32_t per = k == MODCP_R32_INT16 ? 2u : 4u;
        uint32_t bytes = ((uint32_t)r->to - (uint32_t)r->from + 1u) * per;
        if (bytes > 65536u) {
            add_fatal(s, MODCP_PF_R32, k, MODCP_EV_PARAM_RECORD, bytes);
            continue;
        }
        ok[k] = true;
    }
    for (uint8_t j = 1; j < 3u; j++) {
        if (!ok[j]) {
            continue;
        }
        const modcp_r32range_t *b = &p->r32[j];
        for (uint8_t i = 0; i < j; i++) {
            const modcp_r32range_t *a = &p->r32[i];
            if (!ok[i]) {
                continue;
            }
            if (a->from <= b->to && b->from <= a->to) {
                add_fatal(s, MODCP_PF_R32, j, MODCP_EV_PARAM_RECORD, i);
                break;
            }
            if (a->db == b->db) {
                add_fatal(s, MODCP_PF_R32, j, MODCP_EV_PARAM_RECORD, b->db);
                break;
            }
        }
    }
}

static void check_limit(issue_sink_t *s, modcp_param_field_t field, const modcp_limit_t *l,
                        bool is_db)
{
    if (l->max == 0u) {
        return; /* area not writable: any min is fine */
    }
    if (l->min > l->max || (is_db && l->min == 0u)) {
        add_fatal(s, field, 0u, MODCP_EV_WRITE_LIMITS, pair(l->min, l->max));
    }
}

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
        switch (e->area) {
        case MODCP_AREA_NONE: /* unused entry */
        case MODCP_AREA_T:
        case MODCP_AREA_C:
            break;
        case MODCP_AREA_DB:
        case MODCP_AREA_M:
        case MODCP_AREA_I:
        case MODCP_AREA_Q:
            if (e->area == MODCP_AREA_DB && e->db == 0u) {
                add_fatal(s, MODCP_PF_SCANNER, i, MODCP_EV_PARAM_RECORD, e->db);
            } else if (e->offset > 0xFFFEu) { /* the word's second byte must exist */
                add_fatal(s, MODCP_PF_SCANNER, i, MODCP_EV_PARAM_RECORD, e->offset);
            }
            break;
        default:
            add_fatal(s, MODCP_PF_SCANNER, i, MODCP_EV_PARAM_RECORD, e->area);
            break;
        }
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
    case MODCP_PF_COILS: check_windows(s, p->coils, MODCP_COIL_WINDOWS, true); break;
    case MODCP_PF_INPUTS: check_windows(s, p->inputs, MODCP_INPUT_WINDOWS, false); break;
    case MODCP_PF_R32:
        if (p->regs32 != 0u) {
            check_r32(s, p);
        }
        break;
    case MODCP_PF_LIM_DB:
        check_limit(s, MODCP_PF_LIM_DB, &p->lim_db, true);
        check_limit(s, MODCP_PF_LIM_M, &p->lim_m, false);
        check_limit(s, MODCP_PF_LIM_Q, &p->lim_q, false);
        break;
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
            add_issue(s, (modcp_param_field_t)r->field, r->index,
                      (modcp_event_t)(0x0E00u | r->event), !warn, v);
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
