/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — console UART with interrupt-driven receive and transmit queues.
 * The queues are the shared ones (modcp/hal_conq.h); this file moves characters between
 * them and the UART. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "cmsdk_regs.h"
#include "modcp/hal_cmsdk.h"

void modcp_cmsdk_con_init(modcp_cmsdk_con_t *con, uintptr_t uart, uint32_t pclk_hz,
                          uint32_t baud)
{
    con->uart = uart;
    con->tx_active = false;
    modcp_conq_init(&con->q);
    uint32_t div = baud != 0u ? pclk_hz / baud : 0u;
    UART_CTRL(uart) = 0u;
    UART_BAUDDIV(uart) = div >= UART_BAUDDIV_MIN ? div : UART_BAUDDIV_MIN;
    UART_STATE(uart) = UART_STATE_RXOVR | UART_STATE_TXOVR;
    UART_INT(uart) = UART_INT_TX | UART_INT_RX | UART_INT_TXOVR | UART_INT_RXOVR;
    UART_CTRL(uart) = UART_CTRL_TXEN | UART_CTRL_RXEN | UART_CTRL_RXINT | UART_CTRL_RXOVRINT;
}

int modcp_cmsdk_con_getc(modcp_cmsdk_con_t *con)
{
    return modcp_conq_getc(&con->q);
}

static void kick(void *ctx)
{
    modcp_cmsdk_con_t *con = ctx;
    uint32_t pm = cmsdk_irq_save();
    if (!con->tx_active) {
        int c = modcp_conq_tx_next(&con->q);
        if (c >= 0) {
            con->tx_active = true;
            UART_INT(con->uart) = UART_INT_TX;
            UART_CTRL(con->uart) |= UART_CTRL_TXINT; /* before the byte: see cmsdk_port.c */
            UART_DATA(con->uart) = (uint32_t)c;
        }
    }
    cmsdk_irq_restore(pm);
}

void modcp_cmsdk_con_write(modcp_cmsdk_con_t *con, const char *s, size_t n)
{
    modcp_conq_write(&con->q, s, n, kick, con);
}

void modcp_cmsdk_con_rx_isr(modcp_cmsdk_con_t *con)
{
    UART_INT(con->uart) = UART_INT_RX;
    while ((UART_STATE(con->uart) & UART_STATE_RXFULL) != 0u) {
        (void)modcp_conq_rx_put(&con->q, (uint8_t)UART_DATA(con->uart));
    }
}

void modcp_cmsdk_con_tx_isr(modcp_cmsdk_con_t *con)
{
    UART_INT(con->uart) = UART_INT_TX;
    if (!con->tx_active) {
        return;
    }
    int c = modcp_conq_tx_next(&con->q);
    if (c >= 0) {
        UART_DATA(con->uart) = (uint32_t)c;
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
