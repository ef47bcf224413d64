/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the events described once (X-macros), as params_fields.h describes the parameters.
 *
 * Everything about an event is in one row here. From the rows come: the enum of event
 * words (modcp/events.h), the Modbus exception a request error is answered with
 * (modcp_event_exception, pdu.c), the English texts, remedies and class names that the
 * simulator and the console print (event_text.c: only an image that shows texts links
 * them), and the tables "Every event" of docs/diagnostics.md (`modcp-conf event-table`,
 * compared with the page by the integration.conf test). Sources: [RTU-2003] §7.5 (classes 05H,
 * 08H, 0EH), [VIPA-341] §8.2 (classes 00H, 07H, 08H 16H/18H), [ASCII-32] §8.5 (08H 38H..3AH, ASCII);
 * events modcp adds say "modcp extension" in their cause.
 *
 * MODCP_EVENT_CLASS_ROWS(C): C(cls, name, heading)
 *   name: the class as the console and the simulator name it ("receive error");
 *   heading: the class's heading in docs/diagnostics.md, with its sources.
 *
 * MODCP_EVENT_ROWS(E), by class and number:
 *   E(NAME, cls, num, exc, answer, text, remedy, cause, path, test)
 *     NAME    the enum constant MODCP_EV_<NAME>; the event word is cls << 8 | num;
 *     exc     the Modbus exception code (1..4) of a request refused with this event while
 *             it is validated and mapped (modcp_event_exception), 0 for the other events;
 *     answer  what else the master gets (docs' column "exc."): after exc when exc is not 0
 *             (" / 01": another code in another case, named in the cause), else the whole
 *             entry ("04": answered 04 by the CPU-job path; "none": the request is not
 *             answered; "—": not a request error);
 *     text, remedy   English, ASCII only (printed by the simulator and the console);
 *     cause, path, test   docs/diagnostics.md only (Markdown): what raises the event in
 *             modcp, the function that raises it, the tests that provoke and assert it.
 *
 * MODCP_EVENT_NA_ROWS(N): events of the manuals that cannot happen in modcp (no enum
 *   constant, no text in the firmware): N(cls, num, source, text, reason). */
#ifndef MODCP_EVENT_ROWS_H
#define MODCP_EVENT_ROWS_H

#define MODCP_EVENT_CLASS_ROWS(C)                                                                 \
    C(0x00, "CP start-up", "CP start-up ([VIPA-341] §8.2; in the diagnostic buffer only)")              \
    C(0x05, "CPU job error", "CPU job errors ([RTU-2003] §7.5, [VIPA-341] §8.2)")                              \
    C(0x07, "send error", "send errors ([VIPA-341] §8.2; used by the RS232 signals)")                   \
    C(0x08, "receive error", "receive errors ([RTU-2003] §7.5, [VIPA-341] §8.2, [ASCII-32] §8.5)")                    \
    C(0x0E, "driver processing error", "general processing errors ([RTU-2003] §7.5)")

#define MODCP_EVENT_ROWS(E)                                                                       \
    /* ---- class 00H: CP start-up (not errors: diagnostic buffer only, diag.c) ---- */        \
    E(PARAMS_TAKEN, 0x00, 0x03, 0, "—",                                                           \
      "parameters taken over", "none",                                                            \
      "a valid parameter record was applied (after the buffer was cleared: the first entry "      \
      "of a new parameterisation, before its warnings)",                                          \
      "`cp.c take_params`",                                                                       \
      "`test_fb_restart.c: test_start_up_events`")                                                \
    E(PARAMS_SAME, 0x00, 0x04, 0, "—",                                                            \
      "parameters already on the CP", "none",                                                     \
      "the CPU side sent the record the CP holds (the same identity and length): nothing "        \
      "changes (an FB retry; the FB sends no record at a restart)",                               \
      "`cp.c take_params`",                                                                       \
      "`test_fb_restart.c: test_same_record_keeps_request_in_progress`")                          \
    /* ---- class 05H: CPU job errors ---- */                                                      \
    E(JOB_LENGTH, 0x05, 0x17, 0, "04",                                                            \
      "job longer than the CP transfer limit",                                                    \
      "read or write fewer bits/registers per request, or raise job_limit",                       \
      "a request needs more bytes than `job_limit` (1024 / 450); [VIPA-341] §8.2 \"transfer length > "   \
      "1 kByte is too large for the CP\" ((05)18H is the master driver's send length)",          \
      "`job.c modcp_job_start` → `cp.c advance` → `pdu.c modcp_pdu_complete`",                    \
      "`test_cp_examples.c: test_exception_04_cpu_errors`; `test_job_fb.c: test_job_limit_450`")  \
    /* ---- class 07H: send errors ---- */                                                         \
    E(CTS_TIMEOUT, 0x07, 0x08, 0, "—",                                                            \
      "RS232: the waiting time for CTS = ON expired; reply not sent",                             \
      "check the partner's CTS output and the cable; increase the data output waiting time "      \
      "(rts_on_delay_ms)",                                                                        \
      "automatic signals: CTS not ON when the data output waiting time ends; the reply is "       \
      "dropped",                                                                                  \
      "`signals.c decide`", "`test_signals.c: test_cts_timeout`")                                 \
    /* ---- class 08H: receive errors ---- */                                                      \
    E(ZVZ, 0x08, 0x06, 0, "—",                                                                    \
      "character delay time exceeded inside a frame",                                             \
      "eliminate the fault in the partner or the interference on the line; RTU: or switch the "   \
      "t1.5 check off",                                                                           \
      "RTU: silence > t1.5 inside a frame (t1.5 check on, normal mode); ASCII: inter-character "  \
      "timeout",                                                                                  \
      "`rtu.c t15_violated`; `ascii.c`",                                                          \
      "`test_line.c: test_t15_end_to_end, test_t15_rates`; `test_link.c: test_t15_check`; "      \
      "`test_ascii.c: test_character_delay_time`")                                                \
    E(CHAR_ERROR, 0x08, 0x0C, 0, "—",                                                             \
      "transmission error (parity, framing or overrun) in a character",                           \
      "check the line for interference; check that baud, data bits, parity and stop bits match "  \
      "the master",                                                                               \
      "parity, framing or overrun reported by the UART (normal mode; on two-wire RS485 in "      \
      "normal mode only inside a frame)",                                                         \
      "`link.c modcp_link_on_error`",                                                             \
      "`test_line.c: test_parity_error_normal, test_rs485_normal_reports_errors_inside_frame`; "  \
      "`test_link.c: test_parity_error_normal_mode`; `test_ascii.c: test_line_errors`")           \
    E(BREAK, 0x08, 0x0D, 0, "—",                                                                  \
      "BREAK: receive line to the partner interrupted",                                           \
      "reconnect or switch on the partner; RS422/485: check the receive wires R(A)/R(B)",         \
      "BREAK reported by the UART (normal mode; on two-wire RS485 in normal mode only inside a "  \
      "frame; never with receive_preset = high, which holds a broken line idle); also a wire "    \
      "break (SF, interrupt)",                                                                    \
      "`link.c modcp_link_on_error`; `cpdiag.c modcp_cpdiag_line_error`",                         \
      "`test_link.c: test_break_idle`; `test_line.c: test_error_after_crc, "                      \
      "test_rs485_normal_reports_errors_inside_frame`; `test_diag.c: test_diag_irq_wire_break`")  \
    E(FRAME_TOO_LONG, 0x08, 0x16, 0, "—",                                                         \
      "received telegram longer than the receive buffer",                                         \
      "check the master's request length and the line for interference",                          \
      "a frame for us longer than the 264-byte receive buffer (ASCII: more than 2 × 252 data "   \
      "characters, [ASCII-32] §8.1: more than 255 decoded bytes from address to LRC, i.e. more than "   \
      "510 hex characters between `:` and CR)",                                                   \
      "`rtu.c rtu_on_timer`; `ascii.c`",                                                          \
      "`test_link.c: test_frame_too_long`; `test_ascii.c: test_frame_too_long`")                  \
    E(SIGNAL_OFF, 0x08, 0x18, 0, "—",                                                             \
      "RS232: DSR = OFF or CTS = OFF before or during sending (automatic signals)",               \
      "check that the partner is switched on and ready, and the cable (DSR, CTS)",                \
      "automatic signals: CTS ON→OFF while sending, or DSR ON→OFF at any time",                   \
      "`signals.c modcp_sig_on_inputs`",                                                          \
      "`test_signals.c: test_cts_off_while_sending, test_dsr_off_while_receiving, "               \
      "test_dsr_off_while_sending, test_dsr_off_while_job_pending`")                              \
    E(BCAST_FC, 0x08, 0x30, 0, "none (never answered)",                                           \
      "broadcast not allowed with this function code",                                            \
      "broadcast only with FC 05, 06, 15, 16",                                                    \
      "address 0 with an FC other than 05/06/15/16 (both sets; flag `F_BCAST` of the "            \
      "function-code table)",                                                                     \
      "`pdu.c dispatch`",                                                                         \
      "`test_cp_examples.c: test_broadcast`; `test_pdu_order.c: "                                 \
      "test_spec52_order_broadcast_before_function_code`")                                        \
    E(ILLEGAL_FC, 0x08, 0x31, 1, "",                                                              \
      "received function code not allowed", "use a supported function code",                     \
      "FC not in the active function set",                                                        \
      "`pdu.c dispatch` (function-code table), `map.c`",                                          \
      "`test_cp_examples.c: test_exception_01`; `test_pdu_order.c: "                              \
      "test_mbap6_order_function_code_before_length`")                                            \
    E(QUANTITY, 0x08, 0x32, 3, "",                                                               \
      "maximum amount of bits or registers exceeded, or bit count not a multiple of 16 for T/C",  \
      "at most 2040 bits, 127 registers (quantity_limits = manual); timers/counters only in "     \
      "steps of 16 bits",                                                                         \
      "quantity out of range: 0, or above the limit of `quantity_limits` (`manual`: ≤ 2040 "      \
      "bits, ≤ 127 registers; `spec`: FC01/02 ≤ 2000, FC15 ≤ 1968, FC03/04 ≤ 125, FC16 ≤ 123; "   \
      "FC23 ≤ 125 / 121 in both); T/C bits not a multiple of 16",                                 \
      "`pdu.c dispatch` (table limit class, `quantity.c`), `map.c`",                              \
      "`test_cp_examples.c: test_exception_03`; `test_qty_limits.c`; "                            \
      "`integration.libmodbus.spec-limits`")                                                      \
    E(BYTE_COUNT, 0x08, 0x33, 3, "",                                                              \
      "amount of bits/registers and byte_count do not match (FC 15/16)",                          \
      "correct the amount or the byte count in the master",                                       \
      "FC15/16 byte count wrong; PDU length outside the table's minimum / maximum",               \
      "`pdu.c dispatch`, `form_ok`", "`test_cp_examples.c: test_exception_03`")                   \
    E(COIL_VALUE, 0x08, 0x34, 3, "",                                                              \
      "illegal coding for set/reset bit (FC 05)", "use only 0000H or FF00H",                      \
      "FC05 value not FF00/0000", "`pdu_rw_internal.h modcp_pdu_rw`",                                      \
      "`test_cp_examples.c: test_exception_03`")                                                  \
    E(DIAG_SUBFC, 0x08, 0x35, 3, " / 01",                                                         \
      "illegal diagnostic sub-function or data field (FC 08)",                                    \
      "use a supported sub-function (0000H in the cp341 function set)",                           \
      "FC08 sub-function not supported (only 0000 in `cp341`: 03, [RTU-2003] §8.7); in `extended` a "    \
      "sub-function it does not implement is exception 01, wrong data 03 "                        \
      "(docs/extended-functions.md, FC08)",                                                       \
      "`pdu_rw.c modcp_pdu_diag0`, `serial_diag.c`",                                              \
      "`test_cp_examples.c: test_exception_03`; `test_interpretations.c: "                        \
      "test_fc08_subcode_other_than_0000_answers_exception_03, "                                        \
      "test_mbap6_8_fc08_unsupported_subfunction_exception_01_event_0835`")                       \
    E(CRC, 0x08, 0x36, 0, "none",                                                                 \
      "CRC/LRC of the request does not match",                                                    \
      "check the master's CRC generation and the line",                                           \
      "bad CRC, or a frame for us shorter than 4 bytes",                                          \
      "`rtu.c rtu_on_timer`; `ascii.c`",                                                          \
      "`test_link.c: test_crc_error`; `test_cp_examples.c: test_other_address_and_crc`; "         \
      "`test_line.c: test_t35_gap_threshold`")                                                    \
    E(SEQUENCE, 0x08, 0x37, 0, "none",                                                            \
      "new request before the last reply was sent",                                               \
      "increase the master's reply timeout",                                                      \
      "the master did not wait for our reply: a request for us or a broadcast started while "    \
      "the previous one was processed or its reply pending (neither is executed)",                \
      "`rtu.c rtu_busy_track`; `ascii.c`",                                                        \
      "`test_link.c: test_sequence_error_while_busy`; `test_line.c: "                             \
      "test_sequence_error_during_turnaround, test_sequence_error_while_job_pending, "            \
      "test_sequence_error_broadcast_while_job_pending`; `test_ascii.c: test_sequence_error`")    \
    E(ASCII_START, 0x08, 0x38, 0, "—",                                                            \
      "wrong start character (not ':')", "check the framing settings (ASCII/RTU)",                \
      "ASCII: a frame that does not start with ':' ([ASCII-32] §8.5)", "`ascii.c`",                      \
      "`test_ascii.c: test_wrong_start`")                                                         \
    E(ASCII_RESTART, 0x08, 0x39, 0, "—",                                                          \
      "start character inside a telegram: reception restarted",                                   \
      "check whether the line is interrupted",                                                    \
      "ASCII: ':' inside a frame restarts reception ([ASCII-32] §8.5)", "`ascii.c`",                     \
      "`test_ascii.c: test_colon_restarts`")                                                      \
    E(ASCII_NOT_HEX, 0x08, 0x3A, 0, "—",                                                          \
      "received character is not a hex character",                                                \
      "make sure the master is in ASCII mode, not RTU",                                           \
      "ASCII: a character other than 0-9, A-F inside a frame ([ASCII-32] §8.5)", "`ascii.c`",           \
      "`test_ascii.c: test_not_hex`")                                                             \
    E(MEI_CODE, 0x08, 0x3B, 3, "",                                                                \
      "read device identification (FC 43/14): ReadDevId code not 01..04",                         \
      "use 01 basic, 02 regular, 03 extended or 04 one object",                                   \
      "*modcp extension* (extended set): FC43/14 ReadDevId code not 01..04", "`devid.c`",         \
      "`test_extended.c: test_fc43_exceptions`")                                                  \
    /* ---- class 0EH: general processing errors ---- */                                          \
    E(INTERNAL_SEND, 0x0E, 0x10, 0, "04 or none",                                                 \
      "internal error: default branch in the send automaton", "restart the CP",                   \
      "a reply that does not fit the buffer; a job started while one runs; a completion "         \
      "without a job",                                                                            \
      "`link.c modcp_link_reply`; `job.c modcp_job_start`; `pdu.c modcp_pdu_complete`",           \
      "`test_link.c: test_reply_too_long`; `test_ascii.c: test_encoder_in_place`; "               \
      "`test_job_fb.c: test_job_limit_450`")                                                      \
    E(INTERNAL_RECEIVE, 0x0E, 0x11, 0, "—",                                                       \
      "internal error: default branch in the receive automaton", "restart the CP",                \
      "the RTU receive automaton finds a state it never uses (corrupted memory); it goes back "   \
      "to idle and the character starts a frame",                                                 \
      "`rtu.c internal_error`", "`test_diag.c: test_internal_receive_error`")                     \
    E(DATA_BITS, 0x0E, 0x20, 0, "—",                                                              \
      "number of data bits not allowed for this framing; CP not ready",                           \
      "RTU: 8 data bits; ASCII: 7 (or 8)",                                                        \
      "RTU ≠ 8; ASCII ≠ 7/8", "`params.c run_checks` → `cp.c take_params`",                       \
      "`test_params.c: test_data_bits`; `test_ascii.c: test_data_bits`")                          \
    E(FMUL, 0x0E, 0x21, 0, "—",                                                                   \
      "character delay value out of range; running with the default",                             \
      "check the parameters (f_MUL 1..10, ASCII timeout 1..6500 ms)",                             \
      "f_MUL outside 1..10 (runs with 1); ASCII timeout outside 1..6500 (runs with 1000)",        \
      "`params.c` → `cp.c take_params`",                                                          \
      "`test_cp_examples.c: test_fmul_corrected`; `test_params.c: test_fmul_corrected`")          \
    E(OPMODE, 0x0E, 0x22, 0, "—",                                                                 \
      "illegal operating mode; CP not ready", "choose normal or interference suppression",        \
      "mode not normal/suppression; `normal` on two-wire RS485 without `rs485_mode_select = on` " \
      "([RTU-2009] Table 5-2: \"selected operating mode not allowed\", driver not ready)",               \
      "`params.c custom_ok` → `cp.c`",                                                            \
      "`test_params.c: test_opmode, test_rs485_normal_needs_mode_select, "           \
      "test_rs485_normal_refused_by_cp`; `test_conf.py: rs485_mode_select`")         \
    E(SLAVE_ADDR, 0x0E, 0x23, 0, "—",                                                             \
      "illegal slave address (0 not allowed); CP not ready", "use 1..255",                        \
      "address 0", "`params.c` → `cp.c`",                                                         \
      "`test_cp_examples.c: test_bad_params_not_ready`; `test_params.c: test_slave_addr`; "       \
      "`test_diag.c: test_diag_irq_param_error`")                                                 \
    E(WRITE_LIMITS, 0x0E, 0x24, 0, "—",                                                           \
      "illegal write-access limits; CP not ready", "MIN must not exceed MAX",                     \
      "MIN > MAX, DB MIN 0", "`params.c check_limits`", "`test_params.c: test_write_limits`")     \
    E(COIL_FROMTO, 0x0E, 0x25, 0, "—",                                                            \
      "illegal from/to combination for FC 01/05/15; CP not ready", "check the coil windows",      \
      "bad area, from > to, DB 0, T/C size, extent", "`params.c check_ranges`",                   \
      "`test_params.c: test_coil_windows_illegal`")                                               \
    E(INPUT_FROMTO, 0x0E, 0x26, 0, "—",                                                           \
      "illegal from/to combination for FC 02; CP not ready", "check the input windows",           \
      "bad area, from > to, DB 0, extent", "`params.c check_ranges`",                             \
      "`test_params.c: test_input_windows`")                                                      \
    E(COIL_OVERLAP, 0x0E, 0x27, 0, "—",                                                           \
      "overlapping from/to windows for FC 01/05/15; CP not ready",                                \
      "make the coil windows disjoint", "two windows overlap", "`params.c check_ranges`",         \
      "`test_params.c: test_coil_windows_overlap`")                                               \
    E(INPUT_OVERLAP, 0x0E, 0x28, 0, "—",                                                          \
      "overlapping from/to windows for FC 02; CP not ready",                                      \
      "make the input windows disjoint", "two windows overlap", "`params.c check_ranges`",        \
      "`test_params.c: test_input_windows`")                                                      \
    E(PARAM_RECORD, 0x0E, 0x2E, 0, "—",                                                           \
      "parameter record unreadable or a parameter out of range; CP not ready",                    \
      "check the configuration with modcp-conf check",                                            \
      "magic, version, length, CRC; every field without an event of its own (baud, interface, "   \
      "turnaround, `rs232_auto` off RS232, `diag_irq` > 1, the ASCII frame other than 7E1 / "     \
      "7O1 / 7N2 on the stop bits ([ASCII-32] §3.1), …)",                                                \
      "`params_record.c modcp_params_decode`, `params.c run_checks` → `cp.c take_params`",        \
      "`test_params.c: test_record_field_errors, test_record_damaged, "                           \
      "test_ascii_frame_7e1_7o1_7n2_accepted, test_ascii_7n1_refused_by_cp`; "           \
      "`test_diag.c: test_diag_irq_parameter`; `test_job_fb.c: test_init_retry_then_success`")    \
    E(XFER_ACK, 0x0E, 0x30, 0, "—",                                                               \
      "unexpected acknowledgement / block from the CPU side",                                     \
      "ignore unless permanent; else check the CP-CPU interface and the CPU-side program",        \
      "a block that fits no message: sequence gap, data before its header, continuation "         \
      "without a start, short INIT (job.c `new_errors`, bit `MODCP_JOB_ERR_PROTO`; "              \
      "`proto_errors` counts them); once per poll",                                               \
      "`cpdiag.c modcp_cpdiag_backplane` (from `cp.c line_poll`)",                                \
      "`test_diag.c: test_backplane_protocol_events`")                                            \
    E(XFER_TIMEOUT, 0x0E, 0x31, 0, "04",                                                          \
      "timeout during data transfer to the CPU",                                                  \
      "check that the user program calls the FB cyclically",                                      \
      "the FB did not answer a read/register-write job within `cpu_timeout_ms`",                  \
      "`job.c modcp_job_poll`",                                                                   \
      "`test_cp_examples.c: test_exception_04_timeouts`; `test_job_fb.c: "                        \
      "test_read_timeout_stale_reply_dropped`")                                                   \
    E(XFER_STATE, 0x0E, 0x33, 0, "04",                                                            \
      "illegal state in the CP-CPU block handshake", "check the CP-CPU interface",                \
      "reply blocks not as announced, a job's data incomplete at the FB",                         \
      "`job.c finish_reply / rx_reply`; `fb.c`",                                                  \
      "`test_job_fb.c: test_reply_checks, test_fb_incomplete_jobs`")                              \
    E(AREA_ACCESS, 0x0E, 0x38, 0, "04",                                                           \
      "error accessing M, Q, T, C or I (area missing or too short)",                              \
      "check that the area exists and is long enough",                                            \
      "area missing or too short in the controller", "`plcmem.c` via `fb.c`",                     \
      "`test_job_fb.c: test_access_errors`")                                                      \
    E(DB_ACCESS, 0x0E, 0x39, 2, " / 04",                                                          \
      "error accessing a DB: missing, too short, or DB boundary crossed",                         \
      "check DB existence and size; do not cross a DB boundary",                                  \
      "request crossing a DB boundary (02, the mapping); DB missing / too short (04, the CPU "    \
      "side)",                                                                                    \
      "`map.c`; `plcmem.c` via `fb.c`",                                                           \
      "`test_cp_examples.c: test_exception_02, test_exception_04_cpu_errors`; `test_job_fb.c: "   \
      "test_access_errors`")                                                                      \
    E(WORK_DB, 0x0E, 0x3A, 0, "04",                                                               \
      "FB work area (instance DB) missing or too short", "check the FB's work DB",                \
      "FC05/15 cannot be placed in the work DB", "`fb.c`",                                        \
      "`test_job_fb.c: test_work_db_missing`")                                                    \
    E(FB_TIMEOUT, 0x0E, 0x3B, 0, "04",                                                            \
      "timeout while the FB executes a write job",                                                \
      "check that the user program calls the FB cyclically",                                      \
      "FC05/15 bit write not acknowledged in time", "`job.c modcp_job_poll`",                     \
      "`test_cp_examples.c: test_exception_04_timeouts`; `test_job_fb.c: "                        \
      "test_bitwrite_timeout`")                                                                   \
    E(ILLEGAL_JOB, 0x0E, 0x3C, 0, "—",                                                            \
      "illegal job from the CPU side (message kind not allowed)",                                 \
      "check the CPU-side program: only PARAMS, INIT and REPLY messages go to the CP",            \
      "the CPU side sent a message kind the CP does not accept (JOB or INIT_ACK travel CP → "     \
      "CPU; unknown kinds; job.c `new_errors`, bit `MODCP_JOB_ERR_ILLEGAL`); once per poll",      \
      "`cpdiag.c modcp_cpdiag_backplane`", "`test_diag.c: test_backplane_protocol_events`")       \
    E(TC_ALIGN, 0x0E, 0x50, 2, "",                                                                \
      "timer/counter address not on a 16-bit boundary", "use addresses that give whole words",    \
      "T/C: start address − from not a multiple of 16", "`map.c`",                                \
      "`test_cp_examples.c: test_exception_02`")                                                  \
    E(NO_WINDOW, 0x0E, 0x51, 2, "",                                                               \
      "Modbus address outside the parameterised from/to areas",                                   \
      "use only parameterised addresses", "start address in no from/to window", "`map.c`",        \
      "`test_cp_examples.c: test_exception_02, test_exception_frame_example`")                    \
    E(WRITE_DENIED, 0x0E, 0x52, 2, "",                                                            \
      "range limit: resulting DB < 1, write outside the enabled limits, or write to the FB work " \
      "area",                                                                                     \
      "restrict writes to the enabled areas",                                                     \
      "resulting DB < 1, a write outside the write limits, a write to the FB's work DB",          \
      "`map.c`",                                                                                  \
      "`test_cp_examples.c: test_manual_464_limits_reject, test_exception_02`")                   \
    E(DB_OVERFLOW, 0x0E, 0x53, 2, "",                                                             \
      "range limit: resulting DB number > 65535", "restrict access",                              \
      "the DB number computed from the address exceeds 65535", "`map.c`",                         \
      "`test_cp_examples.c: test_exception_02`")                                                  \
    E(PAST_END, 0x0E, 0x54, 2, "",                                                                \
      "access beyond the window end or the controller area end", "restrict access",               \
      "the request runs past its window's to, or past the end of the area", "`map.c`",            \
      "`test_cp_examples.c: test_exception_02`")                                                  \
    E(AREA_READONLY, 0x0E, 0x55, 2, "",                                                           \
      "write access to this memory area not allowed", "write only to M and Q",                    \
      "a write to T or C (FC05/15), or a scanner write to T, C or I", "`map.c`, `scanner.c`",     \
      "`test_cp_examples.c: test_exception_02`")                                                  \
    E(FB_NOT_RUNNING, 0x0E, 0x56, 4, "",                                                          \
      "data link not possible: communication FB not running",                                     \
      "call the FB cyclically; re-initialise with CP_START",                                      \
      "INIT not yet acknowledged: every request, whatever its function code, length or address "  \
      "(step 3 of the order of checks)",                                                          \
      "`pdu.c dispatch`; `fb.c`",                                                                 \
      "`test_cp_examples.c: test_exception_04_not_initialised`; `test_pdu_order.c: "              \
      "test_spec6_not_initialised_before_function_code, "                                         \
      "test_spec6_not_initialised_before_length_quantity_address, "                               \
      "test_spec6_not_initialised_broadcast`")                                                    \
    E(FB_ERROR, 0x0E, 0x57, 0, "04",                                                              \
      "error in the communication FB while processing the function code",                         \
      "see the FB's ERROR_NR / ERROR_INFO",                                                       \
      "ERROR_NR 10..19 from the FB", "`fb.c` → `job.c rx_reply`",                                 \
      "`test_job_fb.c: test_reply_checks` (`expect_fb_error`)")                                   \
    E(COMMLOSS, 0x0E, 0x60, 0, "—",                                                               \
      "communication loss: no valid request for this slave within the supervision time",          \
      "check the master and the line; the CPU side resets the latched flag (modcp_bp_commloss_reset)",               \
      "*modcp extension*: no valid request within `commloss_ms` after the first write",           \
      "`commloss.c`", "`test_extended.c`")

#define MODCP_EVENT_NA_ROWS(N)                                                                    \
    N(0x05, 0x18, "[VIPA-341] §8.2", "send transfer length too large (> 4 kByte) or too small",         \
      "a Modbus master driver's event (\"Modbus master only\"); the slave's job over its "      \
      "transfer limit is (05)17H")                                                                \
    N(0x0E, 0x01, "[RTU-2003] §7.5", "error initialising the driver-specific SCC process",               \
      "modcp is one firmware image, not a driver loaded into a CP operating system. There is "    \
      "no SCC process to start.")                                                                 \
    N(0x0E, 0x02, "[RTU-2003] §7.5", "wrong SCC process active",                                         \
      "the same: there are no exchangeable SCC drivers")                                          \
    N(0x0E, 0x03, "[RTU-2003] §7.5", "wrong data-transfer process (interface to the SFBs)",              \
      "the backplane interface is compiled in. There are no SFB processes to load.")              \
    N(0x0E, 0x04, "[RTU-2003] §7.5", "illegal interface submodule",                                      \
      "the interface hardware is fixed per board. A port without DE or RTS/DTR leaves "           \
      "`set_de` / `set_signal` NULL, and the core works without them.")                           \
    N(0x0E, 0x05, "[RTU-2003] §7.5", "dongle missing or faulty", "no licence dongle")                    \
    N(0x0E, 0x06, "[RTU-2003] §7.5", "dongle has no valid contents", "no licence dongle")                \
    N(0x0E, 0x12, "[RTU-2003] §7.5", "default branch in the active automaton",                           \
      "the CP 441-2's automata for its BSEND/RCV job interface. modcp has a receive automaton "   \
      "((0E)11H), a send path ((0E)10H) and the backplane job automaton, whose illegal states "   \
      "are (0E)33H.")                                                                             \
    N(0x0E, 0x13, "[RTU-2003] §7.5", "default branch in the passive automaton", "as (0E)12H")           \
    N(0x0E, 0x32, "[RTU-2003] §7.5",                                                                     \
      "error in the transfer to the CPU with RCV (detail in the SYSTAT entry before it)",         \
      "there is no SFB RCV. A failed transfer is a timeout ((0E)31H), a handshake error "         \
      "((0E)33H) or an unexpected block ((0E)30H), so there is no second-level event to "         \
      "report.")                                                                                  \
    N(0x08, 0x0A, "[VIPA-341] §8.2", "no free receive buffer",                                           \
      "the CP takes one request at a time. A request while one is pending is (08)37H.")

#endif
