/* SPDX-License-Identifier: Apache-2.0 */
/* An application outside the modcp tree: one CP, its CPU side (FB) and a controller
 * memory with DB800, wired with nothing but modcp's public headers. It starts the FB,
 * sends the manual's FC03 example (slave 5, registers 0x50..0x51 = DB800.DBW160/162)
 * and checks the reply byte for byte (Siemens CP 341 MODBUS slave manual, 2003, §9).
 * Exit 0 when the reply is right. */
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/hal.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"

typedef struct {
    uint8_t tx[300];
    uint16_t tx_len;
    uint32_t timer_us;
} port_t;

static void tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    port_t *p = ctx;
    if (len <= sizeof p->tx) {
        memcpy(p->tx, buf, len);
        p->tx_len = len;
    }
}

static void arm(void *ctx, uint32_t us)
{
    ((port_t *)ctx)->timer_us = us;
}

static port_t port;
static modcp_backplane_t bp;
static modcp_cp_t cp;
static modcp_fb_t fb;
static uint8_t work[64], db800[1024], record[512];
static modcp_db_t dbs[2] = {{80u, sizeof work, work}, {800u, sizeof db800, db800}};

int main(void)
{
    modcp_params_t p;
    modcp_params_defaults(&p);
    p.slave_addr = 5;
    p.hr_base_db = 800;
    size_t n = modcp_params_encode(&p, record, sizeof record);
    if (n == 0u) {
        return 2;
    }
    modcp_plcmem_t mem = {.dbs = dbs, .db_count = 2};
    const modcp_hal_t hal = {.ctx = &port, .uart_tx = tx, .timer_arm = arm};
    db800[160] = 0x87;
    db800[161] = 0x65;
    db800[162] = 0x43;
    db800[163] = 0x21;
    modcp_bp_init(&bp);
    modcp_cp_init(&cp, &hal, &bp);
    modcp_fb_init(&fb, &bp, &mem, record, (uint16_t)n, 80u, 5000u);

    uint32_t now = 1000000u;
    modcp_fb_out_t out = {0};
    for (int i = 0; i < 100 && !out.cp_start_ok; i++, now += 1000u) {
        modcp_fb_in_t in = {true};
        modcp_fb_call(&fb, &in, &out, now / 1000u);
        modcp_cp_poll(&cp, now);
    }
    if (!out.cp_start_ok) {
        return 3;
    }
    static const uint8_t req[] = {0x05, 0x03, 0x00, 0x50, 0x00, 0x02, 0xC5, 0x9E};
    for (unsigned i = 0; i < sizeof req; i++, now += 1146u) {
        modcp_cp_on_rx(&cp, req[i], now);
    }
    for (int i = 0; i < 100 && port.tx_len == 0u; i++, now += 1000u) {
        modcp_cp_on_timer(&cp, now); /* the end-of-frame timer (and its re-arms) */
        modcp_fb_in_t in = {true};
        modcp_fb_call(&fb, &in, &out, now / 1000u);
        modcp_cp_poll(&cp, now);
    }
    static const uint8_t want[] = {0x05, 0x03, 0x04, 0x87, 0x65, 0x43, 0x21, 0x76, 0x70};
    return port.tx_len == sizeof want && memcmp(port.tx, want, sizeof want) == 0 ? 0 : 1;
}
