/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — event texts and remedies in English (004 §7.5, 001 §8.2, 003 §8.5).
 * Kept in its own file so images that do not show texts do not link it. */
#include "modcp/diag.h"

typedef struct {
    modcp_event_t ev;
    const char *text;
    const char *remedy;
} event_text_t;

static const event_text_t texts[] = {
    {MODCP_EV_JOB_LENGTH, "job longer than the CPU transfer limit",
     "read or write fewer bits/registers per request, or raise job_limit"},
    {MODCP_EV_ZVZ, "character delay time exceeded inside a frame",
     "eliminate the fault in the partner or the interference on the line"},
    {MODCP_EV_CHAR_ERROR, "transmission error (parity, framing or overrun) in a character",
     "check the line for interference; check that baud, data bits, parity and stop bits match the master"},
    {MODCP_EV_BREAK, "BREAK: receive line to the partner interrupted",
     "reconnect or switch on the partner; RS422/485: check the receive wires R(A)/R(B)"},
    {MODCP_EV_FRAME_TOO_LONG, "received telegram longer than the receive buffer",
     "check the master's request length and the line for interference"},
    {MODCP_EV_CTS_TIMEOUT, "RS232: the waiting time for CTS = ON expired; reply not sent",
     "check the partner's CTS output and the cable; increase the data output waiting time"},
    {MODCP_EV_SIGNAL_OFF, "RS232: DSR = OFF or CTS = OFF before or during sending (automatic signals)",
     "check that the partner is switched on and ready, and the cable (DSR, CTS)"},
    {MODCP_EV_BCAST_FC, "broadcast not allowed with this function code",
     "broadcast only with FC 05, 06, 15, 16"},
    {MODCP_EV_ILLEGAL_FC, "received function code not allowed", "use a supported function code"},
    {MODCP_EV_QUANTITY,
     "maximum amount of bits or registers exceeded, or bit count not a multiple of 16 for T/C",
     "at most 2040 bits, 127 registers; timers/counters only in steps of 16 bits"},
    {MODCP_EV_BYTE_COUNT, "amount of bits/registers and byte_count do not match (FC 15/16)",
     "correct the amount or the byte count in the master"},
    {MODCP_EV_COIL_VALUE, "illegal coding for set/reset bit (FC 05)", "use only 0000H or FF00H"},
    {MODCP_EV_DIAG_SUBFC, "illegal diagnostic sub-function or data field (FC 08)",
     "use a supported sub-function (0000H in the cp341 function set)"},
    {MODCP_EV_CRC, "CRC/LRC of the request does not match", "check the master's CRC generation and the line"},
    {MODCP_EV_SEQUENCE, "new request before the last reply was sent",
     "increase the master's reply timeout"},
    {MODCP_EV_ASCII_START, "wrong start character (not ':')", "check the framing settings (ASCII/RTU)"},
    {MODCP_EV_ASCII_RESTART, "start character inside a telegram: reception restarted",
     "check whether the line is interrupted"},
    {MODCP_EV_ASCII_NOT_HEX, "received character is not a hex character",
     "make sure the master is in ASCII mode, not RTU"},
    {MODCP_EV_INTERNAL_SEND, "internal error: default branch in the send automaton", "restart the CP"},
    {MODCP_EV_INTERNAL_RECEIVE, "internal error: default branch in the receive automaton", "restart the CP"},
    {MODCP_EV_DATA_BITS, "number of data bits not allowed for this framing; CP not ready",
     "RTU: 8 data bits; ASCII: 7 (or 8)"},
    {MODCP_EV_FMUL, "character delay value out of range; running with the default",
     "check the parameters (f_MUL 1..10, ASCII timeout 1..6500 ms)"},
    {MODCP_EV_OPMODE, "illegal operating mode; CP not ready", "choose normal or interference suppression"},
    {MODCP_EV_SLAVE_ADDR, "illegal slave address (0 not allowed); CP not ready", "use 1..255"},
    {MODCP_EV_WRITE_LIMITS, "illegal write-access limits; CP not ready", "MIN must not exceed MAX"},
    {MODCP_EV_COIL_FROMTO, "illegal from/to combination for FC 01/05/15; CP not ready",
     "check the coil windows"},
    {MODCP_EV_INPUT_FROMTO, "illegal from/to combination for FC 02; CP not ready",
     "check the input windows"},
    {MODCP_EV_COIL_OVERLAP, "overlapping from/to windows for FC 01/05/15; CP not ready",
     "make the coil windows disjoint"},
    {MODCP_EV_INPUT_OVERLAP, "overlapping from/to windows for FC 02; CP not ready",
     "make the input windows disjoint"},
    {MODCP_EV_PARAM_RECORD, "parameter record unreadable or a parameter out of range; CP not ready",
     "check the configuration with modcp-conf check"},
    {MODCP_EV_XFER_ACK, "unexpected acknowledgement / block from the CPU side",
     "ignore unless permanent; else check the CP-CPU interface"},
    {MODCP_EV_XFER_TIMEOUT, "timeout during data transfer to the CPU",
     "check that the user program calls the FB cyclically"},
    {MODCP_EV_XFER_ERROR, "error during transfer to the CPU", "check the CP-CPU interface"},
    {MODCP_EV_XFER_STATE, "illegal state in the CP-CPU block handshake", "check the CP-CPU interface"},
    {MODCP_EV_AREA_ACCESS, "error accessing M, Q, T, C or I (area missing or too short)",
     "check that the area exists and is long enough"},
    {MODCP_EV_DB_ACCESS, "error accessing a DB: missing, too short, or DB boundary crossed",
     "check DB existence and size; do not cross a DB boundary"},
    {MODCP_EV_WORK_DB, "FB work area (instance DB) missing or too short", "check the FB's work DB"},
    {MODCP_EV_FB_TIMEOUT, "timeout while the FB executes a write job",
     "check that the user program calls the FB cyclically"},
    {MODCP_EV_ILLEGAL_JOB, "illegal job from the CPU side (message kind not allowed)",
     "check the CPU-side program: only PARAMS, INIT and REPLY messages go to the CP"},
    {MODCP_EV_TC_ALIGN, "timer/counter address not on a 16-bit boundary", "use addresses that give whole words"},
    {MODCP_EV_NO_WINDOW, "Modbus address outside the parameterised from/to areas",
     "use only parameterised addresses"},
    {MODCP_EV_WRITE_DENIED,
     "range limit: resulting DB < 1, write outside the enabled limits, or write to the FB work area",
     "restrict writes to the enabled areas"},
    {MODCP_EV_DB_OVERFLOW, "range limit: resulting DB number > 65535", "restrict access"},
    {MODCP_EV_PAST_END, "access beyond the window end or the controller area end", "restrict access"},
    {MODCP_EV_AREA_READONLY, "write access to this memory area not allowed", "write only to M and Q"},
    {MODCP_EV_FB_NOT_RUNNING, "data link not possible: communication FB not initialised",
     "call the FB cyclically; re-initialise with CP_START"},
    {MODCP_EV_FB_ERROR, "the communication FB reported an error", "see the FB's ERROR_NR / ERROR_INFO"},
    {MODCP_EV_MEI_CODE, "read device identification (FC 43/14): ReadDevId code not 01..04",
     "use 01 basic, 02 regular, 03 extended or 04 one object"},
    {MODCP_EV_COMMLOSS, "communication loss: no valid request for this slave within the supervision time",
     "check the master and the line; the flag clears with the next valid request"},
};

static const event_text_t *find(modcp_event_t ev)
{
    for (unsigned i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        if (texts[i].ev == ev) {
            return &texts[i];
        }
    }
    return 0;
}

const char *modcp_event_text(modcp_event_t ev)
{
    const event_text_t *t = find(ev);
    return t ? t->text : "unknown event";
}

const char *modcp_event_remedy(modcp_event_t ev)
{
    const event_text_t *t = find(ev);
    return t ? t->remedy : "";
}
