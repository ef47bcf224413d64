/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: the monotonic clock, sleeping and spinning until an absolute time. */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <errno.h>
#include <time.h>

uint64_t modcp_posix_now_us64(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

uint32_t modcp_posix_now_us(void)
{
    return (uint32_t)(modcp_posix_now_us64() & 0xFFFFFFFFu);
}

uint32_t modcp_posix_now_ms(void)
{
    return (uint32_t)((modcp_posix_now_us64() / 1000u) & 0xFFFFFFFFu);
}

void modcp_posix_sleep_until_us64(uint64_t t_us)
{
    struct timespec ts;
    ts.tv_sec = (time_t)(t_us / 1000000u);
    ts.tv_nsec = (long)((t_us % 1000000u) * 1000u);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR) {
    }
}

void modcp_posix_spin_until_us64(uint64_t t_us)
{
    while (modcp_posix_now_us64() < t_us) {
    }
}
