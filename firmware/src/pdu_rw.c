/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — handlers of the manual's function set ([RTU-2003] §6), one per class: bits (FC01,
 * 02, 05, 15), registers (FC03, 04, 06, 16), and FC08 sub-function 0000. Each maps its
 * request and sets up one CPU job; the reply is encoded by pdu.c from s->x.echo /
 * s->x.rbytes when the job is done.
 *
 * The function-code table (pdu.c) has already checked the length against its minimum
 * and maximum and, for FC01/02/03/04/15/16, the quantity against the limits of the
 * framing and register width (s->addr, s->qty (1 for FC05 / 06), s->r32_kind,
 * s->fcflags set) and the form (FC06's value width, FC15 / FC16's byte count: (08)33H).
 * What is left here: FC05's value ((08)34H, exception 03), then the address
 * mapping ((0E)5xH, exception 02; map.c). Every field of the request is read before
 * the first reply byte is written. */
#include "pdu_rw_internal.h"

void modcp_pdu_align_bits(uint8_t *d, uint8_t shift, uint16_t qty)
{
    uint16_t n = (uint16_t)((qty + 7u) / 8u);
    if (shift != 0u) {
        for (uint16_t i = 0; i < n; i++) {
            d[i] = (uint8_t)((d[i] >> shift) | (d[i + 1u] << (8u - shift)));
        }
    }
    if ((qty & 7u) != 0u) {
        d[n - 1u] &= (uint8_t)((1u << (qty & 7u)) - 1u);
    }
}

/* The table's handler of FC01 / 02 / 03 / 04 / 05 / 06 / 15 / 16 (pdu_rw_internal.h). */
modcp_pdu_action_t modcp_pdu_rw(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)out_len;
    return modcp_pdu_rw_inline(s, env, pdu, len, cap);
}

/* FC08 in the manual set: sub-function 0000 (return query data) only. */
modcp_pdu_action_t modcp_pdu_diag0(modcp_pdu_t *s, const modcp_pdu_env_t *env, uint8_t *pdu,
                                   uint16_t len, uint16_t cap, uint16_t *out_len)
{
    (void)env;
    (void)cap;
    if (modcp_get16(pdu + 1) != 0x0000u) {
        return modcp_pdu_err(s, MODCP_EV_DIAG_SUBFC, MODCP_EXC_ILLEGAL_VALUE);
    }
    *out_len = len; /* echo, unchanged */
    return MODCP_PDU_REPLY;
}
