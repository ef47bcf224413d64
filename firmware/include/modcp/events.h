/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — event words (class byte << 8 | number byte), as tabled in the manuals.
 * The events are described once, in modcp/event_rows.h: the enum below is generated
 * from its rows (MODCP_EV_<NAME>). */
#ifndef MODCP_EVENTS_H
#define MODCP_EVENTS_H

#include <stdint.h>

#include "modcp/event_rows.h"

typedef uint16_t modcp_event_t; /* 0 = no event */

#define MODCP_EVENT(cls, num) ((modcp_event_t)((((unsigned)(cls)) << 8) | (unsigned)(num)))
#define MODCP_EVENT_CLASS(ev) ((uint8_t)((ev) >> 8))
#define MODCP_EVENT_NUMBER(ev) ((uint8_t)((ev)&0xFFu))

#define MODCP_EV_ENUM_ROW_(NAME, cls, num, ...) MODCP_EV_##NAME = ((cls) * 256) + (num),
enum {
    MODCP_EV_NONE = 0x0000,
    MODCP_EVENT_ROWS(MODCP_EV_ENUM_ROW_)
};
#undef MODCP_EV_ENUM_ROW_

#endif
