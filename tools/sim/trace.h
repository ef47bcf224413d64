/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — frame trace: every frame received and sent with a microsecond time
 * stamp and its meaning, decoded in the tool from the bytes (the core is untouched).
 * The text trace (--trace) reads the line (trace_obs.c) and formats with these; the
 * receive side below (sim_trace_rx / _poll) serves the per-member debugging trace
 * (MODCP_SIM_MEMBER_RX).
 *
 *   [    1.234567] master 05 03 00 50 00 02 C5 9E | slave 5 FC03 read holding registers addr 0x0050 (80) qty 2
 *   [    1.246012] slave 5 05 03 04 87 65 43 21 76 70 | FC03 reply, 4 data bytes
 *   [    2.000100] master 07 03 00 00 00 01 84 6C | not for us (slave 7)
 *   [    2.100000] event (08)36H receive error: CRC/LRC of the request does not match
 * The sender of every frame is named (master, or the slave with its address; on a bus
 * the member's name). Lines come in time order: an event raised while a request is
 * still being received is printed after that request. In ASCII a byte that is not
 * printable is shown in hex as <E9>. */
#ifndef MODCP_SIM_TRACE_H
#define MODCP_SIM_TRACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/events.h"

#define SIM_TRACE_MAX 1200u

typedef struct {
    uint8_t own_addr;
    bool ascii;
    uint64_t gap_us; /* end of a received frame: t3.5 (RTU) or the inter-character timeout */
    uint8_t rx[SIM_TRACE_MAX];
    size_t rx_len;
    bool rx_errors;
    uint64_t rx_t0;   /* time stamp of the first byte (us since start) */
    uint64_t rx_last; /* time stamp of the last byte */
    void (*print)(void *user, const char *line);
    void *user;
    char rx_label[24]; /* sender of received frames ("master") */
    char tx_label[24]; /* sender of sent frames ("slave 5", "@b slave 5") */
    char ev_label[24]; /* prefix of event lines ("" or "@b ") */
    bool any_addr;     /* a bus's trace: no request is "not for us" */
} sim_trace_t;

void sim_trace_init(sim_trace_t *t, uint8_t own_addr, bool ascii, uint64_t gap_us,
                    void (*print)(void *user, const char *line), void *user);
/* Names of the senders (NULL keeps the default) and the prefix of event lines. */
void sim_trace_labels(sim_trace_t *t, const char *rx, const char *tx, const char *ev);
/* A received character (errors: MODCP_LINE_*), at t us since start. */
void sim_trace_rx(sim_trace_t *t, uint8_t byte, uint8_t errors, uint64_t t_us);
/* Ends a received frame after the gap. */
void sim_trace_poll(sim_trace_t *t, uint64_t t_us);

/* A trace line's length at most */
#define SIM_TRACE_LINE 4096u
/* A frame's trace line without its time: "LABEL BYTES | meaning[ NOTE]"; errors: a line
 * error in it. */
void sim_trace_format(const sim_trace_t *t, const char *label, const uint8_t *buf, size_t len,
                      bool reply, bool errors, const char *note, char *out, size_t cap);
/* An event's trace line without its time: "PREFIXevent (08)36H receive error: ...". */
void sim_trace_format_event(const char *prefix, modcp_event_t ev, char *out, size_t cap);
/* "[    1.234567] text" to the trace's print function. */
void sim_trace_print(sim_trace_t *t, const char *text, uint64_t t_us);

/* Meaning of a PDU (pdu[0] = function code) in words. */
void sim_describe_pdu(const uint8_t *pdu, size_t len, bool reply, char *out, size_t cap);

/* The value of a hex digit 0-9 A-F a-f, -1 for any other character. */
int sim_hex_value(uint8_t c);

#endif
