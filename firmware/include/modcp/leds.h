/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the CP's LEDs SF / TXD / RXD ([RTU-2003] §7.2, [VIPA-341] §1.2; docs/diagnostics.md).
 *
 *  SF  (group error, [RTU-2003] §7.2, [ASCII-32] §10.1): on at power-on and whenever the CP has no
 *      valid parameters, while a wire break (BREAK on RxD in normal mode) is present,
 *      and with RS232 automatic signals while CTS / DSR are not asserted; not for an FB
 *      that is not (yet) initialised. The caller computes it; leds.c only drives it.
 *  TXD: on while a reply is being sent and MODCP_LED_MIN_ON_US (200 ms) after its
 *      transmission complete, retriggered by every reply ([ALTIVAR] §8: "each LED lights for
 *      200 ms when a frame travels"), and at least 200 ms from switching on.
 *  RXD: on while characters are received (any address: the line is alive) and 200 ms
 *      after the last character, retriggered by every frame; a frame keeps it on until
 *      it has ended (no character for the link's t3.5), and it is on for at least 200 ms
 *      from switching on (a late poll).
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
