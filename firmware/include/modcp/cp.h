/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP side wired together: one object, no globals, several instances
 * possible. A port creates a modcp_cp_t, calls modcp_cp_init() with its HAL and the
 * backplane, and then feeds events:
 *   UART rx interrupt     -> modcp_cp_on_rx() / modcp_cp_on_line_error()
 *   UART DMA / FIFO       -> modcp_cp_on_rx_block() (characters back to back)
 *   one-shot timer        -> modcp_cp_on_timer()
 *   transmission complete -> modcp_cp_on_tx_done()
 *   RS232 CTS / DSR change -> modcp_cp_on_signals()  (automatic secondary signals)
 *   CP task (often)       -> modcp_cp_poll()  (backplane, job timeouts, LEDs)
 * The CP is configured by the PARAMS record the CPU side sends over the backplane;
 * until then (or with an invalid record) it is not ready and the line is ignored.
 * Members marked with a feature switch (modcp/features.h) exist only when it is on.
 * Until the FB's INIT arrives every request gets exception 04 and (0E)56H. */
#ifndef MODCP_CP_H
#define MODCP_CP_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/cpdiag.h"
#include "modcp/diag.h"
#include "modcp/features.h"
#include "modcp/hal.h"
#include "modcp/job.h"
#include "modcp/leds.h"
#include "modcp/link.h"
#include "modcp/map.h"
#include "modcp/params.h"
#include "modcp/pdu.h"
#include "modcp/signals.h"

#if MODCP_SHARED_PARAMS_BUFFER
#define MODCP_CP_BUF_SIZE                                                                    \
    (MODCP_LINK_BUF_MAX > MODCP_PARAMS_RECORD_MAX ? MODCP_LINK_BUF_MAX : MODCP_PARAMS_RECORD_MAX)
#endif

typedef struct modcp_cp {
    /* (the backplane is kept by the job, job.bp; the HAL by the link, the LEDs and the
     * signals) */
    /* (the flags and small members first, then the often used sub-structs, the params
     * and the buffers last: Thumb has 2-byte loads / stores only for a byte at offsets
     * 0..31, a halfword at 0..62, a word at 0..124 of the struct a pointer points to) */
    bool published;       /* the status area shows the CP's state (cp.c publish()) */
    bool publish_all;     /* ... and the RS232 signals are to be rewritten too */
    bool configured;      /* valid PARAMS applied */
    bool request_pending; /* a request waits for its job */
    bool ack_pending;     /* an INIT_ACK could not be sent yet */
    uint16_t record_crc;  /* modcp_bp_record_id() of the record applied ... */
    uint16_t record_len;  /* ... and its length (param_event NONE: one was applied) */
    modcp_event_t param_event; /* first fatal parameter event, NONE if configured */
    modcp_event_t ack_event;
    uint32_t err_mark_us; /* link.last_us after the last line error: when it moves on, a
                             character was received (the end of a wire break) */
    modcp_job_t job; /* (the frame that has ended is on the stack: modcp_cp_on_timer; the
                        request's PDU is at buf + 1) */
    modcp_link_t link;
    modcp_pdu_t pdu;
    /* what the PDU engine works with, set up once (cp_init): the parameters, areas,
     * diagnostics and extended state, and env.fb_ready: INIT received and acknowledged
     * (stored here only) */
    modcp_pdu_env_t env;
    /* line discipline and diagnostics (signals.c, leds.c, cpdiag.c) */
#if MODCP_WITH_RS232_SIGNALS
    modcp_sig_t sig;       /* RS232 automatic secondary signals */
#endif
    modcp_leds_t leds;     /* SF / TXD / RXD */
    modcp_cpdiag_t cpdiag; /* wire break, diagnostic interrupt, SYSTAT service */
#if MODCP_WITH_EXTENDED
    modcp_ext_t ext;       /* extended function set: comm loss, ASCII delimiter (ext.h) */
#endif
    modcp_areas_t areas;
    modcp_diag_t diag;
    modcp_params_t params;
#if MODCP_SHARED_PARAMS_BUFFER
    uint8_t buf[MODCP_CP_BUF_SIZE];            /* frame buffer (first MODCP_LINK_BUF_MAX
                                                  bytes), and the PARAMS record as it
                                                  arrives while the link is off */
#else
    uint8_t buf[MODCP_LINK_BUF_MAX];           /* frame buffer: request, then reply (ASCII:
                                                  hex-encoded in place, see link.h) */
    uint8_t record[MODCP_PARAMS_RECORD_MAX];   /* PARAMS record as it arrives */
#endif
} modcp_cp_t;

/* Set up the CP on its HAL and backplane (not ready until PARAMS and INIT arrive). */
void modcp_cp_init(modcp_cp_t *cp, const modcp_hal_t *hal, modcp_backplane_t *bp);

/* UART receive interrupt: one received character. */
void modcp_cp_on_rx(modcp_cp_t *cp, uint8_t byte, uint32_t now_us);
/* UART with DMA / FIFO: n characters back to back, the last one ended at end_us. */
void modcp_cp_on_rx_block(modcp_cp_t *cp, const uint8_t *b, uint16_t n, uint32_t end_us);
/* UART receive interrupt: a character lost to line errors (MODCP_LINE_* bits). */
void modcp_cp_on_line_error(modcp_cp_t *cp, uint8_t line_errors, uint32_t now_us);
/* The one-shot timer armed through the HAL expired. */
void modcp_cp_on_timer(modcp_cp_t *cp, uint32_t now_us);
/* The last character of the reply has left the line. */
void modcp_cp_on_tx_done(modcp_cp_t *cp, uint32_t now_us);
/* RS232 inputs CTS / DSR (true = ON), at start and on every change; used with
 * automatic secondary signals (params.rs232_auto, see modcp/signals.h). */
void modcp_cp_on_signals(modcp_cp_t *cp, bool cts, bool dsr, uint32_t now_us);
/* CP task, often: backplane, job timeouts, LEDs, status area. */
void modcp_cp_poll(modcp_cp_t *cp, uint32_t now_us);

/* Ready: configured and the FB initialised. */
bool modcp_cp_ready(const modcp_cp_t *cp);

#endif
