/* modcp — diagnostics store: diagnostic buffer, SYSTAT, STATUS word, counters. */
#include "modcp/diag.h"

#include <string.h>
#include "commlog_internal.h"
#include "diag_internal.h"

void modcp_diag_init(modcp_diag_t *d)
{
    memset(d, 0, sizeof *d);
}

void modcp_diag_event(modcp_diag_t *d, modcp_event_t ev)
{
    if (ev == MODCP_EV_NONE) {
        return;
    }
    /* diagnostic buffer: ring of 9, newest first */
    memmove(&d->buffer[1], &d->buffer[0], (MODCP_DIAG_BUFFER - 1u) * sizeof d->buffer[0]);
    d->buffer[0] = ev;
    if (d->buffer_len < MODCP_DIAG_BUFFER) {
        d->buffer_len++;
    }
    /* SYSTAT: only the first six events until read; U = overflow */
    if (d->systat_len < MODCP_SYSTAT_EVENTS) {
        d->systat[d->systat_len++] = ev;
        d->systat_flags |= MODCP_SYSTAT_F;
    } else {
        d->systat_flags |= MODCP_SYSTAT_U;
    }
    if (ev == MODCP_EV_BREAK) {
        d->systat_flags |= MODCP_SYSTAT_B;
    }
    /* STATUS word: bits 12..8 class, 7..0 number */
    d->status = (uint16_t)(ev & 0x1FFFu);
    d->events_total++;
}

/* Every counter but the bus and slave message counts (modcp_diag_count, inline). Out of
 * line also under LTO: called from a few cold paths, one copy is enough. */
__attribute__((noinline)) void modcp_diag_count_error(modcp_diag_t *d, modcp_counter_t c)
{
    if ((unsigned)c >= MODCP_CNT_COUNT) {
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
    memset(d->counters, 0, sizeof d->counters);
}

void modcp_diag_clear_buffer(modcp_diag_t *d)
{
    memset(d->buffer, 0, sizeof d->buffer);
    d->buffer_len = 0;
}

void modcp_diag_read_systat(modcp_diag_t *d, bool run, uint8_t out[16])
{
    memset(out, 0, 16);
    out[0] = run ? MODCP_SYSTAT_RUN : MODCP_SYSTAT_FAULT;
    out[2] = d->systat_flags;
    for (uint8_t i = 0; i < d->systat_len; i++) {
        out[4u + 2u * i] = (uint8_t)(d->systat[i] >> 8);
        out[5u + 2u * i] = (uint8_t)(d->systat[i] & 0xFFu);
    }
    d->systat_len = 0;
    d->systat_flags = 0;
    memset(d->systat, 0, sizeof d->systat);
}
