/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — diagnostics store: diagnostic buffer, SYSTAT, STATUS word, counters. */
#include "modcp/diag.h"

#include <stddef.h>
#include <string.h>
#include "commlog_internal.h"
#include "diag_internal.h"

void modcp_diag_init(modcp_diag_t *d)
{
    (void)memset(d, 0, sizeof *d);
}

_Static_assert((size_t)offsetof(modcp_diag_t, systat_zero) == (size_t)offsetof(modcp_diag_t, systat_flags) + 1u &&
                   (size_t)offsetof(modcp_diag_t, systat) == (size_t)offsetof(modcp_diag_t, systat_flags) + 2u &&
                   (size_t)offsetof(modcp_diag_t, systat_flags) == (size_t)offsetof(modcp_diag_t, systat_len) + 1u,
               "diag: SYSTAT from systat_flags on is the image from byte 2 on");
/* Keep a base pointer in a register: GCC folds it back into d + offset otherwise, with
 * 4-byte Thumb-2 loads and stores beyond byte 31. An empty asm it cannot see through. */
#if defined(__GNUC__)
#define KEEP_BASE(p) __asm__("" : "+r"(p))
#else
#define KEEP_BASE(p) ((void)0)
#endif
/* offsets of the SYSTAT members from buffer_len */
#define B_AT(f) (offsetof(modcp_diag_t, f) - offsetof(modcp_diag_t, buffer_len))
#define B_LEN B_AT(systat_len)
#define B_FLAGS B_AT(systat_flags)
#define B_EVENTS B_AT(systat)
#define SYSTAT_FROM_FLAGS (2u + 2u * MODCP_SYSTAT_EVENTS) /* image bytes 2..15 */

void modcp_diag_event(modcp_diag_t *d, modcp_event_t ev)
{
    if (ev == MODCP_EV_NONE) {
        return;
    }
    /* diagnostic buffer: ring of 9, newest first */
    (void)memmove(&d->buffer[1], &d->buffer[0], (MODCP_DIAG_BUFFER - 1u) * sizeof d->buffer[0]);
    d->buffer[0] = ev;
    /* buffer_len and the SYSTAT block through one pointer: their offsets from it are
     * small (short Thumb loads; from d they are beyond byte 31) */
    uint8_t *b = &d->buffer_len;
    KEEP_BASE(b);
    if (b[0] < MODCP_DIAG_BUFFER) {
        b[0]++;
    }
    if (ev < 0x0100u) { /* class 00H, CP start-up ([VIPA-341] §8.2): not an error, so not in
                           SYSTAT ("error area") nor in STATUS (an error's, [VIPA-341] §8.1) */
        d->events_total++;
        return;
    }
    /* SYSTAT: only the first six events until read; U = overflow (F is set then: the
     * first event set it) */
    unsigned n = b[B_LEN];
    unsigned f = b[B_FLAGS] | MODCP_SYSTAT_F;
    if (n < MODCP_SYSTAT_EVENTS) {
        b[B_EVENTS + 2u * n] = (uint8_t)(ev >> 8);
        b[B_EVENTS + 2u * n + 1u] = (uint8_t)ev;
        b[B_LEN] = (uint8_t)(n + 1u);
    } else {
        f |= MODCP_SYSTAT_U;
    }
    if (ev == MODCP_EV_BREAK) {
        f |= MODCP_SYSTAT_B;
    }
    b[B_FLAGS] = (uint8_t)f;
    /* STATUS word: bits 12..8 class, 7..0 number */
    d->status = (uint16_t)(ev & 0x1FFFu);
    d->events_total++;
}

/* Every counter but the bus and slave message counts (modcp_diag_count, inline). Out of
 * line also under LTO: called from a few cold paths, one copy is enough. */
__attribute__((noinline)) void modcp_diag_count_error(modcp_diag_t *d, modcp_counter_t c)
{
    if ((unsigned)c >= (unsigned)MODCP_CNT_COUNT) {
        return;
    }
    if (d->counters[c] != UINT16_MAX) {
        d->counters[c]++; /* error counts saturate */
    }
#if MODCP_WITH_EXTENDED
    modcp_comm_counted(&d->comm, (unsigned)c); /* FC12 event log, overrun flag */
#endif
}

void modcp_diag_clear_counters(modcp_diag_t *d)
{
    (void)memset(d->counters, 0, sizeof d->counters);
#if MODCP_WITH_EXTENDED
    modcp_comm_clear(&d->comm); /* FC11's event counter, the diagnostic register */
#endif
}

#if MODCP_WITH_EXTENDED
void modcp_diag_clear_overrun(modcp_diag_t *d)
{
    d->counters[MODCP_CNT_CHAR_OVERRUN] = 0;
    modcp_comm_clear_overrun(&d->comm);
}
#endif

_Static_assert(offsetof(modcp_diag_t, buffer_len) == offsetof(modcp_diag_t, buffer) +
                                                       sizeof((modcp_diag_t *)0)->buffer,
               "diag: buffer_len right after the buffer (one memset clears both)");

void modcp_diag_clear_buffer(modcp_diag_t *d)
{
    /* the events and buffer_len */
    (void)memset((uint8_t *)d + offsetof(modcp_diag_t, buffer), 0, sizeof d->buffer + 1u);
}

void modcp_diag_read_systat(modcp_diag_t *d, bool run, uint8_t out[16])
{
    out[0] = run ? MODCP_SYSTAT_RUN : MODCP_SYSTAT_FAULT;
    out[1] = 0u;
    const uint8_t *from = (const uint8_t *)d + offsetof(modcp_diag_t, systat_flags);
    memcpy(&out[2], from, SYSTAT_FROM_FLAGS);
    /* cleared: length, flags, events */
    memset((uint8_t *)d + offsetof(modcp_diag_t, systat_len), 0, 1u + SYSTAT_FROM_FLAGS);
}
