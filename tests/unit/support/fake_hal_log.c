/* SPDX-License-Identifier: Apache-2.0 */
#include "fake_hal_log.h"

#include <string.h>

static void add(fake_hal_log_t *f, uint8_t kind, uint32_t value)
{
    if (f->n < FAKE_HAL_LOG_MAX) {
        f->log[f->n].kind = kind;
        f->log[f->n].value = value;
        f->log[f->n].at = f->now;
        f->n++;
    }
}

static void fhl_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    fake_hal_log_t *f = ctx;
    uint16_t n = len < FAKE_HAL_LOG_TX ? len : FAKE_HAL_LOG_TX;
    memcpy(f->tx, buf, n);
    f->tx_len = len;
    f->tx_calls++;
    add(f, FHL_TX, len);
}

static void fhl_arm(void *ctx, uint32_t us)
{
    add(ctx, FHL_ARM, us);
}

static void fhl_de(void *ctx, bool on)
{
    fake_hal_log_t *f = ctx;
    f->de = on;
    add(f, FHL_DE, on ? 1u : 0u);
}

static void fhl_led(void *ctx, modcp_led_t led, bool on)
{
    add(ctx, FHL_LED, ((uint32_t)led << 1) | (on ? 1u : 0u));
}

static void fhl_sig(void *ctx, modcp_signal_t sig, bool on)
{
    add(ctx, FHL_SIG, ((uint32_t)sig << 1) | (on ? 1u : 0u));
}

void fake_hal_log_init(fake_hal_log_t *f, modcp_hal_t *hal, bool with_de)
{
    memset(f, 0, sizeof *f);
    memset(hal, 0, sizeof *hal);
    hal->ctx = f;
    hal->uart_tx = fhl_tx;
    hal->timer_arm = fhl_arm;
    if (with_de) {
        hal->set_de = fhl_de;
        hal->set_led = fhl_led;
        hal->set_signal = fhl_sig;
    }
}

void fake_hal_log_clear(fake_hal_log_t *f)
{
    f->n = 0;
    f->tx_len = 0;
    f->tx_calls = 0;
}

size_t fake_hal_log_count(const fake_hal_log_t *f, uint8_t kind)
{
    size_t c = 0;
    for (size_t i = 0; i < f->n; i++) {
        if (f->log[i].kind == kind) {
            c++;
        }
    }
    return c;
}

const fake_hal_log_entry_t *fake_hal_log_last(const fake_hal_log_t *f, uint8_t kind)
{
    for (size_t i = f->n; i > 0; i--) {
        if (f->log[i - 1].kind == kind) {
            return &f->log[i - 1];
        }
    }
    return NULL;
}

long fake_hal_log_find(const fake_hal_log_t *f, uint8_t kind, size_t from)
{
    for (size_t i = from; i < f->n; i++) {
        if (f->log[i].kind == kind) {
            return (long)i;
        }
    }
    return -1;
}
