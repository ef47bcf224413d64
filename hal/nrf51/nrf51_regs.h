/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (nRF51) — the registers used, from the nRF51 Series Reference Manual v3.0
 * (CLOCK, TIMER, UART, GPIO chapters). No vendor headers. Private to hal/nrf51.
 * Every peripheral register is 32 bits wide and accessed as a word. Tasks are triggered
 * by writing 1; events are cleared by writing 0. */
#ifndef MODCP_NRF51_REGS_H
#define MODCP_NRF51_REGS_H

#include <stdint.h>

#define NRF_REG(base, off) (*(volatile uint32_t *)((base) + (uintptr_t)(off)))

/* CLOCK (0x40000000) */
#define NRF_CLOCK 0x40000000u
#define CLOCK_TASKS_HFCLKSTART NRF_REG(NRF_CLOCK, 0x000u)
#define CLOCK_EVENTS_HFCLKSTARTED NRF_REG(NRF_CLOCK, 0x100u)

/* TIMER0 (32 bit), TIMER1 / TIMER2 (16 bit on silicon) */
#define TIMER_TASKS_START(b) NRF_REG(b, 0x000u)
#define TIMER_TASKS_STOP(b) NRF_REG(b, 0x004u)
#define TIMER_TASKS_CLEAR(b) NRF_REG(b, 0x00Cu)
#define TIMER_TASKS_CAPTURE(b, n) NRF_REG(b, 0x040u + 4u * (uint32_t)(n))
#define TIMER_EVENTS_COMPARE(b, n) NRF_REG(b, 0x140u + 4u * (uint32_t)(n))
#define TIMER_SHORTS(b) NRF_REG(b, 0x200u)
#define TIMER_INTENSET(b) NRF_REG(b, 0x304u)
#define TIMER_INTENCLR(b) NRF_REG(b, 0x308u)
#define TIMER_MODE(b) NRF_REG(b, 0x504u)
#define TIMER_BITMODE(b) NRF_REG(b, 0x508u)
#define TIMER_PRESCALER(b) NRF_REG(b, 0x510u)
#define TIMER_CC(b, n) NRF_REG(b, 0x540u + 4u * (uint32_t)(n))
#define TIMER_SHORTS_COMPARE_CLEAR(n) (1u << (n))
#define TIMER_SHORTS_COMPARE_STOP(n) (1u << (8u + (n)))
#define TIMER_INT_COMPARE(n) (1u << (16u + (n)))
#define TIMER_MODE_TIMER 0u
#define TIMER_BITMODE_16 0u
#define TIMER_BITMODE_32 3u
#define TIMER_PRESCALER_1MHZ 4u /* 16 MHz / 2^4 */

/* UART0 (0x40002000) */
#define UART_TASKS_STARTRX(b) NRF_REG(b, 0x000u)
#define UART_TASKS_STOPRX(b) NRF_REG(b, 0x004u)
#define UART_TASKS_STARTTX(b) NRF_REG(b, 0x008u)
#define UART_TASKS_STOPTX(b) NRF_REG(b, 0x00Cu)
#define UART_EVENTS_RXDRDY(b) NRF_REG(b, 0x108u)
#define UART_EVENTS_TXDRDY(b) NRF_REG(b, 0x11Cu)
#define UART_EVENTS_ERROR(b) NRF_REG(b, 0x124u)
#define UART_INTENSET(b) NRF_REG(b, 0x304u)
#define UART_INTENCLR(b) NRF_REG(b, 0x308u)
#define UART_ERRORSRC(b) NRF_REG(b, 0x480u) /* write 1 to clear a bit */
#define UART_ENABLE(b) NRF_REG(b, 0x500u)
#define UART_PSELRTS(b) NRF_REG(b, 0x508u)
#define UART_PSELTXD(b) NRF_REG(b, 0x50Cu)
#define UART_PSELCTS(b) NRF_REG(b, 0x510u)
#define UART_PSELRXD(b) NRF_REG(b, 0x514u)
#define UART_RXD(b) NRF_REG(b, 0x518u)
#define UART_TXD(b) NRF_REG(b, 0x51Cu)
#define UART_BAUDRATE(b) NRF_REG(b, 0x524u)
#define UART_CONFIG(b) NRF_REG(b, 0x56Cu)
#define UART_INT_RXDRDY (1u << 2)
#define UART_INT_TXDRDY (1u << 7)
#define UART_INT_ERROR (1u << 9)
#define UART_ENABLE_ON 4u
#define UART_PSEL_DISCONNECTED 0xFFFFFFFFu
#define UART_CONFIG_PARITY_EVEN 0x0Eu /* PARITY = 0x7: included, even */
#define UART_ERRORSRC_OVERRUN 0x1u
#define UART_ERRORSRC_PARITY 0x2u
#define UART_ERRORSRC_FRAMING 0x4u
#define UART_ERRORSRC_BREAK 0x8u

/* GPIO (0x50000000), port 0 */
#define NRF_GPIO 0x50000000u
#define GPIO_OUTSET NRF_REG(NRF_GPIO, 0x508u)
#define GPIO_OUTCLR NRF_REG(NRF_GPIO, 0x50Cu)
#define GPIO_DIRSET NRF_REG(NRF_GPIO, 0x518u)
#define GPIO_PIN_CNF(n) NRF_REG(NRF_GPIO, 0x700u + 4u * (uint32_t)(n))
#define GPIO_PIN_CNF_INPUT_CONNECT 0x0u
#define GPIO_PIN_CNF_PULLUP (3u << 2)

/* PRIMASK critical section (ARMv6-M has no BASEPRI). */
static inline uint32_t nrf51_irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void nrf51_irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

/* NVIC set-pending (the only NVIC access the HAL itself makes). */
#define NRF_NVIC_ISPR (*(volatile uint32_t *)0xE000E200u)

#endif
