/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — character and frame timing derived from the parameters ([RTU-2003] §5.3, docs/diagnostics.md).
 * Integer arithmetic only; results are rounded up to whole microseconds. */
#include <stdint.h>

#include "modcp/params.h"
#include "params_internal.h"

#define US_PER_S 1000000u
#define T35_BITS_X10 385u /* 3.5 characters of 11 bits, x10 */
#define T15_BITS_X10 165u /* 1.5 characters of 11 bits, x10 */
#define MODBUS_FIXED_ABOVE 19200u
#define MODBUS_T35_FIXED_US 1750u
#define MODBUS_T15_FIXED_US 750u
#define DEFAULT_BAUD 9600u

/* baud 0 is rejected by validation; treat it as the default instead of dividing by 0 */
static uint32_t eff_baud(const modcp_params_t *p)
{
    return p->baud != 0u ? p->baud : DEFAULT_BAUD;
}

/* ceil(num / den) for num >= 1 (every caller: bits x 1e6 or more): no remainder */
static uint32_t div_ceil(uint32_t num, uint32_t den)
{
    return (num - 1u) / den + 1u;
}

/* ceil(bits_x10 / 10 * 1e6 / baud) = ceil(bits_x10 * 100000 / baud); fits in 32 bits
 * for bits_x10 <= 385 (38,500,000). */
static uint32_t bit_time_us(uint32_t bits_x10, uint32_t baud)
{
    return div_ceil(bits_x10 * (US_PER_S / 10u), baud);
}

/* The manual's TIME_OUT table ([RTU-2003] §5.3): 300 ... 76800 baud, 300 x 2^k, is 38,400,000 /
 * baud us (128 ms ... 0.5 ms); other rates (57600 -> 669, 115200 -> 335) by the 3.5 x
 * 11-bit rule. Computed instead of a switch of nine rates. */
static uint32_t table_timeout_us(uint32_t baud)
{
    uint32_t k = baud / 300u;
    if (k * 300u == baud && k <= 256u && (k & (k - 1u)) == 0u) {
        return 38400000u / baud;
    }
    return bit_time_us(T35_BITS_X10, baud);
}

uint32_t modcp_params_t35_us(const modcp_params_t *p)
{
    uint32_t baud = eff_baud(p);
    if (p->eof_timing == (uint8_t)MODCP_EOF_MODBUS) {
        return baud > MODBUS_FIXED_ABOVE ? MODBUS_T35_FIXED_US : bit_time_us(T35_BITS_X10, baud);
    }
    uint32_t f = (p->f_mul >= 1u && p->f_mul <= 10u) ? p->f_mul : 1u; /* (0E)21H: run with 1 */
    return table_timeout_us(baud) * f;
}

uint32_t modcp_params_t15_us(const modcp_params_t *p)
{
    uint32_t baud = eff_baud(p);
    return baud > MODBUS_FIXED_ABOVE ? MODBUS_T15_FIXED_US : bit_time_us(T15_BITS_X10, baud);
}

uint32_t modcp_params_char_us(const modcp_params_t *p)
{
    uint32_t baud = eff_baud(p);
    uint32_t bits = 1u + (uint32_t)p->data_bits + (p->parity != (uint8_t)MODCP_PARITY_NONE ? 1u : 0u) +
                    (uint32_t)p->stop_bits;
    return div_ceil(bits * US_PER_S, baud);
}
