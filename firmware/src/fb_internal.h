/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — what fb.c (the FB call, job execution) and fb_init.c (its initialisation)
 * share. Internal to the core: not part of the public API. */
#ifndef MODCP_FB_INTERNAL_H
#define MODCP_FB_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/fb.h"

/* An initialisation attempt from now on: PARAMS (with_params) then INIT. */
void modcp_fb_start_attempt(modcp_fb_t *fb, uint32_t now_ms, bool with_params);
/* An initialisation step; false when it failed in this call (START_TIME over). */
bool modcp_fb_run_init(modcp_fb_t *fb, uint32_t now_ms);
/* The same, with the common case inline: running, nothing of the first call's PARAMS
 * left to push (nothing to do). */
static inline bool modcp_fb_init_step(modcp_fb_t *fb, uint32_t now_ms)
{
    if (fb->state != (uint8_t)MODCP_FBST_INIT_SEND && fb->state != (uint8_t)MODCP_FBST_INIT_WAIT &&
        !fb->params_pending) {
        return true;
    }
    return modcp_fb_run_init(fb, now_ms);
}

#endif
