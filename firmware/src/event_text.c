/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — event texts, remedies and class names in English, generated from the event rows
 * (modcp/event_rows.h). Kept in its own file so images that do not show texts do not
 * link it. */
#include "modcp/diag.h"

typedef struct {
    modcp_event_t ev;
    const char *text;
    const char *remedy;
} event_text_t;

#define TEXT_ROW(NAME, cls, num, exc, answer, text, remedy, ...) {MODCP_EV_##NAME, text, remedy},
static const event_text_t texts[] = {MODCP_EVENT_ROWS(TEXT_ROW)};
#undef TEXT_ROW

static const event_text_t *find(modcp_event_t ev)
{
    for (unsigned i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        if (texts[i].ev == ev) {
            return &texts[i];
        }
    }
    return 0;
}

const char *modcp_event_text(modcp_event_t ev)
{
    const event_text_t *t = find(ev);
    return t ? t->text : "unknown event";
}

const char *modcp_event_remedy(modcp_event_t ev)
{
    const event_text_t *t = find(ev);
    return t ? t->remedy : "";
}

const char *modcp_event_class_text(uint8_t cls)
{
    switch (cls) {
#define CLASS_ROW(c, name, heading)                                                               \
    case (c): return name;
        MODCP_EVENT_CLASS_ROWS(CLASS_ROW)
#undef CLASS_ROW
    default: return "other event";
    }
}
