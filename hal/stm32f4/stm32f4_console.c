/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — console USART (8N1) with interrupt-driven receive and transmit
 * queues. Single producer / single consumer each way. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal_stm32f4.h"
#include "stm32f4_regs.h"

#define RX_MASK (MODCP_STM32_CON_RX - 1u)
#define TX_MASK (MODCP_STM32_CON_TX - 1u)

void modcp_stm32_con_init(modcp_stm32_con_t *con, uintptr_t usart, uint8_t irq, uint32_t clk_hz,
                          uint32_t baud)
{
    con->usart = usart;
    con->irq = irq;
    con->rx_head = con->rx_tail = 0u;
    con->tx_head = con->tx_tail = 0u;
    USART_CR1(usart) = 0u;
    USART_BRR(usart) = (clk_hz + baud / 2u) / baud;
    USART_CR2(usart) = 0u;
    USART_CR3(usart) = 0u;
    USART_CR1(usart) = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
}

int modcp_stm32_con_getc(modcp_stm32_con_t *con)
{
    uint32_t t = con->rx_tail;
    if (t == con->rx_head) {
        return -1;
    }
    int c = con->rx[t & RX_MASK];
    con->rx_tail = t + 1u;
    return c;
}

static void enable_txe(modcp_stm32_con_t *con)
{
    uint32_t pm = stm32_irq_save();
    USART_CR1(con->usart) |= USART_CR1_TXEIE;
    stm32_irq_restore(pm);
    stm32_irq_pend(con->irq); /* QEMU 7.2 raises no TXE interrupt: see hal_stm32f4.h */
}

void modcp_stm32_con_write(modcp_stm32_con_t *con, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        while (con->tx_head - con->tx_tail >= MODCP_STM32_CON_TX) {
            enable_txe(con); /* full: the TXE interrupt makes room */
        }
        con->tx[con->tx_head & TX_MASK] = (uint8_t)s[i];
        con->tx_head++;
    }
    enable_txe(con);
}

void modcp_stm32_con_isr(modcp_stm32_con_t *con)
{
    uintptr_t u = con->usart;
    uint32_t sr = USART_SR(u);
    while ((sr & (USART_SR_RXNE | USART_SR_ORE)) != 0u) {
        uint8_t b = (uint8_t)USART_DR(u);
        if ((sr & (USART_SR_FE | USART_SR_PE)) == 0u &&
            con->rx_head - con->rx_tail < MODCP_STM32_CON_RX) {
            con->rx[con->rx_head & RX_MASK] = b;
            con->rx_head++;
        }
        sr = USART_SR(u);
    }
    if ((USART_CR1(u) & USART_CR1_TXEIE) != 0u) {
        while (con->tx_tail != con->tx_head && (USART_SR(u) & USART_SR_TXE) != 0u) {
            USART_DR(u) = con->tx[con->tx_tail & TX_MASK];
            con->tx_tail++;
        }
        if (con->tx_tail == con->tx_head) {
            USART_CR1(u) &= ~USART_CR1_TXEIE;
        }
    }
}
