/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the line model: every character on the serial line with its start time
 * and its bits, from every source, in time order to every observer.
 *
 *   sources    the master's pty (or serial device), each member's transmitter (after
 *              the bus's reply faults), a QEMU member's UART, the noise fault. Each
 *              writes characters with sim_line_put_frame (a transmitter: back to back
 *              from its first start bit) or sim_line_put_arrived (a pty: the chunk read
 *              at t; its last stop bit is taken to end then, the others before it,
 *              never over characters already on the line).
 *   the line   holds the characters for a while (hold_us: a pty chunk is back-dated, a
 *              reply is handed over at its start) and releases them in the order of
 *              their start bits (sim_line_tick, sim_line_close). Characters of two
 *              sources that overlap are flagged SIM_CH_COLLIDED.
 *   notes      lines of text for the text trace (events, fault remarks, collisions,
 *              console output while the trace runs) are held and released with the
 *              characters, in the same time order (sim_line_note).
 *   observers  read the released characters through one interface (sim_observer_t):
 *              the text trace (trace_obs.c), the Wireshark capture (capture.c), the
 *              waveform (vcd.c).
 * Times are us since the simulator started (the trace's time), 64 bits. Any thread. */
#ifndef MODCP_SIM_LINE_H
#define MODCP_SIM_LINE_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* every Modbus address (1..247) plus QEMU members: no bitmask or array limits below this */
#define SIM_LINE_MAX_MEMBERS 256
#define SIM_LINE_QUEUE 4096
#define SIM_LINE_MAX_OBSERVERS 4

/* sources other than a member (a member is its index 0..n-1) */
#define SIM_SRC_MASTER (-1)
#define SIM_SRC_NOISE (-2)

/* flags of a character */
#define SIM_CH_PARITY 0x01u   /* its parity bit is wrong */
#define SIM_CH_FRAMING 0x02u  /* its stop bit is 0 */
#define SIM_CH_BREAK 0x04u    /* not a character: the line held at 0 for len_us */
#define SIM_CH_COLLIDED 0x08u /* another source sent at the same time */
#define SIM_CH_DE_CUT 0x10u   /* the sender's DE went off at de_off_us, inside it */

/* line settings (every member's: they agree) */
typedef struct {
    uint8_t data_bits, parity, stop_bits; /* parity: modcp_parity_t (0 none, 1 odd, 2 even) */
    bool ascii;
    uint32_t baud;
    uint32_t char_us;
    uint32_t t35_us; /* RTU t3.5 (ASCII: the character timeout): the end of a frame */
} sim_line_cfg_t;

typedef struct {
    uint64_t t_us;      /* start of its start bit */
    uint32_t len_us;    /* time on the line: one character, or a BREAK's length */
    uint32_t de_off_us; /* SIM_CH_DE_CUT: DE off this long after t_us */
    int16_t src;        /* member index, SIM_SRC_MASTER, SIM_SRC_NOISE */
    uint8_t byte;
    uint8_t flags;      /* SIM_CH_* */
} sim_char_t;

/* A line of text at a time, for the text trace: handed to the observers in the same
 * time order as the characters (before a character of the same time). */
#define SIM_NOTE_MAX 1024
#define SIM_LINE_NOTES 256
enum {
    SIM_NOTE_LINE,   /* a trace line of its own: an event, a collision, a reply not sent */
    SIM_NOTE_FRAME,  /* a remark on src's next frame ("(fault: CRC corrupted)") */
    SIM_NOTE_OUTPUT  /* console output, printed as it is */
};
typedef struct {
    uint64_t t_us;
    int16_t src;
    uint8_t kind; /* SIM_NOTE_* */
    char text[SIM_NOTE_MAX];
} sim_note_t;

typedef struct sim_observer sim_observer_t;
struct sim_observer {
    /* a character, in the order of t_us */
    void (*on_char)(sim_observer_t *o, const sim_char_t *c);
    /* a note, in the same order (NULL: not read) */
    void (*on_note)(sim_observer_t *o, const sim_note_t *n);
    /* everything up to t has been handed over (NULL: not read) */
    void (*on_time)(sim_observer_t *o, uint64_t t);
    /* the line closes: write what is left */
    void (*on_close)(sim_observer_t *o);
};

typedef struct {
    sim_line_cfg_t cfg;
    size_t n_members;
    char names[SIM_LINE_MAX_MEMBERS][24]; /* "a" for member @a */
    uint8_t addr[SIM_LINE_MAX_MEMBERS];
    uint64_t t0_real_us; /* wall-clock time of t = 0 (us since the epoch) */
    uint64_t hold_us;
    pthread_mutex_t mu;
    sim_char_t q[SIM_LINE_QUEUE]; /* held, sorted by t_us: a ring from qh, qn of them */
    size_t qh, qn;
    sim_note_t notes[SIM_LINE_NOTES]; /* held notes, sorted by t_us: a ring from nh, nn */
    size_t nh, nn;
    uint64_t released; /* start of the last character released */
    uint64_t last_end[2 + SIM_LINE_MAX_MEMBERS]; /* end of each source's last character */
    int16_t last_src;  /* the last released character's source */
    uint64_t last_rel_end;
    sim_observer_t *obs[SIM_LINE_MAX_OBSERVERS];
    _Atomic size_t nobs;
} sim_line_t;

void sim_line_init(sim_line_t *l, const sim_line_cfg_t *cfg, uint64_t t0_us64);
/* Member i's name and address (for the observers' labels). */
void sim_line_member(sim_line_t *l, size_t i, const char *name, uint8_t addr);
/* false: too many observers (any thread) */
bool sim_line_observe(sim_line_t *l, sim_observer_t *o);
/* Anyone watching? (Sources skip the work when not.) Any thread. */
bool sim_line_watched(const sim_line_t *l);

/* n characters of src back to back from t0 (a UART's transmission); flags: per
 * character or NULL. */
void sim_line_put_frame(sim_line_t *l, int src, const uint8_t *b, const uint8_t *flags, size_t n,
                        uint64_t t0);
/* n characters of src read at t_end (a pty delivers them at once): the last stop bit
 * ends at t_end, each one before it a character earlier, but none before the end of a
 * character already put (of any source; then the last ends after t_end). */
void sim_line_put_arrived(sim_line_t *l, int src, const uint8_t *b, const uint8_t *flags, size_t n,
                          uint64_t t_end);
/* One character or BREAK. */
void sim_line_put(sim_line_t *l, const sim_char_t *c);
/* A note at t_us (printf-style text) from src; nothing when nobody watches. */
void sim_line_note(sim_line_t *l, uint64_t t_us, int src, unsigned kind, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* Release what is older than now - hold_us to the observers. */
void sim_line_tick(sim_line_t *l, uint64_t now);
/* Release everything and close the observers. */
void sim_line_close(sim_line_t *l);

/* Level (0/1) of bit i (0 = start) of character v; bits past the frame are 1. */
int sim_line_bit(const sim_line_cfg_t *cfg, uint8_t v, unsigned i);
/* Bits of one character: start, data, parity, stop. */
unsigned sim_line_nbits(const sim_line_cfg_t *cfg);
/* "master", "@a", "noise" */
const char *sim_line_src_name(const sim_line_t *l, int src);

#endif
