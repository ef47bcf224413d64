/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the bus's state, shared by its files (bus.c, bus_decode.c, bus_fault.c,
 * bus_deliver.c); nothing outside tools/sim/bus*.c includes it. */
#ifndef MODCP_SIM_BUS_INTERNAL_H
#define MODCP_SIM_BUS_INTERNAL_H


#include "bus.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "modcp/crc.h"
#include "modcp/hal_posix.h"
#include "trace.h"

/* transmissions on the line at once (every member's reply, noise, fault pieces); the
 * loops run to the high-water mark s_hi only */
#define MAX_SENDERS (SIM_BUS_MAX_MEMBERS + 64)

/* a set of members (any number up to SIM_BUS_MAX_MEMBERS) */
#define MSET_WORDS ((SIM_BUS_MAX_MEMBERS + 63) / 64)
typedef struct {
    uint64_t w[MSET_WORDS];
} mset_t;
static inline void mset_add(mset_t *s, size_t m)
{
    s->w[m / 64u] |= (uint64_t)1u << (m % 64u);
}
static inline bool mset_has(const mset_t *s, size_t m)
{
    return (s->w[m / 64u] & ((uint64_t)1u << (m % 64u))) != 0u;
}
static inline void mset_or(mset_t *a, const mset_t *b)
{
    for (size_t i = 0; i < MSET_WORDS; i++) {
        a->w[i] |= b->w[i];
    }
}
#define NOISE (-1)
#define SPIN_US 50.0

typedef struct {
    bool used;
    int who; /* member index or NOISE */
    uint8_t b[MODCP_POSIX_TX_MAX];
    uint16_t len;
    double t0; /* us since the bus's t0: start of the first start bit */
    /* serial faults of this transmission (0: none) */
    uint16_t parity_k, framing_k; /* 1-based byte with a wrong parity bit / a 0 stop bit */
    uint8_t cut_bits;             /* DE off this many bits before the last stop bit ends */
    double low_us;                /* a BREAK: no characters, the line held at 0 this long */
} sender_t;

/* a character of the master for the members, due at t (the master's serial faults) */
typedef struct {
    uint8_t byte, errors;
    double t; /* end of its stop bit */
} mchar_t;
#define MQ_MAX 2048

struct sim_bus {
    sim_line_cfg_t line;
    sim_line_t *wire; /* the line model (observers); NULL: none */
    bool solo;        /* one slave: its trace lines without its name */
    double c_us;   /* character time */
    double bit_us; /* bit time */
    unsigned nbits;
    size_t n;
    char names[SIM_BUS_MAX_MEMBERS][24];
    uint8_t addr[SIM_BUS_MAX_MEMBERS];
    int member_fd[SIM_BUS_MAX_MEMBERS];
    int wake_fd[SIM_BUS_MAX_MEMBERS];
    /* sim_bus_member_quiet: while *quiet[m], only a frame for member m wakes it */
    const atomic_bool *quiet[SIM_BUS_MAX_MEMBERS];
    double last_t[SIM_BUS_MAX_MEMBERS]; /* end of the last character handed to member m */
    /* what each member heard: byte + the member's clock at the end of its stop bit */
    pthread_mutex_t rx_mu;
    struct {
        uint8_t b[8192];
        uint8_t e[8192]; /* MODCP_LINE_* */
        uint32_t t[8192];
        size_t head, tail;
    } rxq[SIM_BUS_MAX_MEMBERS];
    int master_fd;
    modcp_posix_event_t wake; /* the bus thread's: a member replied, a request to stop */
    uint64_t t0_us64;
    void (*print)(void *user, const char *line);
    void *user;
    atomic_bool stop;
    atomic_bool trace_on;

    pthread_mutex_t mu; /* everything below */
    sender_t s[MAX_SENDERS];
    size_t s_hi; /* s[s_hi..] are unused */
    double from; /* the receiver looks for the next start bit from here */
    sim_fault_t fault[SIM_BUS_MAX_MEMBERS];
    sim_fault_t mfault; /* the master's direction (@master) */
    mchar_t mq[MQ_MAX]; /* the master's characters not yet due (a gap, a BREAK) */
    size_t mq_n;
    double reply_end; /* end of the last reply's last stop bit (early=US) */
    uint32_t rng;
    /* what the receiver heard, cut at t3.5 like a frame */
    uint8_t heard[SIM_TRACE_MAX];
    size_t heard_len;
    double heard_t0, heard_end;
    bool heard_collided;
    mset_t heard_mask; /* members that sent during the frame */
    /* the characters for the members, handed over when the line pauses: a member's
     * core cuts frames by t1.5 / t3.5 of its own clock, so a late wake-up of the bus
     * thread must not open a gap inside a frame it hears (a UART never does) */
    uint8_t mbuf[SIM_TRACE_MAX];
    uint8_t merr[SIM_TRACE_MAX]; /* MODCP_LINE_* of each */
    mset_t mdeaf[SIM_TRACE_MAX]; /* members sending while the character was on the line */
    double mt[SIM_TRACE_MAX];      /* end of its stop bit */
    size_t mlen;
    sim_trace_t tr;      /* formats the trace's notes of the replies and collisions */
    /* MODCP_SIM_BUS_LOG=FILE: the bus thread's polls, reads and writes, each with its
     * CLOCK_MONOTONIC time (the times master_bus prints its errors with); off: NULL */
    FILE *log;
    pthread_mutex_t log_mu;
};

typedef struct {
    double start; /* start bit's falling edge */
    uint8_t byte;
    mset_t mask;     /* members sending during the character */
    unsigned senders; /* senders (members and noise) during it */
    uint8_t errors;  /* MODCP_LINE_PARITY / _FRAMING / _BREAK as the receiver found it */
    double len_us;   /* a BREAK's length (else one character) */
} rxchar_t;

/* us since the bus's t0 (bus.c) */
double now_rel(const sim_bus_t *b);
/* one line of the bus log, MODCP_SIM_BUS_LOG (bus.c) */
void blog(sim_bus_t *b, const char *what, const uint8_t *p, size_t n);

/* the line's levels and its receiver (bus_decode.c) */
double end_of(const sim_bus_t *b, const sender_t *s);
bool decode_next(const sim_bus_t *b, rxchar_t *out);

/* the reply faults' random choices and transforms (bus_fault.c) */
uint32_t rnd(sim_bus_t *b);
bool chance(sim_bus_t *b, uint8_t pct);
uint16_t exception_frame(const sim_bus_t *b, const uint8_t *in, uint16_t len, uint8_t code,
                         uint8_t *out);
void corrupt_check(const sim_bus_t *b, uint8_t *buf, uint16_t len);
double reply_faults(sim_bus_t *b, sim_fault_t *f, uint8_t *buf, uint16_t *len, char *note,
                    size_t cap);
/* The serial faults of f on a transmission s (counted; the gap and the BREAK make
 * senders of their own: at most 3, in extra[], returns how many); b->mu held. */
size_t serial_faults(sim_bus_t *b, sim_fault_t *f, sender_t *s, sender_t **extra, char *note,
                     size_t cap);
sender_t *new_sender(sim_bus_t *b);
/* The master's characters (read at t) through its serial faults into b->mq (bus_master.c). */
void master_faults(sim_bus_t *b, const uint8_t *buf, size_t n, double t);
/* The master's characters due by now to the members; the time the next one is due or -1. */
double master_due(sim_bus_t *b, double now);

/* what the receiver heard, to the master and the members (bus_deliver.c) */
void heard_flush(sim_bus_t *b);
void deliver(sim_bus_t *b, size_t m, const uint8_t *bytes, const uint8_t *errors, const double *t,
             size_t n);
void master_write(sim_bus_t *b, const uint8_t *p, size_t n);
void members_flush(sim_bus_t *b);

#endif
