/* SPDX-License-Identifier: Apache-2.0 */
/* Helpers shared by the C test masters (master_libmodbus, master_ext, master_regs32):
 * pass/fail bookkeeping, hex strings, an independent bitwise Modbus CRC (deliberately
 * not the core's table code), and reading a reply of known length with a deadline. */
#ifndef MODCP_MASTER_UTIL_H
#define MODCP_MASTER_UTIL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

extern int passed, failed; /* checks so far; the masters print "N passed, M failed" */
extern bool verbose;       /* print passing checks too */

/* Count one check; print it when it fails (or always with verbose). */
void ok(bool cond, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
double now_s(void);
/* "05 03 00 50" -> bytes (at most cap); exits with 3 on a malformed string. */
size_t hex(const char *s, uint8_t *out, size_t cap);
/* bytes -> "05 03 00 50" */
void fmt_hex(const uint8_t *b, size_t n, char *out, size_t cap);
uint16_t crc16(const uint8_t *p, size_t n);
/* Append the CRC (low byte first); returns the new length. */
size_t add_crc(uint8_t *b, size_t n);
/* Read until `want` bytes arrived on fd or wait_ms passed; returns the bytes read. */
int read_want(int fd, uint8_t *rsp, size_t want, int wait_ms);

#endif
