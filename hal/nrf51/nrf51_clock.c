/* modcp HAL (nRF51) — the crystal, TIMER0 as the microsecond time base and the tick,
 * and GPIO outputs. */
#include <stdbool.h>
#include <stdint.h>

#include "modcp/hal_nrf51.h"
#include "nrf51_regs.h"

#define HFCLK_SPINS 100000u
#define CC_NOW 0u  /* CAPTURE target: the current count */
#define CC_TICK 1u /* compare: the next tick */

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
static uint32_t tick_us;
static uint32_t tick_next;
static uint32_t ms_last_us;
static uint32_t ms_rem_us;
static uint32_t ms_count;

void modcp_nrf51_clock_init(uintptr_t timer, uint32_t tick)
{
    clk_timer = timer;
    tick_us = tick != 0u ? tick : 1000u;
    TIMER_TASKS_STOP(timer) = 1u;
    TIMER_MODE(timer) = TIMER_MODE_TIMER;
    TIMER_BITMODE(timer) = TIMER_BITMODE_32;
    TIMER_PRESCALER(timer) = TIMER_PRESCALER_1MHZ;
    TIMER_SHORTS(timer) = 0u;
    TIMER_INTENCLR(timer) = 0xFFFFFFFFu;
    TIMER_TASKS_CLEAR(timer) = 1u;
    TIMER_EVENTS_COMPARE(timer, CC_TICK) = 0u;
    tick_next = tick_us;
    TIMER_CC(timer, CC_TICK) = tick_next;
    TIMER_INTENSET(timer) = TIMER_INT_COMPARE(CC_TICK);
    ms_last_us = 0u;
    ms_rem_us = 0u;
    ms_count = 0u;
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
    uint32_t now = modcp_nrf51_clock_us();
    ms_rem_us += now - ms_last_us;
    ms_last_us = now;
    if (ms_rem_us >= 1000u) {
        ms_count += ms_rem_us / 1000u;
        ms_rem_us %= 1000u;
    }
    uint32_t ms = ms_count;
    nrf51_irq_restore(pm);
    return ms;
}

bool modcp_nrf51_clock_tick_isr(void)
{
    if (TIMER_EVENTS_COMPARE(clk_timer, CC_TICK) == 0u) {
        return false;
    }
    TIMER_EVENTS_COMPARE(clk_timer, CC_TICK) = 0u;
    uint32_t now = modcp_nrf51_clock_us();
    tick_next += tick_us;
    /* Late by more than a tick (a long critical section, or a busy host under QEMU):
     * skip the missed ticks. A compare value already passed would only match again
     * after the 32-bit counter wrapped (71 minutes). */
    if ((int32_t)(tick_next - now) < 16) {
        tick_next = now + tick_us;
    }
    TIMER_CC(clk_timer, CC_TICK) = tick_next;
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
