/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — free-running time base.
 *
 * One APB timer counts down from 0xFFFFFFFF at PCLK and reloads (period 2^32 cycles).
 * Each read converts the cycles elapsed since the previous read into microseconds and
 * milliseconds, carrying the remainders, so the two counters never drift and wrap at
 * 2^32 as the core expects. */
#include <stdint.h>

#include "cmsdk_regs.h"
#include "modcp/hal_cmsdk.h"

static uintptr_t clk_base;
static uint32_t clk_cyc_per_us = 1u;
static uint32_t clk_last;    /* counter value at the previous read */
static uint32_t clk_cyc_rem; /* cycles not yet counted as a microsecond */
static uint32_t clk_us;
static uint32_t clk_us_rem; /* microseconds not yet counted as a millisecond */
static uint32_t clk_ms;

void modcp_cmsdk_clock_init(uintptr_t base, uint32_t pclk_hz)
{
    clk_base = base;
    clk_cyc_per_us = pclk_hz / 1000000u != 0u ? pclk_hz / 1000000u : 1u;
    TIMER_CTRL(base) = 0u;
    TIMER_INT(base) = 1u;
    TIMER_RELOAD(base) = 0xFFFFFFFFu;
    TIMER_VALUE(base) = 0xFFFFFFFFu;
    clk_last = 0xFFFFFFFFu;
    clk_cyc_rem = 0u;
    clk_us = 0u;
    clk_us_rem = 0u;
    clk_ms = 0u;
    TIMER_CTRL(base) = TIMER_CTRL_EN; /* no interrupt: it is read, not waited for */
}

static void clock_update(void)
{
    uint32_t v = TIMER_VALUE(clk_base);
    uint32_t cycles = clk_last - v; /* down counter, period 2^32 */
    clk_last = v;
    uint32_t us = cycles / clk_cyc_per_us;
    clk_cyc_rem += cycles % clk_cyc_per_us;
    if (clk_cyc_rem >= clk_cyc_per_us) {
        clk_cyc_rem -= clk_cyc_per_us;
        us++;
    }
    clk_us += us;
    clk_us_rem += us;
    if (clk_us_rem >= 1000u) {
        clk_ms += clk_us_rem / 1000u;
        clk_us_rem %= 1000u;
    }
}

uint32_t modcp_cmsdk_clock_us(void)
{
    uint32_t pm = cmsdk_irq_save();
    clock_update();
    uint32_t us = clk_us;
    cmsdk_irq_restore(pm);
    return us;
}

uint32_t modcp_cmsdk_clock_ms(void)
{
    uint32_t pm = cmsdk_irq_save();
    clock_update();
    uint32_t ms = clk_ms;
    cmsdk_irq_restore(pm);
    return ms;
}
