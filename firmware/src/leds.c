/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — LEDs SF / TXD / RXD (see modcp/leds.h). */
#include "modcp/leds.h"

#include <stddef.h>
#include "leds_internal.h"

_Static_assert(((int)MODCP_LED_SF == 0) && ((int)MODCP_LED_TXD == 1) && ((int)MODCP_LED_RXD == 2),
               "leds: SF is bit 0, TXD / RXD index on_us by led - 1");

void modcp_leds_switch(modcp_leds_t *x, const modcp_hal_t *hal, unsigned want, uint32_t now_us)
{
    unsigned changed = want ^ x->bits;
    unsigned went_on = want & changed;
    x->bits = (uint8_t)want;
    if ((went_on & MODCP_LED_BIT(MODCP_LED_TXD)) != 0u) { /* SF has no minimum on-time */
        x->on_us[(unsigned)MODCP_LED_TXD - 1u] = now_us;
    }
    if ((went_on & MODCP_LED_BIT(MODCP_LED_RXD)) != 0u) {
        x->on_us[(unsigned)MODCP_LED_RXD - 1u] = now_us;
    }
    if (hal == NULL || hal->set_led == NULL) {
        return;
    }
    for (unsigned led = MODCP_LED_SF; changed != 0u; led++, changed >>= 1) {
        if ((changed & 1u) != 0u) {
            hal->set_led(hal->ctx, (modcp_led_t)led, (want & MODCP_LED_BIT(led)) != 0u);
        }
    }
}

/* x is zeroed (modcp_cp_init clears the CP object, the LEDs' only owner). */
void modcp_leds_init(modcp_leds_t *x, const modcp_hal_t *hal)
{
    /* set every LED explicitly at power-on, in order: SF on, TXD / RXD off (from levels
     * taken as the opposite, each of the three is a change) */
    x->bits = (uint8_t)(MODCP_LED_BIT(MODCP_LED_TXD) | MODCP_LED_BIT(MODCP_LED_RXD));
    modcp_leds_switch(x, hal, MODCP_LED_BIT(MODCP_LED_SF), 0u);
}
