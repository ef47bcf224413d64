/* SPDX-License-Identifier: Apache-2.0 */
/* modcp board — BBC micro:bit v1 (nRF51822 QFAA: Cortex-M0, 16 MHz, 256 KB flash,
 * 16 KB RAM), as QEMU's `microbit` machine models it.
 *
 * Pin map (micro:bit v1 schematic; change here for another nRF51 board):
 *   UART0  P0.24 TX, P0.25 RX   Modbus line (the USB interface chip's serial port)
 *                                IRQ 2   (QEMU -serial #0, its only serial port)
 *   P0.1   edge connector pin 2  RS485 driver enable (DE), active high
 *   LED matrix: row 1 (P0.13) driven high; SF = column 1 (P0.4), TXD = column 2
 *          (P0.5), RXD = column 3 (P0.6), active low
 * Timers:
 *   TIMER0  32-bit microsecond time base (free running, no interrupt)
 *   TIMER1  end-of-frame one-shot                                           IRQ 9
 *   TIMER2  1 ms tick (CP task, wakes the main loop)                        IRQ 10
 * No SysTick (the nRF51's Cortex-M0 has none; QEMU models one anyway, unused here).
 * No console: the nRF51 has a single UART and the Modbus line uses it; the console
 * functions of board.h read nothing and write nowhere (see docs/porting.md). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "board/cortexm.h"
#include "board/startup.h"
#include "modcp/hal_nrf51.h"

#define TICK_US 1000u

#define PIN_TXD 24u
#define PIN_RXD 25u
#define PIN_DE 1u
#define PIN_ROW1 13u
#define PIN_COL1 4u
#define PIN_COL9 12u

/* ARMv6-M: the NVIC priority and SHPR registers are word-access only. */
#define NVIC_IPR_WORD(irq) CM_REG(0xE000E400u + 4u * ((uint32_t)(irq) / 4u))
#define SCB_SHPR3 CM_REG(0xE000ED20u) /* bits 23:16 PendSV, 31:24 SysTick */

static void irq_enable(unsigned irq, uint8_t prio)
{
    uint32_t shift = 8u * (irq % 4u);
    NVIC_IPR_WORD(irq) = (NVIC_IPR_WORD(irq) & ~(0xFFu << shift)) | ((uint32_t)prio << shift);
    NVIC_ICPR(0) = 1u << irq;
    NVIC_ISER(0) = 1u << irq;
}

static modcp_nrf51_port_t port;
static bool hfclk_crystal;

static const modcp_nrf51_cfg_t port_cfg = {
    .uart = MODCP_NRF51_UART0,
    .uart_irq = MODCP_NRF51_IRQ_UART0,
    .txd_pin = PIN_TXD,
    .rxd_pin = PIN_RXD,
    .timer = MODCP_NRF51_TIMER1,
    .now_us = modcp_nrf51_clock_us,
    .de = {PIN_DE, false},
    .led = {{PIN_COL1, true}, {PIN_COL1 + 1u, true}, {PIN_COL1 + 2u, true}},
};

const char *board_name(void)
{
    return hfclk_crystal ? "microbit (nRF51822 Cortex-M0, UART0 + TIMER, no console)"
                         : "microbit (nRF51822 Cortex-M0, UART0 + TIMER, no console; RC clock)";
}

void board_init(void)
{
    hfclk_crystal = modcp_nrf51_hfclk_start();
    /* LED matrix: every column off (high), row 1 on, rows 2 and 3 off */
    for (uint32_t pin = PIN_COL1; pin <= PIN_COL9; pin++) {
        modcp_nrf51_pin_t col = {(uint8_t)pin, true};
        modcp_nrf51_pin_output(&col);
    }
    modcp_nrf51_pin_t row1 = {PIN_ROW1, false};
    modcp_nrf51_pin_t row2 = {PIN_ROW1 + 1u, false};
    modcp_nrf51_pin_t row3 = {PIN_ROW1 + 2u, false};
    modcp_nrf51_pin_output(&row2);
    modcp_nrf51_pin_output(&row3);
    modcp_nrf51_pin_output(&row1);
    modcp_nrf51_pin_set(&row1, true);

    /* the CP task runs at the CP's priority */
    SCB_SHPR3 = (SCB_SHPR3 & ~(0xFFu << 16)) | ((uint32_t)PRIO_CP << 16);
    modcp_nrf51_clock_init(MODCP_NRF51_TIMER0);
    modcp_nrf51_tick_init(MODCP_NRF51_TIMER2, TICK_US);
    irq_enable(MODCP_NRF51_IRQ_TIMER2, PRIO_CP);
    modcp_nrf51_port_init(&port, &port_cfg);
}

const modcp_hal_t *board_modbus_hal(void)
{
    return &port.hal;
}

void board_modbus_start(modcp_cp_t *cp, const modcp_params_t *line)
{
    modcp_nrf51_port_start(&port, cp, line);
    irq_enable(MODCP_NRF51_IRQ_UART0, PRIO_CP);
    irq_enable(MODCP_NRF51_IRQ_TIMER1, PRIO_CP);
}

uint32_t board_now_us(void)
{
    return modcp_nrf51_clock_us();
}

uint32_t board_now_ms(void)
{
    return modcp_nrf51_clock_ms();
}

/* No console: nothing is ever typed, output goes nowhere. */
int board_console_getc(void)
{
    return -1;
}

void board_console_write(const char *s, size_t n)
{
    (void)s;
    (void)n;
}

void board_cp_task_request(void)
{
    SCB_ICSR = ICSR_PENDSVSET;
}

/* ---- interrupt handlers ---- */

static void uart0_handler(void)
{
    modcp_nrf51_port_uart_isr(&port);
}

static void timer2_handler(void)
{
    if (modcp_nrf51_tick_isr()) {
        modcp_nrf51_port_uart_isr(&port); /* safety net: a TXDRDY without its interrupt */
        board_cp_task_request();
    }
}

static void timer1_handler(void)
{
    modcp_nrf51_port_timer_isr(&port);
}

static void pendsv_handler(void)
{
    app_cp_task();
}

/* Every interrupt not used here goes to Default_Handler. */
#define D Default_Handler
__attribute__((section(".isr_vector"), used)) static const CM_VECTORS_T(MODCP_NRF51_IRQ_COUNT) vectors = {
    .sp = _estack,
    .handler = {
        Reset_Handler, D, D, 0, 0, 0, 0, 0, 0, 0, D, 0, 0, pendsv_handler, D,
        /* 0 POWER_CLOCK, 1 RADIO */ D, D,
        /* 2 UART0 */ uart0_handler,
        /* 3 .. 7 */ D, D, D, D, D,
        /* 8 TIMER0 */ D,
        /* 9 TIMER1 */ timer1_handler,
        /* 10 TIMER2 */ timer2_handler,
        /* 11 .. 31 */
        D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D, D,
    },
};
#undef D
