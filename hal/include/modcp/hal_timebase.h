/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the time base a port builds from a hardware counter (shared by the Cortex-M
 * ports; docs/porting.md §1 "Shared pieces").
 *
 * The core wants microseconds wrapping at 2^32 (board_now_us) and the application
 * milliseconds (board_now_ms). A counter that runs at a whole number of MHz, up or down,
 * `bits` wide (24 for SysTick, 32 for most timers) and wrapping at 2^bits, is turned into
 * both: each read converts the cycles elapsed since the previous read, carrying the
 * remainders (cycles not yet a microsecond, microseconds not yet a millisecond), so the
 * two counts never drift and wrap at 2^32 as the core expects.
 *
 * The port reads the counter and calls modcp_timebase_feed() with interrupts masked
 * (the state is shared by thread mode and interrupts), at least once per counter period
 * (2^bits cycles: 335 ms for SysTick at 50 MHz, 171 s for 32 bits at 25 MHz) — the
 * board's 1 ms tick does that. Pure: no hardware, no globals (the port owns the state). */
#ifndef MODCP_HAL_TIMEBASE_H
#define MODCP_HAL_TIMEBASE_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint32_t mask;       /* 2^bits - 1 */
    uint32_t cyc_per_us; /* counter cycles per microsecond (>= 1) */
    bool down;           /* the counter counts down */
    uint32_t last;       /* counter value at the previous read */
    uint32_t cyc_rem;    /* cycles not yet counted as a microsecond */
    uint32_t us;         /* microseconds, wrapping at 2^32 */
    uint32_t us_rem;     /* microseconds not yet counted as a millisecond */
    uint32_t ms;         /* milliseconds, wrapping at 2^32 */
} modcp_timebase_t;

/* Start at 0 us / 0 ms with the counter at `count`; hz is the counter's clock (a whole
 * number of MHz; below 1 MHz it is taken as 1 MHz), bits its width (1..32). */
static inline void modcp_timebase_init(modcp_timebase_t *tb, uint32_t hz, uint32_t bits,
                                       bool down, uint32_t count)
{
    tb->mask = bits >= 32u ? 0xFFFFFFFFu : (1u << bits) - 1u;
    tb->cyc_per_us = hz / 1000000u != 0u ? hz / 1000000u : 1u;
    tb->down = down;
    tb->last = count & tb->mask;
    tb->cyc_rem = 0u;
    tb->us = 0u;
    tb->us_rem = 0u;
    tb->ms = 0u;
}

/* A counter reading: advance us / ms by the cycles since the previous one (less than one
 * counter period ago). */
static inline void modcp_timebase_feed(modcp_timebase_t *tb, uint32_t count)
{
    count &= tb->mask;
    uint32_t cycles = (tb->down ? tb->last - count : count - tb->last) & tb->mask;
    tb->last = count;
    uint32_t us = cycles / tb->cyc_per_us;
    tb->cyc_rem += cycles % tb->cyc_per_us;
    if (tb->cyc_rem >= tb->cyc_per_us) {
        tb->cyc_rem -= tb->cyc_per_us;
        us++;
    }
    tb->us += us;
    tb->us_rem += us;
    if (tb->us_rem >= 1000u) {
        tb->ms += tb->us_rem / 1000u;
        tb->us_rem %= 1000u;
    }
}

#endif
