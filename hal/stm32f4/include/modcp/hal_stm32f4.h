/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL for STM32F4 (STM32F405/407; QEMU netduinoplus2).
 *
 *   Clock         HSI 16 MHz -> PLL 168 MHz (no crystal needed), APB1 42 MHz, APB2 84 MHz
 *   Time base     TIM5 (32 bit) counting microseconds, free running: CNT is the time
 *   Modbus port   USART: RXNE interrupt (with PE / FE / ORE), TXE to feed bytes and TC —
 *                 transmission complete of the last stop bit — for modcp_cp_on_tx_done().
 *                 The transmit interrupt is also pended by software when a transmission
 *                 starts (harmless on silicon, where TXE raises it anyway): QEMU 7.2's
 *                 USART model raises only RXNE interrupts; its DR write is synchronous
 *                 and leaves TXE and TC set, so the ISR's "while TXE: write" loop sends
 *                 the whole frame and then finds TC set.
 *                 End-of-frame one-shot: TIM2 in one-pulse mode (32 bit, 1 us ticks), or
 *                 the SysTick deadline timer (see below)
 *                 GPIO outputs for RS485 DE and the SF / TXD / RXD LEDs
 *   Console       a second USART with interrupt-driven queues
 *   Tick          SysTick: 1 ms tick for the board, and (SysTick one-shot mode) the
 *                 end-of-frame deadline, multiplexed on the one counter
 *
 * QEMU: QEMU 7.2's STM32 timer model schedules its update interrupt at "now + the
 * absolute time of the match" (hw/timer/stm32f2xx_timer.c, set_alarm adds the absolute
 * hit time to the current clock), so a 1 ms TIM2 one-shot armed 10 s after reset fires
 * after about 10 s. Its counter (TIM5 CNT) is correct. QEMU 7.2 also has no RCC model
 * (reads 0, so the PLL never reports ready). modcp_stm32_is_qemu() recognises that
 * (RCC_CR reads 0; on silicon HSION/HSIRDY are set from reset) and the board then uses
 * the SysTick one-shot and QEMU's fixed clocks (1 GHz timer clock, 168 MHz core). On
 * silicon the end-of-frame timer is TIM2 in one-pulse mode.
 *
 * Line errors: PE -> MODCP_LINE_PARITY, FE -> MODCP_LINE_FRAMING, or MODCP_LINE_BREAK
 * when the character read with FE is 0x00 (a BREAK is an all-zero frame without stop
 * bit). The character that carries an error is reported as the error, in its place.
 * ORE: DR holds the character received before the lost one; it is delivered, then the
 * lost one reported as MODCP_LINE_OVERRUN (modcp/hal.h). NF (noise) alone is not an error: the majority vote's value
 * is taken.
 *
 * RS232 secondary signals: this port wires no RTS / DTR outputs and no CTS / DSR
 * inputs (set_signal is NULL); it reports CTS and DSR permanently ON at start (a 3-wire
 * line), so automatic secondary signals keep their timing and never see CTS / DSR
 * drop. A board with modem lines adds two GPIO outputs in set_signal and reports its
 * inputs (EXTI on both edges) with modcp_cp_on_signals() from an interrupt at the CP's
 * priority.
 *
 * Concurrency: the port's interrupt entry points, the SysTick handler and the CP task
 * must run at one interrupt priority. */
#ifndef MODCP_HAL_STM32F4_H
#define MODCP_HAL_STM32F4_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/cp.h"
#include "modcp/hal.h"
#include "modcp/hal_conq.h"
#include "modcp/hal_eof.h"
#include "modcp/hal_timebase.h"

/* Peripheral bases and interrupt numbers of the STM32F405/407 (RM0090). */
#define STM32_GPIOA 0x40020000u
#define STM32_GPIOB 0x40020400u
#define STM32_GPIOC 0x40020800u
#define STM32_GPIOD 0x40020C00u
#define STM32_USART1 0x40011000u
#define STM32_USART2 0x40004400u
#define STM32_USART3 0x40004800u
#define STM32_USART6 0x40011400u
#define STM32_TIM2 0x40000000u
#define STM32_TIM3 0x40000400u
#define STM32_TIM4 0x40000800u
#define STM32_TIM5 0x40000C00u
enum {
    STM32_IRQ_TIM2 = 28,
    STM32_IRQ_TIM3 = 29,
    STM32_IRQ_TIM4 = 30,
    STM32_IRQ_USART1 = 37,
    STM32_IRQ_USART2 = 38,
    STM32_IRQ_USART3 = 39,
    STM32_IRQ_TIM5 = 50,
    STM32_IRQ_USART6 = 71,
    STM32_IRQ_COUNT = 82,
};

/* ---- clocks -------------------------------------------------------------------- */

typedef struct {
    uint32_t hclk_hz;     /* core / SysTick */
    uint32_t pclk1_hz;    /* APB1: USART2/3 */
    uint32_t pclk2_hz;    /* APB2: USART1/6 */
    uint32_t tim_apb1_hz; /* TIM2..5 kernel clock */
    bool qemu;            /* running in QEMU (see above) */
} modcp_stm32_clocks_t;

bool modcp_stm32_is_qemu(void);
/* Silicon: HSI -> PLL 168 MHz, flash wait states, bus prescalers (falls back to HSI
 * 16 MHz if the PLL does not lock). QEMU: nothing to program. Fills *out. */
void modcp_stm32_clock_init(modcp_stm32_clocks_t *out);
/* Enable peripheral clocks (RCC_AHB1ENR / APB1ENR / APB2ENR bit masks). */
void modcp_stm32_rcc_enable(uint32_t ahb1, uint32_t apb1, uint32_t apb2);

/* ---- GPIO ---------------------------------------------------------------------- */

typedef struct {
    uintptr_t port; /* STM32_GPIOx; 0 = no pin */
    uint8_t pin;    /* 0..15 */
    bool active_low;
} modcp_stm32_pin_t;

void modcp_stm32_pin_output(const modcp_stm32_pin_t *p);
void modcp_stm32_pin_af(uintptr_t port, uint8_t pin, uint8_t af, bool pull_up);
void modcp_stm32_pin_set(const modcp_stm32_pin_t *p, bool on);

/* ---- time base: TIM5 as a 32-bit microsecond counter ------------------------------ */

void modcp_stm32_clock_us_init(uintptr_t tim, uint32_t tim_clk_hz);
uint32_t modcp_stm32_clock_us(void);
uint32_t modcp_stm32_clock_ms(void); /* since init, from the microseconds */

/* ---- SysTick: board tick + optional end-of-frame deadline -------------------------- */

/* Start SysTick on the core clock: tick(now_us) every tick_us. */
void modcp_stm32_systick_init(uint32_t hclk_hz, uint32_t (*now_us)(void), uint32_t tick_us,
                              void (*tick)(uint32_t now_us));
/* Call from the SysTick handler. */
void modcp_stm32_systick_isr(void);

/* ---- Modbus port ---------------------------------------------------------------- */

typedef enum {
    MODCP_STM32_ONESHOT_TIM2 = 0,    /* TIM2 one-pulse mode (silicon) */
    MODCP_STM32_ONESHOT_SYSTICK = 1, /* SysTick deadline (QEMU) */
} modcp_stm32_oneshot_t;

typedef struct {
    uintptr_t usart;
    uint8_t usart_irq; /* its NVIC interrupt number */
    uint32_t usart_clk_hz;
    uint8_t oneshot; /* modcp_stm32_oneshot_t */
    uintptr_t tim;   /* TIM2..5 for MODCP_STM32_ONESHOT_TIM2 (32-bit: TIM2 or TIM5) */
    uint32_t tim_clk_hz;
    uint32_t (*now_us)(void);
    modcp_stm32_pin_t de;     /* RS485 driver enable; port 0 = none */
    modcp_stm32_pin_t led[3]; /* SF, TXD, RXD (modcp_led_t order); port 0 = none */
} modcp_stm32_cfg_t;

typedef struct {
    modcp_hal_t hal; /* hand &port->hal to modcp_cp_init() */
    const modcp_stm32_cfg_t *cfg;
    modcp_cp_t *cp;
    const uint8_t *tx_buf;
    uint16_t tx_len;
    uint16_t tx_pos;
    uint8_t data_mask; /* 0x7F with 7 data bits */
    bool rs485;
    uint32_t rx_bytes;
    uint32_t tx_bytes;
    uint32_t line_errors;
    modcp_eof_t eof; /* end-of-frame handler (modcp/hal_eof.h), mark = rx_bytes + line_errors */
} modcp_stm32_port_t;

/* End-of-frame expiries in a row without a received character before the core hears of
 * it (see oneshot_fired in stm32f4_port.c). */
#ifndef MODCP_STM32_EOF_QUIET_ROUNDS
#define MODCP_STM32_EOF_QUIET_ROUNDS 3u /* 1: report the first quiet expiry (no confirmation; experiments) */
#endif

/* Fill port->hal and set up the pins and the one-shot timer (interrupts not enabled). */
void modcp_stm32_port_init(modcp_stm32_port_t *port, const modcp_stm32_cfg_t *cfg);
/* Program the USART (baud, data bits 7/8, parity, stop bits 1/2) and start receiving
 * for cp. The caller then enables the USART and TIM interrupts at the CP priority. */
void modcp_stm32_port_start(modcp_stm32_port_t *port, modcp_cp_t *cp, const modcp_params_t *p);

void modcp_stm32_port_usart_isr(modcp_stm32_port_t *port);
void modcp_stm32_port_tim_isr(modcp_stm32_port_t *port);

/* ---- console USART --------------------------------------------------------------- */

typedef struct {
    uintptr_t usart;
    uint8_t irq;
    modcp_conq_t q; /* the shared queues (modcp/hal_conq.h) */
} modcp_stm32_con_t;

void modcp_stm32_con_init(modcp_stm32_con_t *con, uintptr_t usart, uint8_t irq, uint32_t clk_hz,
                          uint32_t baud);
int modcp_stm32_con_getc(modcp_stm32_con_t *con);
void modcp_stm32_con_write(modcp_stm32_con_t *con, const char *s, size_t n);
void modcp_stm32_con_isr(modcp_stm32_con_t *con);

#endif
