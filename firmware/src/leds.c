/* modcp — LEDs SF / TXD / RXD (see modcp/leds.h). */
#include "modcp/leds.h"

#include <stddef.h>
#include "leds_internal.h"

void modcp_leds_change(modcp_leds_t *x, modcp_led_t led, bool on, uint32_t now_us)
{
    x->on[led] = on;
    x->bits = (uint8_t)((x->bits & ~(1u << led)) | ((unsigned)on << led));
    if (led != MODCP_LED_SF) {
        x->on_us[led - 1u] = now_us; /* SF has no minimum on-time */
    }
    if (x->hal != NULL && x->hal->set_led != NULL) {
        x->hal->set_led(x->hal->ctx, led, on);
    }
}

/* x is zeroed (modcp_cp_init clears the CP object, the LEDs' only owner). */
void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal)
{
    x->hal = hal;
    /* set every LED explicitly at power-on, in order: SF on, TXD / RXD off */
    for (unsigned led = MODCP_LED_SF; led < MODCP_LED_COUNT; led++) {
        modcp_leds_change(x, (modcp_led_t)led, led == MODCP_LED_SF, 0);
    }
}

void modcp_leds_configure(modcp_leds_t *x, uint32_t quiet_us)
{
    x->quiet_us = quiet_us;
}
