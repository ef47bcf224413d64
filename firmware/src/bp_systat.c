/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — CPU side of the SYSTAT service ([RTU-2003] §7.4; see modcp/cpdiag.h): a request
 * number written by the CPU side, answered by the CP in the status area. */
#include <string.h>

#include "modcp/backplane.h"

uint32_t modcp_bp_systat_request(modcp_backplane_t *bp)
{
    uint32_t req = atomic_load_explicit(&bp->systat_req, memory_order_relaxed) + 1u;
    if (req == 0u) {
        req = 1u; /* 0 is "never asked" (the CP's initial acknowledgement) */
    }
    atomic_store_explicit(&bp->systat_req, req, memory_order_release);
    return req;
}

void modcp_bp_commloss_reset(modcp_backplane_t *bp)
{
    uint32_t n = atomic_load_explicit(&bp->commloss_reset, memory_order_relaxed) + 1u;
    atomic_store_explicit(&bp->commloss_reset, n, memory_order_release);
}

bool modcp_bp_systat_result(const modcp_backplane_t *bp, uint32_t req, uint8_t out[16])
{
    modcp_cp_status_t st;
    if (!modcp_bp_read_status(bp, &st) || st.systat_ack != req) {
        return false;
    }
    (void)memcpy(out, st.systat, sizeof st.systat);
    return true;
}
