/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CPU side's FB initialisation (fb.c's step 4, [RTU-2003] §5.5): START_TIME
 * check, a retry every MODCP_FB_RETRY_MS while the CP answers "not ready" or is silent,
 * PARAMS then INIT pushed as the ring has room. */
#include <stddef.h>

#include "modcp/crc.h"
#include "backplane_internal.h"
#include "fb_internal.h"
#include "plcmem_internal.h"

static bool put_block(modcp_fb_t *fb, uint8_t kind, uint8_t flags, uint8_t tag,
                      const uint8_t *data, uint8_t len)
{
    return modcp_ring_put_data(&fb->bp->to_cp, &fb->tx_seq, kind, flags, tag, data, len);
}

void modcp_fb_start_attempt(modcp_fb_t *fb, uint32_t now_ms, bool with_params)
{
    fb->state = MODCP_FBST_INIT_SEND;
    fb->params_pending = with_params && fb->record_len > 0u;
    fb->params_pos = 0;
    fb->init_sent = false;
    fb->retry_t0_ms = now_ms;
}

/* Push PARAMS blocks; true when the whole record is out. */
static bool push_params(modcp_fb_t *fb)
{
    while (fb->params_pending) {
        uint32_t rest = (uint32_t)fb->record_len - fb->params_pos;
        uint8_t n = (uint8_t)(rest > MODCP_BLOCK_SIZE ? MODCP_BLOCK_SIZE : rest);
        bool last = n == rest;
        uint8_t flags = (uint8_t)((fb->params_pos == 0u ? MODCP_BLK_FIRST : 0u) |
                                  (last ? MODCP_BLK_LAST : 0u));
        if (!put_block(fb, MODCP_BP_PARAMS, flags, 0, fb->record + fb->params_pos, n)) {
            return false;
        }
        fb->params_pos = (uint16_t)(fb->params_pos + n);
        if (last) {
            fb->params_pending = false;
        }
    }
    return true;
}

static void send_init(modcp_fb_t *fb)
{
    modcp_bp_init_t init;
    modcp_plcmem_areas(fb->mem, &init.areas); /* the real area sizes */
    init.areas.work_db = fb->work_db;
    init.record_crc = fb->record_len > 0u ? modcp_bp_record_id(fb->record, fb->record_len) : 0u;
    uint8_t d[MODCP_BLOCK_SIZE];
    uint8_t n = modcp_bp_init_encode(&init, d);
    if (put_block(fb, MODCP_BP_INIT, MODCP_BLK_FIRST | MODCP_BLK_LAST, 0, d, n)) {
        fb->init_sent = true;
        fb->state = MODCP_FBST_INIT_WAIT;
    }
}

bool modcp_fb_run_init(modcp_fb_t *fb, uint32_t now_ms)
{
    if ((fb->state != (uint8_t)MODCP_FBST_INIT_SEND) &&
        (fb->state != (uint8_t)MODCP_FBST_INIT_WAIT)) {
        if (fb->params_pending) {
            (void)push_params(fb); /* PARAMS of the first call */
        }
        return true;
    }
    if ((uint32_t)(now_ms - fb->init_t0_ms) >= fb->start_time_ms) {
        fb->state = MODCP_FBST_FAILED;
        fb->params_pending = false;
        fb->out.cp_start_ok = false;
        fb->out.cp_start_error = true;
        fb->out.error_nr = MODCP_FB_ERR_INIT;
        fb->out.error_info = fb->init_event;
        fb->err_changed = true;
        return false;
    }
    if (fb->state == (uint8_t)MODCP_FBST_INIT_WAIT &&
        (uint32_t)(now_ms - fb->retry_t0_ms) >= MODCP_FB_RETRY_MS) {
        fb->cp_has_params = false; /* not ready or silent: the record goes again */
        modcp_fb_start_attempt(fb, now_ms, true);
    }
    if (fb->state == (uint8_t)MODCP_FBST_INIT_SEND && push_params(fb) && !fb->init_sent) {
        send_init(fb);
    }
    return true;
}
