/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL: threads without timer slack, with a short time slice. */
#define _GNU_SOURCE
#include "modcp/hal_posix.h"

#include <pthread.h>
#include <string.h>
#ifdef __linux__
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

/* The threads run a few microseconds at a time and must run when they wake: ask the
 * scheduler (Linux 6.12+, EEVDF) for a short time slice, 100 us instead of the default
 * (0.7 ms x (1 + log2 CPUs): 1.4 ms on two). A task's virtual deadline is its slice
 * ahead, so a woken thread with a short slice has the earlier deadline and preempts a
 * compiler that is running instead of waiting for its slice to end; its share of the
 * processor is unchanged. Policy and nice value stay as they are; an older kernel
 * ignores the request. */
static void short_slice(void)
{
#if defined(__linux__) && defined(SYS_sched_setattr) && defined(SYS_sched_getattr)
    struct {
        uint32_t size, policy;
        uint64_t flags;
        int32_t nice;
        uint32_t prio;
        uint64_t runtime, deadline, period;
    } sa;
    memset(&sa, 0, sizeof sa);
    if (syscall(SYS_sched_getattr, 0, &sa, (unsigned)sizeof sa, 0u) == 0 &&
        sa.policy == 0u /* SCHED_OTHER */) {
        sa.size = (uint32_t)sizeof sa;
        sa.runtime = 100000u; /* ns */
        (void)syscall(SYS_sched_setattr, 0, &sa, 0u);
    }
#endif
}

/* Every thread of the port's owner waits for deadlines of a few hundred microseconds
 * (t3.5, a character time, the CPU cycle): ask the kernel not to add its default timer
 * slack (50 us on Linux) to those waits. */
static void *thread_entry(void *arg)
{
    modcp_posix_thread_t *t = arg;
#ifdef PR_SET_TIMERSLACK
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL); /* 1 ns: as exact as the clock */
#endif
    short_slice();
    return t->fn(t->arg);
}

int modcp_posix_thread_start(modcp_posix_thread_t *t, void *(*fn)(void *), void *arg)
{
    t->fn = fn;
    t->arg = arg;
    int rc = pthread_create(&t->handle, NULL, thread_entry, t);
    return rc == 0 ? 0 : -rc;
}

void modcp_posix_thread_join(modcp_posix_thread_t *t)
{
    (void)pthread_join(t->handle, NULL);
}
