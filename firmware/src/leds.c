/* modcp — LEDs SF / TXD / RXD (see modcp/leds.h). */
#include "modcp/leds.h"

#include <stddef.h>
#include <string.h>
#include "leds_internal.h"

static void change(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us)
{
    x->on[led] = on;
    x->bits = (uint8_t)((x->bits & ~(1u << led)) | ((unsigned)on << led));
    x->on_us[led] = now_us;
    if (x->hal != NULL && x->hal->set_led != NULL) {
        x->hal->set_led(x->hal->ctx, led, on);
    }
}

/* Set a level; the HAL hears of changes only. */
static inline void set(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us)
{
    if (x->on[led] != on) {
        change(x, led, on, now_us);
    }
}

void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal)
{
    memset(x, 0, sizeof *x);
    x->hal = hal;
    /* set every LED explicitly at power-on, in order: SF on, TXD / RXD off */
    for (unsigned led = MODCP_LED_SF; led < MODCP_LED_COUNT; led++) {
        change(x, (modcp_led_t)led, led == MODCP_LED_SF, 0);
    }
}

void modcp_leds_configure(modcp_leds_t *x, uint32_t quiet_us)
{
    x->quiet_us = quiet_us;
}

static bool min_on_elapsed(const modcp_leds_t *x, modcp_led_t led, uint32_t now_us)
{
    return now_us - x->on_us[led] >= MODCP_LED_MIN_ON_US;
}

void modcp_leds_poll(modcp_leds_t *x, bool sf, const modcp_link_t *l, uint32_t now_us)
{
    set(x, MODCP_LED_SF, sf, now_us);

    if (l->tx_starts != x->tx_seen || l->tx_on) { /* started since the last poll, or on */
        x->tx_seen = l->tx_starts;
        set(x, MODCP_LED_TXD, true, now_us);
    } else if (x->on[MODCP_LED_TXD] && min_on_elapsed(x, MODCP_LED_TXD, now_us)) {
        set(x, MODCP_LED_TXD, false, now_us);
    }

    if (l->last_us != x->rx_seen_us) { /* a character since the last poll */
        x->rx_seen_us = l->last_us;
        set(x, MODCP_LED_RXD, true, now_us);
    } else if (x->on[MODCP_LED_RXD] && min_on_elapsed(x, MODCP_LED_RXD, now_us) &&
               now_us - l->last_us >= x->quiet_us) {
        set(x, MODCP_LED_RXD, false, now_us);
    }
}
