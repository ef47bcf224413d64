/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — RS232 automatic secondary signals ([RTU-2003] §2.4, [VIPA-341] §1.6; docs/parameters.md).
 *
 * Only with params.rs232_auto (interface RS232; validation refuses it otherwise):
 *  - configure: DTR = ON (CP ready), RTS = OFF. Not ready / not automatic: both OFF
 *    (also at power-on: "the outputs are OFF").
 *  - a reply: RTS = ON and the data output waiting time (rts_on_delay_ms) starts.
 *    When it has elapsed and CTS = ON the reply is sent. CTS not ON then: (07)08H,
 *    the reply is dropped, RTS = OFF.
 *  - CTS ON -> OFF while sending: (08)18H, the transmission is aborted
 *    (hal->uart_tx_abort), RTS = OFF.
 *  - after the last character (transmission complete) RTS = OFF when the time to
 *    RTS off (rts_off_delay_ms) has elapsed; the CP does not wait for CTS OFF. The
 *    link stays in TX until then: half duplex, no request is taken while RTS is ON.
 *  - receiving only while DSR = ON (characters and line errors with DSR OFF are
 *    dropped before the link). DSR ON -> OFF: (08)18H once; a send in progress
 *    (waiting for CTS or sending) is aborted and so is the frame being received.
 *    A reply that becomes ready while DSR is OFF is dropped without a second event.
 *
 * Timer: the one-shot timer is shared with the link. signals.c arms it only while the
 * link holds a reply in TURNAROUND (data output waiting time) or is in TX after the
 * last character (time to RTS off); in those states the link never arms it, and
 * modcp_sig_on_timer() claims the expiry. An early expiry re-arms the remainder, so
 * the reply never leaves before rts_on_delay and RTS never drops before rts_off_delay. */
/* Public for layout only: modcp_cp_t embeds modcp_sig_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/signals_internal.h). */
#ifndef MODCP_SIGNALS_H
#define MODCP_SIGNALS_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/diag.h"
#include "modcp/hal.h"
#include "modcp/link.h"
#include "modcp/params.h"

typedef enum {
    MODCP_SIGST_IDLE = 0, /* no reply in progress */
    MODCP_SIGST_WAIT_CTS, /* RTS ON, data output waiting time running */
    MODCP_SIGST_SENDING,  /* the reply is on the line */
    MODCP_SIGST_RTS_OFF,  /* last character sent, time to RTS off running */
} modcp_sig_state_t;

typedef struct {
    const modcp_hal_t *hal;
    modcp_diag_t *diag;
    bool enabled;          /* automatic mode configured and CP configured */
    uint32_t on_delay_us;  /* data output waiting time */
    uint32_t off_delay_us; /* time to RTS off */
    uint8_t state;         /* modcp_sig_state_t */
    uint32_t t0_us;        /* start of the running wait */
    bool cts, dsr;         /* inputs as last reported by the port (OFF until reported) */
    bool cts_missing;      /* CTS was not ON when needed ((07)08H, or OFF while sending),
                              until it is ON again: lights SF with DSR OFF ([ASCII-32] §10.1) */
    bool rts, dtr;         /* outputs as last set */
    uint16_t aborts;       /* sends and receptions aborted by CTS / DSR */
} modcp_sig_t;

#define MODCP_SIGBIT_RTS 0x01u
#define MODCP_SIGBIT_DTR 0x02u
#define MODCP_SIGBIT_CTS 0x04u
#define MODCP_SIGBIT_DSR 0x08u
#define MODCP_SIGBIT_AUTO 0x80u /* automatic mode active */

#endif
