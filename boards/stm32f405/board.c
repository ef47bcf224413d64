/* SPDX-License-Identifier: Apache-2.0 */
/* modcp board — STM32F405 (also STM32F407; QEMU netduinoplus2), Cortex-M4F.
 *
 * Pin map (an STM32F4-Discovery-style board; change here for another board):
 *   USART1  PA9 TX, PA10 RX (AF7)  Modbus line          IRQ 37  (QEMU -serial #0)
 *   USART2  PA2 TX, PA3 RX  (AF7)  monitor console      IRQ 38  (QEMU -serial #1)
 *   PA8                            RS485 driver enable (DE), active high
 *   PD14 red = SF, PD12 green = TXD, PD13 orange = RXD  LEDs, active high
 * Timers:
 *   TIM5    32-bit microsecond time base (free running)
 *   TIM2    end-of-frame one-shot, one-pulse mode        IRQ 28 (silicon)
 *   SysTick 1 ms tick; in QEMU also the end-of-frame one-shot (see hal_stm32f4.h)
 * Clock: HSI 16 MHz -> PLL 168 MHz; APB1 42 MHz (TIM 84 MHz), APB2 84 MHz. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "board/cortexm.h"
#include "board/startup.h"
#include "modcp/hal_stm32f4.h"

#define CONSOLE_BAUD 115200u
#define TICK_US 1000u

/* RCC enable bits */
#define AHB1_GPIOA (1u << 0)
#define AHB1_GPIOD (1u << 3)
#define APB1_TIM2 (1u << 0)
#define APB1_TIM5 (1u << 3)
#define APB1_USART2 (1u << 17)
#define APB2_USART1 (1u << 4)

#define AF_USART 7u

static modcp_stm32_clocks_t clocks;
static modcp_stm32_cfg_t port_cfg;
static modcp_stm32_port_t port;
static modcp_stm32_con_t con;

const char *board_name(void)
{
    return clocks.qemu ? "stm32f405 (Cortex-M4F, USART + TIM; QEMU netduinoplus2)"
                       : "stm32f405 (Cortex-M4F, USART + TIM)";
}

static void tick(uint32_t now_us)
{
    (void)now_us;
    (void)modcp_stm32_clock_ms(); /* keeps the millisecond count extended */
    board_cp_task_request();
}

void board_init(void)
{
    SCB_VTOR = 0x08000000u;
    modcp_stm32_clock_init(&clocks);
    modcp_stm32_rcc_enable(AHB1_GPIOA | AHB1_GPIOD, APB1_TIM2 | APB1_TIM5 | APB1_USART2,
                           APB2_USART1);
    modcp_stm32_clock_us_init(STM32_TIM5, clocks.tim_apb1_hz);

    modcp_stm32_pin_af(STM32_GPIOA, 9, AF_USART, false);
    modcp_stm32_pin_af(STM32_GPIOA, 10, AF_USART, true);
    modcp_stm32_pin_af(STM32_GPIOA, 2, AF_USART, false);
    modcp_stm32_pin_af(STM32_GPIOA, 3, AF_USART, true);
    modcp_stm32_con_init(&con, STM32_USART2, STM32_IRQ_USART2, clocks.pclk1_hz, CONSOLE_BAUD);
    cm_irq_enable(STM32_IRQ_USART2, PRIO_CONSOLE);

    SCB_SHPR(CM_EXC_PENDSV - 4) = PRIO_CP;
    SCB_SHPR(CM_EXC_SYSTICK - 4) = PRIO_CP;
    modcp_stm32_systick_init(clocks.hclk_hz, modcp_stm32_clock_us, TICK_US, tick);

    port_cfg = (modcp_stm32_cfg_t){
        .usart = STM32_USART1,
        .usart_irq = STM32_IRQ_USART1,
        .usart_clk_hz = clocks.pclk2_hz,
        .oneshot = clocks.qemu ? (uint8_t)MODCP_STM32_ONESHOT_SYSTICK
                               : (uint8_t)MODCP_STM32_ONESHOT_TIM2,
        .tim = STM32_TIM2,
        .tim_clk_hz = clocks.tim_apb1_hz,
        .now_us = modcp_stm32_clock_us,
        .de = {STM32_GPIOA, 8, false},
        .led = {{STM32_GPIOD, 14, false}, {STM32_GPIOD, 12, false}, {STM32_GPIOD, 13, false}},
    };
    modcp_stm32_port_init(&port, &port_cfg);
}

const modcp_hal_t *board_modbus_hal(void)
{
    return &port.hal;
}

void board_modbus_start(modcp_cp_t *cp, const modcp_params_t *line)
{
    modcp_stm32_port_start(&port, cp, line);
    cm_irq_enable(STM32_IRQ_USART1, PRIO_CP);
    if (port_cfg.oneshot == (uint8_t)MODCP_STM32_ONESHOT_TIM2) {
        cm_irq_enable(STM32_IRQ_TIM2, PRIO_CP);
    }
}

uint32_t board_now_us(void)
{
    return modcp_stm32_clock_us();
}

uint32_t board_now_ms(void)
{
    return modcp_stm32_clock_ms();
}

int board_console_getc(void)
{
    return modcp_stm32_con_getc(&con);
}

void board_console_write(const char *s, size_t n)
{
    modcp_stm32_con_write(&con, s, n);
}

void board_cp_task_request(void)
{
    SCB_ICSR = ICSR_PENDSVSET;
}

/* ---- interrupt handlers ---- */

static void usart1_handler(void)
{
    modcp_stm32_port_usart_isr(&port);
}

static void usart2_handler(void)
{
    modcp_stm32_con_isr(&con);
}

static void tim2_handler(void)
{
    modcp_stm32_port_tim_isr(&port);
}

static void systick_handler(void)
{
    modcp_stm32_systick_isr();
}

static void pendsv_handler(void)
{
    app_cp_task();
}

/* Every interrupt not used here goes to Default_Handler. */
#define D Default_Handler
__attribute__((section(".isr_vector"), used)) static const CM_VECTORS_T(STM32_IRQ_COUNT) vectors = {
    .sp = _estack,
    .handler = {
        Reset_Handler, D, D, D, D, D, 0, 0, 0, 0, D, D, 0, pendsv_handler, systick_handler,
        /* IRQ 0 .. 27 */
        D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D,
        /* 28 TIM2 */ tim2_handler,
        /* 29 .. 36 */ D, D, D, D, D, D, D, D,
        /* 37 USART1 */ usart1_handler,
        /* 38 USART2 */ usart2_handler,
        /* 39 .. 81 */
        D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D,
        D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D,
    },
};
#undef D
