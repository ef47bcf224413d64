/* modcp — the parameter record: defaults, validation, effective copy, binary form.
 *
 * Validation rules and the events they raise (004 §2, §3, §7.5; 003 §3, §4.5, §8.6).
 * One issue per bad field (per window / range / scanner entry / ID string); for a
 * field with several problems only the first one found is reported.
 *
 *   data_bits      RTU: 8; ASCII: 7 or 8 ............................ (0E)20H fatal
 *   slave_addr     0 ................................................ (0E)23H fatal
 *   opmode         not 0/1 .......................................... (0E)22H fatal
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
 *                  than RS232, regs32 > 1, fset > 1, cpu_model > 1, job_limit not 0
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
 * Binary record (little-endian, fixed widths, fields in declaration order):
 *   "MCPR" | u16 version | u16 payload length | payload | u16 CRC-16 (low byte first)
 * ID strings occupy 16 bytes each (the characters up to the NUL, zero padded; the
 * decoder always terminates them). The record is 316 bytes (RECORD_BYTES);
 * decode accepts trailing bytes after it (the record may sit in a padded block). */
#include "modcp/params.h"

#include <string.h>

#include "modcp/crc.h"

/* ---- binary layout ---------------------------------------------------------- */

#define BITWIN_BYTES 9u  /* area u8, from, to, start, db u16 */
#define R32_BYTES 6u     /* from, to, db */
#define LIMIT_BYTES 4u   /* min, max */
#define SCAN_BYTES 5u    /* area u8, db, offset */
#define HEADER_BYTES 8u  /* magic, version, length */
#define CRC_BYTES 2u

#define PAYLOAD_BYTES                                                                     \
    (4u + 9u /* data_bits .. t15_check */ + 2u /* ascii timeout */ + 1u /* iface */ +     \
     2u /* turnaround */ + 1u /* rs232_auto */ + 2u + 2u /* rts delays */ +               \
     MODCP_COIL_WINDOWS * BITWIN_BYTES + MODCP_INPUT_WINDOWS * BITWIN_BYTES + 2u + 2u +   \
     1u /* regs32 */ + 3u * R32_BYTES + 3u * LIMIT_BYTES + 1u + 1u /* fset, cpu */ +     \
     4u * 2u /* job limit, cpu timeout, start time, commloss */ + 2u + 1u /* scan */ +   \
     MODCP_SCANNER_MAX * SCAN_BYTES + 4u * MODCP_ID_STRING_MAX + 1u /* diag_irq */)

#define RECORD_BYTES (HEADER_BYTES + PAYLOAD_BYTES + CRC_BYTES)

_Static_assert(RECORD_BYTES <= MODCP_PARAMS_RECORD_MAX, "parameter record too large");
_Static_assert(PAYLOAD_BYTES <= 0xFFFFu, "payload length must fit u16");

static const uint8_t record_magic[4] = {'M', 'C', 'P', 'R'};

/* ---- defaults ----------------------------------------------------------------- */

static void set_id(char *dst, const char *src)
{
    size_t n = strlen(src);
    if (n > MODCP_ID_STRING_MAX) {
        n = MODCP_ID_STRING_MAX;
    }
    memset(dst, 0, MODCP_ID_STRING_MAX + 1u);
    memcpy(dst, src, n);
}

void modcp_params_defaults(modcp_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->baud = 9600u;
    p->data_bits = 8u;
    p->parity = MODCP_PARITY_EVEN;
    p->stop_bits = 1u;
    p->slave_addr = 222u; /* as the manuals print it (004 §2.2) */
    p->framing = MODCP_FRAMING_RTU;
    p->opmode = MODCP_OPMODE_NORMAL;
    p->f_mul = 1u;
    p->eof_timing = MODCP_EOF_MANUAL;
    p->t15_check = 0u;
    p->ascii_timeout_ms = 1000u;
    p->iface = MODCP_IFACE_RS232;
    p->turnaround_ms = 0u;
    p->rs232_auto = 0u;
    p->rts_on_delay_ms = 0u;
    p->rts_off_delay_ms = 0u;
    /* coils / inputs: area NONE (memset); hr/ir base 0 = register functions not
     * configured; regs32 off; limits {0,0} = writes disabled */
#if MODCP_WITH_EXTENDED
    p->fset = MODCP_FSET_EXTENDED;
#else
    p->fset = MODCP_FSET_CP341; /* the only set in a build without the extended set */
#endif
    p->cpu_model = MODCP_CPU_CP341;
    p->job_limit = 0u;
    p->cpu_timeout_ms = 1000u;
    p->start_time_ms = 5000u;
    p->commloss_ms = 0u;
    p->scan_start = 0u;
    p->scan_count = 0u;
    set_id(p->vendor, "modcp");
    set_id(p->product, "modcp-cp");
    set_id(p->revision, "0.1");
    set_id(p->app_name, "");
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

static bool fmul_ok(uint8_t f)
{
    return f >= 1u && f <= 10u;
}

static bool ascii_timeout_ok(uint16_t t)
{
    return t >= 1u && t <= 6500u;
}

static uint16_t model_limit(uint8_t cpu_model)
{
    return cpu_model == MODCP_CPU_CP441 ? 450u : 1024u;
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

static bool id_terminated(const char *str)
{
    for (size_t i = 0; i <= MODCP_ID_STRING_MAX; i++) {
        if (str[i] == '\0') {
            return true;
        }
    }
    return false;
}

static void check_scanner(issue_sink_t *s, const modcp_params_t *p)
{
    if (p->scan_count > MODCP_SCANNER_MAX || (!MODCP_WITH_EXTENDED && p->scan_count != 0u) ||
        (uint32_t)p->scan_start + (uint32_t)p->scan_count > 0x10000u) {
        add_fatal(s, MODCP_PF_SCANNER, 0xFFu, MODCP_EV_PARAM_RECORD, p->scan_count);
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

static void run_checks(const modcp_params_t *p, issue_sink_t *s)
{
    const modcp_event_t rec = MODCP_EV_PARAM_RECORD;

    if (!baud_ok(p->baud)) {
        add_fatal(s, MODCP_PF_BAUD, 0u, rec, p->baud);
    }
    if (p->framing == MODCP_FRAMING_ASCII ? (p->data_bits != 7u && p->data_bits != 8u)
                                          : p->data_bits != 8u) {
        add_fatal(s, MODCP_PF_DATA_BITS, 0u, MODCP_EV_DATA_BITS, p->data_bits);
    }
    if (p->parity > MODCP_PARITY_EVEN) {
        add_fatal(s, MODCP_PF_PARITY, 0u, rec, p->parity);
    }
    if (p->stop_bits != 1u && p->stop_bits != 2u) {
        add_fatal(s, MODCP_PF_STOP_BITS, 0u, rec, p->stop_bits);
    }
    if (p->slave_addr == 0u) {
        add_fatal(s, MODCP_PF_SLAVE_ADDR, 0u, MODCP_EV_SLAVE_ADDR, p->slave_addr);
    }
    if (p->framing > MODCP_FRAMING_ASCII ||
        (!MODCP_WITH_ASCII && p->framing == MODCP_FRAMING_ASCII)) { /* compiled out */
        add_fatal(s, MODCP_PF_FRAMING, 0u, rec, p->framing);
    }
    if (p->opmode > MODCP_OPMODE_SUPPRESS) {
        add_fatal(s, MODCP_PF_OPMODE, 0u, MODCP_EV_OPMODE, p->opmode);
    }
    if (!fmul_ok(p->f_mul)) {
        add_issue(s, MODCP_PF_FMUL, 0u, MODCP_EV_FMUL, false, p->f_mul);
    }
    if (p->eof_timing > MODCP_EOF_MODBUS) {
        add_fatal(s, MODCP_PF_EOF_TIMING, 0u, rec, p->eof_timing);
    }
    if (p->t15_check > 1u) {
        add_fatal(s, MODCP_PF_T15_CHECK, 0u, rec, p->t15_check);
    }
    if (!ascii_timeout_ok(p->ascii_timeout_ms)) {
        add_issue(s, MODCP_PF_ASCII_TIMEOUT, 0u, MODCP_EV_FMUL, false, p->ascii_timeout_ms);
    }
    if (p->iface > MODCP_IFACE_RS485) {
        add_fatal(s, MODCP_PF_IFACE, 0u, rec, p->iface);
    }
    if (p->turnaround_ms > 100u) {
        add_fatal(s, MODCP_PF_TURNAROUND, 0u, rec, p->turnaround_ms);
    }
    if (p->rs232_auto > 1u || (p->rs232_auto == 1u && p->iface != MODCP_IFACE_RS232) ||
        (!MODCP_WITH_RS232_SIGNALS && p->rs232_auto != 0u)) { /* compiled out */
        add_fatal(s, MODCP_PF_RS232_AUTO, 0u, rec, p->rs232_auto);
    }
    /* rts delays: every value 0 ... 65535 ms is legal */
    check_windows(s, p->coils, MODCP_COIL_WINDOWS, true);
    check_windows(s, p->inputs, MODCP_INPUT_WINDOWS, false);
    /* hr/ir base: 0 = not configured, 1 ... 65535 legal */
    if (p->regs32 > 1u) {
        add_fatal(s, MODCP_PF_REGS32, 0u, rec, p->regs32);
    }
    if (p->regs32 != 0u) {
        check_r32(s, p);
    }
    check_limit(s, MODCP_PF_LIM_DB, &p->lim_db, true);
    check_limit(s, MODCP_PF_LIM_M, &p->lim_m, false);
    check_limit(s, MODCP_PF_LIM_Q, &p->lim_q, false);
    if (p->fset > MODCP_FSET_EXTENDED ||
        (!MODCP_WITH_EXTENDED && p->fset == MODCP_FSET_EXTENDED)) { /* compiled out */
        add_fatal(s, MODCP_PF_FSET, 0u, rec, p->fset);
    }
    if (p->cpu_model > MODCP_CPU_CP441) {
        add_fatal(s, MODCP_PF_CPU_MODEL, 0u, rec, p->cpu_model);
    }
    if (p->job_limit != 0u && (p->job_limit < 32u || p->job_limit > model_limit(p->cpu_model))) {
        add_fatal(s, MODCP_PF_JOB_LIMIT, 0u, rec, p->job_limit);
    }
    if (p->cpu_timeout_ms == 0u) {
        add_fatal(s, MODCP_PF_CPU_TIMEOUT, 0u, rec, p->cpu_timeout_ms);
    }
    if (p->start_time_ms == 0u) {
        add_fatal(s, MODCP_PF_START_TIME, 0u, rec, p->start_time_ms);
    }
    if (p->commloss_ms != 0u &&
        (p->commloss_ms < 100u || p->commloss_ms > 30000u || !MODCP_WITH_EXTENDED)) {
        add_fatal(s, MODCP_PF_COMMLOSS, 0u, rec, p->commloss_ms);
    }
    check_scanner(s, p);
    const char *ids[4] = {p->vendor, p->product, p->revision, p->app_name};
    for (uint8_t i = 0; i < 4u; i++) {
        if (!id_terminated(ids[i])) {
            add_fatal(s, MODCP_PF_ID_STRING, i, rec, (uint8_t)ids[i][MODCP_ID_STRING_MAX]);
        }
    }
    if (p->diag_irq > 1u) {
        add_fatal(s, MODCP_PF_DIAG_IRQ, 0u, rec, p->diag_irq);
    }
}

size_t modcp_params_validate(const modcp_params_t *p, modcp_param_issue_t *out, size_t max)
{
    issue_sink_t s = {out, max, 0u, MODCP_EV_NONE, MODCP_EV_NONE};
    run_checks(p, &s);
    return s.n;
}

modcp_event_t modcp_params_apply(const modcp_params_t *in, modcp_params_t *out,
                                 modcp_event_t *first_warning)
{
    issue_sink_t s = {NULL, 0u, 0u, MODCP_EV_NONE, MODCP_EV_NONE};
    run_checks(in, &s);
    if (out != in) {
        memcpy(out, in, sizeof *out);
    }
    if (!fmul_ok(out->f_mul)) {
        out->f_mul = 1u;
    }
    if (!ascii_timeout_ok(out->ascii_timeout_ms)) {
        out->ascii_timeout_ms = 1000u;
    }
    if (first_warning != NULL) {
        *first_warning = s.first_warning;
    }
    return s.first_fatal;
}

uint16_t modcp_params_job_limit(const modcp_params_t *p)
{
    return p->job_limit != 0u ? p->job_limit : model_limit(p->cpu_model);
}

/* ---- binary record ------------------------------------------------------------ */

typedef struct {
    uint8_t *b;
    size_t pos;
} wr_t;

static void w8(wr_t *w, uint8_t v)
{
    w->b[w->pos++] = v;
}

static void w16(wr_t *w, uint16_t v)
{
    w8(w, (uint8_t)(v & 0xFFu));
    w8(w, (uint8_t)(v >> 8));
}

static void w32(wr_t *w, uint32_t v)
{
    w16(w, (uint16_t)(v & 0xFFFFu));
    w16(w, (uint16_t)(v >> 16));
}

static void wstr(wr_t *w, const char *str)
{
    bool end = false;
    for (size_t i = 0; i < MODCP_ID_STRING_MAX; i++) {
        if (str[i] == '\0') {
            end = true;
        }
        w8(w, end ? 0u : (uint8_t)str[i]);
    }
}

static void wwin(wr_t *w, const modcp_bitwin_t *win)
{
    w8(w, win->area);
    w16(w, win->from);
    w16(w, win->to);
    w16(w, win->start);
    w16(w, win->db);
}

typedef struct {
    const uint8_t *b;
    size_t pos;
} rd_t;

static uint8_t r8(rd_t *r)
{
    return r->b[r->pos++];
}

static uint16_t r16(rd_t *r)
{
    uint16_t lo = r8(r);
    uint16_t hi = r8(r);
    return (uint16_t)(lo | (uint16_t)(hi << 8));
}

static uint32_t r32(rd_t *r)
{
    uint32_t lo = r16(r);
    uint32_t hi = r16(r);
    return lo | (hi << 16);
}

static void rstr(rd_t *r, char *str)
{
    for (size_t i = 0; i < MODCP_ID_STRING_MAX; i++) {
        str[i] = (char)r8(r);
    }
    str[MODCP_ID_STRING_MAX] = '\0';
}

static void rwin(rd_t *r, modcp_bitwin_t *win)
{
    win->area = r8(r);
    win->from = r16(r);
    win->to = r16(r);
    win->start = r16(r);
    win->db = r16(r);
}

size_t modcp_params_encode(const modcp_params_t *p, uint8_t *buf, size_t cap)
{
    if (buf == NULL || cap < RECORD_BYTES) {
        return 0u;
    }
    wr_t w = {buf, 0u};
    for (size_t i = 0; i < sizeof record_magic; i++) {
        w8(&w, record_magic[i]);
    }
    w16(&w, (uint16_t)MODCP_PARAMS_VERSION);
    w16(&w, (uint16_t)PAYLOAD_BYTES);

    w32(&w, p->baud);
    w8(&w, p->data_bits);
    w8(&w, p->parity);
    w8(&w, p->stop_bits);
    w8(&w, p->slave_addr);
    w8(&w, p->framing);
    w8(&w, p->opmode);
    w8(&w, p->f_mul);
    w8(&w, p->eof_timing);
    w8(&w, p->t15_check);
    w16(&w, p->ascii_timeout_ms);
    w8(&w, p->iface);
    w16(&w, p->turnaround_ms);
    w8(&w, p->rs232_auto);
    w16(&w, p->rts_on_delay_ms);
    w16(&w, p->rts_off_delay_ms);
    for (size_t i = 0; i < MODCP_COIL_WINDOWS; i++) {
        wwin(&w, &p->coils[i]);
    }
    for (size_t i = 0; i < MODCP_INPUT_WINDOWS; i++) {
        wwin(&w, &p->inputs[i]);
    }
    w16(&w, p->hr_base_db);
    w16(&w, p->ir_base_db);
    w8(&w, p->regs32);
    for (size_t i = 0; i < 3u; i++) {
        w16(&w, p->r32[i].from);
        w16(&w, p->r32[i].to);
        w16(&w, p->r32[i].db);
    }
    w16(&w, p->lim_db.min);
    w16(&w, p->lim_db.max);
    w16(&w, p->lim_m.min);
    w16(&w, p->lim_m.max);
    w16(&w, p->lim_q.min);
    w16(&w, p->lim_q.max);
    w8(&w, p->fset);
    w8(&w, p->cpu_model);
    w16(&w, p->job_limit);
    w16(&w, p->cpu_timeout_ms);
    w16(&w, p->start_time_ms);
    w16(&w, p->commloss_ms);
    w16(&w, p->scan_start);
    w8(&w, p->scan_count);
    for (size_t i = 0; i < MODCP_SCANNER_MAX; i++) {
        w8(&w, p->scan[i].area);
        w16(&w, p->scan[i].db);
        w16(&w, p->scan[i].offset);
    }
    wstr(&w, p->vendor);
    wstr(&w, p->product);
    wstr(&w, p->revision);
    wstr(&w, p->app_name);
    w8(&w, p->diag_irq);

    uint16_t crc = modcp_crc16(buf, w.pos);
    w16(&w, crc);
    return w.pos;
}

modcp_event_t modcp_params_decode(const uint8_t *buf, size_t len, modcp_params_t *p)
{
    if (buf == NULL || p == NULL || len < RECORD_BYTES) {
        return MODCP_EV_PARAM_RECORD;
    }
    for (size_t i = 0; i < sizeof record_magic; i++) {
        if (buf[i] != record_magic[i]) {
            return MODCP_EV_PARAM_RECORD;
        }
    }
    rd_t r = {buf, sizeof record_magic};
    uint16_t version = r16(&r);
    uint16_t plen = r16(&r);
    if (version != MODCP_PARAMS_VERSION || plen != PAYLOAD_BYTES) {
        return MODCP_EV_PARAM_RECORD;
    }
    size_t crc_at = HEADER_BYTES + PAYLOAD_BYTES;
    uint16_t crc = (uint16_t)(buf[crc_at] | (uint16_t)(buf[crc_at + 1u] << 8));
    if (modcp_crc16(buf, crc_at) != crc) {
        return MODCP_EV_PARAM_RECORD;
    }

    /* The record is sound: from here on nothing can fail, decode straight into p. */
    memset(p, 0, sizeof *p);
    p->baud = r32(&r);
    p->data_bits = r8(&r);
    p->parity = r8(&r);
    p->stop_bits = r8(&r);
    p->slave_addr = r8(&r);
    p->framing = r8(&r);
    p->opmode = r8(&r);
    p->f_mul = r8(&r);
    p->eof_timing = r8(&r);
    p->t15_check = r8(&r);
    p->ascii_timeout_ms = r16(&r);
    p->iface = r8(&r);
    p->turnaround_ms = r16(&r);
    p->rs232_auto = r8(&r);
    p->rts_on_delay_ms = r16(&r);
    p->rts_off_delay_ms = r16(&r);
    for (size_t i = 0; i < MODCP_COIL_WINDOWS; i++) {
        rwin(&r, &p->coils[i]);
    }
    for (size_t i = 0; i < MODCP_INPUT_WINDOWS; i++) {
        rwin(&r, &p->inputs[i]);
    }
    p->hr_base_db = r16(&r);
    p->ir_base_db = r16(&r);
    p->regs32 = r8(&r);
    for (size_t i = 0; i < 3u; i++) {
        p->r32[i].from = r16(&r);
        p->r32[i].to = r16(&r);
        p->r32[i].db = r16(&r);
    }
    p->lim_db.min = r16(&r);
    p->lim_db.max = r16(&r);
    p->lim_m.min = r16(&r);
    p->lim_m.max = r16(&r);
    p->lim_q.min = r16(&r);
    p->lim_q.max = r16(&r);
    p->fset = r8(&r);
    p->cpu_model = r8(&r);
    p->job_limit = r16(&r);
    p->cpu_timeout_ms = r16(&r);
    p->start_time_ms = r16(&r);
    p->commloss_ms = r16(&r);
    p->scan_start = r16(&r);
    p->scan_count = r8(&r);
    for (size_t i = 0; i < MODCP_SCANNER_MAX; i++) {
        p->scan[i].area = r8(&r);
        p->scan[i].db = r16(&r);
        p->scan[i].offset = r16(&r);
    }
    rstr(&r, p->vendor);
    rstr(&r, p->product);
    rstr(&r, p->revision);
    rstr(&r, p->app_name);
    p->diag_irq = r8(&r);
    return MODCP_EV_NONE;
}
