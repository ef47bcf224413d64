/* SPDX-License-Identifier: Apache-2.0 */
/* modcp board — ARM MPS2 with the AN385 FPGA image (Cortex-M3), as QEMU's mps2-an385
 * models it.
 *
 * Memory map and interrupts used (AN385 application note; QEMU hw/arm/mps2.c):
 *   0x40004000 UART0  Modbus line        IRQ 0 RX, 1 TX   (QEMU -serial #0)
 *   0x40005000 UART1  monitor console    IRQ 2 RX, 3 TX   (QEMU -serial #1)
 *              UART0..2 overflow         IRQ 12 (combined)
 *   0x40000000 TIMER0 end-of-frame one-shot   IRQ 8
 *   0x40001000 TIMER1 free-running time base  (no interrupt)
 *   0x40002000 DUALTIMER timer 1: transmit complete (one character time)  IRQ 10
 *   SysTick    1 ms tick (CP task, wakes the main loop)
 *   0x40010000 CMSDK AHB GPIO0, pin 0: RS485 driver enable (DE)
 *   0x40028000 FPGAIO LED register: LED0 = SF, LED1 = TXD or RXD activity
 * PCLK = core clock = 25 MHz. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "board/board.h"
#include "board/cortexm.h"
#include "board/startup.h"
#include "modcp/hal_cmsdk.h"

#define SYSCLK_HZ 25000000u
#define CONSOLE_BAUD 115200u

#define UART0_BASE 0x40004000u
#define UART1_BASE 0x40005000u
#define TIMER0_BASE 0x40000000u
#define TIMER1_BASE 0x40001000u
#define DUALTIMER_BASE 0x40002000u
#define GPIO0_BASE 0x40010000u
#define FPGAIO_LED CM_REG(0x40028000u)

#define GPIO0_DATAOUT CM_REG(GPIO0_BASE + 0x004u)
#define GPIO0_OUTENSET CM_REG(GPIO0_BASE + 0x010u)
#define DE_PIN (1u << 0)

enum {
    IRQ_UART0_RX = 0,
    IRQ_UART0_TX = 1,
    IRQ_UART1_RX = 2,
    IRQ_UART1_TX = 3,
    IRQ_TIMER0 = 8,
    IRQ_TIMER1 = 9,
    IRQ_DUALTIMER = 10,
    IRQ_UART_OVF = 12,
    IRQ_COUNT = 32,
};

static modcp_cmsdk_port_t port;
static modcp_cmsdk_con_t con;
static bool led_state[3];

static void set_de(bool on)
{
    if (on) {
        GPIO0_DATAOUT |= DE_PIN;
    } else {
        GPIO0_DATAOUT &= ~DE_PIN;
    }
}

static void set_led(modcp_led_t led, bool on)
{
    if ((unsigned)led > 2u) {
        return;
    }
    led_state[led] = on;
    uint32_t v = (led_state[MODCP_LED_SF] ? 1u : 0u) |
                 ((led_state[MODCP_LED_TXD] || led_state[MODCP_LED_RXD]) ? 2u : 0u);
    FPGAIO_LED = v;
}

static const modcp_cmsdk_cfg_t port_cfg = {
    .uart = UART0_BASE,
    .timer = TIMER0_BASE,
    .dualtimer = DUALTIMER_BASE,
    .pclk_hz = SYSCLK_HZ,
    .now_us = modcp_cmsdk_clock_us,
    .set_de = set_de,
    .set_led = set_led,
};

const char *board_name(void)
{
    return "mps2-an385 (Cortex-M3, CMSDK UART + timers)";
}

void board_init(void)
{
    SCB_VTOR = 0x00000000u;
    modcp_cmsdk_clock_init(TIMER1_BASE, SYSCLK_HZ);
    GPIO0_OUTENSET = DE_PIN;
    set_de(false);
    FPGAIO_LED = 0u;
    modcp_cmsdk_con_init(&con, UART1_BASE, SYSCLK_HZ, CONSOLE_BAUD);
    cm_irq_enable(IRQ_UART1_RX, PRIO_CONSOLE);
    cm_irq_enable(IRQ_UART1_TX, PRIO_CONSOLE);
    /* the CP task and the tick run at the CP's priority */
    SCB_SHPR(CM_EXC_PENDSV - 4) = PRIO_CP;
    SCB_SHPR(CM_EXC_SYSTICK - 4) = PRIO_CP;
    SYST_RVR = SYSCLK_HZ / 1000u - 1u;
    SYST_CVR = 0u;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE;
    modcp_cmsdk_port_init(&port, &port_cfg);
}

const modcp_hal_t *board_modbus_hal(void)
{
    return &port.hal;
}

void board_modbus_start(modcp_cp_t *cp, const modcp_params_t *line)
{
    modcp_cmsdk_port_start(&port, cp, line);
    cm_irq_enable(IRQ_UART0_RX, PRIO_CP);
    cm_irq_enable(IRQ_UART0_TX, PRIO_CP);
    cm_irq_enable(IRQ_TIMER0, PRIO_CP);
    cm_irq_enable(IRQ_DUALTIMER, PRIO_CP);
    cm_irq_enable(IRQ_UART_OVF, PRIO_CP);
}

uint32_t board_now_us(void)
{
    return modcp_cmsdk_clock_us();
}

uint32_t board_now_ms(void)
{
    return modcp_cmsdk_clock_ms();
}

int board_console_getc(void)
{
    return modcp_cmsdk_con_getc(&con);
}

void board_console_write(const char *s, size_t n)
{
    modcp_cmsdk_con_write(&con, s, n);
}

void board_cp_task_request(void)
{
    SCB_ICSR = ICSR_PENDSVSET;
}

/* ---- interrupt handlers ---- */

static void uart0_rx_handler(void)
{
    modcp_cmsdk_port_rx_isr(&port);
}

static void uart0_tx_handler(void)
{
    modcp_cmsdk_port_tx_isr(&port);
}

static void uart1_rx_handler(void)
{
    modcp_cmsdk_con_rx_isr(&con);
}

static void uart1_tx_handler(void)
{
    modcp_cmsdk_con_tx_isr(&con);
}

/* UART0..2 overflow share one line. It runs at the CP's priority; the console part
 * only clears its flags. */
static void uart_ovf_handler(void)
{
    modcp_cmsdk_port_overflow_isr(&port);
    modcp_cmsdk_con_overflow_isr(&con);
}

static void timer0_handler(void)
{
    modcp_cmsdk_port_timer_isr(&port);
}

static void dualtimer_handler(void)
{
    modcp_cmsdk_port_txc_isr(&port);
}

static void systick_handler(void)
{
    (void)modcp_cmsdk_clock_us(); /* keeps the time base extended */
    board_cp_task_request();
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
        [14] = systick_handler,
        [15 + IRQ_UART0_RX] = uart0_rx_handler,
        [15 + IRQ_UART0_TX] = uart0_tx_handler,
        [15 + IRQ_UART1_RX] = uart1_rx_handler,
        [15 + IRQ_UART1_TX] = uart1_tx_handler,
        [15 + 4] = Default_Handler,
        [15 + 5] = Default_Handler,
        [15 + 6] = Default_Handler,
        [15 + 7] = Default_Handler,
        [15 + IRQ_TIMER0] = timer0_handler,
        [15 + IRQ_TIMER1] = Default_Handler,
        [15 + IRQ_DUALTIMER] = dualtimer_handler,
        [15 + 11] = Default_Handler,
        [15 + IRQ_UART_OVF] = uart_ovf_handler,
        [15 + 13] = Default_Handler,
        [15 + 14] = Default_Handler,
        [15 + 15] = Default_Handler,
        [15 + 16] = Default_Handler,
        [15 + 17] = Default_Handler,
        [15 + 18] = Default_Handler,
        [15 + 19] = Default_Handler,
        [15 + 20] = Default_Handler,
        [15 + 21] = Default_Handler,
        [15 + 22] = Default_Handler,
        [15 + 23] = Default_Handler,
        [15 + 24] = Default_Handler,
        [15 + 25] = Default_Handler,
        [15 + 26] = Default_Handler,
        [15 + 27] = Default_Handler,
        [15 + 28] = Default_Handler,
        [15 + 29] = Default_Handler,
        [15 + 30] = Default_Handler,
        [15 + 31] = Default_Handler,
    },
};
