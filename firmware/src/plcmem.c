/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — controller memory model (CPU side only).
 *
 * Every access is checked completely before anything is copied, in uint32 arithmetic
 * (offset + length cannot wrap), so a refused access never writes a single byte.
 * T and C elements travel high byte first (controller byte order). */
#include "modcp/plcmem.h"

#include <stddef.h>
#include <string.h>
#include "plcmem_internal.h"

modcp_db_t *modcp_plcmem_db(const modcp_plcmem_t *mem, uint16_t number)
{
    return modcp_plcmem_find_db(mem, number);
}

void modcp_plcmem_areas(const modcp_plcmem_t *mem, modcp_areas_t *out)
{
    out->i_bytes = mem->i_size;
    out->q_bytes = mem->q_size;
    out->m_bytes = mem->m_size;
    out->timers = mem->t_count;
    out->counters = mem->c_count;
    out->work_db = 0;
}

/* The element storage of a T / C operand covering n elements, or NULL. */
static uint16_t *word_area(const modcp_plcmem_t *mem, const modcp_operand_t *op, uint32_t n)
{
    uint16_t *base = NULL;
    uint32_t count = 0;
    if (op->area == (uint8_t)MODCP_AREA_T) {
        base = mem->t;
        count = mem->t_count;
    } else if (op->area == (uint8_t)MODCP_AREA_C) {
        base = mem->c;
        count = mem->c_count;
    } else {
        /* I, Q, M: base and count set above */
    }
    if (base == NULL || (uint32_t)op->offset + n > count) {
        return NULL;
    }
    return base + op->offset;
}

static bool is_word_area(uint8_t area)
{
    return area == (uint8_t)MODCP_AREA_T || area == (uint8_t)MODCP_AREA_C;
}

modcp_event_t modcp_plcmem_read(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                uint8_t *out, uint16_t len)
{
    if (is_word_area(op->area)) {
        if ((len & 1u) != 0u) {
            return MODCP_EV_AREA_ACCESS; /* half an element */
        }
        uint32_t n = (uint32_t)len / 2u;
        const uint16_t *w = word_area(mem, op, n);
        if (w == NULL) {
            return MODCP_EV_AREA_ACCESS;
        }
        for (uint32_t k = 0; k < n; k++) {
            out[2u * k] = (uint8_t)(w[k] >> 8);
            out[2u * k + 1u] = (uint8_t)(w[k] & 0xFFu);
        }
        return MODCP_EV_NONE;
    }
    modcp_event_t ev;
    const uint8_t *src = modcp_plcmem_byte_area(mem, op, len, &ev);
    if (src == NULL) {
        return ev;
    }
    if (len > 0u) {
        (void)memcpy(out, src, len);
    }
    return MODCP_EV_NONE;
}

modcp_event_t modcp_plcmem_write(modcp_plcmem_t *mem, const modcp_operand_t *op,
                                 const uint8_t *in, uint16_t len)
{
    if (is_word_area(op->area)) {
        if ((len & 1u) != 0u) {
            return MODCP_EV_AREA_ACCESS;
        }
        uint32_t n = (uint32_t)len / 2u;
        uint16_t *w = word_area(mem, op, n);
        if (w == NULL) {
            return MODCP_EV_AREA_ACCESS;
        }
        for (uint32_t k = 0; k < n; k++) {
            w[k] = (uint16_t)(((unsigned)in[2u * k] << 8) | (unsigned)in[2u * k + 1u]);
        }
        return MODCP_EV_NONE;
    }
    modcp_event_t ev;
    uint8_t *dst = modcp_plcmem_byte_area(mem, op, len, &ev);
    if (dst == NULL) {
        return ev;
    }
    if (len > 0u) {
        (void)memcpy(dst, in, len);
    }
    return MODCP_EV_NONE;
}

modcp_event_t modcp_plcmem_locate(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                  uint16_t len, uint8_t **bytes)
{
    *bytes = NULL;
    if (is_word_area(op->area)) {
        return (len & 1u) == 0u && word_area(mem, op, (uint32_t)len / 2u) != NULL
                   ? MODCP_EV_NONE
                   : MODCP_EV_AREA_ACCESS;
    }
    modcp_event_t ev;
    *bytes = modcp_plcmem_byte_area(mem, op, len, &ev);
    return ev;
}

/* Bytes a bit operand touches (op->bit may exceed 7). */
static uint32_t bit_span(const modcp_operand_t *op)
{
    return op->count == 0u ? 0u : ((uint32_t)op->bit + op->count - 1u) / 8u + 1u;
}

modcp_event_t modcp_plcmem_locate_bits(const modcp_plcmem_t *mem, const modcp_operand_t *op,
                                       uint8_t **bytes)
{
    *bytes = NULL;
    if (is_word_area(op->area)) {
        return MODCP_EV_AREA_ACCESS; /* T / C are words, never bit-written */
    }
    modcp_event_t ev;
    *bytes = modcp_plcmem_byte_area(mem, op, bit_span(op), &ev);
    return ev;
}

/* Destination byte k takes its low sh bits from source byte k - 1 (shifted down) and
 * its high bits from source byte k (shifted up). */
void modcp_bits_put(uint8_t *dst, uint32_t first, uint32_t count, const uint8_t *bits)
{
    if (count == 0u) {
        return;
    }
    dst = &dst[first / 8u];
    unsigned sh = first & 7u;
    uint32_t end = sh + count;       /* one past the last bit, counted from dst[0] bit 0 */
    uint32_t last = (end - 1u) / 8u; /* the last destination byte */
    uint32_t sbytes = (count + 7u) / 8u;
    unsigned head = (0xFFu << sh) & 0xFFu;
    unsigned tail = 0xFFu >> (7u - ((end - 1u) & 7u));
    if (last == 0u) {
        unsigned mask = head & tail;
        dst[0] = (uint8_t)((dst[0] & ~mask) | (((unsigned)bits[0] << sh) & mask));
        return;
    }
    if (sh == 0u) { /* byte-aligned: whole source bytes as they are */
        (void)memcpy(dst, bits, last);
        dst[last] = (uint8_t)((dst[last] & ~tail) | (bits[last] & tail));
        return;
    }
    unsigned cur = bits[0];
    dst[0] = (uint8_t)((dst[0] & ~head) | ((cur << sh) & head));
    unsigned carry = cur >> (8u - sh);
    for (uint32_t k = 1; k < last; k++) {
        cur = bits[k]; /* k < last <= sbytes: inside the source */
        dst[k] = (uint8_t)((cur << sh) | carry);
        carry = cur >> (8u - sh);
    }
    cur = last < sbytes ? bits[last] : 0u;
    dst[last] = (uint8_t)((dst[last] & ~tail) | (((cur << sh) | carry) & tail));
}

modcp_event_t modcp_plcmem_write_bits(modcp_plcmem_t *mem, const modcp_operand_t *op,
                                      const uint8_t *bits)
{
    uint8_t *dst;
    modcp_event_t ev = modcp_plcmem_locate_bits(mem, op, &dst);
    if (dst != NULL) {
        modcp_bits_put(dst, op->bit, op->count, bits);
    }
    return ev;
}
