/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the function-code table: what the core knows about each function code, in one
 * place ([MB-APP] §6, [RTU-2003] §6, docs/extended-functions.md). Read by the PDU engine
 * (pdu.c: function sets, broadcast rule, length, quantity limit class, handler) and by
 * the RTU framing in modem mode (rtu_modem.c: where a request ends without t3.5 — its
 * length, or its byte count — and which ones a broadcast may start); the unit tests read
 * it for the quantity limit of a function code. Internal to the core. */
#ifndef MODCP_FC_TABLE_INTERNAL_H
#define MODCP_FC_TABLE_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "modcp/features.h"
#include "modcp/quantity.h"

/* Flags of a row (modcp_fc_row_t.flags; the PDU handlers see them in s->fcflags). A row
 * with no flags is no function code. */
#define F_CP341 0x01u   /* in function set cp341 (the manual's, [RTU-2003] §6) */
#define F_EXT 0x02u     /* in function set extended (docs/extended-functions.md) */
#define F_BCAST 0x04u   /* broadcast may run it (docs/diagnostics.md: FC 05, 06, 15, 16) */
#define F_ADDR 0x08u    /* start address at pdu[1..2] (s->addr) */
#define F_R32 0x10u     /* holding registers: width by the start address ([ASCII-32] §4.5) */
#define F_SCAN 0x20u    /* extended: on scanner addresses the scanner's handler runs */
#define F_WRITE 0x40u   /* writes controller memory (arms the comm-loss supervision) */
#define F_NOCOUNT 0x80u /* not counted by the FC11 event counter (FC11, FC12) */

/* modcp_fc_row_t.form: the quantity limit class (MODCP_QLIM_*, quantity at pdu[3..4],
 * limits in quantity.c) in the low bits, and the form of the request PDU (its length
 * min_len at least). */
#define FC_LIM 0x0Fu   /* the limit class */
#define FC_EXACT 0x80u /* exactly min_len bytes */
#define FC_COUNT 0x40u /* pdu[min_len - 1] is a byte count: min_len + count bytes */
#define FC_PLUS2 0x20u /* in its usual form min_len + 2 bytes (FC06's 16-bit value, FC08's
                          sub-function and data, FC43's object id): modem mode expects its
                          CRC there */
#define FC_OPEN 0x10u  /* longer forms exist (FC08, FC43; an F_R32 row of FC_PLUS2 form, FC06,
                          too while 32-bit registers are on): a wrong CRC at the usual length
                          is no end of the frame (modem mode: t3.5 ends it) */
_Static_assert(MODCP_QLIM_COUNT <= FC_LIM + 1u, "the limit classes fit FC_LIM");

/* The handlers (pdu.c handlers[]) by index; a row of a function code the build does not
 * serve names H_RW and is in no function set of it. */
#define H_RW 0u    /* pdu_rw.c: FC01 / 02 / 05 / 15, FC03 / 04 / 06 / 16 */
#define H_DIAG0 1u /* pdu_rw.c: FC08 sub 0000 (cp341 set) */
#if MODCP_WITH_EXTENDED
#define H_FC08 2u /* serial_diag.c */
#define H_FC11 3u
#define H_FC12 4u
#define H_FC17 5u /* devid.c */
#define H_FC43 6u
#define H_FC22 7u /* pdu_ext.c */
#define H_FC23 8u
#endif

typedef struct { /* 4 bytes */
    uint8_t min_len; /* request PDU length, function code included */
    uint8_t flags;   /* F_*; 0: no function code */
    uint8_t form;    /* FC_LIM class | FC_EXACT / FC_COUNT / FC_PLUS2 (| FC_OPEN) */
    uint8_t run;     /* H_*: the handler */
} modcp_fc_row_t;

/* Rows by function code up to 17H, then FC43 (2BH) and the extended set's FC08 (FC08's
 * own row is the cp341 set's). Every build holds the rows of every function code modem
 * mode knows; those of the extended set are in no function set without it. */
#define MODCP_FC_ROW_FC43 0x18u
#define MODCP_FC_ROW_FC08_EXT 0x19u
#if MODCP_WITH_EXTENDED
#define MODCP_FC_ROWS 0x1Au
#else
#define MODCP_FC_ROWS 0x19u
#endif
extern const modcp_fc_row_t modcp_fc_table[MODCP_FC_ROWS];

/* The row of function code fc whatever the function set (FC08: the cp341 set's), NULL
 * for a function code without one. */
static inline const modcp_fc_row_t *modcp_fc_row(uint8_t fc)
{
    size_t i = fc;
    if (fc == 0x2Bu) {
        i = MODCP_FC_ROW_FC43;
    } else if (fc >= MODCP_FC_ROW_FC43) {
        return NULL;
    } else {
        /* a row by its function code */
    }
    const modcp_fc_row_t *r = &modcp_fc_table[i];
    return r->flags != 0u ? r : NULL;
}

#endif
