/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (TI Stellaris LM3S) — the registers used, from the LM3S6965 data sheet
 * (DS-LM3S6965) and the ARM PL011 TRM; no vendor headers. */
#ifndef MODCP_LM3S_REGS_H
#define MODCP_LM3S_REGS_H

#include <stdint.h>

#define LM3S_REG(a) (*(volatile uint32_t *)(uintptr_t)(a))

/* System control */
#define SYSCTL_BASE 0x400FE000u
#define SYSCTL_RIS LM3S_REG(SYSCTL_BASE + 0x050u)
#define SYSCTL_RCC LM3S_REG(SYSCTL_BASE + 0x060u)
#define SYSCTL_RCGC1 LM3S_REG(SYSCTL_BASE + 0x104u)
#define SYSCTL_RCGC2 LM3S_REG(SYSCTL_BASE + 0x108u)
#define SYSCTL_RIS_PLLLRIS (1u << 6)
#define RCC_MOSCDIS (1u << 0)
#define RCC_OSCSRC_MASK (3u << 4)
#define RCC_XTAL_MASK (0xFu << 6)
#define RCC_XTAL_8MHZ (0xEu << 6)
#define RCC_BYPASS (1u << 11)
#define RCC_PWRDN (1u << 13)
#define RCC_USESYSDIV (1u << 22)
#define RCC_SYSDIV_MASK (0xFu << 23)
#define RCC_SYSDIV(d) ((uint32_t)((d) - 1u) << 23) /* PLL 200 MHz / d */

/* GPIO (APB aperture) */
#define GPIO_DATA(b, pins) LM3S_REG((b) + ((uint32_t)(pins) << 2)) /* masked data */
#define GPIO_DIR(b) LM3S_REG((b) + 0x400u)
#define GPIO_AFSEL(b) LM3S_REG((b) + 0x420u)
#define GPIO_DEN(b) LM3S_REG((b) + 0x51Cu)

/* General-purpose timer (GPTM), used as one 32-bit timer A */
#define GPTM_CFG(b) LM3S_REG((b) + 0x00u)
#define GPTM_TAMR(b) LM3S_REG((b) + 0x04u)
#define GPTM_CTL(b) LM3S_REG((b) + 0x0Cu)
#define GPTM_IMR(b) LM3S_REG((b) + 0x18u)
#define GPTM_RIS(b) LM3S_REG((b) + 0x1Cu)
#define GPTM_MIS(b) LM3S_REG((b) + 0x20u)
#define GPTM_ICR(b) LM3S_REG((b) + 0x24u)
#define GPTM_TAILR(b) LM3S_REG((b) + 0x28u)
#define GPTM_CFG_32BIT 0u
#define GPTM_TAMR_ONESHOT 1u
#define GPTM_TAMR_PERIODIC 2u
#define GPTM_CTL_TAEN (1u << 0)
#define GPTM_INT_TATO (1u << 0) /* timer A time-out */

/* UART (ARM PL011) */
#define UART_DR(b) LM3S_REG((b) + 0x000u)
#define UART_RSR(b) LM3S_REG((b) + 0x004u) /* write: clear the error flags */
#define UART_FR(b) LM3S_REG((b) + 0x018u)
#define UART_IBRD(b) LM3S_REG((b) + 0x024u)
#define UART_FBRD(b) LM3S_REG((b) + 0x028u)
#define UART_LCRH(b) LM3S_REG((b) + 0x02Cu)
#define UART_CTL(b) LM3S_REG((b) + 0x030u)
#define UART_IFLS(b) LM3S_REG((b) + 0x034u)
#define UART_IM(b) LM3S_REG((b) + 0x038u)
#define UART_RIS(b) LM3S_REG((b) + 0x03Cu)
#define UART_MIS(b) LM3S_REG((b) + 0x040u)
#define UART_ICR(b) LM3S_REG((b) + 0x044u)
#define UART_DR_FE (1u << 8)
#define UART_DR_PE (1u << 9)
#define UART_DR_BE (1u << 10)
#define UART_DR_OE (1u << 11)
#define UART_FR_RXFE (1u << 4)
#define UART_FR_TXFF (1u << 5)
#define UART_LCRH_PEN (1u << 1)
#define UART_LCRH_EPS (1u << 2)
#define UART_LCRH_STP2 (1u << 3)
#define UART_LCRH_FEN (1u << 4)
#define UART_LCRH_WLEN_7 (2u << 5)
#define UART_LCRH_WLEN_8 (3u << 5)
#define UART_CTL_UARTEN (1u << 0)
#define UART_CTL_TXE (1u << 8)
#define UART_CTL_RXE (1u << 9)
#define UART_INT_RX (1u << 4)
#define UART_INT_TX (1u << 5)
#define UART_INT_RT (1u << 6)
#define UART_INT_ERR (0xFu << 7) /* FE, PE, BE, OE */

/* PRIMASK save / restore (thread-mode accesses shared with interrupts). */
static inline uint32_t lm3s_irq_save(void)
{
    uint32_t pm;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(pm)::"memory");
    return pm;
}

static inline void lm3s_irq_restore(uint32_t pm)
{
    __asm__ volatile("msr primask, %0" ::"r"(pm) : "memory");
}

#endif
