/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — SysTick as a deadline timer with two clients: the board's
 * periodic tick and, in SysTick one-shot mode, the end-of-frame one-shot. Deadlines are
 * absolute microsecond times of the TIM5 time base; SysTick is reprogrammed after every
 * expiry and every arm for the nearest deadline (at most 2^24 core cycles ahead, ~99 ms
 * at 168 MHz; a longer wait simply takes several expiries). An expiry that comes a
 * little early (SysTick and TIM5 round differently) re-arms for the rest, so a deadline
 * never fires before its time. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal_stm32f4.h"
#include "stm32f4_internal.h"
#include "stm32f4_regs.h"

static uint32_t st_cyc_per_us = 1u;
static uint32_t (*st_now)(void);
static uint32_t st_tick_us;
static uint32_t st_tick_next;
static void (*st_tick)(uint32_t now_us);
static bool st_os_armed;
static uint32_t st_os_deadline;
static void (*st_os_fire)(void *ctx, uint32_t now_us);
static void *st_os_ctx;

static uint32_t until(uint32_t deadline, uint32_t now)
{
    int32_t d = (int32_t)(deadline - now);
    return d > 0 ? (uint32_t)d : 1u;
}

static void program(uint32_t now)
{
    uint32_t us = until(st_tick_next, now);
    if (st_os_armed) {
        uint32_t os = until(st_os_deadline, now);
        if (os < us) {
            us = os;
        }
    }
    uint32_t max_us = SYST_MAX / st_cyc_per_us;
    if (us > max_us) {
        us = max_us;
    }
    SYST_CSR = 0u;
    SYST_RVR = us * st_cyc_per_us - 1u;
    SYST_CVR = 0u;
    SCB_ICSR = SCB_ICSR_PENDSTCLR;
    SYST_CSR = SYST_CSR_ENABLE | SYST_CSR_TICKINT | SYST_CSR_CLKSOURCE;
}

void modcp_stm32_systick_init(uint32_t hclk_hz, uint32_t (*now_us)(void), uint32_t tick_us,
                              void (*tick)(uint32_t now_us))
{
    st_cyc_per_us = hclk_hz / 1000000u != 0u ? hclk_hz / 1000000u : 1u;
    st_now = now_us;
    st_tick_us = tick_us != 0u ? tick_us : 1000u;
    st_tick = tick;
    st_os_armed = false;
    uint32_t now = st_now();
    st_tick_next = now + st_tick_us;
    program(now);
}

void stm32_systick_oneshot(uint32_t us, void (*fire)(void *ctx, uint32_t now_us), void *ctx)
{
    uint32_t now = st_now();
    st_os_fire = fire;
    st_os_ctx = ctx;
    st_os_armed = us != 0u;
    st_os_deadline = now + us;
    program(now);
}

void modcp_stm32_systick_isr(void)
{
    uint32_t now = st_now();
    if (st_os_armed && (int32_t)(now - st_os_deadline) >= 0) {
        st_os_armed = false;
        st_os_fire(st_os_ctx, now); /* may arm the next one-shot */
    }
    if ((int32_t)(now - st_tick_next) >= 0) {
        st_tick_next += st_tick_us;
        if ((int32_t)(now - st_tick_next) >= 0) {
            st_tick_next = now + st_tick_us; /* fell behind: no burst of ticks */
        }
        if (st_tick != NULL) {
            st_tick(now);
        }
    }
    program(st_now());
}
