/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — registers of the ARM CMSDK APB UART, APB timer and APB dual timer
 * (ARM Cortex-M System Design Kit Technical Reference Manual, DDI 0479). Private to
 * hal/cmsdk. */
#ifndef MODCP_CMSDK_REGS_H
#define MODCP_CMSDK_REGS_H

#include <stdint.h>

#define CMSDK_REG(base, off) (*(volatile uint32_t *)((base) + (uintptr_t)(off)))

/* APB UART */
#define UART_DATA(b) CMSDK_REG(b, 0x00u)
#define UART_STATE(b) CMSDK_REG(b, 0x04u)
#define UART_CTRL(b) CMSDK_REG(b, 0x08u)
#define UART_INT(b) CMSDK_REG(b, 0x0Cu) /* read: INTSTATUS, write 1: INTCLEAR */
#define UART_BAUDDIV(b) CMSDK_REG(b, 0x10u)
#define UART_STATE_TXFULL 0x01u
#define UART_STATE_RXFULL 0x02u
#define UART_STATE_TXOVR 0x04u
#define UART_STATE_RXOVR 0x08u /* write 1 to clear */
#define UART_CTRL_TXEN 0x01u
#define UART_CTRL_RXEN 0x02u
#define UART_CTRL_TXINT 0x04u
#define UART_CTRL_RXINT 0x08u
#define UART_CTRL_TXOVRINT 0x10u
#define UART_CTRL_RXOVRINT 0x20u
#define UART_INT_TX 0x01u
#define UART_INT_RX 0x02u
#define UART_INT_TXOVR 0x04u
#define UART_INT_RXOVR 0x08u
#define UART_BAUDDIV_MIN 16u

/* APB timer (32-bit down counter, reloads from RELOAD at zero) */
#define TIMER_CTRL(b) CMSDK_REG(b, 0x00u)
#define TIMER_VALUE(b) CMSDK_REG(b, 0x04u)
#define TIMER_RELOAD(b) CMSDK_REG(b, 0x08u)
#define TIMER_INT(b) CMSDK_REG(b, 0x0Cu) /* read: INTSTATUS, write 1: INTCLEAR */
#define TIMER_CTRL_EN 0x01u
#define TIMER_CTRL_IRQEN 0x08u

/* APB dual timer, timer 1 (SP804 programmer's model) */
#define DUAL_LOAD(b) CMSDK_REG(b, 0x00u)
#define DUAL_VALUE(b) CMSDK_REG(b, 0x04u)
#define DUAL_CTRL(b) CMSDK_REG(b, 0x08u)
#define DUAL_INTCLR(b) CMSDK_REG(b, 0x0Cu)
#define DUAL_RIS(b) CMSDK_REG(b, 0x10u)
#define DUAL_MIS(b) CMSDK_REG(b, 0x14u)
#define DUAL_CTRL_ONESHOT 0x01u
#define DUAL_CTRL_32BIT 0x02u
#define DUAL_CTRL_INTEN 0x20u
#define DUAL_CTRL_PERIODIC 0x40u
#define DUAL_CTRL_EN 0x80u

/* PRIMASK critical section for the few places where thread mode and an interrupt
 * share a register read-modify-write or a counter. */
static inline uint32_t cmsdk_irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void cmsdk_irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

#endif
