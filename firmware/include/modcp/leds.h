/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP's LEDs SF / TXD / RXD (004 §7.2, 001 §1.2; SPEC §7).
 *
 *  SF  (group error): on at power-on and whenever the CP is not ready (no or invalid
 *      parameters, FB not initialised), and while a wire break (BREAK on RxD in normal
 *      mode) is present. The caller computes it; leds.c only drives it.
 *  TXD: on while a reply is being sent; on for at least MODCP_LED_MIN_ON_US.
 *  RXD: on while characters are received (any address: the line is alive); a received
 *      frame keeps it on until it has ended (no character for the link's t3.5) and
 *      at least MODCP_LED_MIN_ON_US have passed since it went on.
 * The LEDs have one source, the link (modcp/link.h): it records the time of the last
 * received character (last_us; not the echo of our own RS485 reply), the transmissions
 * started (tx_starts) and whether one is on the line (tx_on, until transmission
 * complete). modcp_leds_poll(), i.e. modcp_cp_poll(), reads them and switches the LEDs:
 * nothing is called per byte. The minimum on-time counts from the moment the LED was
 * switched on, so every frame is visible for at least 200 ms however late the poll
 * comes. set_led (the link's HAL) is called only when a level changes. */
/* Public for layout only: modcp_cp_t embeds modcp_leds_t, so the type is here; its fields
 * are private and its functions are internal (firmware/src/leds_internal.h). */
#ifndef MODCP_LEDS_H
#define MODCP_LEDS_H

#include <stdbool.h>
#include <stdint.h>

#include "modcp/hal.h"
#include "modcp/link.h"

#define MODCP_LED_MIN_ON_US 200000u
#define MODCP_LED_COUNT 3u

typedef struct {
    uint32_t on_us[MODCP_LED_COUNT - 1u]; /* when TXD / RXD (index led - 1) went on */
    uint32_t rx_seen_us; /* the link's last_us at the last poll */
    uint16_t tx_seen;    /* the link's tx_starts at the last poll */
    uint8_t bits;        /* the levels as last set (1 << modcp_led_t) */
} modcp_leds_t;

#endif
