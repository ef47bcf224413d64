/* modcp — monitor console (S7 notation). Portable C11: no OS, no heap, no globals.
 *
 * Decisions (documented in docs/simulator.md):
 *  - B and W values print as hex and unsigned decimal, D values as hex and signed
 *    int32 (or as float with the `float` keyword); T and C as hex and unsigned.
 *  - set accepts decimal, 0x.. or 16#.. hex, negative numbers (two's complement in
 *    the operand's width), and for D operands a float (a value with '.', 'e', inf,
 *    nan, or the keyword `float` after it).
 *  - dump prints at most 256 bytes (T/C: 128 elements), 16 per line.
 *  - set on T, C and I is allowed: the console is the user program's view of the
 *    controller memory, not the master's. */
#include "modcp/console.h"
#include "modcp/signals.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define LINE_MAX_CHARS 256u
#define MAX_TOKENS 8u
#define DUMP_MAX_BYTES 256u
#define DUMP_PER_LINE 16u

/* ---- output buffer --------------------------------------------------------- */

typedef struct {
    char *buf;
    size_t cap;
    size_t len;
    bool overflow;
} out_t;

static void out_init(out_t *o, char *buf, size_t cap)
{
    o->buf = buf;
    o->cap = cap;
    o->len = 0;
    o->overflow = false;
    if (cap > 0u) {
        buf[0] = '\0';
    }
}

static void out_printf(out_t *o, const char *fmt, ...)
{
    if (o->overflow || o->cap == 0u) {
        o->overflow = true;
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    size_t room = o->cap - o->len;
    int n = vsnprintf(o->buf + o->len, room, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= room) {
        o->overflow = true;
        o->buf[o->len] = '\0'; /* drop the partial piece */
        return;
    }
    o->len += (size_t)n;
}

/* Start a new line (a '\n' separator unless the output is empty). */
static void out_nl(out_t *o)
{
    if (o->len > 0u) {
        out_printf(o, "\n");
    }
}

static void out_finish(out_t *o)
{
    if (!o->overflow || o->cap == 0u) {
        return;
    }
    /* cut at a line boundary and mark the cut */
    while (o->len > 0u && o->len + 4u > o->cap) {
        size_t i = o->len - 1u;
        while (i > 0u && o->buf[i] != '\n') {
            i--;
        }
        o->len = i;
    }
    o->buf[o->len] = '\0';
    if (o->len + 4u <= o->cap) {
        if (o->len > 0u) {
            o->buf[o->len++] = '\n';
        }
        if (o->len + 3u < o->cap) {
            memcpy(o->buf + o->len, "...", 4u);
            o->len += 3u;
        }
    }
}

static int fail(out_t *o, const char *fmt, ...)
{
    o->len = 0;
    o->overflow = false;
    if (o->cap == 0u) {
        return MODCP_CONSOLE_ERROR;
    }
    o->buf[0] = '\0';
    out_printf(o, "error: ");
    if (!o->overflow) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = o->cap - o->len;
        int n = vsnprintf(o->buf + o->len, room, fmt, ap);
        va_end(ap);
        if (n > 0) {
            o->len += ((size_t)n < room) ? (size_t)n : room - 1u;
        }
    }
    o->overflow = false;
    return MODCP_CONSOLE_ERROR;
}

/* ---- small helpers ----------------------------------------------------------- */

static char up(char c)
{
    return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c;
}

static bool ieq(const char *a, const char *b)
{
    while (*a != '\0' && *b != '\0') {
        if (up(*a) != up(*b)) {
            return false;
        }
        a++;
        b++;
    }
    return *a == *b;
}

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* Decimal number 0..65535 at *s; advances *s. */
static bool parse_u16(const char **s, uint16_t *v)
{
    const char *p = *s;
    uint32_t n = 0;
    if (!is_digit(*p)) {
        return false;
    }
    while (is_digit(*p)) {
        n = n * 10u + (uint32_t)(*p - '0');
        if (n > 0xFFFFu) {
            return false;
        }
        p++;
    }
    *s = p;
    *v = (uint16_t)n;
    return true;
}

/* ".b" with b in 0..7 */
static bool parse_bit(const char **s, uint8_t *bit)
{
    const char *p = *s;
    if (*p != '.' || p[1] < '0' || p[1] > '7' || is_digit(p[2])) {
        return false;
    }
    *bit = (uint8_t)(p[1] - '0');
    *s = p + 2;
    return true;
}

static uint8_t width_of(char c)
{
    switch (up(c)) {
    case 'B': return MODCP_S7_BYTE;
    case 'W': return MODCP_S7_WORD;
    case 'D': return MODCP_S7_DWORD;
    case 'X': return MODCP_S7_BIT;
    default: return 0xFFu;
    }
}

/* ---- operands --------------------------------------------------------------- */

bool modcp_s7op_parse(const char *s, modcp_s7op_t *op)
{
    modcp_s7op_t r;
    memset(&r, 0, sizeof r);
    if (s == NULL || op == NULL) {
        return false;
    }
    char a = up(s[0]);
    if (a == 'D' && up(s[1]) == 'B') {
        const char *p = s + 2;
        r.area = MODCP_AREA_DB;
        if (!parse_u16(&p, &r.db) || r.db == 0u) {
            return false;
        }
        if (p[0] != '.' || up(p[1]) != 'D' || up(p[2]) != 'B') {
            return false;
        }
        r.width = width_of(p[3]);
        if (r.width == 0xFFu) {
            return false;
        }
        p += 4;
        if (!parse_u16(&p, &r.offset)) {
            return false;
        }
        if (r.width == MODCP_S7_BIT && !parse_bit(&p, &r.bit)) {
            return false;
        }
        if (*p != '\0') {
            return false;
        }
        *op = r;
        return true;
    }
    if (a == 'T' || a == 'C') {
        const char *p = s + 1;
        r.area = a == 'T' ? MODCP_AREA_T : MODCP_AREA_C;
        r.width = MODCP_S7_WORD;
        if (!parse_u16(&p, &r.offset) || *p != '\0') {
            return false;
        }
        *op = r;
        return true;
    }
    if (a == 'M' || a == 'I' || a == 'Q') {
        const char *p = s + 1;
        r.area = a == 'M' ? MODCP_AREA_M : (a == 'I' ? MODCP_AREA_I : MODCP_AREA_Q);
        if (is_digit(*p)) {
            r.width = MODCP_S7_BIT;
            if (!parse_u16(&p, &r.offset) || !parse_bit(&p, &r.bit)) {
                return false;
            }
        } else {
            r.width = width_of(*p);
            if (r.width == 0xFFu || r.width == MODCP_S7_BIT) {
                return false;
            }
            p++;
            if (!parse_u16(&p, &r.offset)) {
                return false;
            }
        }
        if (*p != '\0') {
            return false;
        }
        *op = r;
        return true;
    }
    return false;
}

static char width_letter(uint8_t w)
{
    switch (w) {
    case MODCP_S7_BYTE: return 'B';
    case MODCP_S7_WORD: return 'W';
    case MODCP_S7_DWORD: return 'D';
    default: return 'X';
    }
}

static char area_letter(uint8_t area)
{
    switch (area) {
    case MODCP_AREA_I: return 'I';
    case MODCP_AREA_Q: return 'Q';
    case MODCP_AREA_M: return 'M';
    case MODCP_AREA_T: return 'T';
    case MODCP_AREA_C: return 'C';
    default: return '?';
    }
}

size_t modcp_s7op_name(const modcp_s7op_t *op, char *out, size_t cap)
{
    int n;
    if (cap == 0u) {
        return 0;
    }
    if (op->area == MODCP_AREA_DB) {
        if (op->width == MODCP_S7_BIT) {
            n = snprintf(out, cap, "DB%u.DBX%u.%u", (unsigned)op->db, (unsigned)op->offset,
                         (unsigned)op->bit);
        } else {
            n = snprintf(out, cap, "DB%u.DB%c%u", (unsigned)op->db, width_letter(op->width),
                         (unsigned)op->offset);
        }
    } else if (op->area == MODCP_AREA_T || op->area == MODCP_AREA_C) {
        n = snprintf(out, cap, "%c%u", area_letter(op->area), (unsigned)op->offset);
    } else if (op->width == MODCP_S7_BIT) {
        n = snprintf(out, cap, "%c%u.%u", area_letter(op->area), (unsigned)op->offset,
                     (unsigned)op->bit);
    } else {
        n = snprintf(out, cap, "%c%c%u", area_letter(op->area), width_letter(op->width),
                     (unsigned)op->offset);
    }
    if (n < 0) {
        out[0] = '\0';
        return 0;
    }
    return (size_t)n < cap ? (size_t)n : cap - 1u;
}

/* The console reads and writes through the controller memory model (plcmem.c), so
 * it checks sizes and DB existence exactly as the FB does. */
static modcp_operand_t operand_of(const modcp_s7op_t *op)
{
    modcp_operand_t o;
    memset(&o, 0, sizeof o);
    o.area = op->area;
    o.db = op->db;
    o.offset = op->offset;
    o.bit = op->width == MODCP_S7_BIT ? op->bit : 0u;
    o.count = 1u; /* one bit for write_bits; reads and writes go by length */
    return o;
}

/* Bytes an operand occupies: 1 for a bit's byte, 2 for T / C elements. */
static uint16_t operand_bytes(const modcp_s7op_t *op)
{
    if (op->area == MODCP_AREA_T || op->area == MODCP_AREA_C) {
        return 2u;
    }
    return op->width == MODCP_S7_BIT ? 1u : op->width;
}

modcp_event_t modcp_s7op_read(const modcp_plcmem_t *mem, const modcp_s7op_t *op, uint32_t *value)
{
    if (mem == NULL || op == NULL || value == NULL) {
        return MODCP_EV_AREA_ACCESS;
    }
    modcp_operand_t o = operand_of(op);
    uint8_t b[4] = {0, 0, 0, 0};
    uint16_t n = operand_bytes(op);
    modcp_event_t ev = modcp_plcmem_read(mem, &o, b, n);
    if (ev != MODCP_EV_NONE) {
        return ev;
    }
    if (op->width == MODCP_S7_BIT && op->area != MODCP_AREA_T && op->area != MODCP_AREA_C) {
        *value = ((uint32_t)b[0] >> op->bit) & 1u;
        return MODCP_EV_NONE;
    }
    uint32_t v = 0;
    for (uint16_t k = 0; k < n; k++) {
        v = (v << 8) | b[k]; /* big-endian as stored; T / C high byte first */
    }
    *value = v;
    return MODCP_EV_NONE;
}

modcp_event_t modcp_s7op_write(modcp_plcmem_t *mem, const modcp_s7op_t *op, uint32_t value)
{
    if (mem == NULL || op == NULL) {
        return MODCP_EV_AREA_ACCESS;
    }
    modcp_operand_t o = operand_of(op);
    if (op->width == MODCP_S7_BIT && op->area != MODCP_AREA_T && op->area != MODCP_AREA_C) {
        uint8_t bit = (uint8_t)(value & 1u);
        return modcp_plcmem_write_bits(mem, &o, &bit);
    }
    uint16_t n = operand_bytes(op);
    uint8_t b[4];
    for (uint16_t k = 0; k < n; k++) {
        b[k] = (uint8_t)(value >> (8u * (n - 1u - k)));
    }
    return modcp_plcmem_write(mem, &o, b, n);
}

/* ---- names ------------------------------------------------------------------- */

const char *modcp_console_fb_state(uint8_t state)
{
    switch (state) {
    case MODCP_FBST_STOPPED: return "STOPPED";
    case MODCP_FBST_INIT_SEND: return "INIT_SEND";
    case MODCP_FBST_INIT_WAIT: return "INIT_WAIT";
    case MODCP_FBST_RUN: return "RUN";
    case MODCP_FBST_FAILED: return "FAILED";
    default: return "UNKNOWN";
    }
}

size_t modcp_console_event_name(modcp_event_t ev, char *out, size_t cap)
{
    if (cap == 0u) {
        return 0;
    }
    int n = snprintf(out, cap, "(%02X)%02XH", (unsigned)MODCP_EVENT_CLASS(ev),
                     (unsigned)MODCP_EVENT_NUMBER(ev));
    if (n < 0) {
        out[0] = '\0';
        return 0;
    }
    return (size_t)n < cap ? (size_t)n : cap - 1u;
}

static const char *class_text(uint8_t cls)
{
    switch (cls) {
    case 0x05u: return "CPU job error";
    case 0x08u: return "receive error";
    case 0x0Eu: return "driver processing error";
    default: return "other";
    }
}

static const char *area_name(uint8_t area)
{
    switch (area) {
    case MODCP_AREA_I: return "I";
    case MODCP_AREA_Q: return "Q";
    case MODCP_AREA_M: return "M";
    case MODCP_AREA_T: return "T";
    case MODCP_AREA_C: return "C";
    default: return "DB";
    }
}

/* ---- value formatting and parsing ---------------------------------------------- */

static float bits_to_float(uint32_t v)
{
    float f;
    memcpy(&f, &v, sizeof f);
    return f;
}

static uint32_t float_to_bits(float f)
{
    uint32_t v;
    memcpy(&v, &f, sizeof v);
    return v;
}

/* Shortest %g representation that reads back as the same float. */
static void format_float(float f, char *buf, size_t cap)
{
    for (int prec = 6; prec <= 9; prec++) {
        (void)snprintf(buf, cap, "%.*g", prec, (double)f);
        float back = (float)strtod(buf, NULL);
        if (float_to_bits(back) == float_to_bits(f)) {
            return;
        }
    }
}

static void print_value(out_t *o, const modcp_s7op_t *op, uint32_t v, bool as_float)
{
    char name[32];
    (void)modcp_s7op_name(op, name, sizeof name);
    switch (op->width) {
    case MODCP_S7_BIT: out_printf(o, "%s = %u", name, (unsigned)v); break;
    case MODCP_S7_BYTE: out_printf(o, "%s = 0x%02X (%u)", name, (unsigned)v, (unsigned)v); break;
    case MODCP_S7_WORD: out_printf(o, "%s = 0x%04X (%u)", name, (unsigned)v, (unsigned)v); break;
    default:
        if (as_float) {
            char fb[40];
            format_float(bits_to_float(v), fb, sizeof fb);
            out_printf(o, "%s = %s (0x%08lX)", name, fb, (unsigned long)v);
        } else {
            long sv;
            if ((v & 0x80000000u) == 0u) {
                sv = (long)v;
            } else if (v == 0x80000000u) {
                sv = -2147483647L - 1L;
            } else {
                sv = -(long)(~v + 1u);
            }
            out_printf(o, "%s = 0x%08lX (%ld)", name, (unsigned long)v, sv);
        }
        break;
    }
}

static bool looks_float(const char *s)
{
    const char *h = (*s == '-' || *s == '+') ? s + 1 : s;
    if ((h[0] == '0' && (h[1] == 'x' || h[1] == 'X')) || (h[0] == '1' && h[1] == '6' && h[2] == '#')) {
        return false; /* hex: 'E' is a digit there */
    }
    for (const char *p = s; *p != '\0'; p++) {
        if (*p == '.' || *p == 'e' || *p == 'E') {
            return true;
        }
    }
    const char *q = (*s == '-' || *s == '+') ? s + 1 : s;
    return ieq(q, "inf") || ieq(q, "nan") || ieq(q, "infinity");
}

/* Parse an integer for a field of `bits` bits (two's complement allowed). */
static bool parse_int(const char *s, unsigned bits, uint32_t *out)
{
    char *end = NULL;
    uint32_t max = bits >= 32u ? 0xFFFFFFFFu : ((1u << bits) - 1u);
    if (s[0] == '1' && s[1] == '6' && s[2] == '#') {
        unsigned long v = strtoul(s + 3, &end, 16);
        if (end == s + 3 || *end != '\0' || v > max) {
            return false;
        }
        *out = (uint32_t)v;
        return true;
    }
    if (s[0] == '-') {
        long v = strtol(s, &end, 0);
        if (end == s || *end != '\0') {
            return false;
        }
        long min = bits >= 32u ? (-2147483647L - 1L) : -(long)(1u << (bits - 1u));
        if (v < min) {
            return false;
        }
        *out = (uint32_t)((unsigned long)v & (unsigned long)max);
        return true;
    }
    if (!is_digit(s[0]) && s[0] != '+') {
        return false;
    }
    unsigned long v = strtoul(s, &end, 0);
    if (end == s || *end != '\0' || v > max) {
        return false;
    }
    *out = (uint32_t)v;
    return true;
}

static bool parse_bool(const char *s, uint32_t *out)
{
    if (ieq(s, "1") || ieq(s, "true") || ieq(s, "on")) {
        *out = 1u;
        return true;
    }
    if (ieq(s, "0") || ieq(s, "false") || ieq(s, "off")) {
        *out = 0u;
        return true;
    }
    return false;
}

/* Explain why an operand cannot be accessed. */
static int operand_error(out_t *o, const modcp_plcmem_t *mem, const modcp_s7op_t *op)
{
    char name[32];
    (void)modcp_s7op_name(op, name, sizeof name);
    if (op->area == MODCP_AREA_DB) {
        const modcp_db_t *db = modcp_plcmem_db(mem, op->db);
        if (db == NULL) {
            return fail(o, "%s: DB%u does not exist", name, (unsigned)op->db);
        }
        return fail(o, "%s: outside DB%u (%u bytes)", name, (unsigned)op->db, (unsigned)db->size);
    }
    if (op->area == MODCP_AREA_T) {
        return fail(o, "%s: outside T (%u timers)", name, (unsigned)mem->t_count);
    }
    if (op->area == MODCP_AREA_C) {
        return fail(o, "%s: outside C (%u counters)", name, (unsigned)mem->c_count);
    }
    unsigned size = op->area == MODCP_AREA_I ? mem->i_size
                                             : (op->area == MODCP_AREA_Q ? mem->q_size : mem->m_size);
    return fail(o, "%s: outside %s (%u bytes)", name, area_name(op->area), size);
}

/* ---- commands ------------------------------------------------------------------ */

typedef struct {
    char *tok[MAX_TOKENS];
    size_t n;
    const char *rest; /* text after the first token (for echo) */
} args_t;

static int cmd_get(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_s7op_t op;
    if (env->mem == NULL) {
        return fail(o, "controller memory not available");
    }
    if (a->n < 2u || a->n > 3u) {
        return fail(o, "usage: get OPERAND [float]");
    }
    if (!modcp_s7op_parse(a->tok[1], &op)) {
        return fail(o, "bad operand '%s' (e.g. MB1000, M1000.3, DB800.DBW0, T100)", a->tok[1]);
    }
    bool as_float = false;
    if (a->n == 3u) {
        if (!ieq(a->tok[2], "float") || op.width != MODCP_S7_DWORD) {
            return fail(o, "'%s': only a D operand can be shown as float", a->tok[2]);
        }
        as_float = true;
    }
    uint32_t v = 0;
    if (modcp_s7op_read(env->mem, &op, &v) != MODCP_EV_NONE) {
        return operand_error(o, env->mem, &op);
    }
    print_value(o, &op, v, as_float);
    return MODCP_CONSOLE_OK;
}

static int cmd_set(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_s7op_t op;
    if (env->mem == NULL) {
        return fail(o, "controller memory not available");
    }
    if (a->n < 3u || a->n > 4u) {
        return fail(o, "usage: set OPERAND VALUE [float]");
    }
    if (!modcp_s7op_parse(a->tok[1], &op)) {
        return fail(o, "bad operand '%s' (e.g. MB1000, M1000.3, DB800.DBW0, T100)", a->tok[1]);
    }
    const char *vs = a->tok[2];
    bool as_float = false;
    if (a->n == 4u) {
        if (!ieq(a->tok[3], "float")) {
            return fail(o, "unexpected '%s'", a->tok[3]);
        }
        as_float = true;
    }
    if (looks_float(vs)) {
        as_float = true;
    }
    uint32_t v = 0;
    if (op.width == MODCP_S7_BIT) {
        if (as_float || !parse_bool(vs, &v)) {
            return fail(o, "bad value '%s' for a bit (0 or 1)", vs);
        }
    } else if (as_float) {
        if (op.width != MODCP_S7_DWORD) {
            return fail(o, "bad value '%s': floats need a D operand", vs);
        }
        char *end = NULL;
        double d = strtod(vs, &end);
        if (end == vs || *end != '\0') {
            return fail(o, "bad float '%s'", vs);
        }
        v = float_to_bits((float)d);
    } else if (!parse_int(vs, 8u * (unsigned)op.width, &v)) {
        return fail(o, "bad value '%s' for a %u-bit operand", vs, 8u * (unsigned)op.width);
    }
    if (modcp_s7op_write(env->mem, &op, v) != MODCP_EV_NONE) {
        return operand_error(o, env->mem, &op);
    }
    uint32_t back = 0;
    (void)modcp_s7op_read(env->mem, &op, &back);
    print_value(o, &op, back, as_float);
    return MODCP_CONSOLE_OK;
}

static bool parse_num16(const char *s, uint16_t *v)
{
    uint32_t x = 0;
    if (!parse_int(s, 16u, &x) || s[0] == '-') {
        return false;
    }
    *v = (uint16_t)x;
    return true;
}

static int cmd_dump(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_plcmem_t *mem = env->mem;
    if (mem == NULL) {
        return fail(o, "controller memory not available");
    }
    if (a->n < 2u || a->n > 4u) {
        return fail(o, "usage: dump M|I|Q|T|C|DBn [START [LEN]]");
    }
    const char *ar = a->tok[1];
    uint8_t area;
    uint16_t dbno = 0;
    if (ieq(ar, "M")) {
        area = MODCP_AREA_M;
    } else if (ieq(ar, "I")) {
        area = MODCP_AREA_I;
    } else if (ieq(ar, "Q")) {
        area = MODCP_AREA_Q;
    } else if (ieq(ar, "T")) {
        area = MODCP_AREA_T;
    } else if (ieq(ar, "C")) {
        area = MODCP_AREA_C;
    } else if (up(ar[0]) == 'D' && up(ar[1]) == 'B') {
        const char *p = ar + 2;
        if (!parse_u16(&p, &dbno) || *p != '\0' || dbno == 0u) {
            return fail(o, "bad area '%s' (M, I, Q, T, C or DBn)", ar);
        }
        area = MODCP_AREA_DB;
    } else {
        return fail(o, "bad area '%s' (M, I, Q, T, C or DBn)", ar);
    }
    uint16_t start = 0;
    uint16_t len = 32;
    if (a->n >= 3u && !parse_num16(a->tok[2], &start)) {
        return fail(o, "bad start '%s'", a->tok[2]);
    }
    if (a->n == 4u && (!parse_num16(a->tok[3], &len) || len == 0u)) {
        return fail(o, "bad length '%s'", a->tok[3]);
    }
    bool words = area == MODCP_AREA_T || area == MODCP_AREA_C;
    uint32_t maxlen = words ? DUMP_MAX_BYTES / 2u : DUMP_MAX_BYTES;
    if (len > maxlen) {
        return fail(o, "length %u too large (at most %u)", (unsigned)len, (unsigned)maxlen);
    }
    uint32_t size;
    const uint8_t *bytes = NULL;
    const uint16_t *elems = NULL;
    switch (area) {
    case MODCP_AREA_M: bytes = mem->m; size = mem->m_size; break;
    case MODCP_AREA_I: bytes = mem->i; size = mem->i_size; break;
    case MODCP_AREA_Q: bytes = mem->q; size = mem->q_size; break;
    case MODCP_AREA_T: elems = mem->t; size = mem->t_count; break;
    case MODCP_AREA_C: elems = mem->c; size = mem->c_count; break;
    default: {
        const modcp_db_t *db = modcp_plcmem_db(mem, dbno);
        if (db == NULL) {
            return fail(o, "DB%u does not exist", (unsigned)dbno);
        }
        bytes = db->data;
        size = db->size;
        break;
    }
    }
    if ((uint32_t)start + len > size || (bytes == NULL && elems == NULL)) {
        if (area == MODCP_AREA_DB) {
            return fail(o, "DB%u: %u..%u outside the DB (%u bytes)", (unsigned)dbno, (unsigned)start,
                        (unsigned)((uint32_t)start + len - 1u), (unsigned)size);
        }
        return fail(o, "%s: %u..%u outside the area (%u %s)", area_name(area), (unsigned)start,
                    (unsigned)((uint32_t)start + len - 1u), (unsigned)size,
                    words ? "elements" : "bytes");
    }
    uint32_t per = words ? DUMP_PER_LINE / 2u : DUMP_PER_LINE;
    for (uint32_t i = 0; i < len; i += per) {
        out_nl(o);
        uint32_t at = (uint32_t)start + i;
        if (area == MODCP_AREA_DB) {
            out_printf(o, "DB%u.DBB%lu:", (unsigned)dbno, (unsigned long)at);
        } else if (words) {
            out_printf(o, "%s%lu:", area_name(area), (unsigned long)at);
        } else {
            out_printf(o, "%sB%lu:", area_name(area), (unsigned long)at);
        }
        for (uint32_t k = i; k < len && k < i + per; k++) {
            if (words) {
                out_printf(o, " %04X", (unsigned)elems[start + k]);
            } else {
                out_printf(o, " %02X", (unsigned)bytes[start + k]);
            }
        }
    }
    return MODCP_CONSOLE_OK;
}

static int cmd_diag(modcp_console_env_t *env, out_t *o)
{
    const modcp_diag_t *d = env->diag;
    if (d == NULL) {
        return fail(o, "diagnostics not available");
    }
    char flags[8];
    size_t fl = 0;
    if ((d->systat_flags & MODCP_SYSTAT_F) != 0u) {
        flags[fl++] = 'F';
    }
    if ((d->systat_flags & MODCP_SYSTAT_U) != 0u) {
        flags[fl++] = 'U';
    }
    if ((d->systat_flags & MODCP_SYSTAT_B) != 0u) {
        flags[fl++] = 'B';
    }
    if (fl == 0u) {
        flags[fl++] = '-';
    }
    flags[fl] = '\0';
    unsigned n = d->buffer_len <= MODCP_DIAG_BUFFER ? d->buffer_len : MODCP_DIAG_BUFFER;
    out_printf(o, "diag: %u events (newest first), total %lu, STATUS 0x%04X, SYSTAT %s", n,
               (unsigned long)d->events_total, (unsigned)d->status, flags);
    for (unsigned i = 0; i < n; i++) {
        modcp_event_t ev = d->buffer[i];
        char en[16];
        (void)modcp_console_event_name(ev, en, sizeof en);
        out_nl(o);
        out_printf(o, "event %u: %s class %02XH %s, number %02XH: %s. Remedy: %s", i + 1u, en,
                   (unsigned)MODCP_EVENT_CLASS(ev), class_text(MODCP_EVENT_CLASS(ev)),
                   (unsigned)MODCP_EVENT_NUMBER(ev), modcp_event_text(ev), modcp_event_remedy(ev));
    }
    return MODCP_CONSOLE_OK;
}

static int cmd_status(modcp_console_env_t *env, out_t *o)
{
    out_printf(o, "status:");
    if (env->fb != NULL) {
        const modcp_fb_t *fb = env->fb;
        out_printf(o, " fb=%s cp_start_ok=%u cp_start_error=%u cp_start_ndr=%u error_nr=%u"
                      " error_info=0x%04X jobs=%lu",
                   modcp_console_fb_state(fb->state), fb->out.cp_start_ok ? 1u : 0u,
                   fb->out.cp_start_error ? 1u : 0u, fb->out.cp_start_ndr ? 1u : 0u,
                   (unsigned)fb->out.error_nr, (unsigned)fb->out.error_info,
                   (unsigned long)fb->jobs_done);
    }
    if (env->paused != NULL) {
        out_printf(o, " paused=%u", *env->paused ? 1u : 0u);
    }
    out_printf(o, " cycles=%lu", (unsigned long)env->cycles);
    char en[16];
    (void)modcp_console_event_name(env->cp_param_event, en, sizeof en);
    out_printf(o, " cp=%s param_event=%s",
               env->cp_ready ? "ready" : (env->cp_configured ? "configured" : "not-configured"),
               env->cp_param_event == MODCP_EV_NONE ? "none" : en);
    const modcp_diag_t *d = env->diag;
    if (d != NULL) {
        out_printf(o, " bus_msg=%u bus_crc=%u exceptions=%u slave_msg=%u no_response=%u nak=%u"
                      " busy=%u overrun=%u events=%lu char_errors=%u breaks=%u too_long=%u t15=%u",
                   (unsigned)d->counters[MODCP_CNT_BUS_MSG], (unsigned)d->counters[MODCP_CNT_BUS_CRC],
                   (unsigned)d->counters[MODCP_CNT_EXCEPTION],
                   (unsigned)d->counters[MODCP_CNT_SLAVE_MSG],
                   (unsigned)d->counters[MODCP_CNT_NO_RESPONSE], (unsigned)d->counters[MODCP_CNT_NAK],
                   (unsigned)d->counters[MODCP_CNT_BUSY],
                   (unsigned)d->counters[MODCP_CNT_CHAR_OVERRUN], (unsigned long)d->events_total,
                   (unsigned)d->char_errors, (unsigned)d->breaks, (unsigned)d->frames_too_long,
                   (unsigned)d->t15_discards);
#if MODCP_WITH_EXTENDED
        /* extended set: FC08 sub 04 listen-only, comm-loss supervision (MODCP_CPST_*) */
        out_printf(o, " listen_only=%u commloss=%u comm_events=%u",
                   d->comm.listen_only ? 1u : 0u,
                   (env->cp_status != NULL && (env->cp_status->flags & MODCP_CPST_COMMLOSS)) ? 1u : 0u,
                   (unsigned)d->comm.event_count);
#endif
    }
    const modcp_cp_status_t *st = env->cp_status;
    if (st != NULL) {
        static const char *const led_names[3] = {"SF", "TXD", "RXD"};
        static const struct {
            uint8_t bit;
            const char *name;
        } sig_names[4] = {{MODCP_SIGBIT_RTS, "RTS"}, {MODCP_SIGBIT_DTR, "DTR"},
                          {MODCP_SIGBIT_CTS, "CTS"}, {MODCP_SIGBIT_DSR, "DSR"}};
        out_printf(o, " leds=");
        bool any = false;
        for (unsigned k = 0; k < 3u; k++) {
            if ((st->leds & (1u << k)) != 0u) {
                out_printf(o, "%s%s", any ? "," : "", led_names[k]);
                any = true;
            }
        }
        out_printf(o, "%s signals=", any ? "" : "off");
        any = false;
        for (unsigned k = 0; k < 4u; k++) {
            if ((st->signals & sig_names[k].bit) != 0u) {
                out_printf(o, "%s%s", any ? "," : "", sig_names[k].name);
                any = true;
            }
        }
        out_printf(o, "%s%s line=%s signal_aborts=%u diag_irq=", any ? "" : "off",
                   (st->signals & MODCP_SIGBIT_AUTO) != 0u ? "(auto)" : "",
                   (st->flags & MODCP_CPST_WIRE_BREAK) != 0u ? "wire-break" : "ok",
                   (unsigned)st->signal_aborts);
        if (st->diag_irq_count == 0u) {
            out_printf(o, "none");
        } else {
            out_printf(o, "%02X.%02X.%02X.%02X(#%lu)", (unsigned)st->diag_irq[0],
                       (unsigned)st->diag_irq[1], (unsigned)st->diag_irq[2],
                       (unsigned)st->diag_irq[3], (unsigned long)st->diag_irq_count);
        }
    }
    return MODCP_CONSOLE_OK;
}

static const char *const help_lines[] = {
    "commands (operands in S7 notation, numbers decimal, 0x.. or 16#..):",
    "  get OP [float]      OP: MB1000 MW MD M1000.3 IB128 I0.1 QB256 Q.. T100 C200",
    "                      DB800.DBB0 DBW0 DBD4 DBX0.1; float: show a D operand as float",
    "  set OP VALUE        e.g. set IB128 0x5A, set M1000.3 1, set DB800.DBD4 1.5",
    "  dump AREA [START [LEN]]  hex dump, AREA = M I Q T C DBn (e.g. dump DB800 0 32)",
    "  diag                diagnostic buffer: events in words, newest first",
    "  status              FB init state and outputs, CP state, serial-line counters",
    "  pause | resume      stop / restart the cyclic user program (FB calls)",
    "  start 0|1           set the FB's CP_START input (a rising edge re-initialises)",
    "  echo TEXT           print TEXT",
    "  help                this text",
};

static int cmd_help(out_t *o)
{
    for (size_t i = 0; i < sizeof help_lines / sizeof help_lines[0]; i++) {
        out_nl(o);
        out_printf(o, "%s", help_lines[i]);
    }
    return MODCP_CONSOLE_OK;
}

static int cmd_pause(modcp_console_env_t *env, bool pause, out_t *o)
{
    if (env->paused == NULL) {
        return fail(o, "pause/resume not available");
    }
    *env->paused = pause;
    out_printf(o, "user program %s", pause ? "paused" : "running");
    return MODCP_CONSOLE_OK;
}

static int cmd_start(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    uint32_t v = 0;
    if (env->cp_start == NULL) {
        return fail(o, "CP_START not available");
    }
    if (a->n != 2u || !parse_bool(a->tok[1], &v)) {
        return fail(o, "usage: start 0|1");
    }
    *env->cp_start = v != 0u;
    out_printf(o, "CP_START = %u", (unsigned)v);
    return MODCP_CONSOLE_OK;
}

int modcp_console_exec(modcp_console_env_t *env, const char *line, char *out, size_t cap)
{
    out_t o;
    char buf[LINE_MAX_CHARS];
    args_t a;
    out_init(&o, out, cap);
    if (line == NULL || env == NULL) {
        return fail(&o, "no command");
    }
    size_t len = strlen(line);
    while (len > 0u && (line[len - 1u] == '\n' || line[len - 1u] == '\r')) {
        len--;
    }
    if (len >= sizeof buf) {
        return fail(&o, "line too long (at most %u characters)", (unsigned)(sizeof buf - 1u));
    }
    memcpy(buf, line, len);
    buf[len] = '\0';

    /* tokenize in place */
    a.n = 0;
    a.rest = "";
    char *p = buf;
    while (*p != '\0') {
        while (*p == ' ' || *p == '\t') {
            p++;
        }
        if (*p == '\0') {
            break;
        }
        if (a.n == 1u) {
            a.rest = line + (p - buf);
        }
        if (a.n == MAX_TOKENS) {
            if (a.n > 0u && ieq(a.tok[0], "echo")) {
                break;
            }
            return fail(&o, "too many arguments");
        }
        a.tok[a.n++] = p;
        while (*p != '\0' && *p != ' ' && *p != '\t') {
            p++;
        }
        if (*p != '\0') {
            *p++ = '\0';
        }
    }
    if (a.n == 0u || a.tok[0][0] == '#' || a.tok[0][0] == ';') {
        return MODCP_CONSOLE_OK; /* blank line or comment */
    }
    const char *c = a.tok[0];
    int rc;
    if (ieq(c, "get")) {
        rc = cmd_get(env, &a, &o);
    } else if (ieq(c, "set")) {
        rc = cmd_set(env, &a, &o);
    } else if (ieq(c, "dump")) {
        rc = cmd_dump(env, &a, &o);
    } else if (ieq(c, "diag")) {
        rc = a.n == 1u ? cmd_diag(env, &o) : fail(&o, "usage: diag");
    } else if (ieq(c, "status")) {
        rc = a.n == 1u ? cmd_status(env, &o) : fail(&o, "usage: status");
    } else if (ieq(c, "pause") || ieq(c, "resume")) {
        rc = a.n == 1u ? cmd_pause(env, ieq(c, "pause"), &o) : fail(&o, "usage: %s", c);
    } else if (ieq(c, "start")) {
        rc = cmd_start(env, &a, &o);
    } else if (ieq(c, "echo")) {
        size_t rl = strlen(a.rest);
        while (rl > 0u && (a.rest[rl - 1u] == '\n' || a.rest[rl - 1u] == '\r')) {
            rl--;
        }
        out_printf(&o, "%.*s", (int)rl, a.rest);
        rc = MODCP_CONSOLE_OK;
    } else if (ieq(c, "help") || ieq(c, "?")) {
        rc = cmd_help(&o);
    } else {
        char name[40];
        (void)snprintf(name, sizeof name, "%s", c);
        rc = fail(&o, "unknown command '%s' (try help)", name);
    }
    if (rc == MODCP_CONSOLE_OK) {
        out_finish(&o);
    }
    return rc;
}
