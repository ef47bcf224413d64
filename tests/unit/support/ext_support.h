/* SPDX-License-Identifier: Apache-2.0 */
/* Test helpers of the extended function set (test_extended.c, test_scanner.c,
 * test_commloss.c): requests and replies as PDUs, the CRC checked and added here. */
#ifndef MODCP_TEST_EXT_SUPPORT_H
#define MODCP_TEST_EXT_SUPPORT_H

#include <stdint.h>

#include "world.h"

/* Send the PDU "03 00 50 00 02" to slave addr (CRC appended), run until the reply
 * (or max_ms). Returns the reply PDU length (0 = no reply); the reply's address and
 * CRC are checked. */
uint16_t ext_request(world_t *w, uint8_t addr, const char *pdu_hex, uint32_t max_ms);
/* The last reply's PDU as "03 04 87 65 43 21" (static buffer). */
const char *ext_reply(const world_t *w);
/* ext_request to addr and compare the reply PDU. */
void ext_expect(world_t *w, uint8_t addr, const char *pdu_hex, const char *reply_pdu_hex);
/* ext_request and expect exception `code` for the request's function code, and ev
 * as the newest event. */
void ext_expect_exception(world_t *w, uint8_t addr, const char *pdu_hex, uint8_t code,
                          modcp_event_t ev);
/* ext_request and expect no reply within 100 ms. */
void ext_expect_silence(world_t *w, uint8_t addr, const char *pdu_hex);
/* A frame for addr with a wrong CRC: silence. */
void ext_bad_crc(world_t *w, uint8_t addr, const char *pdu_hex);
/* A UART line error (MODCP_LINE_*) as a frame of its own, then t3.5 of silence. */
void ext_line_error(world_t *w, uint8_t flags);
/* FC08 counter sub-function (0B..12) read through the line. */
uint16_t ext_counter(world_t *w, uint8_t addr, uint8_t sub);
/* A started world (CP_START_OK) with params p (NULL: [RTU-2003] §9 example set). */
world_t *ext_started(const modcp_params_t *p);
/* The CP status area as the CPU side reads it. */
modcp_cp_status_t ext_status(world_t *w);

#endif
