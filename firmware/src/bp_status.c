/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP status area on the backplane: a single-writer seqlock. The CP side
 * publishes (in place, between begin and end, or from a copy), the CPU side copies;
 * neither ever waits for the other. */
#include <string.h>

#include "modcp/backplane.h"
#include "backplane_internal.h"

void modcp_bp_publish_status(modcp_backplane_t *bp, const modcp_cp_status_t *st)
{
    (void)memcpy(modcp_bp_status_begin(bp), st, sizeof *st);
    modcp_bp_status_end(bp);
}

bool modcp_bp_read_status(const modcp_backplane_t *bp, modcp_cp_status_t *out)
{
    uint32_t s1 = atomic_load_explicit(&bp->status_seq, memory_order_acquire);
    if ((s1 & 1u) != 0u) {
        return false;
    }
    (void)memcpy(out, &bp->status, sizeof *out);
    atomic_thread_fence(memory_order_acquire);
    uint32_t s2 = atomic_load_explicit(&bp->status_seq, memory_order_relaxed);
    return s1 == s2;
}
