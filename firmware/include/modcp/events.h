/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — event words (class byte << 8 | number byte), as tabled in the manuals.
 * 004 §7.5 (classes 05H, 08H, 0EH), 001 §8.2 (08 16H over-long telegram),
 * 003 §8.5 (08 38H..3AH ASCII). Extensions of modcp are marked "modcp". */
#ifndef MODCP_EVENTS_H
#define MODCP_EVENTS_H

#include <stdint.h>

typedef uint16_t modcp_event_t; /* 0 = no event */

#define MODCP_EVENT(cls, num) ((modcp_event_t)((((unsigned)(cls)) << 8) | (unsigned)(num)))
#define MODCP_EVENT_CLASS(ev) ((uint8_t)((ev) >> 8))
#define MODCP_EVENT_NUMBER(ev) ((uint8_t)((ev)&0xFFu))

enum {
    MODCP_EV_NONE = 0x0000,

    /* class 05H: CPU job errors */
    MODCP_EV_JOB_LENGTH = 0x0518, /* job longer than the CPU transfer limit */

    /* class 07H: send errors (001 §8.2) */
    MODCP_EV_CTS_TIMEOUT = 0x0708,  /* RS232 auto: CTS not ON when the data output waiting time expired */

    /* class 08H: receive errors */
    MODCP_EV_ZVZ = 0x0806,          /* character delay time exceeded (t1.5 / ASCII timeout) */
    MODCP_EV_CHAR_ERROR = 0x080C,   /* parity, framing or overrun error in a character */
    MODCP_EV_BREAK = 0x080D,        /* BREAK: receive line interrupted */
    MODCP_EV_FRAME_TOO_LONG = 0x0816, /* telegram longer than the receive buffer (001 §8.2) */
    MODCP_EV_SIGNAL_OFF = 0x0818,   /* RS232 auto: DSR = OFF or CTS = OFF before/during sending (001 §8.2) */
    MODCP_EV_BCAST_FC = 0x0830,     /* broadcast not allowed with this function code */
    MODCP_EV_ILLEGAL_FC = 0x0831,   /* function code not supported */
    MODCP_EV_QUANTITY = 0x0832,     /* quantity out of range / T,C count not multiple of 16 */
    MODCP_EV_BYTE_COUNT = 0x0833,   /* byte count does not match quantity (FC15/16) */
    MODCP_EV_COIL_VALUE = 0x0834,   /* FC05 value not FF00/0000 */
    MODCP_EV_DIAG_SUBFC = 0x0835,   /* FC08 sub-function not supported */
    MODCP_EV_CRC = 0x0836,          /* CRC (ASCII: LRC) mismatch */
    MODCP_EV_SEQUENCE = 0x0837,     /* new request before the last reply was sent */
    MODCP_EV_ASCII_START = 0x0838,  /* wrong start character (ASCII) */
    MODCP_EV_ASCII_RESTART = 0x0839, /* ':' inside a frame restarts reception (ASCII) */
    MODCP_EV_ASCII_NOT_HEX = 0x083A, /* non-hex character inside a frame (ASCII) */
    MODCP_EV_MEI_CODE = 0x083B,     /* modcp: FC43/14 ReadDevId code not 01..04 (exception 03) */

    /* class 0EH: general processing errors of the driver */
    MODCP_EV_INTERNAL_SEND = 0x0E10,
    MODCP_EV_INTERNAL_RECEIVE = 0x0E11,
    MODCP_EV_DATA_BITS = 0x0E20,     /* data bits invalid for the framing */
    MODCP_EV_FMUL = 0x0E21,          /* f_MUL outside 1..10, runs with 1 */
    MODCP_EV_OPMODE = 0x0E22,        /* illegal operating mode */
    MODCP_EV_SLAVE_ADDR = 0x0E23,    /* illegal slave address (0) */
    MODCP_EV_WRITE_LIMITS = 0x0E24,  /* illegal write limits */
    MODCP_EV_COIL_FROMTO = 0x0E25,   /* illegal from/to FC01/05/15 */
    MODCP_EV_INPUT_FROMTO = 0x0E26,  /* illegal from/to FC02 */
    MODCP_EV_COIL_OVERLAP = 0x0E27,  /* overlapping windows FC01/05/15 */
    MODCP_EV_INPUT_OVERLAP = 0x0E28, /* overlapping windows FC02 */
    MODCP_EV_PARAM_RECORD = 0x0E2E,  /* parameter record unreadable (magic, version, CRC, length) */
    MODCP_EV_XFER_ACK = 0x0E30,      /* unexpected acknowledgement from the CPU side */
    MODCP_EV_XFER_TIMEOUT = 0x0E31,  /* timeout during data transfer to/from the CPU */
    MODCP_EV_XFER_ERROR = 0x0E32,
    MODCP_EV_XFER_STATE = 0x0E33,    /* illegal state / sequence number in the block handshake */
    MODCP_EV_AREA_ACCESS = 0x0E38,   /* M, Q, T, C, I access error (FC01/02) */
    MODCP_EV_DB_ACCESS = 0x0E39,     /* DB missing, too short, or DB boundary crossed */
    MODCP_EV_WORK_DB = 0x0E3A,       /* FB work area missing or too short (FC05/15) */
    MODCP_EV_FB_TIMEOUT = 0x0E3B,    /* timeout while the FB executes a write job */
    MODCP_EV_ILLEGAL_JOB = 0x0E3C,   /* illegal job (message kind) from the CPU side */
    MODCP_EV_TC_ALIGN = 0x0E50,      /* T/C start not on a 16-bit boundary */
    MODCP_EV_NO_WINDOW = 0x0E51,     /* address outside every from/to window */
    MODCP_EV_WRITE_DENIED = 0x0E52,  /* DB < 1, write outside limits, write to work area */
    MODCP_EV_DB_OVERFLOW = 0x0E53,   /* resulting DB > 65535 */
    MODCP_EV_PAST_END = 0x0E54,      /* past the window end or the controller area end */
    MODCP_EV_AREA_READONLY = 0x0E55, /* write to T, C or I */
    MODCP_EV_FB_NOT_RUNNING = 0x0E56, /* FB not initialised */
    MODCP_EV_FB_ERROR = 0x0E57,      /* FB reported an error */
    MODCP_EV_COMMLOSS = 0x0E60,      /* modcp: comm-loss supervision expired (no valid request
                                        for our address within commloss_ms) */
};

#endif
