/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — monitor console: the answer buffer and the scanning of numbers and words.
 * Portable C11: no OS, no heap, no globals. */
#include "console_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- answer buffer ---------------------------------------------------------- */

void con_out_init(out_t *o, char *buf, size_t cap)
{
    o->buf = buf;
    o->cap = cap;
    o->len = 0;
    o->overflow = false;
    if (cap > 0u) {
        buf[0] = '\0';
    }
}

void con_printf(out_t *o, const char *fmt, ...)
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
void con_nl(out_t *o)
{
    if (o->len > 0u) {
        con_printf(o, "\n");
    }
}

void con_finish(out_t *o)
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

int con_fail(out_t *o, const char *fmt, ...)
{
    o->len = 0;
    o->overflow = false;
    if (o->cap == 0u) {
        return MODCP_CONSOLE_ERROR;
    }
    o->buf[0] = '\0';
    con_printf(o, "error: ");
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

/* ---- scanning ------------------------------------------------------------------ */

bool con_ieq(const char *a, const char *b)
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

bool con_parse_u16(const char **s, uint16_t *v)
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

bool con_parse_int(const char *s, unsigned bits, uint32_t *out)
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

bool con_parse_bool(const char *s, uint32_t *out)
{
    if (con_ieq(s, "1") || con_ieq(s, "true") || con_ieq(s, "on")) {
        *out = 1u;
        return true;
    }
    if (con_ieq(s, "0") || con_ieq(s, "false") || con_ieq(s, "off")) {
        *out = 0u;
        return true;
    }
    return false;
}
