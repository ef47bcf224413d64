/* SPDX-License-Identifier: Apache-2.0 */
/* Test world: one CP, one FB, the backplane between them, controller memory laid out
 * for the manual's example parameter set ([RTU-2003] §9), and a fake HAL that records what
 * the CP transmits. Time is simulated. */
#ifndef MODCP_TEST_WORLD_H
#define MODCP_TEST_WORLD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "fc_table_internal.h"
#include "quantity_internal.h"

#define WORLD_DBS 7
#define WORLD_WORK_DB 80

typedef struct {
    uint8_t tx[600];
    uint16_t tx_len;
    unsigned tx_count;
    uint32_t timer_us;
    bool de;
    unsigned de_on_count;
    int rx_preset; /* the last set_rx_preset, -1 before any */
} fake_hal_t;

typedef struct {
    modcp_backplane_t bp;
    modcp_cp_t cp;
    modcp_fb_t fb;
    modcp_plcmem_t mem;
    modcp_db_t dbs[WORLD_DBS];
    uint8_t db_data[WORLD_DBS][1024];
    uint8_t i[256], q[320], m[2600];
    uint16_t t[240], c[240];
    fake_hal_t fake;
    modcp_hal_t hal;
    modcp_params_t params;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    uint16_t record_len;
    uint32_t now_us;
    bool fb_paused; /* the user program does not call the FB */
    modcp_fb_out_t fb_out;
} world_t;

/* The [RTU-2003] §9 parameter set (example_params.h). */
void world_example_params(modcp_params_t *p);

/* Allocate a world with params p (NULL: the example set), not yet started. */
world_t *world_new(const modcp_params_t *p);
void world_free(world_t *w);
/* Run CP_START and cycles until CP_START_OK or CP_START_ERROR (or max_ms). A plain
 * start leaves one entry in the diagnostic buffer, (00)03H "parameters taken over" (VIPA
 * CP 341 manual §7.2); world_start clears the buffer when that is all it holds, so that
 * each test counts its own events (a start with warnings keeps them, with (00)03H
 * under them). world_start_keep leaves it (test_fb_restart.c test_start_up_events). */
bool world_start(world_t *w, uint32_t max_ms);
bool world_start_keep(world_t *w, uint32_t max_ms);
/* Advance time by us, running FB cycles (1 ms) and CP polls. */
void world_run(world_t *w, uint32_t us);
/* Send frame bytes (hex string incl. CRC) to the CP, end it with t3.5 silence and run
 * until a reply was transmitted or max_ms passed. Returns the reply length (0 = none);
 * the reply is in w->fake.tx. */
uint16_t world_request(world_t *w, const char *hex, uint32_t max_ms);
/* The same with raw bytes (the CRC is appended). */
uint16_t world_request_raw(world_t *w, const uint8_t *frame, size_t len, uint32_t max_ms);
/* Reply as "05 03 04 ..." (static buffer). */
const char *world_reply_hex(const world_t *w);
/* Newest event of the diagnostic buffer. */
modcp_event_t world_last_event(const world_t *w);
uint8_t *world_db(world_t *w, uint16_t number);

/* The largest quantity of function code fc for the limit set and framing of p and the
 * register kind (modcp_regs32_kind), by fc's limit class in the function-code table
 * (fc_table.c); 0 for a function code without a quantity. */
static inline uint16_t world_qty_max(const modcp_params_t *p, uint8_t fc, uint8_t r32_kind)
{
    const modcp_fc_row_t *r = modcp_fc_row(fc);
    return modcp_qty_limit(p, r != NULL ? (uint8_t)(r->form & FC_LIM) : 0u, r32_kind);
}

#endif
