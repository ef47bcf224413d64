/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the RTU framing backend's own interface: its receive state and what its two
 * variants share. rtu.c holds the receive automaton's common part, normal operation and
 * the end of a frame; rtu_modem.c interference suppression = modem mode, built on
 * rtu.c's common part (rtu_modem.c calls rtu.c, never the other way). Only these two
 * files include it; the link knows the backend by its ops (link_internal.h). */
#ifndef MODCP_RTU_INTERNAL_H
#define MODCP_RTU_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "link_internal.h"

#define RTU_MIN_FRAME 4u /* address, function, CRC */

/* RTU receive state, in l->fr. Our frame (modem mode: the candidate) is stored in the
 * link's buffer, by the link below l->run_stop (normal operation: the capacity; modem
 * mode: the function code, byte count, last character need a look); its CRC is computed
 * over the buffer where it matters (rtu_crc_ok). */
typedef struct {
    uint16_t count;    /* characters of the stretch that is not our frame (a skipped
                          frame; modem mode: the stretch being followed), up to 4 */
    uint16_t total;    /* modem mode: the candidate's length by its function code, 0: by
                          t3.5 (normal operation: always 0) */
    uint16_t skip_crc; /* CRC over the stretch that is not our frame (bus counters) */
    uint8_t flags;     /* RTU_M_* */
    bool modem;        /* interference suppression = modem mode (rtu_modem.c) */
    bool r32_on;       /* 32-bit registers on: a register write of a width set by the start
                          address (F_R32, FC_PLUS2: FC06) has a longer form (4 data bytes to
                          an int32 / float register, [ASCII-32] §4.5) */
} modcp_rtu_t;
_Static_assert(sizeof(modcp_rtu_t) <= sizeof(modcp_link_fr_t), "modcp_link_fr_t holds it");

/* modcp_rtu_t.flags (modem mode) */
#define RTU_M_LEAD 0x01u  /* the stretch began with our address or 0 */
#define RTU_M_FIRST 0x02u /* the candidate is the stretch's first character */
#define RTU_M_OPEN 0x04u  /* a wrong CRC at the length: continue to t3.5 (FC08, FC43; FC06
                           with 32-bit registers) */
#define RTU_M_SBAD 0x08u  /* the stretch around the candidate had a line error */

static inline modcp_rtu_t *rtu_of(modcp_link_t *l)
{
    return (modcp_rtu_t *)(void *)&l->fr;
}

static inline const modcp_rtu_t *rtu_of_c(const modcp_link_t *l)
{
    return (const modcp_rtu_t *)(const void *)&l->fr;
}

/* Where the link stops storing our frame's characters for us (0: not in RX). With the
 * t1.5 check on, the port's per-character entry always reaches the framing. */
static inline void rtu_stop(modcp_link_t *l, uint16_t stop)
{
    link_set_stop(l, l->t15_us == 0u ? stop : 0u, stop);
}

/* The frame in buf[0 .. len) is at least 4 characters and ends in its valid CRC. */
bool rtu_crc_ok(const modcp_link_t *l);
/* A character of the stretch that is not part of our frame (bus counters only). */
void rtu_fold(modcp_link_t *l, uint8_t b);
/* Our address (or 0) starts our frame (modem mode: a candidate) at buf[0]. */
void rtu_cand_start(modcp_link_t *l, uint8_t b);
/* Our frame (modem mode: the candidate) given up: its first n characters folded into
 * the stretch, state SKIP. */
void rtu_unclaim(modcp_link_t *l, uint16_t n);
/* A character or line error (err, b 0) the states both variants handle alike: a frame's
 * start (IDLE, SKIP after t3.5), the busy states, a state RTU never uses. False: RX or
 * SKIP within t3.5, the variant's own (nothing done). */
bool rtu_other_common(modcp_link_t *l, uint8_t b, uint32_t now_us, bool err);
/* With the t1.5 check on: does a character at now_us come too late for our frame (RX)?
 * (Inline: every character with the check on comes here.) */
static inline bool rtu_t15_late(const modcp_link_t *l, uint32_t now_us)
{
    return l->t15_us != 0u && l->state == (uint8_t)MODCP_LINK_RX &&
           now_us - l->last_us > l->t15_us + l->char_us;
}
/* The same, counted once per frame when it is so (the caller damages or drops the frame
 * next), (08)0EH in normal mode. */
bool rtu_t15_violated(modcp_link_t *l, uint32_t now_us);
/* The rest of the ops, the same for both variants. */
bool rtu_in_frame(const modcp_link_t *l);
bool rtu_on_timer(modcp_link_t *l, uint32_t now_us, modcp_frame_t *f);
uint16_t rtu_encode(modcp_link_t *l, uint16_t pdu_len);
/* The common part of configuring a variant: false if the buffer is too small. */
bool rtu_setup(modcp_link_t *l, bool modem);

#endif
