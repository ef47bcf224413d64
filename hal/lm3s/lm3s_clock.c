/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (LM3S) — core clock, SysTick time base, 1 ms tick, console UART. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "lm3s_regs.h"
#include "modcp/hal_lm3s.h"

#define SYST_CSR LM3S_REG(0xE000E010u)
#define SYST_RVR LM3S_REG(0xE000E014u)
#define SYST_CVR LM3S_REG(0xE000E018u)
#define SYST_CSR_ENABLE 0x1u
#define SYST_CSR_CLKSOURCE 0x4u /* processor clock */

#define PLL_LOCK_WAIT 200000u

uint32_t modcp_lm3s_clock_init(uint32_t sysdiv)
{
    /* Data sheet 6.3 (PLL): bypass, select the crystal, power up the PLL, wait for its
     * lock, then the divider and no bypass. */
    uint32_t rcc = SYSCTL_RCC;
    rcc |= RCC_BYPASS;
    rcc &= ~RCC_USESYSDIV;
    SYSCTL_RCC = rcc;
    rcc &= ~(RCC_XTAL_MASK | RCC_OSCSRC_MASK | RCC_MOSCDIS | RCC_PWRDN);
    rcc |= RCC_XTAL_8MHZ; /* OSCSRC 0: main oscillator */
    SYSCTL_RCC = rcc;
    rcc = (rcc & ~RCC_SYSDIV_MASK) | RCC_SYSDIV(sysdiv) | RCC_USESYSDIV;
    SYSCTL_RCC = rcc;
    uint32_t n = 0u;
    while ((SYSCTL_RIS & SYSCTL_RIS_PLLLRIS) == 0u && n < PLL_LOCK_WAIT) {
        n++;
    }
    if ((SYSCTL_RIS & SYSCTL_RIS_PLLLRIS) == 0u) {
        return 8000000u; /* no lock: stays on the crystal (bypass) */
    }
    SYSCTL_RCC = rcc & ~RCC_BYPASS;
    return 200000000u / sysdiv;
}

/* ---- time base: SysTick over its 24 bits ---- */

static modcp_timebase_t tb;

void modcp_lm3s_time_init(uint32_t hz)
{
    SYST_CSR = 0u;
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0u; /* reloads from RVR */
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_CLKSOURCE;
    modcp_timebase_init(&tb, hz, 24u, true, SYST_CVR);
}

uint32_t modcp_lm3s_now_us(void)
{
    uint32_t pm = lm3s_irq_save();
    modcp_timebase_feed(&tb, SYST_CVR);
    uint32_t us = tb.us;
    lm3s_irq_restore(pm);
    return us;
}

uint32_t modcp_lm3s_now_ms(void)
{
    uint32_t pm = lm3s_irq_save();
    modcp_timebase_feed(&tb, SYST_CVR);
    uint32_t ms = tb.ms;
    lm3s_irq_restore(pm);
    return ms;
}

/* ---- 1 ms tick ---- */

void modcp_lm3s_tick_init(uintptr_t gptm, uint32_t clk_hz)
{
    GPTM_CTL(gptm) = 0u;
    GPTM_CFG(gptm) = GPTM_CFG_32BIT;
    GPTM_TAMR(gptm) = GPTM_TAMR_PERIODIC;
    GPTM_TAILR(gptm) = clk_hz / 1000u - 1u;
    GPTM_ICR(gptm) = GPTM_INT_TATO;
    GPTM_IMR(gptm) = GPTM_INT_TATO;
    GPTM_CTL(gptm) = GPTM_CTL_TAEN;
}

bool modcp_lm3s_tick_ack(uintptr_t gptm)
{
    if ((GPTM_MIS(gptm) & GPTM_INT_TATO) == 0u) {
        return false;
    }
    GPTM_ICR(gptm) = GPTM_INT_TATO;
    return true;
}

/* ---- console UART ---- */

void modcp_lm3s_con_init(modcp_lm3s_con_t *con, uintptr_t uart, uint32_t clk_hz, uint32_t baud)
{
    con->uart = uart;
    con->tx_active = false;
    modcp_conq_init(&con->q);
    uint32_t brd = modcp_lm3s_brd(clk_hz, baud);
    UART_CTL(uart) = 0u;
    UART_IBRD(uart) = brd >> 6;
    UART_FBRD(uart) = brd & 63u;
    UART_LCRH(uart) = UART_LCRH_WLEN_8 | UART_LCRH_FEN;
    UART_IFLS(uart) = 0u; /* 1/8 full: receive interrupt early, receive timeout after */
    UART_ICR(uart) = 0x7F0u;
    UART_IM(uart) = UART_INT_RX | UART_INT_RT;
    UART_CTL(uart) = UART_CTL_UARTEN | UART_CTL_TXE | UART_CTL_RXE;
}

int modcp_lm3s_con_getc(modcp_lm3s_con_t *con)
{
    return modcp_conq_getc(&con->q);
}

/* Fill the transmit FIFO from the queue; the transmit interrupt while there is more. */
static void con_fill(modcp_lm3s_con_t *con)
{
    uintptr_t u = con->uart;
    while ((UART_FR(u) & UART_FR_TXFF) == 0u) {
        int c = modcp_conq_tx_next(&con->q);
        if (c < 0) {
            UART_IM(u) &= ~UART_INT_TX;
            con->tx_active = false;
            return;
        }
        UART_ICR(u) = UART_INT_TX;
        UART_DR(u) = (uint32_t)c;
    }
    con->tx_active = true;
    UART_IM(u) |= UART_INT_TX;
}

static void con_kick(void *ctx)
{
    modcp_lm3s_con_t *con = ctx;
    uint32_t pm = lm3s_irq_save();
    if (!con->tx_active) {
        con_fill(con);
    }
    lm3s_irq_restore(pm);
}

void modcp_lm3s_con_write(modcp_lm3s_con_t *con, const char *s, size_t n)
{
    modcp_conq_write(&con->q, s, n, con_kick, con);
}

void modcp_lm3s_con_isr(modcp_lm3s_con_t *con)
{
    uintptr_t u = con->uart;
    UART_ICR(u) = UART_INT_RX | UART_INT_RT | UART_INT_ERR;
    while ((UART_FR(u) & UART_FR_RXFE) == 0u) {
        uint32_t d = UART_DR(u);
        if ((d & (UART_DR_FE | UART_DR_PE | UART_DR_BE)) == 0u) {
            (void)modcp_conq_rx_put(&con->q, (uint8_t)d);
        }
    }
    if (con->tx_active && (UART_MIS(u) & UART_INT_TX) != 0u) {
        con_fill(con);
    }
}
