/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — one RS485 line shared by several members (slaves) and the master.
 *
 * The master's pty is the line's one end; every member has its own pty, whose far
 * end the bus holds. The bus thread
 *   - forwards every byte the master writes to every member at once (same timing);
 *   - puts every member's reply on the line bit by bit: a member's reply is handed
 *     to the bus when its UART starts (sim_bus_tx, from the member's CP thread), the
 *     line level at any time is the wired AND of all senders' levels (idle and stop
 *     bits 1, start bit 0: a driven 0 wins), and one UART receiver decodes the line
 *     (falling edge = start bit, sampled in the middle of each bit). Each character
 *     it decodes goes to the master and to every member that is not sending then
 *     (a half-duplex transceiver does not hear itself). One sender gives back its
 *     bytes exactly; two overlapping senders give what a receiver on a real line
 *     would read from the mixed levels: a garbled frame, never two clean replies.
 *     Members take their characters with the line time of each (sim_bus_take), so a
 *     member thread that runs late still sees the gaps (t1.5, t3.5) of the line;
 *   - applies the per-member faults (drop, delay, CRC, exception 06 / 04, silence,
 *     noise) to the replies before they reach the line, and counts them;
 *   - puts on the line model (line.h) what it carries, and, for the text trace, notes:
 *     a reply's faults, a reply not sent, the noise, each collision with what the
 *     receiver heard (the trace reads the frames themselves from the line).
 * All members share the line settings (the caller checks that they agree). */
#ifndef MODCP_SIM_BUS_H
#define MODCP_SIM_BUS_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "line.h"

#define SIM_BUS_MAX_MEMBERS SIM_LINE_MAX_MEMBERS
/* modcp members (configs) on one bus: one per Modbus address */
#define SIM_BUS_MAX_SLAVES 247

typedef struct {
    /* settings (0 = off) */
    uint8_t drop_pct;       /* drop this share of replies */
    uint8_t crc_pct;        /* corrupt the CRC (LRC) of this share */
    uint8_t exc06_pct;      /* answer exception 06 (busy) instead */
    uint8_t exc04_pct;      /* answer exception 04 (slave device failure) instead */
    uint32_t delay_min_ms;  /* delay each reply by min..max ms (fixed when equal) */
    uint32_t delay_max_ms;
    uint32_t silent_left;   /* do not answer the next N requests */
    uint16_t noise_bytes;   /* N random bytes on the line one t3.5 after each reply */
    /* serial-layer faults of every frame (a member's replies; @master: the requests) */
    uint16_t parity_k;      /* byte k (1-based) with a wrong parity bit */
    uint16_t framing_k;     /* byte k with its stop bit 0 */
    uint32_t break_ms;      /* a BREAK of this many ms after the frame's first byte */
    uint16_t gap_k;         /* a pause of gap_us after byte k */
    uint32_t gap_us;
    uint8_t de_cut_bits;    /* DE released this many bits before the last stop bit ends */
    uint32_t early_us;      /* @master: a request that follows a reply starts this long after
                               the reply's last stop bit (0: when the master wrote it) */
    /* counters */
    uint32_t replies;       /* replies the member's CP sent (@master: requests) */
    uint32_t dropped, crc_corrupted, exc06, exc04, delayed, silenced, noise_sent;
    uint32_t collisions;    /* replies that overlapped another sender's on the line */
    uint32_t parity_errs, framing_errs, breaks_sent, gaps_made, de_cuts, early_sent;
    bool used; /* a fault was set (even off) */
} sim_fault_t;

typedef struct sim_bus sim_bus_t;

/* master_fd: the pty master the master's side opens; member_fd[i]: the far end of
 * member i's pty (what it sends is not read: the bus puts its replies on the line from
 * sim_bus_tx); wake_fd[i]: written when member i has characters to take (sim_bus_take).
 * wake_fd[i] < 0 makes member i external: member_fd[i] is a tty (a QEMU board's
 * Modbus UART): the line's characters are written to it, and what it writes is put on
 * the line (paced from its arrival; faults do not apply to it).
 * names[i]: "a" (printed as "@a"), addr[i]: its slave address (for the trace).
 * print: one trace line (thread-safe). */
sim_bus_t *sim_bus_new(const sim_line_cfg_t *line, size_t n, const char *const names[],
                       const uint8_t addr[], int master_fd, const int member_fd[],
                       const int wake_fd[], uint64_t t0_us64,
                       void (*print)(void *user, const char *line), void *user, uint32_t seed);

/* The characters member m heard, each with the time (the member's 32-bit us clock)
 * its stop bit ended on the line: a member fed with these times frames them by the
 * line's timing, however late its thread runs. Only those that ended by until_us (the
 * member's `now`: a character that arrived after the member read its clock belongs to
 * its next turn, after its own transmission-complete and timers due by then); *more
 * says that some are left. errors[i]: MODCP_LINE_* (a parity or framing error, BREAK:
 * the character is lost to the error). *more: characters due by until_us are left
 * (cap was reached). Returns how many (at most cap). */
size_t sim_bus_take(sim_bus_t *b, size_t m, uint8_t *bytes, uint8_t *errors, uint32_t *t_us,
                    size_t cap, uint32_t until_us, bool *more);
/* While *quiet (its CP has nothing to do: its thread sleeps, the scheduler's shared tick
 * takes its characters, sim_bus_take), member m's thread is woken only by a frame it
 * must answer or report promptly: one that begins with its address or 0 (broadcast),
 * a character with a line error, and any ASCII character; the frames of the other
 * addresses just wait in its queue. NULL (the default): every character wakes it. */
void sim_bus_member_quiet(sim_bus_t *b, size_t m, const atomic_bool *quiet);
/* The time of the next character member m has not taken (it may lie ahead: the
 * master's faulted requests are handed over with their times); false: none. */
bool sim_bus_next_time(sim_bus_t *b, size_t m, uint32_t *t_us);
void sim_bus_free(sim_bus_t *b);

/* The bus thread's body: runs until sim_bus_stop. */
void *sim_bus_thread(void *bus);
void sim_bus_stop(sim_bus_t *b);
void sim_bus_trace(sim_bus_t *b, bool on);
/* The line model the bus's sources write to (before the bus thread starts); solo: one
 * slave, its trace lines "slave 5" (else "@a slave 5"). */
void sim_bus_set_line(sim_bus_t *b, sim_line_t *wire, bool solo);

/* A member's UART starts a reply (buf as handed to the UART) at now_us (the member's
 * clock as passed to its core). Any thread. */
void sim_bus_tx(sim_bus_t *b, size_t member, const uint8_t *buf, uint16_t len, uint32_t now_us);

/* Faults of a member: "KIND=VALUE" (drop=P, crc=P, exc06=P, exc04=P with P in %,
 * delay=MS or delay=MIN-MAX, silent=N, noise=N; serial: parity=K, framing=K, break=MS,
 * gap=K:US, de_cut=BITS) or "off". member SIM_BUS_MASTER: the master's direction (the
 * serial kinds and early=US). false + err on a bad one. */
#define SIM_BUS_MASTER ((size_t)-1)
bool sim_bus_fault_set(sim_bus_t *b, size_t member, const char *spec, char *err, size_t cap);
/* "faults: drop=30% ... | replies=12 dropped=4 ..." */
void sim_bus_fault_describe(sim_bus_t *b, size_t member, char *out, size_t cap);
/* The master's direction has (or had) a serial fault: `status` shows its line. */
bool sim_bus_master_faulted(sim_bus_t *b);
/* Copy of a member's fault state (for tests in the tool). */
sim_fault_t sim_bus_fault_get(sim_bus_t *b, size_t member);

/* Parse a fault spec without a bus (command-line check). */
bool sim_fault_parse(sim_fault_t *f, const char *spec, char *err, size_t cap);

#endif
