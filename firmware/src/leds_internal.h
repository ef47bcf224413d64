/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the core's internal interface of leds.c (modcp/leds.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_LEDS_INTERNAL_H
#define MODCP_LEDS_INTERNAL_H

#include "modcp/leds.h"

#define MODCP_LED_BIT(led) (1u << (unsigned)(led))

/* Power-on: SF on, TXD and RXD off, each set at the HAL; x zeroed (inside the CP
 * object, which modcp_cp_init clears). */
void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal);
/* Switch the levels to want (bits 1 << modcp_led_t); the HAL hears of each LED that
 * changes, in the order SF, TXD, RXD (leds.c). */
void modcp_leds_switch(modcp_leds_t *x, const modcp_hal_t *hal, unsigned want, uint32_t now_us);
/* Drive the LEDs at now_us from the link's receive / transmit record; sf: the group
 * error is present. Inline: a few compares once per poll (the CP's only caller); a
 * change of level is the out-of-line part. */
static inline void modcp_leds_poll(modcp_leds_t *x, bool sf, const modcp_link_t *l,
                                   uint32_t now_us)
{
    unsigned want = (x->bits & ~MODCP_LED_BIT(MODCP_LED_SF)) | (unsigned)sf; /* SF: bit 0 */

    if (l->tx_starts != x->tx_seen || l->tx_on) { /* started since the last poll, or on */
        x->tx_seen = l->tx_starts;
        want |= MODCP_LED_BIT(MODCP_LED_TXD);
    } else if ((want & MODCP_LED_BIT(MODCP_LED_TXD)) != 0u &&
               now_us - x->on_us[(unsigned)MODCP_LED_TXD - 1u] >= MODCP_LED_MIN_ON_US &&
               now_us - l->tx_end_us >= MODCP_LED_MIN_ON_US) {
        want &= ~MODCP_LED_BIT(MODCP_LED_TXD);
    } else {
        /* TXD stays as it is */
    }

    if (l->last_us != x->rx_seen_us) { /* a character since the last poll */
        x->rx_seen_us = l->last_us;
        want |= MODCP_LED_BIT(MODCP_LED_RXD);
    } else if ((want & MODCP_LED_BIT(MODCP_LED_RXD)) != 0u &&
               now_us - x->on_us[(unsigned)MODCP_LED_RXD - 1u] >= MODCP_LED_MIN_ON_US &&
               now_us - l->last_us >= MODCP_LED_MIN_ON_US && now_us - l->last_us >= l->t35_us) {
        want &= ~MODCP_LED_BIT(MODCP_LED_RXD);
    } else {
        /* RXD stays as it is */
    }

    if (want != x->bits) {
        modcp_leds_switch(x, l->hal, want, now_us);
    }
}
/* Levels as bits (1 << modcp_led_t) for the status area. */
static inline uint8_t modcp_leds_bits(const modcp_leds_t *x)
{
    return x->bits;
}

#endif
