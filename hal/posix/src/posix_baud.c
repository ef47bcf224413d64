/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — POSIX HAL internal: arbitrary baud rates via termios2 (Linux). Kept apart
 * because <asm/termbits.h> and <termios.h> cannot be included together. */
#include "posix_baud.h"

#include <errno.h>

#ifdef __linux__
#include <asm/ioctls.h>
#include <asm/termbits.h>
#include <sys/ioctl.h>

int modcp_posix_custom_baud(int fd, uint32_t baud)
{
    struct termios2 t2;
    if (ioctl(fd, TCGETS2, &t2) != 0) {
        return -errno;
    }
    t2.c_cflag &= (tcflag_t)~CBAUD;
    t2.c_cflag |= BOTHER;
    t2.c_ispeed = baud;
    t2.c_ospeed = baud;
    if (ioctl(fd, TCSETS2, &t2) != 0) {
        return -errno;
    }
    return 0;
}
#else
int modcp_posix_custom_baud(int fd, uint32_t baud)
{
    (void)fd;
    (void)baud;
    return -ENOTSUP;
}
#endif
