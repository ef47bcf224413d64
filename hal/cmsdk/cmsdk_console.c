/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — console UART with interrupt-driven receive and transmit queues.
 * Single producer / single consumer each way: the receive ISR fills rx, thread mode
 * empties it; thread mode fills tx, the transmit ISR empties it. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cmsdk_regs.h"
#include "modcp/hal_cmsdk.h"

#define RX_MASK (MODCP_CMSDK_CON_RX - 1u)
#define TX_MASK (MODCP_CMSDK_CON_TX - 1u)

void modcp_cmsdk_con_init(modcp_cmsdk_con_t *con, uintptr_t uart, uint32_t pclk_hz,
                          uint32_t baud)
{
    con->uart = uart;
    con->rx_head = con->rx_tail = 0u;
    con->tx_head = con->tx_tail = 0u;
    con->tx_active = false;
    uint32_t div = baud != 0u ? pclk_hz / baud : 0u;
    UART_CTRL(uart) = 0u;
    UART_BAUDDIV(uart) = div >= UART_BAUDDIV_MIN ? div : UART_BAUDDIV_MIN;
    UART_STATE(uart) = UART_STATE_RXOVR | UART_STATE_TXOVR;
    UART_INT(uart) = UART_INT_TX | UART_INT_RX | UART_INT_TXOVR | UART_INT_RXOVR;
    UART_CTRL(uart) = UART_CTRL_TXEN | UART_CTRL_RXEN | UART_CTRL_RXINT | UART_CTRL_RXOVRINT;
}

int modcp_cmsdk_con_getc(modcp_cmsdk_con_t *con)
{
    uint32_t t = con->rx_tail;
    if (t == con->rx_head) {
        return -1;
    }
    int c = con->rx[t & RX_MASK];
    con->rx_tail = t + 1u;
    return c;
}

static void kick(modcp_cmsdk_con_t *con)
{
    uint32_t pm = cmsdk_irq_save();
    if (!con->tx_active && con->tx_tail != con->tx_head) {
        con->tx_active = true;
        UART_INT(con->uart) = UART_INT_TX;
        UART_CTRL(con->uart) |= UART_CTRL_TXINT; /* before the byte: see cmsdk_port.c */
        uint8_t b = con->tx[con->tx_tail & TX_MASK];
        con->tx_tail++;
        UART_DATA(con->uart) = b;
    }
    cmsdk_irq_restore(pm);
}

void modcp_cmsdk_con_write(modcp_cmsdk_con_t *con, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        while (con->tx_head - con->tx_tail >= MODCP_CMSDK_CON_TX) {
            kick(con); /* full: wait for the transmit interrupt to make room */
        }
        con->tx[con->tx_head & TX_MASK] = (uint8_t)s[i];
        con->tx_head++;
    }
    kick(con);
}

void modcp_cmsdk_con_rx_isr(modcp_cmsdk_con_t *con)
{
    UART_INT(con->uart) = UART_INT_RX;
    while ((UART_STATE(con->uart) & UART_STATE_RXFULL) != 0u) {
        uint8_t b = (uint8_t)UART_DATA(con->uart);
        if (con->rx_head - con->rx_tail < MODCP_CMSDK_CON_RX) {
            con->rx[con->rx_head & RX_MASK] = b;
            con->rx_head++;
        }
    }
}

void modcp_cmsdk_con_tx_isr(modcp_cmsdk_con_t *con)
{
    UART_INT(con->uart) = UART_INT_TX;
    if (!con->tx_active) {
        return;
    }
    if (con->tx_tail != con->tx_head) {
        UART_DATA(con->uart) = con->tx[con->tx_tail & TX_MASK];
        con->tx_tail++;
    } else {
        UART_CTRL(con->uart) &= ~UART_CTRL_TXINT;
        con->tx_active = false;
    }
}

void modcp_cmsdk_con_overflow_isr(modcp_cmsdk_con_t *con)
{
    if ((UART_INT(con->uart) & UART_INT_RXOVR) != 0u) {
        UART_STATE(con->uart) = UART_STATE_RXOVR;
        UART_INT(con->uart) = UART_INT_RXOVR;
    }
}
