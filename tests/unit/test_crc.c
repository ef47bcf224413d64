/* SPDX-License-Identifier: Apache-2.0 */
/* CRC-16 and LRC against the standard vectors and the manual's frames ([RTU-2003] §9). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "frames.h"
#include "modcp/crc.h"
#include "crc_internal.h"

static void check_frame_crc(const char *hex)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b);
    assert_true(n >= 4);
    uint16_t crc = modcp_crc16(b, n - 2);
    assert_int_equal(crc & 0xFF, b[n - 2]);
    assert_int_equal(crc >> 8, b[n - 1]);
    /* CRC over the whole frame including its CRC is 0 */
    assert_int_equal(modcp_crc16(b, n), 0);
}

static void test_standard_vectors(void **state)
{
    (void)state;
    const uint8_t v1[] = {0x01, 0x03, 0x00, 0x00, 0x00, 0x0A};
    assert_int_equal(modcp_crc16(v1, sizeof v1), 0xCDC5); /* sent C5 CD */
    const uint8_t v2[] = {0x11, 0x03, 0x00, 0x6B, 0x00, 0x03};
    assert_int_equal(modcp_crc16(v2, sizeof v2), 0x8776); /* sent 76 87 */
    const uint8_t check[] = "123456789";
    assert_int_equal(modcp_crc16(check, 9), 0x4B37); /* CRC-16/MODBUS check value */
    assert_int_equal(modcp_crc16(check, 0), 0xFFFF);
}

static void test_incremental_equals_whole(void **state)
{
    (void)state;
    const uint8_t check[] = "123456789";
    uint16_t c = MODCP_CRC_INIT;
    for (size_t i = 0; i < 9; i++) {
        c = modcp_crc16_update(c, &check[i], 1);
    }
    assert_int_equal(c, 0x4B37);
}

/* Every length and start offset (the four-byte steps of the speed build and the byte
 * steps of its tail, on aligned and unaligned data) gives the byte-by-byte CRC. */
static void test_blocks_equal_bytes(void **state)
{
    (void)state;
    uint8_t d[300];
    uint32_t x = 12345u;
    for (size_t i = 0; i < sizeof d; i++) {
        x = x * 1103515245u + 12345u;
        d[i] = (uint8_t)(x >> 16);
    }
    for (size_t off = 0; off < 4; off++) {
        uint16_t c = MODCP_CRC_INIT;
        for (size_t n = 0; off + n <= sizeof d; n++) {
            assert_int_equal(modcp_crc16_update(MODCP_CRC_INIT, &d[off], n), c);
            if (off + n < sizeof d) {
                c = modcp_crc16_byte(c, d[off + n]);
            }
        }
    }
}

static void test_manual_frames(void **state)
{
    (void)state;
    /* [RTU-2003] §9 computed vectors for every worked example of §6 */
    check_frame_crc("05 01 00 40 00 20 3D 82");
    check_frame_crc("05 01 04 01 17 02 18 0E 83");
    check_frame_crc("05 02 10 30 00 18 7D 4B");
    check_frame_crc("05 02 03 12 34 56 4F 31");
    check_frame_crc("05 03 00 50 00 02 C5 9E");
    check_frame_crc("05 03 04 87 65 43 21 76 70");
    check_frame_crc("05 04 02 C0 00 03 B0 0B");
    check_frame_crc("05 04 06 A1 A2 A3 A4 A5 A6 2A 76");
    check_frame_crc("05 05 08 09 FF 00 5F DC");
    check_frame_crc("05 06 01 80 2B 1A 17 61");
    check_frame_crc("05 08 00 00 A5 C3 DA 8E");
    check_frame_crc("05 0F 04 80 00 0C 02 CD 09 19 E6");
    check_frame_crc("05 0F 04 80 00 0C 54 92");
    check_frame_crc("05 10 00 32 00 03 06 CD 09 DE 1A EF 2B 92 ED");
    check_frame_crc("05 10 00 32 00 03 20 43");
    check_frame_crc("05 85 02 82 90");
}

static void test_append(void **state)
{
    (void)state;
    uint8_t f[10] = {0x11, 0x03, 0x00, 0x6B, 0x00, 0x03, 0xAA, 0xAA, 0xAA, 0xAA};
    assert_int_equal(modcp_crc16_append(f, 6), 8);
    assert_int_equal(f[6], 0x76); /* low byte first */
    assert_int_equal(f[7], 0x87);
    assert_int_equal(f[8], 0xAA); /* nothing after it touched */
    assert_int_equal(modcp_crc16(f, 8), 0);
}

static void test_lrc(void **state)
{
    (void)state;
    /* Modbus serial line spec example: 11 03 00 6B 00 03 -> LRC 7E */
    const uint8_t f[] = {0x11, 0x03, 0x00, 0x6B, 0x00, 0x03};
    assert_int_equal(modcp_lrc(f, sizeof f), 0x7E);
    const uint8_t z[] = {0x00};
    assert_int_equal(modcp_lrc(z, 1), 0x00);
    const uint8_t one[] = {0x01};
    assert_int_equal(modcp_lrc(one, 1), 0xFF);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_standard_vectors),
        cmocka_unit_test(test_incremental_equals_whole),
        cmocka_unit_test(test_blocks_equal_bytes),
        cmocka_unit_test(test_manual_frames),
        cmocka_unit_test(test_append),
        cmocka_unit_test(test_lrc),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
