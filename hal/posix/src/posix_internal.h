/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL internal: what the port's files share. */
#ifndef MODCP_POSIX_INTERNAL_H
#define MODCP_POSIX_INTERNAL_H

#include <stddef.h>

#include "modcp/hal_posix.h"

/* Read the characters waiting on the port's descriptor into rx[] (at most cap; a
 * device's PARMRK marks decoded into MODCP_LINE_* errors, an overrun since the last
 * read marked on the last character). Returns the number of characters (0 when none
 * is waiting) or -errno. */
int modcp_posix_serial_read(modcp_posix_port_t *p, modcp_posix_rx_t *rx, size_t cap);

#endif
