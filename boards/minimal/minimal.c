/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core alone in a minimal image, for the size report (tools/size).
 *
 * References exactly the CP side's event interface (modcp_cp_init / on_rx /
 * on_line_error / on_timer / on_tx_done / poll / ready) with a HAL whose callbacks do
 * nothing, and feeds it dummy events read from volatile locations so nothing can be
 * optimised away. With MINIMAL_WITH_FB the CPU side's FB and a one-DB controller memory
 * are linked too (the figure of a whole CP + CPU node). Never run. */
#include <stdbool.h>
#include <stdint.h>

#include "board/startup.h"
#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/hal.h"
#if defined(MINIMAL_WITH_FB)
#include "modcp/fb.h"
#include "modcp/plcmem.h"
#endif

static void nop_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    (void)ctx;
    (void)buf;
    (void)len;
}

static void nop_arm(void *ctx, uint32_t us)
{
    (void)ctx;
    (void)us;
}

static const modcp_hal_t hal = {.uart_tx = nop_tx, .timer_arm = nop_arm};
static modcp_backplane_t bp;
static modcp_cp_t cp;

/* dummy event sources */
volatile uint8_t minimal_event;
volatile uint8_t minimal_byte;
volatile uint32_t minimal_now;
volatile bool minimal_ready;

#if defined(MINIMAL_WITH_FB)
static uint8_t db1[64];
static modcp_db_t dbs[1] = {{1u, sizeof db1, db1}};
static modcp_plcmem_t mem = {NULL, NULL, NULL, NULL, NULL, 0u, 0u, 0u, 0u, 0u, dbs, 1u};
static const uint8_t record[4] = {0};
static modcp_fb_t fb;
#endif

int main(void)
{
    modcp_bp_init(&bp);
    modcp_cp_init(&cp, &hal, &bp);
#if defined(MINIMAL_WITH_FB)
    modcp_fb_init(&fb, &bp, &mem, record, (uint16_t)sizeof record, 0u, 1000u);
#endif
    for (;;) {
        uint32_t now = minimal_now;
        switch (minimal_event) {
        case 0: modcp_cp_on_rx(&cp, minimal_byte, now); break;
        case 1: modcp_cp_on_line_error(&cp, minimal_byte, now); break;
        case 2: modcp_cp_on_timer(&cp, now); break;
        case 3: modcp_cp_on_tx_done(&cp, now); break;
        default: modcp_cp_poll(&cp, now); break;
        }
        minimal_ready = modcp_cp_ready(&cp);
#if defined(MINIMAL_WITH_FB)
        modcp_fb_in_t in = {true};
        modcp_fb_out_t out;
        modcp_fb_call(&fb, &in, &out, now / 1000u);
#endif
    }
}

__attribute__((section(".isr_vector"), used)) static const CM_VECTORS_T(0) vectors = {
    .sp = _estack,
    .handler = {Reset_Handler, Default_Handler, Default_Handler, Default_Handler,
                Default_Handler, Default_Handler, 0, 0, 0, 0, Default_Handler,
                Default_Handler, 0, Default_Handler, Default_Handler},
};
