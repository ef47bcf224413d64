/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL for the host: a UART on a pseudo-terminal (or a real serial
 * device with termios from the parameters), the monotonic clock, the one-shot timer,
 * and threads. It implements modcp_hal_t; it does not call the core: the port's
 * owner (modcp-sim's CP thread) waits with modcp_posix_wait() and feeds what happened
 * to modcp_cp_on_rx() / _on_line_error() / _on_timer() / _on_tx_done().
 * The wait ends on an event, never on a fixed poll: a character on the line, the
 * one-shot timer's deadline, the time of the next paced reply byte, or a wake-up from
 * another thread (modcp_posix_wake(), e.g. the CPU side after it put a reply on the
 * backplane); max_us only bounds it for the owner's housekeeping.
 *
 * Transmission timing: on a pseudo-terminal nothing paces the bytes, so the port does
 * it: byte k of a reply is written when its last stop bit would have left the line
 * (t0 + (k+1) x character time), and "transmission complete" is reported together
 * with the last byte. A master therefore never sees the end of a reply before the
 * CP's transmitter is done, exactly as on a wire. The same holds for a --device that
 * is itself a pseudo-terminal (/dev/pts/N). On a real device the kernel paces;
 * "transmission complete" is reported after len x character time once the driver's
 * output queue is empty. */
#ifndef MODCP_HAL_POSIX_H
#define MODCP_HAL_POSIX_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal.h"

#define MODCP_POSIX_TX_MAX 1024u

typedef struct {
    uint8_t byte;
    uint8_t errors; /* MODCP_LINE_* (0 = a good character); BREAK comes with byte 0 */
} modcp_posix_rx_t;

/* An event another thread can signal (a non-blocking pipe): e.g. a "backplane
 * interrupt" from one side to the other. Signals before a wait are not lost; several
 * give one wake-up. */
typedef struct {
    int rd, wr;
} modcp_posix_event_t;

typedef struct modcp_posix_port {
    int fd;       /* pty master or device */
    int slave_fd; /* pty: a slave fd kept open so the master never reads EIO; else -1 */
    modcp_posix_event_t wake; /* modcp_posix_wake ends modcp_posix_wait */
    bool is_pty; /* we own the pty master (open_pty) */
    bool paced;  /* nothing paces the bytes (a pty on either side): the port does */
    char path[256]; /* the device a master opens (pty slave name or the device) */
    char link[256]; /* symlink to path made by open_pty ("" = none) */
    uint32_t char_us;
    uint8_t parity; /* modcp_parity_t, to classify marked characters */
    /* clock as the owner last passed it to the core (timer_arm is relative to it) */
    uint32_t now_us;
    /* one-shot timer */
    bool timer_armed;
    uint32_t timer_deadline_us;
    /* a wake-up (modcp_posix_wake) the owner expects at about expect_us, e.g. the
     * other side's reply at its next cycle: watched for, not slept through */
    bool expect_armed;
    uint32_t expect_us;
    /* transmission */
    uint8_t tx_buf[MODCP_POSIX_TX_MAX];
    uint16_t tx_len;
    uint16_t tx_pos; /* bytes written */
    uint32_t tx_t0_us;
    bool tx_active;
    /* outputs */
    bool de, led[3], rts, dtr;
    /* RS232 inputs as last reported (modcp_posix_modem_inputs) */
    bool inputs_known, cts, dsr;
    /* receive decoding (PARMRK on a device) */
    uint8_t mark_state;
    uint8_t rx_preset; /* the CP's receive-line preset (hal set_rx_preset): with
                          MODCP_RXP_HIGH a broken line looks idle, BREAK is not seen */
    uint32_t overruns; /* last TIOCGICOUNT overrun count */
    /* optional observer of transmitted frames (for the trace) */
    void (*on_tx)(void *user, const uint8_t *buf, uint16_t len, uint32_t now_us);
    void *on_tx_user;
} modcp_posix_port_t;

/* Microseconds (wrapping at 2^32) and milliseconds of CLOCK_MONOTONIC. */
uint32_t modcp_posix_now_us(void);
uint32_t modcp_posix_now_ms(void);
/* Full-width monotonic microseconds (for time stamps since start). */
uint64_t modcp_posix_now_us64(void);

/* Open a pseudo-terminal in raw mode; link (may be NULL or "") gets a symlink to the
 * slave. An existing link is replaced only when it is stale (its target is gone):
 * -EBUSY when it points at a device that exists (e.g. a running instance's pty),
 * -EEXIST when link is not a symlink. Returns 0 or -errno. */
int modcp_posix_open_pty(modcp_posix_port_t *p, const char *link, uint32_t char_us);

/* Open a serial device with baud / data bits / parity / stop bits (termios; rates
 * without a Bxxx constant such as 76800 via termios2 on Linux). Returns 0 or -errno. */
int modcp_posix_open_device(modcp_posix_port_t *p, const char *path, uint32_t baud,
                            uint8_t data_bits, uint8_t parity, uint8_t stop_bits,
                            uint32_t char_us);

/* Close; removes the symlink if it still points at our pty. */
void modcp_posix_close(modcp_posix_port_t *p);

/* The modcp_hal_t of this port (uart_tx, timer_arm, set_de, set_led, set_signal). */
void modcp_posix_hal(modcp_posix_port_t *p, modcp_hal_t *hal);

/* Wait up to max_us for something to happen (received characters, timer expiry,
 * transmission progress, modcp_posix_wake() from another thread). On return *now_us
 * is the current time; *tx_done and *timer_fired tell what is due (deliver tx_done
 * first, then the timer, then the characters), and up to cap received characters are
 * in rx[]. Returns the number of characters, or -errno on a read error. The timer's
 * deadline and a reply's first byte are kept to within a few microseconds (the last
 * 50 us before them are spent watching the clock, not asleep); so is a wake-up the
 * owner expects (expect_armed: from 50 us before expect_us until 50 us after it). */
int modcp_posix_wait(modcp_posix_port_t *p, uint32_t max_us, modcp_posix_rx_t *rx, size_t cap,
                     bool *tx_done, bool *timer_fired, uint32_t *now_us);

/* End the owner's modcp_posix_wait() now (or its next one, if it is not waiting).
 * Any thread may call it; several calls before the wait ends give one wake-up. */
void modcp_posix_wake(modcp_posix_port_t *p);

/* RS232 inputs CTS / DSR for modcp_cp_on_signals(): true when they changed since the
 * last call (the first call always reports). A pty has no modem lines: the partner is
 * modelled as always ready (CTS and DSR ON). A device is read with TIOCMGET. */
bool modcp_posix_modem_inputs(modcp_posix_port_t *p, bool *cts, bool *dsr);

/* Threads (pthreads): start fn(arg); 0 or -errno. The thread runs without timer
 * slack (Linux PR_SET_TIMERSLACK), so its timed waits end when they are due, and with
 * a 100 us time slice (Linux 6.12+ sched_setattr), so it runs when it wakes rather
 * than after a busy neighbour's slice. t must
 * stay in place until the thread has started fn (keep it until the join). */
typedef struct {
    pthread_t handle;
    void *(*fn)(void *);
    void *arg;
} modcp_posix_thread_t;
int modcp_posix_thread_start(modcp_posix_thread_t *t, void *(*fn)(void *), void *arg);
void modcp_posix_thread_join(modcp_posix_thread_t *t);

/* Sleep until the absolute CLOCK_MONOTONIC time in microseconds (64-bit). */
void modcp_posix_sleep_until_us64(uint64_t t_us);
/* Watch the clock (no sleep) until the absolute time t_us: for the last few tens of
 * microseconds before a deadline that must not be late; keep it that short. */
void modcp_posix_spin_until_us64(uint64_t t_us);

int modcp_posix_event_open(modcp_posix_event_t *e); /* 0 or -errno */
void modcp_posix_event_close(modcp_posix_event_t *e);
void modcp_posix_event_signal(modcp_posix_event_t *e);
/* For a caller that polls e->rd itself: take the signals that are pending. */
void modcp_posix_event_clear(modcp_posix_event_t *e);
/* Sleep until the absolute time t_us (64-bit) or a signal; true when signalled. */
bool modcp_posix_event_wait_until(modcp_posix_event_t *e, uint64_t t_us);

#endif
