/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (nRF51) — the crystal, the microsecond time base (TIMER0), the periodic
 * tick (TIMER2) and GPIO outputs. */
#include <stdbool.h>
#include <stdint.h>

#include "modcp/hal_nrf51.h"
#include "nrf51_regs.h"

#define HFCLK_SPINS 100000u
#define CC_NOW 0u /* CAPTURE target: the current count */

bool modcp_nrf51_hfclk_start(void)
{
    CLOCK_EVENTS_HFCLKSTARTED = 0u;
    CLOCK_TASKS_HFCLKSTART = 1u;
    for (uint32_t i = 0; i < HFCLK_SPINS; i++) {
        if (CLOCK_EVENTS_HFCLKSTARTED != 0u) {
            return true;
        }
    }
    return false;
}

static uintptr_t clk_timer;
static uintptr_t tick_timer;
static modcp_timebase_t ms_tb; /* milliseconds from the microseconds (modcp/hal_timebase.h) */

static void timer_setup(uintptr_t t, uint32_t bitmode)
{
    TIMER_TASKS_STOP(t) = 1u;
    TIMER_MODE(t) = TIMER_MODE_TIMER;
    TIMER_BITMODE(t) = bitmode;
    TIMER_PRESCALER(t) = TIMER_PRESCALER_1MHZ;
    TIMER_SHORTS(t) = 0u;
    TIMER_INTENCLR(t) = 0xFFFFFFFFu;
    TIMER_TASKS_CLEAR(t) = 1u;
    for (uint32_t n = 0; n < 4u; n++) {
        TIMER_EVENTS_COMPARE(t, n) = 0u;
    }
}

void modcp_nrf51_clock_init(uintptr_t timer)
{
    clk_timer = timer;
    timer_setup(timer, TIMER_BITMODE_32); /* free running, no interrupt */
    modcp_timebase_init(&ms_tb, 1000000u, 32u, false, 0u);
    TIMER_TASKS_START(timer) = 1u;
}

uint32_t modcp_nrf51_clock_us(void)
{
    /* CC[0] is shared by every reader: capture and read it as one step */
    uint32_t pm = nrf51_irq_save();
    TIMER_TASKS_CAPTURE(clk_timer, CC_NOW) = 1u;
    uint32_t v = TIMER_CC(clk_timer, CC_NOW);
    nrf51_irq_restore(pm);
    return v;
}

uint32_t modcp_nrf51_clock_ms(void)
{
    uint32_t pm = nrf51_irq_save();
    modcp_timebase_feed(&ms_tb, modcp_nrf51_clock_us()); /* at least every 71 minutes (the tick does) */
    uint32_t ms = ms_tb.ms;
    nrf51_irq_restore(pm);
    return ms;
}

void modcp_nrf51_tick_init(uintptr_t timer, uint32_t tick_us)
{
    tick_timer = timer;
    timer_setup(timer, TIMER_BITMODE_16);
    /* COMPARE[0] clears the counter: periodic, like SysTick, in hardware. (A compare
     * value moved along on the free-running counter instead could be set behind the
     * counter when the interrupt comes late, and then match only after a wrap.) */
    TIMER_CC(timer, 0) = tick_us != 0u && tick_us <= 0xFFFFu ? tick_us : 1000u;
    TIMER_SHORTS(timer) = TIMER_SHORTS_COMPARE_CLEAR(0);
    TIMER_INTENSET(timer) = TIMER_INT_COMPARE(0);
    TIMER_TASKS_START(timer) = 1u;
}

bool modcp_nrf51_tick_isr(void)
{
    if (TIMER_EVENTS_COMPARE(tick_timer, 0) == 0u) {
        return false;
    }
    TIMER_EVENTS_COMPARE(tick_timer, 0) = 0u;
    (void)modcp_nrf51_clock_ms(); /* keeps the millisecond count extended */
    return true;
}

void modcp_nrf51_pin_output(const modcp_nrf51_pin_t *p)
{
    if (p->pin == MODCP_NRF51_PIN_NONE) {
        return;
    }
    modcp_nrf51_pin_set(p, false);
    GPIO_DIRSET = 1u << p->pin;
}

void modcp_nrf51_pin_set(const modcp_nrf51_pin_t *p, bool on)
{
    if (p->pin == MODCP_NRF51_PIN_NONE) {
        return;
    }
    if (on != p->active_low) {
        GPIO_OUTSET = 1u << p->pin;
    } else {
        GPIO_OUTCLR = 1u << p->pin;
    }
}
