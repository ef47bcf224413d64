/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — console USART (8N1) with interrupt-driven receive and transmit
 * queues: the shared ones (modcp/hal_conq.h). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal_stm32f4.h"
#include "stm32f4_regs.h"

void modcp_stm32_con_init(modcp_stm32_con_t *con, uintptr_t usart, uint8_t irq, uint32_t clk_hz,
                          uint32_t baud)
{
    con->usart = usart;
    con->irq = irq;
    modcp_conq_init(&con->q);
    USART_CR1(usart) = 0u;
    USART_BRR(usart) = (clk_hz + baud / 2u) / baud;
    USART_CR2(usart) = 0u;
    USART_CR3(usart) = 0u;
    USART_CR1(usart) = USART_CR1_UE | USART_CR1_TE | USART_CR1_RE | USART_CR1_RXNEIE;
}

int modcp_stm32_con_getc(modcp_stm32_con_t *con)
{
    return modcp_conq_getc(&con->q);
}

static void enable_txe(void *ctx)
{
    modcp_stm32_con_t *con = ctx;
    uint32_t pm = stm32_irq_save();
    USART_CR1(con->usart) |= USART_CR1_TXEIE;
    stm32_irq_restore(pm);
    stm32_irq_pend(con->irq); /* QEMU 7.2 raises no TXE interrupt: see hal_stm32f4.h */
}

void modcp_stm32_con_write(modcp_stm32_con_t *con, const char *s, size_t n)
{
    modcp_conq_write(&con->q, s, n, enable_txe, con);
}

void modcp_stm32_con_isr(modcp_stm32_con_t *con)
{
    uintptr_t u = con->usart;
    uint32_t sr = USART_SR(u);
    while ((sr & (USART_SR_RXNE | USART_SR_ORE)) != 0u) {
        uint8_t b = (uint8_t)USART_DR(u);
        if ((sr & (USART_SR_FE | USART_SR_PE)) == 0u) {
            (void)modcp_conq_rx_put(&con->q, b);
        }
        sr = USART_SR(u);
    }
    if ((USART_CR1(u) & USART_CR1_TXEIE) != 0u) {
        while ((USART_SR(u) & USART_SR_TXE) != 0u) {
            int c = modcp_conq_tx_next(&con->q);
            if (c < 0) {
                USART_CR1(u) &= ~USART_CR1_TXEIE;
                break;
            }
            USART_DR(u) = (uint32_t)c;
        }
    }
}
