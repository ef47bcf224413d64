/* SPDX-License-Identifier: Apache-2.0 */
/* Test helpers: hex frames with and without CRC. */
#ifndef MODCP_TEST_FRAMES_H
#define MODCP_TEST_FRAMES_H

#include <stddef.h>
#include <stdint.h>

/* Parse "05 03 00 50" into out; returns the byte count (asserts on bad input). */
size_t hex_frame(const char *hex, uint8_t *out, size_t cap);
/* Append the Modbus CRC (low byte first); returns the new length. */
size_t add_crc(uint8_t *buf, size_t len);

#endif
