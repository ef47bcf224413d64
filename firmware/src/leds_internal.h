/* modcp — the core's internal interface of leds.c (modcp/leds.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_LEDS_INTERNAL_H
#define MODCP_LEDS_INTERNAL_H

#include "modcp/leds.h"

/* Power-on: SF on, TXD and RXD off; x zeroed (inside the CP object, which
 * modcp_cp_init clears). */
void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal);
/* Silence that ends a received frame (t3.5 of the link). */
void modcp_leds_configure(modcp_leds_t *x, uint32_t quiet_us);
/* Switch a level (leds.c): the HAL hears of it. */
void modcp_leds_change(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us);
/* Set a level; the HAL hears of changes only. */
static inline void modcp_leds_set(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us)
{
    if (x->on[led] != on) {
        modcp_leds_change(x, led, on, now_us);
    }
}
static inline bool modcp_leds_min_on_elapsed(const modcp_leds_t *x, modcp_led_t led,
                                             uint32_t now_us)
{
    return now_us - x->on_us[led - 1u] >= MODCP_LED_MIN_ON_US; /* TXD / RXD */
}
/* Drive the LEDs at now_us from the link's receive / transmit record; sf: the group
 * error is present. Inline: a few compares once per poll (the CP's only caller); a
 * change of level is the out-of-line part. */
static inline void modcp_leds_poll(modcp_leds_t *x, bool sf, const modcp_link_t *l,
                                   uint32_t now_us)
{
    modcp_leds_set(x, MODCP_LED_SF, sf, now_us);

    if (l->tx_starts != x->tx_seen || l->tx_on) { /* started since the last poll, or on */
        x->tx_seen = l->tx_starts;
        modcp_leds_set(x, MODCP_LED_TXD, true, now_us);
    } else if (x->on[MODCP_LED_TXD] && modcp_leds_min_on_elapsed(x, MODCP_LED_TXD, now_us)) {
        modcp_leds_set(x, MODCP_LED_TXD, false, now_us);
    }

    if (l->last_us != x->rx_seen_us) { /* a character since the last poll */
        x->rx_seen_us = l->last_us;
        modcp_leds_set(x, MODCP_LED_RXD, true, now_us);
    } else if (x->on[MODCP_LED_RXD] && modcp_leds_min_on_elapsed(x, MODCP_LED_RXD, now_us) &&
               now_us - l->last_us >= x->quiet_us) {
        modcp_leds_set(x, MODCP_LED_RXD, false, now_us);
    }
}
/* Levels as bits (1 << modcp_led_t) for the status area. */
static inline uint8_t modcp_leds_bits(const modcp_leds_t *x)
{
    return x->bits; /* kept by every change of a level (leds.c) */
}

#endif
