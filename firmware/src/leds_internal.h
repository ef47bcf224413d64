/* modcp — the core's internal interface of leds.c (modcp/leds.h holds what a port or
 * an application calls). Not part of the public API: for the core, its tests and tools. */
#ifndef MODCP_LEDS_INTERNAL_H
#define MODCP_LEDS_INTERNAL_H

#include "modcp/leds.h"

/* Power-on: SF on, TXD and RXD off. */
void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal);
/* Silence that ends a received frame (t3.5 of the link). */
void modcp_leds_configure(modcp_leds_t *x, uint32_t quiet_us);
/* Drive the LEDs at now_us from the link's receive / transmit record; sf: the group
 * error is present. */
void modcp_leds_poll(modcp_leds_t *x, bool sf, const modcp_link_t *l, uint32_t now_us);
/* Levels as bits (1 << modcp_led_t) for the status area. */
static inline uint8_t modcp_leds_bits(const modcp_leds_t *x)
{
    return x->bits; /* kept by every change of a level (leds.c) */
}

#endif
