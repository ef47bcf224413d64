/* SPDX-License-Identifier: Apache-2.0 */
#include "frames.h"

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <cmocka.h>

#include "modcp/crc.h"

size_t hex_frame(const char *hex, uint8_t *out, size_t cap)
{
    size_t n = 0;
    while (*hex) {
        if (isspace((unsigned char)*hex)) {
            hex++;
            continue;
        }
        assert_true(isxdigit((unsigned char)hex[0]) && isxdigit((unsigned char)hex[1]));
        char tmp[3] = {hex[0], hex[1], 0};
        assert_true(n < cap);
        out[n++] = (uint8_t)strtoul(tmp, NULL, 16);
        hex += 2;
    }
    return n;
}

size_t add_crc(uint8_t *buf, size_t len)
{
    uint16_t crc = modcp_crc16(buf, len);
    buf[len] = (uint8_t)(crc & 0xFF);
    buf[len + 1] = (uint8_t)(crc >> 8);
    return len + 2;
}
