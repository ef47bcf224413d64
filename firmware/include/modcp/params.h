/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP's parameter record (docs/parameters.md).
 *
 * modcp_params_t is the in-memory form. The binary record (what the CPU side hands
 * to the CP, what modcp-conf writes) is a portable little-endian serialisation of it:
 *   "MCPR" magic, u16 version, u16 payload length, payload, u16 CRC-16 (Modbus CRC
 *   over everything before it).
 * Validation returns one issue per bad field with the manual's event number.
 * The record's fields, widths, order, defaults, ranges and events are described once, as
 * the rows of firmware/src/params_fields.h (params.c, params_record.c, tools/conf and the
 * tables of docs/parameters.md come from them). */
#ifndef MODCP_PARAMS_H
#define MODCP_PARAMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/events.h"
#include "modcp/features.h"
#include "modcp/hal.h" /* modcp_rx_preset_t */

#define MODCP_PARAMS_VERSION 4u /* 2: rs485_mode_select ([RTU-2009] Table 5-2), quantity_limits;
                                   3: db_in_32bit_mode ([ASCII-32] §3.7);
                                   4: receive_preset ([RTU-2009] Table 5-8), commloss_auto_clear */
#define MODCP_PARAMS_RECORD_MAX 328u /* upper bound of the serialised record (checked at compile time) */

typedef enum { MODCP_PARITY_NONE = 0, MODCP_PARITY_ODD = 1, MODCP_PARITY_EVEN = 2 } modcp_parity_t;

typedef enum { MODCP_FRAMING_RTU = 0, MODCP_FRAMING_ASCII = 1 } modcp_framing_t;
typedef enum { MODCP_OPMODE_NORMAL = 0, MODCP_OPMODE_SUPPRESS = 1 } modcp_opmode_t;
typedef enum { MODCP_EOF_MANUAL = 0, MODCP_EOF_MODBUS = 1 } modcp_eof_timing_t;
typedef enum { MODCP_IFACE_RS232 = 0, MODCP_IFACE_RS422 = 1, MODCP_IFACE_RS485 = 2 } modcp_iface_t;
typedef enum { MODCP_FSET_CP341 = 0, MODCP_FSET_EXTENDED = 1 } modcp_fset_t;
typedef enum { MODCP_CPU_CP341 = 0, MODCP_CPU_CP441 = 1 } modcp_cpu_model_t; /* job limit 1024 / 450 */
/* Quantity limits (modcp/quantity.h): the manuals' (2040 bits, 127 registers in RTU) or
 * the Modbus application protocol's (2000 / 1968 bits, 125 / 123 registers), whose
 * replies always fit the 256-byte RTU ADU. */
typedef enum { MODCP_QLIMITS_MANUAL = 0, MODCP_QLIMITS_SPEC = 1 } modcp_qty_limits_t;

/* Controller memory areas. */
typedef enum {
    MODCP_AREA_NONE = 0,
    MODCP_AREA_I = 1,
    MODCP_AREA_Q = 2,
    MODCP_AREA_M = 3,
    MODCP_AREA_T = 4,
    MODCP_AREA_C = 5,
    MODCP_AREA_DB = 6,
} modcp_area_t;

/* The structs of the mapping lists with a one-byte first member are packed (GCC, Clang)
 * where the CPU loads a 2-byte member from an odd address in one instruction: no padding
 * byte after the area (one per window, 10 in modcp_params_t, 16 more with the scanner).
 * Elsewhere (Cortex-M0/M0+: byte loads would cost flash) they keep their natural layout,
 * the area in a 2-byte slot. params_record.c and params.c follow either layout
 * (MODCP_PARAMS_PACKED_LAYOUT; params.c checks it at compile time). */
#ifndef MODCP_PARAMS_PACKED_LAYOUT /* (a build may choose: 0 = natural layout) */
#if defined(__GNUC__) && !(defined(__arm__) && !defined(__ARM_FEATURE_UNALIGNED))
#define MODCP_PARAMS_PACKED_LAYOUT 1
#else
#define MODCP_PARAMS_PACKED_LAYOUT 0
#endif
#endif
#if MODCP_PARAMS_PACKED_LAYOUT
#define MODCP_PARAMS_PACKED __attribute__((packed))
#else
#define MODCP_PARAMS_PACKED
#endif

/* A bit window: Modbus bit addresses from..to (inclusive) map onto area starting at
 * byte `start` (M, Q, I, DB bytes) or element `start` (T, C, 16 bits each).
 * For DB windows `db` is the DB number. area == MODCP_AREA_NONE: window unused.
 * 9 bytes (packed; 10 otherwise). */
typedef struct MODCP_PARAMS_PACKED {
    uint8_t area;
    uint16_t from;
    uint16_t to;
    uint16_t start;
    uint16_t db;
} modcp_bitwin_t;

#define MODCP_COIL_WINDOWS 6  /* FC01/05/15: M, Q, T, C + two DB-bit windows */
#define MODCP_INPUT_WINDOWS 4 /* FC02: M, I + two DB-bit windows */

typedef struct {
    uint16_t min;
    uint16_t max; /* 0 = area not writable */
} modcp_limit_t;

/* 32-bit register range ([ASCII-32] §4.5): registers from..to map onto DB `db`; int32 and
 * float registers are 4 bytes (DBD), int16 registers 2 bytes (DBW), as in the manual's
 * examples (3050 -> DBW100). */
typedef enum { MODCP_R32_INT16 = 0, MODCP_R32_INT32 = 1, MODCP_R32_FLOAT = 2 } modcp_r32_kind_t;
typedef struct {
    uint16_t from;
    uint16_t to;
    uint16_t db;
} modcp_r32range_t;

/* An operand a scanner register points at (word operands: MW, IW, QW, DBn.DBWm, T, C);
 * 5 bytes (packed; 6 otherwise). */
typedef struct MODCP_PARAMS_PACKED {
    uint8_t area;    /* modcp_area_t; NONE = unused entry */
    uint16_t db;     /* DB number for MODCP_AREA_DB */
    uint16_t offset; /* byte offset (M, I, Q, DB) or element number (T, C) */
} modcp_operand_ref_t;

#define MODCP_SCANNER_MAX 16
#define MODCP_ID_STRING_MAX 16

typedef struct {
    /* Members grouped by width (4, 1, 2 bytes, the 2-byte arrays, the packed windows, the
     * strings) so the struct has no padding and the often-read members stay at small
     * offsets (Thumb's 2-byte loads reach byte 31, halfword 62, word 124: the limits and
     * the 32-bit ranges before the windows); the record's order is that of the rows
     * (params_fields.h), not of the members. */
    uint32_t baud; /* 300 ... 115200 */
    /* character frame */
    uint8_t data_bits;  /* RTU 8; ASCII 7 (8 allowed) */
    uint8_t parity;     /* modcp_parity_t */
    uint8_t stop_bits;  /* 1, 2 */
    /* protocol */
    uint8_t slave_addr; /* 1 ... 255 */
    uint8_t framing;    /* modcp_framing_t */
    uint8_t opmode;     /* modcp_opmode_t */
    uint8_t f_mul;      /* 1 ... 10 */
    uint8_t eof_timing; /* modcp_eof_timing_t */
    uint8_t t15_check;  /* 0 off, 1 on */
    /* interface */
    uint8_t iface;      /* modcp_iface_t */
    uint8_t rs232_auto; /* RS232 automatic secondary signals: 0 off, 1 on */
    uint8_t rx_preset;  /* modcp_rx_preset_t: receive-line preset of RS422 / RS485 */
    /* mapping */
    uint8_t regs32; /* 32-bit registers on (replaces the DB offset scheme of FC03/06/16) */
    uint8_t r32_lim_db; /* with regs32: 0 (default, [ASCII-32] §3.7, §5.4) the DB write limits lim_db
                           do not apply to the three 32-bit ranges' DBs; 1: they do */
    /* function set and CPU link */
    uint8_t fset;           /* modcp_fset_t */
    uint8_t rs485_sel;      /* [RTU-2009] Table 5-2 "enable operating-mode selection for RS485":
                               0 (default): RS485 two-wire runs in interference suppression
                               (modem) mode only, opmode normal is refused with (0E)22H;
                               1: opmode normal is allowed on RS485 too */
    uint8_t qty_limits;     /* modcp_qty_limits_t */
    uint8_t cpu_model;      /* modcp_cpu_model_t */
    uint8_t scan_count;     /* indirection scanner: 0 = off, 1 ... 16 */
    /* diagnostics */
    uint8_t diag_irq; /* diagnostic interrupt records ([VIPA-341] §8.4): 0 off (default), 1 on */
    uint8_t commloss_auto; /* comm loss: 0 (default) latched until the CPU side resets it
                              ([ALTIVAR] §7, SLF1), 1: cleared by the next valid request */
    /* 16-bit members */
    uint16_t ascii_timeout_ms; /* protocol: 1 ... 6500 */
    uint16_t turnaround_ms;    /* interface: RS485 delay before the reply, 0 ... 100 */
    uint16_t rts_on_delay_ms;  /* data output waiting time (RTS on -> CTS expected) */
    uint16_t rts_off_delay_ms; /* time to RTS off after the last character */
    uint16_t hr_base_db;       /* FC03/06/16, 1 ... 65535 */
    uint16_t ir_base_db;       /* FC04, 1 ... 65535 */
    uint16_t job_limit;        /* bytes per CPU job; 0 = the model's limit (1024 / 450) */
    uint16_t cpu_timeout_ms;   /* CPU job timeout */
    uint16_t start_time_ms;    /* FB init time (START_TIME) */
    uint16_t commloss_ms;      /* 0 off, 100 ... 30000 */
    uint16_t scan_start;       /* indirection scanner: first scanner register address */
    /* write limits */
    modcp_limit_t lim_db; /* resulting DB numbers */
    modcp_limit_t lim_m;  /* flag bytes */
    modcp_limit_t lim_q;  /* output bytes */
    /* mapping */
    modcp_r32range_t r32[3]; /* indexed by modcp_r32_kind_t */
    modcp_bitwin_t coils[MODCP_COIL_WINDOWS];   /* FC01/05/15 */
    modcp_bitwin_t inputs[MODCP_INPUT_WINDOWS]; /* FC02 */
#if MODCP_WITH_EXTENDED
    /* Kept only with the extended set (164 bytes): without it the record still carries
     * them (one record for every build), the decoder skips them and scan_count must be
     * 0 (params.c). The strings come first so that every row's member starts below byte
     * 255 (params_fields.h: the rows keep one-byte offsets). */
    /* device identification (extended set), NUL-terminated */
    char vendor[MODCP_ID_STRING_MAX + 1];
    char product[MODCP_ID_STRING_MAX + 1];
    char revision[MODCP_ID_STRING_MAX + 1];
    char app_name[MODCP_ID_STRING_MAX + 1];
    modcp_operand_ref_t scan[MODCP_SCANNER_MAX]; /* indirection scanner entries */
#endif
} modcp_params_t;

/* Field identifiers, used in validation issues so tools can name section/key. */
typedef enum {
    MODCP_PF_RECORD = 0,
    MODCP_PF_BAUD,
    MODCP_PF_DATA_BITS,
    MODCP_PF_PARITY,
    MODCP_PF_STOP_BITS,
    MODCP_PF_SLAVE_ADDR,
    MODCP_PF_FRAMING,
    MODCP_PF_OPMODE,
    MODCP_PF_FMUL,
    MODCP_PF_EOF_TIMING,
    MODCP_PF_T15_CHECK,
    MODCP_PF_ASCII_TIMEOUT,
    MODCP_PF_IFACE,
    MODCP_PF_TURNAROUND,
    MODCP_PF_RS232_AUTO,
    MODCP_PF_RTS_ON_DELAY,
    MODCP_PF_RTS_OFF_DELAY,
    MODCP_PF_COILS,  /* index = window */
    MODCP_PF_INPUTS, /* index = window */
    MODCP_PF_HR_BASE,
    MODCP_PF_IR_BASE,
    MODCP_PF_REGS32,
    MODCP_PF_R32,    /* index = kind */
    MODCP_PF_LIM_DB,
    MODCP_PF_LIM_M,
    MODCP_PF_LIM_Q,
    MODCP_PF_FSET,
    MODCP_PF_CPU_MODEL,
    MODCP_PF_JOB_LIMIT,
    MODCP_PF_CPU_TIMEOUT,
    MODCP_PF_START_TIME,
    MODCP_PF_COMMLOSS,
    MODCP_PF_SCANNER, /* index = entry, 0xFF = start/count */
    MODCP_PF_ID_STRING,
    MODCP_PF_DIAG_IRQ,
    MODCP_PF_RS485_SEL,
    MODCP_PF_QTY_LIMITS,
    MODCP_PF_R32_LIM_DB,
    MODCP_PF_RX_PRESET,
    MODCP_PF_COMMLOSS_AUTO,
    MODCP_PF_COUNT
} modcp_param_field_t;

/* The rule a field breaks (the reason of an issue; tools/conf says it in words). */
typedef enum {
    MODCP_PR_NONE = 0,
    MODCP_PR_RANGE,   /* outside the row's range (params_fields.h: min .. max, 0 if allowed) */
    MODCP_PR_RULE,    /* in the range, refused by the row's further rule (MODCP_PF_CUSTOM) */
    MODCP_PR_AREA,    /* a window's or scanner entry's area is not allowed there: the area */
    MODCP_PR_FROM_TO, /* from > to (a write limit: min > max): from << 16 | to */
    MODCP_PR_DB_ZERO, /* DB 0 (a write limit: DB MIN 0) */
    MODCP_PR_TC_SIZE, /* a T/C window is not whole 16-bit elements: its size in bits */
    MODCP_PR_EXTENT,  /* ends beyond byte / element 65535 (a 32-bit range: its bytes, more than
                         one DB; a scanner entry: its offset) */
    MODCP_PR_OVERLAP, /* overlaps an earlier window / range: the index of that one (other) */
    MODCP_PR_SAME_DB  /* a 32-bit range on the DB of an earlier one (other): the DB number */
} modcp_param_rule_t;

typedef struct {
    uint8_t field;       /* modcp_param_field_t */
    uint8_t index;       /* window / range / entry index where the field is an array */
    modcp_event_t event; /* the manual's event, e.g. MODCP_EV_SLAVE_ADDR */
    bool fatal;          /* true: CP stays not ready; false: corrected (e.g. f_MUL -> 1) */
    uint8_t rule;        /* modcp_param_rule_t: which rule the value breaks */
    uint8_t other;       /* OVERLAP, SAME_DB: the earlier entry's index; else 0xFF */
    uint32_t value;      /* the offending value */
} modcp_param_issue_t;

/* Defaults of docs/parameters.md (no mapping windows, all writes disabled). */
void modcp_params_defaults(modcp_params_t *p);

/* Serialise to buf (cap bytes). Returns the record length, or 0 if cap is too small. */
size_t modcp_params_encode(const modcp_params_t *p, uint8_t *buf, size_t cap);

/* Parse a record. Returns MODCP_EV_NONE or MODCP_EV_PARAM_RECORD (bad magic, version,
 * length or CRC); p is fully written only on success. Does not validate field values. */
modcp_event_t modcp_params_decode(const uint8_t *buf, size_t len, modcp_params_t *p);

/* End-of-frame gap in microseconds for RTU (manual table x f_MUL, or the Modbus rule). */
uint32_t modcp_params_t35_us(const modcp_params_t *p);
/* One character time in microseconds (start + data + parity + stop bits). */
uint32_t modcp_params_char_us(const modcp_params_t *p);

#endif
