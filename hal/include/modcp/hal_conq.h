/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the monitor console's interrupt-driven queues (shared by the Cortex-M ports;
 * docs/porting.md §1 "Shared pieces").
 *
 * Single producer / single consumer each way: the console UART's receive interrupt puts
 * characters into rx and thread mode takes them (board_console_getc); thread mode puts
 * the output into tx (board_console_write) and the transmit interrupt takes it. The
 * queue knows no hardware: the port supplies `kick`, which starts the transmit
 * interrupt if it is not running (with interrupts masked around its register accesses),
 * and its interrupt handler calls modcp_conq_rx_put / modcp_conq_tx_next. Pure: no
 * globals (the port owns the queue). */
#ifndef MODCP_HAL_CONQ_H
#define MODCP_HAL_CONQ_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define MODCP_CONQ_RX 128u  /* power of two */
#define MODCP_CONQ_TX 2048u /* power of two */

typedef struct {
    volatile uint32_t rx_head, rx_tail; /* rx: ISR writes head, thread mode tail */
    volatile uint32_t tx_head, tx_tail; /* tx: thread mode writes head, ISR tail */
    uint32_t rx_dropped;                /* characters lost to a full rx queue */
    uint8_t rx[MODCP_CONQ_RX];
    uint8_t tx[MODCP_CONQ_TX];
} modcp_conq_t;

static inline void modcp_conq_init(modcp_conq_t *q)
{
    q->rx_head = q->rx_tail = 0u;
    q->tx_head = q->tx_tail = 0u;
    q->rx_dropped = 0u;
}

/* Thread mode: the next received character, or -1. */
static inline int modcp_conq_getc(modcp_conq_t *q)
{
    uint32_t t = q->rx_tail;
    if (t == q->rx_head) {
        return -1;
    }
    int c = q->rx[t & (MODCP_CONQ_RX - 1u)];
    q->rx_tail = t + 1u;
    return c;
}

/* Receive interrupt: one character; false (and counted) when the queue is full. */
static inline bool modcp_conq_rx_put(modcp_conq_t *q, uint8_t b)
{
    uint32_t h = q->rx_head;
    if (h - q->rx_tail >= MODCP_CONQ_RX) {
        q->rx_dropped++;
        return false;
    }
    q->rx[h & (MODCP_CONQ_RX - 1u)] = b;
    q->rx_head = h + 1u;
    return true;
}

/* Thread mode: queue n characters, waiting (kick, then spin) while the queue is full,
 * and kick the transmitter at the end. */
static inline void modcp_conq_write(modcp_conq_t *q, const char *s, size_t n,
                                    void (*kick)(void *ctx), void *ctx)
{
    for (size_t i = 0; i < n; i++) {
        while (q->tx_head - q->tx_tail >= MODCP_CONQ_TX) {
            kick(ctx); /* full: the transmit interrupt makes room */
        }
        q->tx[q->tx_head & (MODCP_CONQ_TX - 1u)] = (uint8_t)s[i];
        q->tx_head = q->tx_head + 1u;
    }
    kick(ctx);
}

/* Transmit interrupt (or kick): the next character to send, or -1 when the queue is
 * empty (switch the transmit interrupt off then). */
static inline int modcp_conq_tx_next(modcp_conq_t *q)
{
    uint32_t t = q->tx_tail;
    if (t == q->tx_head) {
        return -1;
    }
    int c = q->tx[t & (MODCP_CONQ_TX - 1u)];
    q->tx_tail = t + 1u;
    return c;
}

#endif
