/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console: get / set / dump over the controller memory.
 *
 *  - B and W values print as hex and unsigned decimal, D values as hex and signed
 *    int32 (or as float with the `float` keyword); T and C as hex and unsigned.
 *  - set accepts decimal, 0x.. or 16#.. hex, negative numbers (two's complement in
 *    the operand's width), and for D operands a float (a value with '.', 'e', inf,
 *    nan, or the keyword `float` after it).
 *  - dump prints at most 256 bytes (T/C: 128 elements), 16 per line.
 *  - set on T, C and I is allowed: the console is the user program's view of the
 *    controller memory, not the master's. */
#include "console_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DUMP_MAX_BYTES 256u
#define DUMP_PER_LINE 16u

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
    case MODCP_S7_BIT: con_printf(o, "%s = %u", name, (unsigned)v); break;
    case MODCP_S7_BYTE: con_printf(o, "%s = 0x%02X (%u)", name, (unsigned)v, (unsigned)v); break;
    case MODCP_S7_WORD: con_printf(o, "%s = 0x%04X (%u)", name, (unsigned)v, (unsigned)v); break;
    default:
        if (as_float) {
            char fb[40];
            format_float(bits_to_float(v), fb, sizeof fb);
            con_printf(o, "%s = %s (0x%08lX)", name, fb, (unsigned long)v);
        } else {
            long sv;
            if ((v & 0x80000000u) == 0u) {
                sv = (long)v;
            } else if (v == 0x80000000u) {
                sv = -2147483647L - 1L;
            } else {
                sv = -(long)(~v + 1u);
            }
            con_printf(o, "%s = 0x%08lX (%ld)", name, (unsigned long)v, sv);
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
    return con_ieq(q, "inf") || con_ieq(q, "nan") || con_ieq(q, "infinity");
}

/* Explain why an operand cannot be accessed. */
static int operand_error(out_t *o, const modcp_plcmem_t *mem, const modcp_s7op_t *op)
{
    char name[32];
    (void)modcp_s7op_name(op, name, sizeof name);
    if (op->area == MODCP_AREA_DB) {
        const modcp_db_t *db = modcp_plcmem_db(mem, op->db);
        if (db == NULL) {
            return con_fail(o, "%s: DB%u does not exist", name, (unsigned)op->db);
        }
        return con_fail(o, "%s: outside DB%u (%u bytes)", name, (unsigned)op->db, (unsigned)db->size);
    }
    if (op->area == MODCP_AREA_T) {
        return con_fail(o, "%s: outside T (%u timers)", name, (unsigned)mem->t_count);
    }
    if (op->area == MODCP_AREA_C) {
        return con_fail(o, "%s: outside C (%u counters)", name, (unsigned)mem->c_count);
    }
    unsigned size = op->area == MODCP_AREA_I ? mem->i_size
                                             : (op->area == MODCP_AREA_Q ? mem->q_size : mem->m_size);
    return con_fail(o, "%s: outside %s (%u bytes)", name, area_name(op->area), size);
}

/* ---- commands ------------------------------------------------------------------ */

int con_cmd_get(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_s7op_t op;
    if (env->mem == NULL) {
        return con_fail(o, "controller memory not available");
    }
    if (a->n < 2u || a->n > 3u) {
        return con_fail(o, "usage: get OPERAND [float]");
    }
    if (!modcp_s7op_parse(a->tok[1], &op)) {
        return con_fail(o, "bad operand '%s' (e.g. MB1000, M1000.3, DB800.DBW0, T100)", a->tok[1]);
    }
    bool as_float = false;
    if (a->n == 3u) {
        if (!con_ieq(a->tok[2], "float") || op.width != MODCP_S7_DWORD) {
            return con_fail(o, "'%s': only a D operand can be shown as float", a->tok[2]);
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

int con_cmd_set(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_s7op_t op;
    if (env->mem == NULL) {
        return con_fail(o, "controller memory not available");
    }
    if (a->n < 3u || a->n > 4u) {
        return con_fail(o, "usage: set OPERAND VALUE [float]");
    }
    if (!modcp_s7op_parse(a->tok[1], &op)) {
        return con_fail(o, "bad operand '%s' (e.g. MB1000, M1000.3, DB800.DBW0, T100)", a->tok[1]);
    }
    const char *vs = a->tok[2];
    bool as_float = false;
    if (a->n == 4u) {
        if (!con_ieq(a->tok[3], "float")) {
            return con_fail(o, "unexpected '%s'", a->tok[3]);
        }
        as_float = true;
    }
    if (looks_float(vs)) {
        as_float = true;
    }
    uint32_t v = 0;
    if (op.width == MODCP_S7_BIT) {
        if (as_float || !con_parse_bool(vs, &v)) {
            return con_fail(o, "bad value '%s' for a bit (0 or 1)", vs);
        }
    } else if (as_float) {
        if (op.width != MODCP_S7_DWORD) {
            return con_fail(o, "bad value '%s': floats need a D operand", vs);
        }
        char *end = NULL;
        double d = strtod(vs, &end);
        if (end == vs || *end != '\0') {
            return con_fail(o, "bad float '%s'", vs);
        }
        v = float_to_bits((float)d);
    } else if (!con_parse_int(vs, 8u * (unsigned)op.width, &v)) {
        return con_fail(o, "bad value '%s' for a %u-bit operand", vs, 8u * (unsigned)op.width);
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
    if (!con_parse_int(s, 16u, &x) || s[0] == '-') {
        return false;
    }
    *v = (uint16_t)x;
    return true;
}

/* M, I, Q, T, C or DBn */
static bool parse_dump_area(const char *ar, uint8_t *area, uint16_t *dbno)
{
    static const struct {
        const char *name;
        uint8_t area;
    } names[5] = {{"M", MODCP_AREA_M}, {"I", MODCP_AREA_I}, {"Q", MODCP_AREA_Q},
                  {"T", MODCP_AREA_T}, {"C", MODCP_AREA_C}};
    for (unsigned k = 0; k < 5u; k++) {
        if (con_ieq(ar, names[k].name)) {
            *area = names[k].area;
            return true;
        }
    }
    if (up(ar[0]) != 'D' || up(ar[1]) != 'B') {
        return false;
    }
    const char *p = ar + 2;
    *area = MODCP_AREA_DB;
    return con_parse_u16(&p, dbno) && *p == '\0' && *dbno != 0u;
}

/* One line per DUMP_PER_LINE bytes from start: "MB10: 01 02 ..", "T3: 0001 ..". */
static void dump_lines(out_t *o, uint8_t area, uint16_t dbno, uint16_t start, uint16_t len,
                       const uint8_t *bytes, const uint16_t *elems)
{
    bool words = elems != NULL;
    uint32_t per = words ? DUMP_PER_LINE / 2u : DUMP_PER_LINE;
    for (uint32_t i = 0; i < len; i += per) {
        con_nl(o);
        uint32_t at = (uint32_t)start + i;
        if (area == MODCP_AREA_DB) {
            con_printf(o, "DB%u.DBB%lu:", (unsigned)dbno, (unsigned long)at);
        } else if (words) {
            con_printf(o, "%s%lu:", area_name(area), (unsigned long)at);
        } else {
            con_printf(o, "%sB%lu:", area_name(area), (unsigned long)at);
        }
        for (uint32_t k = i; k < len && k < i + per; k++) {
            if (words) {
                con_printf(o, " %04X", (unsigned)elems[start + k]);
            } else {
                con_printf(o, " %02X", (unsigned)bytes[start + k]);
            }
        }
    }
}

int con_cmd_dump(modcp_console_env_t *env, const args_t *a, out_t *o)
{
    modcp_plcmem_t *mem = env->mem;
    if (mem == NULL) {
        return con_fail(o, "controller memory not available");
    }
    if (a->n < 2u || a->n > 4u) {
        return con_fail(o, "usage: dump M|I|Q|T|C|DBn [START [LEN]]");
    }
    const char *ar = a->tok[1];
    uint8_t area = MODCP_AREA_NONE;
    uint16_t dbno = 0;
    if (!parse_dump_area(ar, &area, &dbno)) {
        return con_fail(o, "bad area '%s' (M, I, Q, T, C or DBn)", ar);
    }
    uint16_t start = 0;
    uint16_t len = 32;
    if (a->n >= 3u && !parse_num16(a->tok[2], &start)) {
        return con_fail(o, "bad start '%s'", a->tok[2]);
    }
    if (a->n == 4u && (!parse_num16(a->tok[3], &len) || len == 0u)) {
        return con_fail(o, "bad length '%s'", a->tok[3]);
    }
    bool words = area == MODCP_AREA_T || area == MODCP_AREA_C;
    uint32_t maxlen = words ? DUMP_MAX_BYTES / 2u : DUMP_MAX_BYTES;
    if (len > maxlen) {
        return con_fail(o, "length %u too large (at most %u)", (unsigned)len, (unsigned)maxlen);
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
            return con_fail(o, "DB%u does not exist", (unsigned)dbno);
        }
        bytes = db->data;
        size = db->size;
        break;
    }
    }
    if ((uint32_t)start + len > size || (bytes == NULL && elems == NULL)) {
        if (area == MODCP_AREA_DB) {
            return con_fail(o, "DB%u: %u..%u outside the DB (%u bytes)", (unsigned)dbno, (unsigned)start,
                        (unsigned)((uint32_t)start + len - 1u), (unsigned)size);
        }
        return con_fail(o, "%s: %u..%u outside the area (%u %s)", area_name(area), (unsigned)start,
                    (unsigned)((uint32_t)start + len - 1u), (unsigned)size,
                    words ? "elements" : "bytes");
    }
    dump_lines(o, area, dbno, start, len, bytes, words ? elems : NULL);
    return MODCP_CONSOLE_OK;
}
