/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — S7 operands for the monitor console: M1000.3, MB / MW / MD, IB.., QB.., Tn, Cn,
 * DBn.DBX/DBB/DBW/DBD; parsed, named and read / written through the controller memory
 * model (plcmem.c). Portable C11: no OS, no heap, no globals. */
#include "console_internal.h"

#include <stdio.h>
#include <string.h>

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

/* "DBn.DBXm.b", "DBn.DBBm", "DBn.DBWm", "DBn.DBDm" from p = after "DB" */
static bool parse_db_operand(const char *p, modcp_s7op_t *r)
{
    r->area = MODCP_AREA_DB;
    if (!con_parse_u16(&p, &r->db) || r->db == 0u) {
        return false;
    }
    if (p[0] != '.' || up(p[1]) != 'D' || up(p[2]) != 'B') {
        return false;
    }
    r->width = width_of(p[3]);
    if (r->width == 0xFFu) {
        return false;
    }
    p += 4;
    if (!con_parse_u16(&p, &r->offset)) {
        return false;
    }
    if (r->width == MODCP_S7_BIT && !parse_bit(&p, &r->bit)) {
        return false;
    }
    return *p == '\0';
}

/* "1000.3", "B1000", "W4", "D8" from p = after the area letter M, I or Q */
static bool parse_area_operand(const char *p, modcp_s7op_t *r)
{
    if (is_digit(*p)) {
        r->width = MODCP_S7_BIT;
        if (!con_parse_u16(&p, &r->offset) || !parse_bit(&p, &r->bit)) {
            return false;
        }
    } else {
        r->width = width_of(*p);
        if (r->width == 0xFFu || r->width == MODCP_S7_BIT) {
            return false;
        }
        p++;
        if (!con_parse_u16(&p, &r->offset)) {
            return false;
        }
    }
    return *p == '\0';
}

bool modcp_s7op_parse(const char *s, modcp_s7op_t *op)
{
    modcp_s7op_t r;
    memset(&r, 0, sizeof r);
    if (s == NULL || op == NULL) {
        return false;
    }
    char a = up(s[0]);
    bool ok = false;
    if (a == 'D' && up(s[1]) == 'B') {
        ok = parse_db_operand(s + 2, &r);
    } else if (a == 'T' || a == 'C') {
        const char *p = s + 1;
        r.area = a == 'T' ? MODCP_AREA_T : MODCP_AREA_C;
        r.width = MODCP_S7_WORD;
        ok = con_parse_u16(&p, &r.offset) && *p == '\0';
    } else if (a == 'M' || a == 'I' || a == 'Q') {
        r.area = a == 'M' ? MODCP_AREA_M : (a == 'I' ? MODCP_AREA_I : MODCP_AREA_Q);
        ok = parse_area_operand(s + 1, &r);
    }
    if (ok) {
        *op = r;
    }
    return ok;
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
