/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — diagnostics store (docs/diagnostics.md). Everyone reports events here; nobody else
 * stores them.
 *  - diagnostic buffer: the last 9 events, newest first ([VIPA-341] §8.3)
 *  - SYSTAT: first 6 events since the last read, F/U/B flags ([RTU-2003] §7.4), clear on read
 *  - STATUS word: last event, class in bits 12..8, number in 7..0 ([VIPA-341] §8.1)
 *  - per-event counters and the Modbus serial-line counters (FC08 0B..12) */
#ifndef MODCP_DIAG_H
#define MODCP_DIAG_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/commlog.h"
#include "modcp/events.h"
#include "modcp/features.h"

#define MODCP_DIAG_BUFFER 9u
#define MODCP_SYSTAT_EVENTS 6u
#define MODCP_COMM_LOG 64u

/* SYSTAT image byte 2 flags and byte 0 states ([RTU-2003] §7.4). */
#define MODCP_SYSTAT_F 0x01u
#define MODCP_SYSTAT_U 0x02u
#define MODCP_SYSTAT_B 0x04u
#define MODCP_SYSTAT_RUN 0x02u
#define MODCP_SYSTAT_FAULT 0x05u

/* Modbus serial-line counters (Modbus over Serial Line V1.02 §6.1). */
typedef enum {
    MODCP_CNT_BUS_MSG = 0,   /* 0B: messages the slave detected on the bus (CRC ok) */
    MODCP_CNT_BUS_CRC,       /* 0C: CRC errors */
    MODCP_CNT_EXCEPTION,     /* 0D: exception responses returned */
    MODCP_CNT_SLAVE_MSG,     /* 0E: messages addressed to us (incl. broadcast) */
    MODCP_CNT_NO_RESPONSE,   /* 0F: messages not answered (broadcast, listen-only) */
    MODCP_CNT_NAK,           /* 10 */
    MODCP_CNT_BUSY,          /* 11 */
    MODCP_CNT_CHAR_OVERRUN,  /* 12: character overruns */
    MODCP_CNT_COUNT
} modcp_counter_t;

/* From events_total to buffer_len the fields are in the order of the CP status area
 * (modcp/backplane.h): cp.c publishes them as one copy (static asserts in cp.c). */
typedef struct {
    uint32_t events_total;
    uint16_t counters[MODCP_CNT_COUNT];
    uint16_t frames_too_long;
    uint16_t char_errors;
    uint16_t breaks;
    uint16_t t15_discards;
    uint16_t status;      /* last event as STATUS word */
    modcp_event_t buffer[MODCP_DIAG_BUFFER]; /* newest first */
    uint8_t buffer_len;
    uint8_t systat_len;   /* events entered in SYSTAT since the last read (0..6) */
    /* from here on SYSTAT as its image ([RTU-2003] §7.4) from byte 2: one copy reads it */
    uint8_t systat_flags; /* MODCP_SYSTAT_F | U | B */
    uint8_t systat_zero;  /* image byte 3: always 0 */
    uint8_t systat[2u * MODCP_SYSTAT_EVENTS]; /* the events, high byte (class) first */
#if MODCP_WITH_EXTENDED
    modcp_comm_t comm; /* FC11 / FC12 event counter and log, listen-only (commlog.h) */
#endif
} modcp_diag_t;

/* Text of an event in English (simulator / console; "unknown event" if unknown). */
const char *modcp_event_text(modcp_event_t ev);
/* Remedy of an event in English (simulator / console; "" if unknown). */
const char *modcp_event_remedy(modcp_event_t ev);
/* Name of an event class in English ("receive error"; "other event" if unknown). */
const char *modcp_event_class_text(uint8_t cls);

#endif
