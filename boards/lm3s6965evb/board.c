/* SPDX-License-Identifier: Apache-2.0 */
/* modcp board — TI Stellaris LM3S6965 evaluation board (Cortex-M3, 256 KB flash, 64 KB
 * SRAM), as QEMU's lm3s6965evb models it.
 *
 * Memory map and interrupts used (LM3S6965 data sheet; QEMU hw/arm/stellaris.c):
 *   0x4000C000 UART0 (PL011)  Modbus line, PA0/PA1     IRQ 5   (QEMU -serial #0)
 *   0x4000D000 UART1 (PL011)  monitor console, PD2/PD3 IRQ 6   (QEMU -serial #1)
 *   0x40030000 GPTM0 timer A  end-of-frame one-shot    IRQ 19
 *   0x40031000 GPTM1 timer A  transmit complete        IRQ 21
 *   0x40032000 GPTM2 timer A  1 ms tick                IRQ 23
 *   SysTick    free running: the time base (GPTM counts cannot be read back in QEMU)
 *   PD4        RS485 driver enable (DE)
 *   PF0        the board's status LED: SF (TXD / RXD: not wired)
 * Core clock: PLL 200 MHz / 4 = 50 MHz from the 8 MHz crystal. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "board/cortexm.h"
#include "board/startup.h"
#include "modcp/hal_lm3s.h"

#define SYSDIV 4u
#define CONSOLE_BAUD 115200u

#define UART0_BASE 0x4000C000u
#define UART1_BASE 0x4000D000u
#define GPTM0_BASE 0x40030000u
#define GPTM1_BASE 0x40031000u
#define GPTM2_BASE 0x40032000u
#define GPIOA_BASE 0x40004000u
#define GPIOD_BASE 0x40007000u
#define GPIOF_BASE 0x40025000u

#define SYSCTL_RCGC1 CM_REG(0x400FE104u)
#define SYSCTL_RCGC2 CM_REG(0x400FE108u)
#define RCGC1_UART0 (1u << 0)
#define RCGC1_UART1 (1u << 1)
#define RCGC1_TIMER0 (1u << 16)
#define RCGC1_TIMER1 (1u << 17)
#define RCGC1_TIMER2 (1u << 18)
#define RCGC2_GPIOA (1u << 0)
#define RCGC2_GPIOD (1u << 3)
#define RCGC2_GPIOF (1u << 5)

#define GPIO_DATA(b, pins) CM_REG((b) + ((uint32_t)(pins) << 2))
#define GPIO_DIR(b) CM_REG((b) + 0x400u)
#define GPIO_AFSEL(b) CM_REG((b) + 0x420u)
#define GPIO_DEN(b) CM_REG((b) + 0x51Cu)
#define DE_PIN (1u << 4)  /* PD4 */
#define LED_PIN (1u << 0) /* PF0 */

enum {
    IRQ_UART0 = 5,
    IRQ_UART1 = 6,
    IRQ_GPTM0 = 19,
    IRQ_GPTM1 = 21,
    IRQ_GPTM2 = 23,
    IRQ_COUNT = 48,
};

static uint32_t clk_hz;
static modcp_lm3s_port_t port;
static modcp_lm3s_con_t con;

static void set_de(bool on)
{
    GPIO_DATA(GPIOD_BASE, DE_PIN) = on ? DE_PIN : 0u;
}

static void set_led(modcp_led_t led, bool on)
{
    if (led == MODCP_LED_SF) {
        GPIO_DATA(GPIOF_BASE, LED_PIN) = on ? LED_PIN : 0u;
    }
}

static modcp_lm3s_cfg_t port_cfg = {
    .uart = UART0_BASE,
    .eof = GPTM0_BASE,
    .txc = GPTM1_BASE,
    .now_us = modcp_lm3s_now_us,
    .set_de = set_de,
    .set_led = set_led,
};

const char *board_name(void)
{
    return "lm3s6965evb (Cortex-M3, TI LM3S6965: PL011 UART + GPTM)";
}

void board_init(void)
{
    SCB_VTOR = 0x00000000u;
    clk_hz = modcp_lm3s_clock_init(SYSDIV);
    SYSCTL_RCGC1 |= RCGC1_UART0 | RCGC1_UART1 | RCGC1_TIMER0 | RCGC1_TIMER1 | RCGC1_TIMER2;
    SYSCTL_RCGC2 |= RCGC2_GPIOA | RCGC2_GPIOD | RCGC2_GPIOF;
    __asm__ volatile("nop\n\tnop\n\tnop"); /* a few clocks before the peripherals answer */
    modcp_lm3s_time_init(clk_hz);
    GPIO_AFSEL(GPIOA_BASE) |= 0x03u; /* PA0 U0Rx, PA1 U0Tx */
    GPIO_DEN(GPIOA_BASE) |= 0x03u;
    GPIO_AFSEL(GPIOD_BASE) |= 0x0Cu; /* PD2 U1Rx, PD3 U1Tx */
    GPIO_DIR(GPIOD_BASE) |= DE_PIN;
    GPIO_DEN(GPIOD_BASE) |= 0x0Cu | DE_PIN;
    GPIO_DIR(GPIOF_BASE) |= LED_PIN;
    GPIO_DEN(GPIOF_BASE) |= LED_PIN;
    set_de(false);
    set_led(MODCP_LED_SF, false);
    modcp_lm3s_con_init(&con, UART1_BASE, clk_hz, CONSOLE_BAUD);
    cm_irq_enable(IRQ_UART1, PRIO_CONSOLE);
    /* the CP task and the tick run at the CP's priority */
    SCB_SHPR(CM_EXC_PENDSV - 4) = PRIO_CP;
    modcp_lm3s_tick_init(GPTM2_BASE, clk_hz);
    cm_irq_enable(IRQ_GPTM2, PRIO_CP);
    port_cfg.clk_hz = clk_hz;
    modcp_lm3s_port_init(&port, &port_cfg);
}

const modcp_hal_t *board_modbus_hal(void)
{
    return &port.hal;
}

void board_modbus_start(modcp_cp_t *cp, const modcp_params_t *line)
{
    modcp_lm3s_port_start(&port, cp, line);
    cm_irq_enable(IRQ_UART0, PRIO_CP);
    cm_irq_enable(IRQ_GPTM0, PRIO_CP);
    cm_irq_enable(IRQ_GPTM1, PRIO_CP);
}

uint32_t board_now_us(void)
{
    return modcp_lm3s_now_us();
}

uint32_t board_now_ms(void)
{
    return modcp_lm3s_now_ms();
}

int board_console_getc(void)
{
    return modcp_lm3s_con_getc(&con);
}

void board_console_write(const char *s, size_t n)
{
    modcp_lm3s_con_write(&con, s, n);
}

void board_cp_task_request(void)
{
    SCB_ICSR = ICSR_PENDSVSET;
}

/* ---- interrupt handlers ---- */

static void uart0_handler(void)
{
    modcp_lm3s_port_uart_isr(&port);
}

static void uart1_handler(void)
{
    modcp_lm3s_con_isr(&con);
}

static void gptm0_handler(void)
{
    modcp_lm3s_port_eof_isr(&port);
}

static void gptm1_handler(void)
{
    modcp_lm3s_port_txc_isr(&port);
}

static void gptm2_handler(void)
{
    if (modcp_lm3s_tick_ack(GPTM2_BASE)) {
        (void)modcp_lm3s_now_us(); /* keeps the time base extended */
        board_cp_task_request();
    }
}

static void pendsv_handler(void)
{
    app_cp_task();
}

__attribute__((section(".isr_vector"), used)) static const CM_VECTORS_T(IRQ_COUNT) vectors = {
    .sp = _estack,
    .handler = {
        [0] = Reset_Handler,
        [1] = Default_Handler, /* NMI */
        [2] = Default_Handler, /* HardFault */
        [3] = Default_Handler, /* MemManage */
        [4] = Default_Handler, /* BusFault */
        [5] = Default_Handler, /* UsageFault */
        [10] = Default_Handler, /* SVCall */
        [11] = Default_Handler, /* DebugMon */
        [13] = pendsv_handler,
        [14] = Default_Handler, /* SysTick: free running, no interrupt */
        [15 + 0] = Default_Handler,
        [15 + 1] = Default_Handler,
        [15 + 2] = Default_Handler,
        [15 + 3] = Default_Handler,
        [15 + 4] = Default_Handler,
        [15 + IRQ_UART0] = uart0_handler,
        [15 + IRQ_UART1] = uart1_handler,
        [15 + 7] = Default_Handler,
        [15 + 8] = Default_Handler,
        [15 + 9] = Default_Handler,
        [15 + 10] = Default_Handler,
        [15 + 11] = Default_Handler,
        [15 + 12] = Default_Handler,
        [15 + 13] = Default_Handler,
        [15 + 14] = Default_Handler,
        [15 + 15] = Default_Handler,
        [15 + 16] = Default_Handler,
        [15 + 17] = Default_Handler,
        [15 + 18] = Default_Handler,
        [15 + IRQ_GPTM0] = gptm0_handler,
        [15 + 20] = Default_Handler,
        [15 + IRQ_GPTM1] = gptm1_handler,
        [15 + 22] = Default_Handler,
        [15 + IRQ_GPTM2] = gptm2_handler,
        [15 + 24] = Default_Handler,
        [15 + 25] = Default_Handler,
        [15 + 26] = Default_Handler,
        [15 + 27] = Default_Handler,
        [15 + 28] = Default_Handler,
        [15 + 29] = Default_Handler,
        [15 + 30] = Default_Handler,
        [15 + 31] = Default_Handler,
        [15 + 32] = Default_Handler,
        [15 + 33] = Default_Handler,
        [15 + 34] = Default_Handler,
        [15 + 35] = Default_Handler,
        [15 + 36] = Default_Handler,
        [15 + 37] = Default_Handler,
        [15 + 38] = Default_Handler,
        [15 + 39] = Default_Handler,
        [15 + 40] = Default_Handler,
        [15 + 41] = Default_Handler,
        [15 + 42] = Default_Handler,
        [15 + 43] = Default_Handler,
        [15 + 44] = Default_Handler,
        [15 + 45] = Default_Handler,
        [15 + 46] = Default_Handler,
        [15 + 47] = Default_Handler,
    },
};
