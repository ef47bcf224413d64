/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL internal: baud rates without a Bxxx constant (e.g. 76800). */
#ifndef MODCP_POSIX_BAUD_H
#define MODCP_POSIX_BAUD_H

#include <stdint.h>

/* Set an arbitrary rate on an open tty; 0 or -errno (-ENOTSUP where impossible). */
int modcp_posix_custom_baud(int fd, uint32_t baud);

#endif
