/* modcp — LEDs SF / TXD / RXD (see modcp/leds.h). */
#include "modcp/leds.h"

#include <stddef.h>
#include <string.h>

static void set(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us)
{
    if (x->on[led] == on) {
        return;
    }
    x->on[led] = on;
    x->on_us[led] = now_us;
    if (x->hal != NULL && x->hal->set_led != NULL) {
        x->hal->set_led(x->hal->ctx, led, on);
    }
}

void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal)
{
    memset(x, 0, sizeof *x);
    x->hal = hal;
    /* set every LED explicitly at power-on: SF on, TXD / RXD off */
    x->on[MODCP_LED_TXD] = true;
    x->on[MODCP_LED_RXD] = true;
    set(x, MODCP_LED_SF, true, 0);
    set(x, MODCP_LED_TXD, false, 0);
    set(x, MODCP_LED_RXD, false, 0);
}

void modcp_leds_configure(modcp_leds_t *x, uint32_t quiet_us)
{
    x->quiet_us = quiet_us;
}

void modcp_leds_rx(modcp_leds_t *x, uint32_t now_us)
{
    x->rx_last_us = now_us;
    x->rx_seen = true;
}

void modcp_leds_tx_start(modcp_leds_t *x)
{
    x->tx_seen = true;
    x->tx_active = true;
}

void modcp_leds_tx_end(modcp_leds_t *x)
{
    x->tx_active = false;
}

static bool min_on_elapsed(const modcp_leds_t *x, modcp_led_t led, uint32_t now_us)
{
    return now_us - x->on_us[led] >= MODCP_LED_MIN_ON_US;
}

void modcp_leds_poll(modcp_leds_t *x, bool sf, uint32_t now_us)
{
    set(x, MODCP_LED_SF, sf, now_us);

    if (x->tx_seen || x->tx_active) {
        x->tx_seen = false;
        set(x, MODCP_LED_TXD, true, now_us);
    } else if (x->on[MODCP_LED_TXD] && min_on_elapsed(x, MODCP_LED_TXD, now_us)) {
        set(x, MODCP_LED_TXD, false, now_us);
    }

    if (x->rx_seen) {
        x->rx_seen = false;
        set(x, MODCP_LED_RXD, true, now_us);
    } else if (x->on[MODCP_LED_RXD] && min_on_elapsed(x, MODCP_LED_RXD, now_us) &&
               now_us - x->rx_last_us >= x->quiet_us) {
        set(x, MODCP_LED_RXD, false, now_us);
    }
}

uint8_t modcp_leds_bits(const modcp_leds_t *x)
{
    uint8_t b = 0;
    for (unsigned i = 0; i < MODCP_LED_COUNT; i++) {
        if (x->on[i]) {
            b = (uint8_t)(b | (1u << i));
        }
    }
    return b;
}
