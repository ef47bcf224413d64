/* SPDX-License-Identifier: Apache-2.0 */
/* Test helper: a fake HAL that records every call in order, with the simulated time
 * at which it happened (the test sets fake_hal_log_t.now before calling the core). */
#ifndef MODCP_TEST_FAKE_HAL_LOG_H
#define MODCP_TEST_FAKE_HAL_LOG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/hal.h"

typedef enum {
    FHL_TX = 1,   /* uart_tx: value = length, bytes in tx[] */
    FHL_ARM = 2,  /* timer_arm: value = us (0 = disarm) */
    FHL_DE = 3,   /* set_de: value = on */
    FHL_LED = 4,  /* set_led: value = led << 1 | on */
    FHL_SIG = 5,  /* set_signal: value = sig << 1 | on */
} fake_hal_log_kind_t;

typedef struct {
    uint8_t kind;
    uint32_t value;
    uint32_t at; /* fake_hal_log_t.now at the call */
} fake_hal_log_entry_t;

#define FAKE_HAL_LOG_MAX 1024
#define FAKE_HAL_LOG_TX 1024

typedef struct {
    uint32_t now;
    fake_hal_log_entry_t log[FAKE_HAL_LOG_MAX];
    size_t n;
    uint8_t tx[FAKE_HAL_LOG_TX]; /* bytes of the last uart_tx */
    uint16_t tx_len;
    unsigned tx_calls;
    bool de;
} fake_hal_log_t;

/* Fill hal with callbacks recording into f. with_de false: set_de, set_led and
 * set_signal are NULL (an RS232 port). */
void fake_hal_log_init(fake_hal_log_t *f, modcp_hal_t *hal, bool with_de);
/* Forget the recorded calls (not the DE level). */
void fake_hal_log_clear(fake_hal_log_t *f);
/* Number of recorded calls of one kind. */
size_t fake_hal_log_count(const fake_hal_log_t *f, uint8_t kind);
/* The last recorded call of a kind, or NULL. */
const fake_hal_log_entry_t *fake_hal_log_last(const fake_hal_log_t *f, uint8_t kind);
/* Index of the first call of a kind at or after index from, or -1. */
long fake_hal_log_find(const fake_hal_log_t *f, uint8_t kind, size_t from);

#endif
