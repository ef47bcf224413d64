/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (CMSDK) — free-running time base.
 *
 * One APB timer counts down from 0xFFFFFFFF at PCLK and reloads (period 2^32 cycles);
 * modcp/hal_timebase.h turns its readings into microseconds and milliseconds. */
#include <stdint.h>

#include "cmsdk_regs.h"
#include "modcp/hal_cmsdk.h"

static uintptr_t clk_base;
static modcp_timebase_t clk_tb; /* the shared extension (modcp/hal_timebase.h) */

void modcp_cmsdk_clock_init(uintptr_t base, uint32_t pclk_hz)
{
    clk_base = base;
    TIMER_CTRL(base) = 0u;
    TIMER_INT(base) = 1u;
    TIMER_RELOAD(base) = 0xFFFFFFFFu;
    TIMER_VALUE(base) = 0xFFFFFFFFu;
    modcp_timebase_init(&clk_tb, pclk_hz, 32u, true, 0xFFFFFFFFu);
    TIMER_CTRL(base) = TIMER_CTRL_EN; /* no interrupt: it is read, not waited for */
}

uint32_t modcp_cmsdk_clock_us(void)
{
    uint32_t pm = cmsdk_irq_save();
    modcp_timebase_feed(&clk_tb, TIMER_VALUE(clk_base));
    uint32_t us = clk_tb.us;
    cmsdk_irq_restore(pm);
    return us;
}

uint32_t modcp_cmsdk_clock_ms(void)
{
    uint32_t pm = cmsdk_irq_save();
    modcp_timebase_feed(&clk_tb, TIMER_VALUE(clk_base));
    uint32_t ms = clk_tb.ms;
    cmsdk_irq_restore(pm);
    return ms;
}
