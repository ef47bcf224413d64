/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the parameter record described once (X-macros).
 *
 * Everything about a parameter is in one row here: its place in the record (the order of
 * the rows is the order of the binary record and of validation), its width, default,
 * legal range, the event and whether it is fatal, its INI section and key, the message
 * of a bad value, and its line in the table of docs/parameters.md. The core expands the
 * rows into the const tables of params.c / params_record.c (no strings: the text
 * columns cost no flash); tools/conf expands them into its key table and renders the
 * documentation table (`modcp-conf doc-table`, compared with docs/parameters.md by the
 * integration.conf test).
 *
 * MODCP_PARAM_ROWS(S, G, M) in record order:
 *   S(member, width, field, index, min, max, def, event, flags,
 *     section, key, syntax, names, rule, meaning, values, source)
 *       a scalar: width 1, 2 or 4 bytes (little-endian in the record), or
 *       MODCP_PW_STR: an ID string, 16 bytes (NUL-padded; the decoder terminates it).
 *       Legal: min <= v <= max, or 0 with MODCP_PF_ZERO_OK; MODCP_PF_CUSTOM: a further rule
 *       in params.c (named in the comment of the row). MODCP_PF_WARN: not fatal, the CP
 *       runs with the default. key "" = no INI key (derived from another key).
 *       syntax: NUM (number), ENUM (one of names), BOOL (on/off), STR (text).
 *   G(member, count, type, members, field)
 *       count consecutive structs from member on, each encoded as the members rows
 *       that follow (window by window); validated by its own function in params.c.
 *   M(type, member, width, count)   a member of the group above (count = the group's), in the
 *       order of the struct: 2 bytes wide, the first may be 1 byte, one after the other as
 *       in the record (a 1-byte member in a 2-byte slot unless packed, modcp/params.h)
 * The composite keys ([coils], [inputs], [registers] ranges, [limits], [scanner]
 * entries) and the tool's own [cpu] keys are documented by MODCP_PARAM_DOC_ROWS(D). */
#ifndef MODCP_PARAMS_FIELDS_H
#define MODCP_PARAMS_FIELDS_H

#include "modcp/features.h"
#include "modcp/params.h"

#define MODCP_PW_STR 16u /* width of an ID string in the record */

#define MODCP_PF_ZERO_OK 0x01u /* 0 is legal besides min .. max ("0 = off") */
#define MODCP_PF_WARN 0x02u    /* not fatal: the CP runs with the default */
#define MODCP_PF_CUSTOM 0x04u  /* a further rule in params.c */

/* The rows as the core keeps them (params.c), 7 bytes each:
 *   S: wf = width | flags << 5 (width 1, 2, 4 or MODCP_PW_STR), field != 0, min .. max the
 *      legal range (min fits a byte; a 4-byte row, the baud rate, has its own rule), max and
 *      def as MODCP_PARAM_CODE (below), event its number in class 0EH.
 *   G: wf = 0; max = count, min = size of one struct, event = number of members, def =
 *      width of the first member (1 or 2). The members follow one another in the record's
 *      order, 2 bytes wide except the first, which may be one byte: a packed struct is
 *      laid out as its bytes in the record, an unpacked one (MODCP_PARAMS_PACKED_LAYOUT 0,
 *      modcp/params.h) gives a one-byte member a 2-byte slot (params.c checks it at
 *      compile time, test_params the members' order).
 *   off: offset into modcp_params_t (every row's member starts below byte 255, the record
 *      struct keeps the long arrays last), MODCP_PARAM_ABSENT for a member this build does
 *      not keep. */
typedef struct {
    uint8_t off;
    uint8_t wf;
    uint8_t field;
    uint8_t event;
    uint8_t min;
    uint8_t max;
    uint8_t def;
} modcp_param_row_t;

/* A maximum or a default in one byte: values below 240 as they are, the larger ones as
 * 240 + their index in MODCP_PARAM_BIG (a maximum above 65535, the baud rate's, is
 * 65535: its own rule checks it). */
#define MODCP_PARAM_BIG 9600u, 1000u, 5000u, 6500u, 65530u, 65535u, 1024u, 30000u, 255u
#define MODCP_PARAM_CODE(v)                                                                       \
    (((unsigned)(v) < 240u)       ? (unsigned)(v)                                                \
     : ((unsigned)(v) == 9600u)  ? 240u                                                         \
     : ((unsigned)(v) == 1000u)  ? 241u                                                         \
     : ((unsigned)(v) == 5000u)  ? 242u                                                         \
     : ((unsigned)(v) == 6500u)  ? 243u                                                         \
     : ((unsigned)(v) == 65530u) ? 244u                                                         \
     : ((unsigned)(v) >= 65535u) ? 245u                                                         \
     : ((unsigned)(v) == 1024u)  ? 246u                                                         \
     : ((unsigned)(v) == 30000u) ? 247u                                                         \
     : ((unsigned)(v) == 255u)   ? 248u                                                         \
                                 : 0x100u)

/* A row whose member this build does not keep (modcp/params.h: the scanner entries and
 * the ID strings without MODCP_WITH_EXTENDED) has off == MODCP_PARAM_ABSENT: its bytes
 * stay in the record (encoded as zeros, skipped by the decoder), nothing validates it.
 * MODCP_PARAM_OFF(member) is the member's offset, or MODCP_PARAM_ABSENT for a member
 * listed as MODCP_PX_ABSENT_<member> below (chosen by the preprocessor, so offsetof never
 * names a missing member). The absent members are one run in record order, the scanner's
 * group first: its row (params.c ROW_SKIP) stands for the whole run
 * (MODCP_PARAM_ABSENT_BYTES), the ID strings' rows add nothing; a build that left out
 * only some of them would need a row of its own per run (unit.test_cp_manual and the
 * other manual-core tests decode the manual build's record through it). */
#define MODCP_PARAM_ABSENT 0xFFu
#if !MODCP_WITH_EXTENDED
#define MODCP_PX_ABSENT_scan MODCP_PX_PROBE
#define MODCP_PX_ABSENT_vendor MODCP_PX_PROBE
#define MODCP_PX_ABSENT_product MODCP_PX_PROBE
#define MODCP_PX_ABSENT_revision MODCP_PX_PROBE
#define MODCP_PX_ABSENT_app_name MODCP_PX_PROBE
#endif
#define MODCP_PX_PROBE ~, 1
#define MODCP_PX_SECOND(a, b, ...) b
#define MODCP_PX_IS(...) MODCP_PX_SECOND(__VA_ARGS__, 0, ~)
#define MODCP_PX_CAT_(a, b) a##b
#define MODCP_PX_CAT(a, b) MODCP_PX_CAT_(a, b)
#define MODCP_PX_IF_0(absent, present) present
#define MODCP_PX_IF_1(absent, present) absent
#define MODCP_PARAM_OFF(member)                                                                   \
    MODCP_PX_CAT(MODCP_PX_IF_, MODCP_PX_IS(MODCP_PX_ABSENT_##member))                             \
    (MODCP_PARAM_ABSENT, offsetof(modcp_params_t, member))
/* sizeof the member (0 for an ID string the build leaves out) */
#define MODCP_PARAM_SIZE(member)                                                                  \
    MODCP_PX_CAT(MODCP_PX_IF_, MODCP_PX_IS(MODCP_PX_ABSENT_##member))                             \
    ((size_t)0u, sizeof(((modcp_params_t *)0)->member))

/* The bytes a member of width w takes in its struct: a one-byte member of a group struct
 * has a 2-byte slot unless the structs are packed (modcp/params.h). */
#define MODCP_PARAM_SLOT(w) (MODCP_PARAMS_PACKED_LAYOUT ? (w) : ((w) + 1u) & ~1u)
/* The width of a group struct's first member (1 or 2; the others are 2 bytes wide), by type;
 * test_params checks that the rows list the members in the order of the struct. */
#define MODCP_PARAM_FIRST_WIDTH_modcp_bitwin_t 1u
#define MODCP_PARAM_FIRST_WIDTH_modcp_r32range_t 2u
#define MODCP_PARAM_FIRST_WIDTH_modcp_limit_t 2u
#define MODCP_PARAM_FIRST_WIDTH_modcp_operand_ref_t 1u
#define MODCP_PARAM_WIDTH(r) ((uint8_t)((r)->wf & 0x1Fu))
#define MODCP_PARAM_FLAGS(r) ((uint8_t)((r)->wf >> 5))


#define MODCP_PARAM_ROWS(S, G, M)                                                                 \
    S(baud, 4, MODCP_PF_BAUD, 0, 300, 115200, 9600, MODCP_EV_PARAM_RECORD, MODCP_PF_CUSTOM,        \
      "serial", "baud", NUM, none,                                                                \
      "must be one of 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 57600, 76800, 115200",      \
      "transmission rate, bit/s", /* custom: one of the table */                                  \
      "300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 57600, 76800, 115200",                     \
      "[RTU-2003] §2.1, [RTU-2009] §2.1")                                                                       \
    S(data_bits, 1, MODCP_PF_DATA_BITS, 0, 7, 8, 8, MODCP_EV_DATA_BITS, MODCP_PF_CUSTOM,          \
      "serial", "data_bits", NUM, none, "must be 8 for RTU, 7 or 8 for ASCII",                    \
      "data bits per character", /* custom: 8 for RTU */                                          \
      "RTU: 8; ASCII: 7 (8: a modcp extension, docs/parameters.md)", "[RTU-2003] §2.1, [ASCII-32] §3.1")                   \
    S(parity, 1, MODCP_PF_PARITY, 0, 0, 2, MODCP_PARITY_EVEN, MODCP_EV_PARAM_RECORD, 0, "serial",  \
      "parity", ENUM, parity, "must be none, odd or even", "parity bit",                          \
      "`none`, `odd`, `even` (`n`, `o`, `e`)", "[RTU-2003] §2.1")                                        \
    S(stop_bits, 1, MODCP_PF_STOP_BITS, 0, 1, 2, 1, MODCP_EV_PARAM_RECORD, MODCP_PF_CUSTOM,       \
      "serial", "stop_bits", NUM, none, "must be 1 or 2",                                         \
      "stop bits; ASCII: 1 with parity even or odd, 2 with parity none (7E1, 7O1, 7N2), "        \
      "`modcp-conf` sets them from the parity when the key is absent",                           \
      /* custom: the ASCII frame */                                                               \
      "1, 2 (ASCII: by the parity)", "[RTU-2003] §2.1, [ASCII-32] §3.1")                                        \
    S(slave_addr, 1, MODCP_PF_SLAVE_ADDR, 0, 1, 255, 222, MODCP_EV_SLAVE_ADDR, 0, "protocol",     \
      "slave_address", NUM, none, "must be 1..255",                                               \
      "the CP's own Modbus address; frames for other addresses are not checked and not "         \
      "answered; 0 is broadcast. The default is the manuals' 222; their examples use 5",          \
      "1 … 255", "[RTU-2003] §2.2")                                                                      \
    S(framing, 1, MODCP_PF_FRAMING, 0, 0, MODCP_WITH_ASCII, MODCP_FRAMING_RTU,                    \
      MODCP_EV_PARAM_RECORD, 0, "protocol", "framing", ENUM, framing, "must be rtu or ascii",     \
      "RTU (binary, CRC-16) or ASCII (`:` hex LRC CR LF)", "`rtu`, `ascii`", "[ASCII-32]")               \
    S(opmode, 1, MODCP_PF_OPMODE, 0, 0, 1, MODCP_OPMODE_NORMAL, MODCP_EV_OPMODE,                 \
      MODCP_PF_CUSTOM, "protocol", "mode", ENUM, mode,                                            \
      "must be normal or suppress (interference suppression)",                                    \
      "operating mode: `normal` reports every character error and BREAK; `suppress` "           \
      "(interference suppression, the 2009 manual's modem mode) silently discards a frame with " \
      "an error, starts a frame at the own address and ignores errors after the CRC. With "     \
      "`interface.type = rs485` (two-wire) the default is `suppress`, and `normal` needs "      \
      "`rs485_mode_select = on`; it then reports errors and BREAK inside a frame and ignores "  \
      "those before, after and between frames ([RTU-2009] §5.6.5)",                                    \
      /* custom: RS485 needs rs485_sel for normal */                                              \
      "`normal`, `suppress` (`interference_suppression`, `modem`)",                               \
      "[RTU-2003] §2.2, [RTU-2009] Table 5-2")                                                                  \
    S(f_mul, 1, MODCP_PF_FMUL, 0, 1, 10, 1, MODCP_EV_FMUL, MODCP_PF_WARN, "protocol", "f_mul",    \
      NUM, none, "must be 1..10; the CP runs with 1",                                             \
      "character delay multiplier: end of frame = TIME_OUT(baud) × f_MUL",                        \
      "1 … 10 (outside: warning, the CP runs with 1)", "[RTU-2003] §2.2, §5.3")                          \
    S(eof_timing, 1, MODCP_PF_EOF_TIMING, 0, 0, 1, MODCP_EOF_MANUAL, MODCP_EV_PARAM_RECORD, 0,    \
      "protocol", "eof_timing", ENUM, eof, "must be manual or modbus",                            \
      "end-of-frame rule: `manual` = the table of [RTU-2003] §5.3 × f_MUL (76800: 0.5 ms … 300: 128 "   \
      "ms; 57600, 115200 by 3.5 × 11 bits); `modbus` = Modbus serial line (3.5 characters, "     \
      "1750 µs above 19200)",                                                                     \
      "`manual`, `modbus`", "[RTU-2003] §5.3, docs/parameters.md")                                                  \
    S(t15_check, 1, MODCP_PF_T15_CHECK, 0, 0, 1, 0, MODCP_EV_PARAM_RECORD, 0, "protocol",         \
      "t15_check", BOOL, none, "must be on or off",                                               \
      "Modbus t1.5 check: a gap longer than 1.5 characters inside a frame discards it "          \
      "((08)06H)",                                                                                \
      "`on`, `off`", "docs/parameters.md")                                                                   \
    S(ascii_timeout_ms, 2, MODCP_PF_ASCII_TIMEOUT, 0, 1, 6500, 1000, MODCP_EV_FMUL,               \
      MODCP_PF_WARN, "protocol", "ascii_timeout_ms", NUM, none,                                   \
      "must be 1..6500 ms; the CP runs with 1000 ms", "ASCII inter-character timeout",            \
      "1 … 6500 (outside: warning, the CP runs with 1000)", "[ASCII-32]")                                \
    S(iface, 1, MODCP_PF_IFACE, 0, 0, 2, MODCP_IFACE_RS232, MODCP_EV_PARAM_RECORD, 0,             \
      "interface", "type", ENUM, iface, "must be rs232, rs422 or rs485",                          \
      "physical interface; `rs485` = two-wire half duplex with direction switching (errors "     \
      "and BREAK between frames ignored; interference suppression unless "                      \
      "`rs485_mode_select = on` and `mode = normal`)",                                          \
      "`rs232`, `rs422`, `rs485`", "[RTU-2003] §2.3")                                                    \
    S(turnaround_ms, 2, MODCP_PF_TURNAROUND, 0, 0, 100, 0, MODCP_EV_PARAM_RECORD, 0,              \
      "interface", "turnaround_ms", NUM, none, "must be 0..100 ms",                               \
      "RS485: wait from the moment the reply is ready to its first bit; the transmitter (DE) " \
      "is enabled at once, when the reply is ready, and drives the idle line during the wait",  \
      "0 … 100",                                                                                  \
      "docs/diagnostics.md")                                                                                \
    S(rs232_auto, 1, MODCP_PF_RS232_AUTO, 0, 0, MODCP_WITH_RS232_SIGNALS, 0,                      \
      MODCP_EV_PARAM_RECORD, MODCP_PF_CUSTOM, "interface", "rs232_auto", BOOL, none,              \
      "must be on or off, and on only with interface.type = rs232",                              \
      "RS232 automatic secondary signals (RTS/CTS/DTR/DSR)", /* custom: RS232 only */            \
      "`on`, `off`; on only with `type = rs232`", "[RTU-2003] §2.4, [VIPA-341]")                                \
    S(rts_on_delay_ms, 2, MODCP_PF_RTS_ON_DELAY, 0, 0, 65530, 10, MODCP_EV_PARAM_RECORD,          \
      MODCP_PF_CUSTOM, "interface", "rts_on_delay_ms", NUM, none,                                 \
      "must be 0..65530 ms in steps of 10 ms",                                                    \
      "data output waiting time: RTS on → CTS expected", /* custom: steps of 10 ms */          \
      "0 … 65530, steps of 10 ms", "[VIPA-341] §1.6, §7.1 ([RTU-2003] §2.4, 000: no values)")                  \
    S(rts_off_delay_ms, 2, MODCP_PF_RTS_OFF_DELAY, 0, 0, 65530, 10, MODCP_EV_PARAM_RECORD,        \
      MODCP_PF_CUSTOM, "interface", "rts_off_delay_ms", NUM, none,                                \
      "must be 0..65530 ms in steps of 10 ms",                                                    \
      "time to RTS off after the last character", /* custom: steps of 10 ms */                  \
      "0 … 65530, steps of 10 ms", "[VIPA-341] §1.6, §7.1 ([RTU-2003] §2.4, 000: no values)")                  \
    S(rx_preset, 1, MODCP_PF_RX_PRESET, 0, 0, 3, MODCP_RXP_DEFAULT, MODCP_EV_PARAM_RECORD,        \
      MODCP_PF_CUSTOM, "interface", "receive_preset", ENUM, rxpreset,                             \
      "must be default, none, break or high; break only with type = rs232 or rs422",             \
      "receive-line preset of RS422 / RS485 (through the HAL's `set_rx_preset`): `break` = "    \
      "R(A) 5 V / R(B) 0 V, a broken line is a BREAK level ((08)0DH, wire break); `high` = "     \
      "R(A) 0 V / R(B) 5 V, a broken line looks idle and BREAK cannot be recognised; `none` = "  \
      "no bias (the partner provides it); `default` = `break` on RS422, `high` on RS485",       \
      /* custom: break not on RS485 ([RTU-2009] Table 5-8 note 1) */                                    \
      "`default`, `none`, `break`, `high`", "[RTU-2009] Table 5-8, [RTU-2003] §2.3")                           \
    G(coils, MODCP_COIL_WINDOWS, modcp_bitwin_t, 5, MODCP_PF_COILS)                               \
    M(modcp_bitwin_t, area, 1, MODCP_COIL_WINDOWS)                                                \
    M(modcp_bitwin_t, from, 2, MODCP_COIL_WINDOWS)                                                \
    M(modcp_bitwin_t, to, 2, MODCP_COIL_WINDOWS)                                                  \
    M(modcp_bitwin_t, start, 2, MODCP_COIL_WINDOWS)                                               \
    M(modcp_bitwin_t, db, 2, MODCP_COIL_WINDOWS)                                                  \
    G(inputs, MODCP_INPUT_WINDOWS, modcp_bitwin_t, 5, MODCP_PF_INPUTS)                            \
    M(modcp_bitwin_t, area, 1, MODCP_INPUT_WINDOWS)                                               \
    M(modcp_bitwin_t, from, 2, MODCP_INPUT_WINDOWS)                                               \
    M(modcp_bitwin_t, to, 2, MODCP_INPUT_WINDOWS)                                                 \
    M(modcp_bitwin_t, start, 2, MODCP_INPUT_WINDOWS)                                              \
    M(modcp_bitwin_t, db, 2, MODCP_INPUT_WINDOWS)                                                 \
    S(hr_base_db, 2, MODCP_PF_HR_BASE, 0, 0, 65535, 0, MODCP_EV_PARAM_RECORD, 0, "registers",     \
      "holding_base_db", NUM, none, "must be a DB number 1..65535 (0: not configured)",           \
      "base DB of FC03/06/16", "1 … 65535 (0 = no holding registers)", "[RTU-2003] §3.4")                \
    S(ir_base_db, 2, MODCP_PF_IR_BASE, 0, 0, 65535, 0, MODCP_EV_PARAM_RECORD, 0, "registers",     \
      "input_base_db", NUM, none, "must be a DB number 1..65535 (0: not configured)",             \
      "base DB of FC04 (read-only)", "1 … 65535 (0 = none)", "[RTU-2003] §3.4")                          \
    S(regs32, 1, MODCP_PF_REGS32, 0, 0, 1, 0, MODCP_EV_PARAM_RECORD, 0, "registers",              \
      "with_32bit_registers", BOOL, none, "must be on or off",                                    \
      "FC03/06/16 use the three ranges below instead of the DB scheme", "`on`, `off`",           \
      "[ASCII-32] §4.5")                                                                                 \
    G(r32, 3, modcp_r32range_t, 3, MODCP_PF_R32)                                                  \
    M(modcp_r32range_t, from, 2, 3)                                                               \
    M(modcp_r32range_t, to, 2, 3)                                                                 \
    M(modcp_r32range_t, db, 2, 3)                                                                 \
    G(lim_db, 3, modcp_limit_t, 2, MODCP_PF_LIM_DB) /* lim_db, lim_m, lim_q */                    \
    M(modcp_limit_t, min, 2, 3)                                                                   \
    M(modcp_limit_t, max, 2, 3)                                                                   \
    S(r32_lim_db, 1, MODCP_PF_R32_LIM_DB, 0, 0, 1, 0, MODCP_EV_PARAM_RECORD, 0, "limits",         \
      "db_in_32bit_mode", BOOL, none, "must be on or off",                                        \
      "with `with_32bit_registers = on`: `off` = the manual's rule, `db` limits FC06/16 in the " \
      "standard DB scheme only and the three 32-bit ranges' DBs stay writable; `on` = `db` "     \
      "limits their writes too",                                                                  \
      "`on`, `off`", "[ASCII-32] §3.7, §5.4")                                                            \
    S(fset, 1, MODCP_PF_FSET, 0, 0, MODCP_WITH_EXTENDED, MODCP_WITH_EXTENDED,                     \
      MODCP_EV_PARAM_RECORD, 0, "protocol", "function_set", ENUM, fset,                           \
      "must be cp341 or extended",                                                                \
      "`cp341` = exactly FC 01–06, 08 sub 0, 15, 16; `extended` adds FC08 diagnostics, 11, 12, " \
      "17, 22, 23, 43/14, the scanner",                                                           \
      "`cp341`, `extended`", "docs/mapping.md")                                                           \
    S(rs485_sel, 1, MODCP_PF_RS485_SEL, 0, 0, 1, 0, MODCP_EV_PARAM_RECORD, 0, "protocol",         \
      "rs485_mode_select", BOOL, none, "must be on or off",                                       \
      "enable operating-mode selection for RS485: `off` = two-wire RS485 runs in interference " \
      "suppression (modem) mode only, `mode = normal` there is refused with (0E)22H; `on` "     \
      "allows `mode = normal` on two-wire RS485 too: errors inside a frame are reported "       \
      "((08)0CH / (08)0DH, wire break)",                                                         \
      "`on`, `off`", "[RTU-2009] Table 5-2")                                                             \
    S(qty_limits, 1, MODCP_PF_QTY_LIMITS, 0, 0, 1, MODCP_QLIMITS_MANUAL, MODCP_EV_PARAM_RECORD,   \
      0, "protocol", "quantity_limits", ENUM, qlimits, "must be manual or spec",                  \
      "largest quantity per request (exception 03 above it): `manual` = the manuals' RTU "       \
      "limits, FC01/02/15 2040 bits, FC03/04/16 127 registers (a 126/127-register reply is "     \
      "257/259 bytes); `spec` = the Modbus application protocol's, FC01/02 2000, FC15 1968, "    \
      "FC03/04 125, FC16 123, FC23 125 / 121: every reply fits the 256-byte RTU ADU",            \
      "`manual`, `spec`", "[RTU-2003] §6, docs/mapping.md, Modbus V1.1b3 §6")                                  \
    S(cpu_model, 1, MODCP_PF_CPU_MODEL, 0, 0, 1, MODCP_CPU_CP341, MODCP_EV_PARAM_RECORD, 0,       \
      "cpu", "model", ENUM, model, "must be cp341 or cp441",                                      \
      "CPU transfer limit per job: `cp341` 1024 bytes, `cp441` 450 bytes", "`cp341`, `cp441`",   \
      "[RTU-2003] §4.4, §4.5")                                                                           \
    S(job_limit, 2, MODCP_PF_JOB_LIMIT, 0, 32, 1024, 0, MODCP_EV_PARAM_RECORD,                    \
      MODCP_PF_ZERO_OK | MODCP_PF_CUSTOM, "cpu", "job_limit", NUM, none,                          \
      "must be 0 (the model's limit) or 32..1024 bytes (cp341) / 32..450 (cp441)",                \
      "bytes per CPU job; 0 = the model's limit", /* custom: the model's limit */                \
      "0, or 32 … 1024 (cp341) / 450 (cp441)", "docs/cpu-cp-interface.md")                                         \
    S(cpu_timeout_ms, 2, MODCP_PF_CPU_TIMEOUT, 0, 1, 65535, 1000, MODCP_EV_PARAM_RECORD, 0,       \
      "cpu", "timeout_ms", NUM, none, "must be 1..65535 ms",                                      \
      "CPU job timeout: exception 04 with (0E)31H (read / register write) or (0E)3BH "           \
      "(FC05/15)",                                                                                \
      "1 … 65535", "[RTU-2003] §4.3")                                                                    \
    S(start_time_ms, 2, MODCP_PF_START_TIME, 0, 1, 65535, 5000, MODCP_EV_PARAM_RECORD, 0, "cpu",  \
      "start_time_ms", NUM, none, "must be 1..65535 ms",                                          \
      "FB init time START_TIME (CP_START_ERROR after it); `modcp-conf` also refuses "            \
      "(P − 1) × `cycle_ms` or less, see below",                                                  \
      "1 … 65535", "[RTU-2003] §4.1")                                                                    \
    S(commloss_ms, 2, MODCP_PF_COMMLOSS, 0, 100, MODCP_WITH_EXTENDED ? 30000u : 0u, 0,              \
      MODCP_EV_PARAM_RECORD, MODCP_PF_ZERO_OK, "supervision", "commloss_ms", NUM, none,           \
      "must be 0 (off) or 100..30000 ms",                                                         \
      "comm-loss supervision: no valid request for our address within this time (armed after "   \
      "the first master write) raises an event and a flag the CPU side sees",                    \
      "0 (off) or 100 … 30000", "[ALTIVAR] §7")                                                         \
    S(commloss_auto, 1, MODCP_PF_COMMLOSS_AUTO, 0, 0, MODCP_WITH_EXTENDED, 0,                     \
      MODCP_EV_PARAM_RECORD, 0, "supervision", "commloss_auto_clear", BOOL, none,                 \
      "must be on or off", "`off`: a comm loss stays latched until the CPU side resets it "      \
      "(`modcp_bp_commloss_reset`) or new parameters arrive, as the Altivar's fault SLF1; "      \
      "`on`: the next valid request for our address clears it",                                 \
      "`on`, `off`", "[ALTIVAR] §7")                                                                    \
    S(scan_start, 2, MODCP_PF_SCANNER, 0xFF, 0, 65535, 0, MODCP_EV_PARAM_RECORD,                  \
      MODCP_PF_CUSTOM, "scanner", "start", NUM, none, "must be 0..65535",                         \
      "first scanner register address", /* custom: with the entries */                          \
      "0 … 65535", "[ALTIVAR] §11")                                                                     \
    S(scan_count, 1, MODCP_PF_SCANNER, 0xFF, 0, 255, 0, MODCP_EV_PARAM_RECORD, MODCP_PF_CUSTOM,   \
      "scanner", "", NUM, none, "", "", "", "") /* the number of [scanner] entries */             \
    G(scan, MODCP_SCANNER_MAX, modcp_operand_ref_t, 3, MODCP_PF_SCANNER)                          \
    M(modcp_operand_ref_t, area, 1, MODCP_SCANNER_MAX)                                            \
    M(modcp_operand_ref_t, db, 2, MODCP_SCANNER_MAX)                                              \
    M(modcp_operand_ref_t, offset, 2, MODCP_SCANNER_MAX)                                          \
    S(vendor, MODCP_PW_STR, MODCP_PF_ID_STRING, 0, 0, 0, 0, MODCP_EV_PARAM_RECORD,                \
      MODCP_PF_CUSTOM, "identification", "vendor", STR, none, "at most 16 characters",            \
      "vendor name (object 00)", "≤ 16 characters", "[ALTIVAR] §10.5")                                  \
    S(product, MODCP_PW_STR, MODCP_PF_ID_STRING, 1, 0, 0, 0, MODCP_EV_PARAM_RECORD,               \
      MODCP_PF_CUSTOM, "identification", "product", STR, none, "at most 16 characters",           \
      "product code (object 01)", "≤ 16 characters", "[ALTIVAR] §10.5")                                 \
    S(revision, MODCP_PW_STR, MODCP_PF_ID_STRING, 2, 0, 0, 0, MODCP_EV_PARAM_RECORD,              \
      MODCP_PF_CUSTOM, "identification", "revision", STR, none, "at most 16 characters",          \
      "revision (object 02); empty: modcp's version", "≤ 16 characters", "[ALTIVAR] §10.5")             \
    S(app_name, MODCP_PW_STR, MODCP_PF_ID_STRING, 3, 0, 0, 0, MODCP_EV_PARAM_RECORD,              \
      MODCP_PF_CUSTOM, "identification", "app_name", STR, none, "at most 16 characters",          \
      "user application name (object 06)", "≤ 16 characters", "[ALTIVAR] §10.5")                        \
    S(diag_irq, 1, MODCP_PF_DIAG_IRQ, 0, 0, 1, 0, MODCP_EV_PARAM_RECORD, 0, "diagnostics",        \
      "interrupt", BOOL, none, "must be on or off",                                               \
      "diagnostic interrupt records for the CPU side", "`on`, `off`", "[VIPA-341] §8.4")

/* The composite record fields' keys in the tables of docs/parameters.md (their rules are
 * in params.c and the document's prose). D(section, key, meaning, values, default, source,
 * event). The tool's own [cpu] keys are described in tools/conf/conf.c. */
#define MODCP_PARAM_DOC_ROWS(D)                                                                   \
    D("registers", "int16",                                                                       \
      "registers `FROM-TO @ DB`: 16-bit values, 2 bytes each from DBB0", "`off` or range", "off", \
      "[ASCII-32] §4.5", "(0E)2EH")                                                                      \
    D("registers", "int32", "32-bit integers, 4 bytes (one DBD) per register", "`off` or range",  \
      "off", "[ASCII-32] §4.5", "(0E)2EH")                                                               \
    D("registers", "float", "32-bit IEEE floats, 4 bytes per register", "`off` or range", "off",  \
      "[ASCII-32] §4.5", "(0E)2EH")                                                                      \
    D("limits", "db", "resulting DB numbers writable by FC06/16",                                 \
      "`MIN-MAX` with 1 ≤ MIN ≤ MAX, or `off`", "off", "[RTU-2003] §3.5", "(0E)24H")                     \
    D("limits", "m", "flag bytes writable by FC05/15", "`MIN-MAX` with MIN ≤ MAX, or `off`",      \
      "off", "[RTU-2003] §3.5", "(0E)24H")                                                               \
    D("limits", "q", "output bytes writable by FC05/15", "`MIN-MAX`, or `off`", "off",            \
      "[RTU-2003] §3.5", "(0E)24H")                                                                      \
    D("scanner", "entries",                                                                       \
      "up to 16 word operands the consecutive registers point at, e.g. `MW10 DB5.DBW20 T3`",      \
      "`MWn`, `IWn`, `QWn`, `DBn.DBWm`, `Tn`, `Cn`", "none (off)", "[ALTIVAR] §11", "(0E)2EH")

/* The core's table has a row for every S and G row except an absent S row: the members a
 * build does not keep (MODCP_PX_ABSENT_ above: the scanner's entries, then the four ID
 * strings, one run in the record) are one row, the absent group's, as wide as the run
 * (MODCP_PARAM_ABSENT_BYTES: a group of one field, params_record.c's walk skips it).
 * MODCP_PARAM_IF_PRESENT(member, absent, present) is the name absent or present. */
#define MODCP_PARAM_IF_PRESENT(member, absent, present)                                          \
    MODCP_PX_CAT(MODCP_PX_IF_, MODCP_PX_IS(MODCP_PX_ABSENT_##member))(absent, present)
#define MODCP_PX_ABS_S(member, width, ...)                                                        \
    +MODCP_PARAM_IF_PRESENT(member, (unsigned)(width), 0u)
#define MODCP_PX_ABS_G(member, count, type, members, field)                                       \
    +MODCP_PARAM_IF_PRESENT(member,                                                              \
                            (unsigned)(count) * ((unsigned)MODCP_PARAM_FIRST_WIDTH_##type +     \
                                                 (2u * ((unsigned)(members) - 1u))),           \
                            0u)
#define MODCP_PARAM_ABSENT_BYTES (0u MODCP_PARAM_ROWS(MODCP_PX_ABS_S, MODCP_PX_ABS_G, MODCP_PX_NONE))

/* The number of rows in the core's table (above), a constant. */
#define MODCP_PARAM_ROW_COUNT (0u MODCP_PARAM_ROWS(MODCP_PX_ONE_S, MODCP_PX_ONE, MODCP_PX_NONE))
#define MODCP_PX_ONE_S(member, ...) +MODCP_PARAM_IF_PRESENT(member, 0u, 1u)
#define MODCP_PX_ONE(...) +1u
#define MODCP_PX_NONE(...)
extern const modcp_param_row_t modcp_param_rows[MODCP_PARAM_ROW_COUNT];

#endif
