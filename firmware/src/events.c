/* modcp — event words -> Modbus exception codes (events.h, 004 ch. 7, SPEC §5.2). */
#include "modcp/events.h"

uint8_t modcp_event_exception(modcp_event_t ev)
{
    if (ev == MODCP_EV_ILLEGAL_FC) {
        return 1u; /* (08)31H illegal function */
    }
    if (ev >= MODCP_EV_QUANTITY && ev <= MODCP_EV_DIAG_SUBFC) {
        return 3u; /* (08)32H..35H illegal data value */
    }
    if (ev == MODCP_EV_DB_ACCESS || (ev >= MODCP_EV_TC_ALIGN && ev <= MODCP_EV_AREA_READONLY)) {
        return 2u; /* (0E)39H DB boundary crossed, (0E)50H..55H illegal data address */
    }
    if (ev == MODCP_EV_FB_NOT_RUNNING) {
        return 4u; /* (0E)56H slave device failure */
    }
    return 0u;
}
