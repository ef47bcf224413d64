/* SPDX-License-Identifier: Apache-2.0 */
/* Link layer, RTU framing and timing: end-of-frame thresholds, address filter, CRC,
 * over-long frames, t1.5, line errors in normal and interference-suppression mode,
 * (08)37H, transmit with CRC, RS485 driver enable and turnaround.
 * Frames are the manual's examples with the CRCs of [RTU-2003] §9. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fake_hal_log.h"
#include "frames.h"
#include "modcp/crc.h"
#include "modcp/diag.h"
#include "modcp/link.h"
#include "modcp/params.h"
#include "diag_internal.h"
#include "link_internal.h"
#include "params_internal.h"

/* [RTU-2003] §6.3 FC03 example request and response ([RTU-2003] §9 CRCs) */
#define FC03_REQ "05 03 00 50 00 02 C5 9E"
#define FC03_RSP "05 03 04 87 65 43 21 76 70"

typedef struct {
    fake_hal_log_t f;
    modcp_hal_t hal;
    modcp_diag_t d;
    modcp_link_t l;
    modcp_params_t p;
    modcp_frame_t fr;
    uint8_t buf[MODCP_ADU_MAX + 32]; /* link gets MODCP_ADU_MAX; the rest is a canary */
} ctx_t;

#define CANARY 0xA5

static void base_params(modcp_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->baud = 9600;
    p->data_bits = 8;
    p->parity = MODCP_PARITY_EVEN;
    p->stop_bits = 1;
    p->slave_addr = 5;
    p->framing = MODCP_FRAMING_RTU;
    p->opmode = MODCP_OPMODE_NORMAL;
    p->f_mul = 1;
    p->eof_timing = MODCP_EOF_MANUAL;
    p->t15_check = 0;
    p->ascii_timeout_ms = 1000;
    p->iface = MODCP_IFACE_RS232;
    p->turnaround_ms = 0;
}

static int setup(void **state)
{
    ctx_t *c = calloc(1, sizeof *c);
    assert_non_null(c);
    fake_hal_log_init(&c->f, &c->hal, true);
    modcp_diag_init(&c->d);
    memset(c->buf, CANARY, sizeof c->buf);
    modcp_link_init(&c->l, &c->hal, &c->d, c->buf, MODCP_ADU_MAX);
    base_params(&c->p);
    *state = c;
    return 0;
}

static int teardown(void **state)
{
    free(*state);
    return 0;
}

/* Apply c->p and forget the HAL calls of configure. */
static void configure(ctx_t *c)
{
    modcp_link_configure(&c->l, &c->p);
    fake_hal_log_clear(&c->f);
}

static void byte_at(ctx_t *c, uint8_t b, uint32_t t)
{
    c->f.now = t;
    modcp_link_on_byte(&c->l, b, t);
}

static void error_at(ctx_t *c, uint8_t flags, uint32_t t)
{
    c->f.now = t;
    modcp_link_on_error(&c->l, flags, t);
}

static bool timer_at(ctx_t *c, uint32_t t)
{
    c->f.now = t;
    return modcp_link_on_timer(&c->l, t, &c->fr);
}

/* Feed n bytes, one character time apart, the first at t0; returns the time of the
 * last one (character ends). */
static uint32_t feed(ctx_t *c, const uint8_t *b, size_t n, uint32_t t0)
{
    uint32_t t = t0;
    for (size_t i = 0; i < n; i++) {
        t = t0 + (uint32_t)i * c->l.char_us;
        byte_at(c, b[i], t);
    }
    return t;
}

static uint32_t feed_hex(ctx_t *c, const char *hex, uint32_t t0)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b);
    return feed(c, b, n, t0);
}

/* Feed a frame and let t3.5 expire; returns on_timer's result, *end = expiry time. */
static bool frame_hex(ctx_t *c, const char *hex, uint32_t t0, uint32_t *end)
{
    uint32_t last = feed_hex(c, hex, t0);
    uint32_t t = last + c->l.t35_us;
    if (end != NULL) {
        *end = t;
    }
    return timer_at(c, t);
}

static void assert_pdu(const ctx_t *c, uint8_t addr, const char *hex)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b);
    assert_int_equal(c->fr.addr, addr);
    assert_int_equal(c->fr.pdu_len, n);
    assert_ptr_equal(c->fr.pdu, &c->buf[1]);
    assert_int_equal(c->fr.pdu_cap, MODCP_ADU_MAX - 3);
    assert_memory_equal(c->fr.pdu, b, n);
}

static void assert_tx(const ctx_t *c, const char *hex)
{
    uint8_t b[300];
    size_t n = hex_frame(hex, b, sizeof b);
    assert_int_equal(c->f.tx_len, n);
    assert_int_equal(link_len(&c->l), n); /* the reply's length on the line */
    assert_memory_equal(c->f.tx, b, n);
}

static void assert_canary(const ctx_t *c)
{
    for (size_t i = MODCP_ADU_MAX; i < sizeof c->buf; i++) {
        assert_int_equal(c->buf[i], CANARY);
    }
}

/* ------------------------------------------------------------------------------ */
/* timing.c                                                                         */

static void test_timing_manual_table(void **state)
{
    (void)state;
    /* [RTU-2003] §5.3 TIME_OUT table x f_MUL ([RTU-2003] §2.2) */
    static const struct {
        uint32_t baud, us;
    } tab[] = {{300, 128000}, {600, 64000},  {1200, 32000}, {2400, 16000},
               {4800, 8000},  {9600, 4000},  {19200, 2000}, {38400, 1000},
               {76800, 500},  {57600, 669},  {115200, 335}};
    modcp_params_t p;
    base_params(&p);
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++) {
        p.baud = tab[i].baud;
        for (uint8_t f = 1; f <= 10; f++) {
            p.f_mul = f;
            assert_int_equal(modcp_params_t35_us(&p), tab[i].us * f);
        }
        p.f_mul = 0; /* (0E)21H: runs with 1 */
        assert_int_equal(modcp_params_t35_us(&p), tab[i].us);
        p.f_mul = 11;
        assert_int_equal(modcp_params_t35_us(&p), tab[i].us);
    }
    /* any other rate: ceil(3.5 x 11 bits) */
    p.f_mul = 1;
    p.baud = 14400; /* 38.5e6 / 14400 = 2673.6 */
    assert_int_equal(modcp_params_t35_us(&p), 2674);
    p.f_mul = 3;
    assert_int_equal(modcp_params_t35_us(&p), 3 * 2674);
}

static void test_timing_modbus_rule(void **state)
{
    (void)state;
    /* Modbus over serial line: 3.5 characters, fixed 1750 us above 19200; f_MUL ignored */
    modcp_params_t p;
    base_params(&p);
    p.eof_timing = MODCP_EOF_MODBUS;
    p.f_mul = 10;
    p.baud = 9600;
    assert_int_equal(modcp_params_t35_us(&p), 4011); /* 4010.4 rounded up */
    p.baud = 19200;
    assert_int_equal(modcp_params_t35_us(&p), 2006); /* 2005.2 */
    p.baud = 300;
    assert_int_equal(modcp_params_t35_us(&p), 128334); /* 128333.3 */
    p.baud = 38400;
    assert_int_equal(modcp_params_t35_us(&p), 1750);
    p.baud = 57600;
    assert_int_equal(modcp_params_t35_us(&p), 1750);
    p.baud = 115200;
    assert_int_equal(modcp_params_t35_us(&p), 1750);
}

static void test_timing_t15_and_char(void **state)
{
    (void)state;
    modcp_params_t p;
    base_params(&p);
    p.baud = 9600;
    assert_int_equal(modcp_params_t15_us(&p), 1719); /* 1718.75 */
    p.baud = 19200;
    assert_int_equal(modcp_params_t15_us(&p), 860); /* 859.4 */
    p.baud = 300;
    assert_int_equal(modcp_params_t15_us(&p), 55000);
    p.baud = 38400;
    assert_int_equal(modcp_params_t15_us(&p), 750);
    p.baud = 115200;
    assert_int_equal(modcp_params_t15_us(&p), 750);

    p.baud = 9600; /* 8E1: 11 bits */
    assert_int_equal(modcp_params_char_us(&p), 1146); /* 1145.8 */
    p.parity = MODCP_PARITY_NONE; /* 8N1: 10 bits */
    assert_int_equal(modcp_params_char_us(&p), 1042);
    p.stop_bits = 2; /* 8N2: 11 bits */
    assert_int_equal(modcp_params_char_us(&p), 1146);
    p.parity = MODCP_PARITY_ODD; /* 8O2: 12 bits */
    assert_int_equal(modcp_params_char_us(&p), 1250);
    p.data_bits = 7; /* 7O1 (ASCII): 10 bits */
    p.stop_bits = 1;
    assert_int_equal(modcp_params_char_us(&p), 1042);
    p.baud = 115200;
    p.data_bits = 8;
    p.parity = MODCP_PARITY_EVEN;
    assert_int_equal(modcp_params_char_us(&p), 96); /* 95.5 */
}

/* ------------------------------------------------------------------------------ */
/* end-of-frame thresholds                                                          */

/* The FC03 request ([RTU-2003] §6.3) is not ended 1 us before t3.5 after its last byte (the
 * early expiry re-arms the timer for the remaining 1 us) and is delivered exactly at
 * t3.5. */
static void check_eof(ctx_t *c, uint32_t baud, uint8_t fmul, uint8_t eof, uint32_t t35)
{
    modcp_diag_init(&c->d);
    c->p.baud = baud;
    c->p.f_mul = fmul;
    c->p.eof_timing = eof;
    configure(c);
    assert_int_equal(c->l.t35_us, t35);
    uint32_t last = feed_hex(c, FC03_REQ, 1000);
    /* armed once, by the first byte (no HAL call per byte); the silence is measured from
     * the last byte's time stamp when the timer expires */
    assert_int_equal(fake_hal_log_count(&c->f, FHL_ARM), 1);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, t35);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->at, 1000);
    if (1000u + t35 > last) {
        /* that expiry comes while bytes kept coming: re-armed for t3.5 after the last */
        assert_false(timer_at(c, 1000u + t35));
        assert_int_equal(c->l.state, MODCP_LINK_RX);
        assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, last - 1000u);
    }

    assert_false(timer_at(c, last + t35 - 1));
    assert_int_equal(c->l.state, MODCP_LINK_RX);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 1);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 0);

    assert_true(timer_at(c, last + t35));
    assert_int_equal(c->l.state, MODCP_LINK_BUSY);
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(c->d.buffer_len, 0);
    modcp_link_done(&c->l);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
}

static void test_eof_thresholds_manual(void **state)
{
    ctx_t *c = *state;
    /* [RTU-2003] §5.3 table x f_MUL 1 and 10 */
    check_eof(c, 300, 1, MODCP_EOF_MANUAL, 128000);
    check_eof(c, 300, 10, MODCP_EOF_MANUAL, 1280000); /* 1279999 vs 1280000 */
    check_eof(c, 9600, 1, MODCP_EOF_MANUAL, 4000);    /* 3999 vs 4000 */
    check_eof(c, 9600, 10, MODCP_EOF_MANUAL, 40000);
    check_eof(c, 19200, 1, MODCP_EOF_MANUAL, 2000);
    check_eof(c, 19200, 10, MODCP_EOF_MANUAL, 20000);
    check_eof(c, 76800, 1, MODCP_EOF_MANUAL, 500);
    check_eof(c, 76800, 10, MODCP_EOF_MANUAL, 5000);
    /* [RTU-2009] §2.1 rates by the 3.5 x 11-bit rule */
    check_eof(c, 57600, 1, MODCP_EOF_MANUAL, 669);
    check_eof(c, 115200, 1, MODCP_EOF_MANUAL, 335);
    check_eof(c, 115200, 10, MODCP_EOF_MANUAL, 3350);
}

static void test_eof_thresholds_modbus(void **state)
{
    ctx_t *c = *state;
    c->p.eof_timing = MODCP_EOF_MODBUS;
    check_eof(c, 9600, 1, MODCP_EOF_MODBUS, 4011);
    check_eof(c, 19200, 10, MODCP_EOF_MODBUS, 2006); /* f_MUL not applied */
    check_eof(c, 38400, 1, MODCP_EOF_MODBUS, 1750);
    check_eof(c, 76800, 10, MODCP_EOF_MODBUS, 1750);
    check_eof(c, 115200, 1, MODCP_EOF_MODBUS, 1750);
}

static void test_stale_expiry_and_time_wrap(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* the frame straddles the 2^32 wrap of the microsecond clock */
    uint32_t t0 = 0xFFFFFFFFu - 3000u;
    uint32_t last = feed_hex(c, FC03_REQ, t0);
    assert_true(last < t0);
    /* an expiry that raced the last byte: re-armed for the rest */
    assert_false(timer_at(c, last + 100));
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 3900);
    assert_true(timer_at(c, last + 4000));
    assert_pdu(c, 5, "03 00 50 00 02");
}

/* ------------------------------------------------------------------------------ */
/* receive                                                                          */

static void test_fc03_request_delivered(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* [RTU-2003] §6.3 FC03 example request */
    assert_true(frame_hex(c, FC03_REQ, 500, NULL));
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(c->l.state, MODCP_LINK_BUSY);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 1);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 0);
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->f.tx_calls, 0);
}

static void test_crc_error(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* [RTU-2003] §6.3 FC03 request with the CRC high byte corrupted: (08)36H, silence */
    assert_false(frame_hex(c, "05 03 00 50 00 02 C5 9F", 500, NULL));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_CRC);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 0);
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 0);
    assert_int_equal(c->f.tx_calls, 0);

    /* a data byte corrupted, then a too-short frame: two more (08)36H, newest first */
    uint32_t end;
    assert_false(frame_hex(c, "05 03 00 51 00 02 C5 9E", 100000, &end));
    assert_false(frame_hex(c, "05 03", end + 10000, &end));
    assert_int_equal(c->d.buffer_len, 3);
    assert_int_equal(c->d.buffer[0], MODCP_EV_CRC);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 3);

    /* the line recovers: the good request is delivered */
    assert_true(frame_hex(c, FC03_REQ, end + 10000, NULL));
    assert_pdu(c, 5, "03 00 50 00 02");
}

static void test_other_address_ignored(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* [RTU-2003] §2.2: frames for address 7 are not checked and not answered; no event */
    uint8_t b[16];
    size_t n = add_crc(b, hex_frame("07 03 00 50 00 02", b, sizeof b));
    uint32_t last = feed(c, b, n, 500);
    assert_int_equal(c->l.state, MODCP_LINK_SKIP);
    assert_int_equal(c->buf[0], CANARY); /* not stored */
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 1); /* bus traffic, CRC good */
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 0);

    /* a corrupted frame for address 7: still no event, counted as a bus CRC error */
    b[n - 1] ^= 0x01;
    last = feed(c, b, n, last + 10000);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 1);
    assert_int_equal(c->f.tx_calls, 0);
}

static void test_own_address_inside_other_frame(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* A frame for 7 whose data contains our address and a complete FC03 request
     * ([RTU-2003] §6.3) is followed to its end and never taken for a request. */
    uint8_t b[32];
    size_t n = hex_frame("07 10 00 00 00 04 08 " FC03_REQ, b, sizeof b);
    n = add_crc(b, n);
    uint32_t last = feed(c, b, n, 500);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 1);
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 0);
}

static void test_late_timer_other_address(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* the expiry after a frame for 7 is late: the next byte, t3.5 after its last,
     * starts our frame anyway */
    uint8_t b[16];
    size_t n = add_crc(b, hex_frame("07 03 00 50 00 02", b, sizeof b));
    uint32_t last = feed(c, b, n, 500);
    assert_true(frame_hex(c, FC03_REQ, last + 4000, NULL));
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 2);
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 1);
}

static void test_broadcast_delivered(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* [RTU-2003] §5.2: address 0 = broadcast; FC06 example data ([RTU-2003] §6.6) */
    uint8_t b[16];
    size_t n = add_crc(b, hex_frame("00 06 01 80 2B 1A", b, sizeof b));
    uint32_t last = feed(c, b, n, 500);
    assert_true(timer_at(c, last + 4000));
    assert_pdu(c, 0, "06 01 80 2B 1A");
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 1);
    modcp_link_done(&c->l); /* never answered */
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->f.tx_calls, 0);
}

static void test_frame_too_long(void **state)
{
    ctx_t *c = *state;
    configure(c);
    /* [VIPA-341] §8.2: a 300-byte frame for us does not fit the 264-byte buffer: (08)16H */
    uint8_t b[300];
    for (size_t i = 0; i < sizeof b; i++) {
        b[i] = (uint8_t)i;
    }
    b[0] = 5;
    b[1] = 0x10;
    add_crc(b, sizeof b - 2);
    uint32_t last = feed(c, b, sizeof b, 500);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.frames_too_long, 1);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_FRAME_TOO_LONG);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 0);
    assert_int_equal(c->d.counters[MODCP_CNT_SLAVE_MSG], 0);
    assert_canary(c);

    /* exactly 264 bytes fit (FC15 with 2040 bits, docs/mapping.md) */
    uint8_t m[MODCP_ADU_MAX];
    memset(m, 0x55, sizeof m);
    m[0] = 5;
    m[1] = 0x0F;
    add_crc(m, sizeof m - 2);
    last = feed(c, m, sizeof m, last + 10000);
    assert_true(timer_at(c, last + 4000));
    assert_int_equal(c->fr.pdu_len, MODCP_ADU_MAX - 3);
    assert_canary(c);
}

static void test_sequence_error_while_busy(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    fake_hal_log_clear(&c->f);
    /* [RTU-2003] §7.5 (08)37H: the master repeats the request before our reply was sent;
     * reported once per frame, the request in the buffer is untouched */
    uint32_t last = feed_hex(c, "05 03 00 60 00 01 00 00", end + 1000);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_SEQUENCE);
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(fake_hal_log_count(&c->f, FHL_ARM), 0);
    assert_int_equal(c->l.state, MODCP_LINK_BUSY);

    /* a frame for another address while busy: no event */
    last = feed_hex(c, "07 03 00 50 00 02 C4 4F", last + 5000);
    assert_int_equal(c->d.buffer_len, 1);
    /* a second frame for us after a t3.5 gap: reported again */
    last = feed_hex(c, FC03_REQ, last + 4000);
    assert_int_equal(c->d.buffer_len, 2);
    assert_int_equal(c->d.buffer[0], MODCP_EV_SEQUENCE);
    assert_int_equal(c->d.buffer[1], MODCP_EV_SEQUENCE);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 1); /* frames seen while busy are lost */

    /* done without reply, later than t3.5 after that frame: back to receiving */
    modcp_link_done(&c->l);
    assert_int_equal(c->l.state, MODCP_LINK_SKIP); /* no time given: one t3.5 to decide */
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 4000);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_true(frame_hex(c, FC03_REQ, last + 20000, NULL));
    assert_int_equal(c->d.buffer_len, 2);
}

static void test_done_then_next_frame_without_timer(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    uint32_t last = feed_hex(c, FC03_REQ, end + 100); /* (08)37H */
    modcp_link_done(&c->l);
    /* the next request starts t3.5 after the one seen while busy, before the timer
     * armed by done expires: it is a new frame and is delivered */
    last = feed_hex(c, FC03_REQ, last + 4000);
    assert_true(timer_at(c, last + 4000));
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_SEQUENCE);
}

static void test_tail_after_tx_done_skipped(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    /* reply, [RTU-2003] §6.3 FC03 response; RS232 full duplex: the master starts a new
     * request while we are still sending */
    uint8_t rsp[] = {0x03, 0x04, 0x87, 0x65, 0x43, 0x21};
    memcpy(c->fr.pdu, rsp, sizeof rsp);
    modcp_link_reply(&c->l, sizeof rsp, false, end + 100);
    assert_int_equal(c->l.state, MODCP_LINK_TX);
    uint8_t req[8];
    hex_frame(FC03_REQ, req, sizeof req);
    uint32_t t0 = end + 2000;
    feed(c, req, 3, t0);
    assert_int_equal(c->d.buffer[0], MODCP_EV_SEQUENCE);
    /* transmission complete in the middle of that frame: its tail is skipped */
    uint32_t tdone = t0 + 2 * 1146 + 500;
    c->f.now = tdone;
    modcp_link_on_tx_done(&c->l, tdone);
    assert_int_equal(c->l.state, MODCP_LINK_SKIP);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 4000 - 500);
    uint32_t last = 0;
    for (size_t i = 3; i < sizeof req; i++) {
        last = t0 + (uint32_t)i * 1146;
        byte_at(c, req[i], last);
    }
    assert_false(timer_at(c, last + 100)); /* raced the last byte: re-armed */
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 3900);
    assert_int_equal(c->l.state, MODCP_LINK_SKIP);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer_len, 1); /* no (08)36H for the tail */
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 0);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_MSG], 1);

    /* tx_done long after that frame: straight to idle */
    assert_true(frame_hex(c, FC03_REQ, last + 10000, &end));
    modcp_link_reply(&c->l, sizeof rsp, false, end);
    feed(c, req, 8, end + 100);
    c->f.now = end + 100 + 7 * 1146 + 4000;
    modcp_link_on_tx_done(&c->l, c->f.now);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
}

/* The receive hot path (link_rx_store, what modcp_cp_on_rx runs first): inside our RTU
 * frame it stores the character with its time; with the t1.5 check or the RS232
 * automatic signals it stores nothing, and the character is the framing's (stored
 * by it all the same). */
static void hot_store_case(ctx_t *c, bool stored)
{
    configure(c);
    byte_at(c, 0x05, 1000); /* our address: the frame starts */
    assert_int_equal(c->l.state, MODCP_LINK_RX);
    assert_int_equal(link_rx_store(&c->l, 0x03, 2146), stored);
    assert_int_equal(link_len(&c->l), stored ? 2 : 1);
    assert_int_equal(c->l.last_us, stored ? 2146u : 1000u);
    if (stored) {
        assert_int_equal(c->buf[1], 0x03);
    } else {
        byte_at(c, 0x03, 2146); /* the framing's way */
        assert_int_equal(link_len(&c->l), 2);
        assert_int_equal(c->buf[1], 0x03);
        assert_int_equal(c->l.last_us, 2146u);
    }
}

static void test_hot_path_store(void **state)
{
    ctx_t *c = *state;
    hot_store_case(c, true);
    c->p.t15_check = 1;
    hot_store_case(c, false);
#if MODCP_WITH_RS232_SIGNALS
    c->p.t15_check = 0;
    c->p.rs232_auto = 1;
    hot_store_case(c, false);
#endif
}

static void test_t15_check(void **state)
{
    ctx_t *c = *state;
    c->p.t15_check = 1;
    configure(c);
    assert_int_equal(c->l.t15_us, 1719);
    assert_int_equal(c->l.char_us, 1146);
    uint8_t req[8];
    hex_frame(FC03_REQ, req, sizeof req);

    /* Modbus serial line: silence > t1.5 inside a frame discards it. Time stamps are
     * character ends, so silence = distance - one character time (9600 8E1: 1146 us).
     * Exactly t1.5 of silence (distance 2865 us): delivered. */
    uint32_t t = 1000;
    for (size_t i = 0; i < 8; i++) {
        byte_at(c, req[i], t);
        if (i < 7) {
            t += (i == 3) ? 1146u + 1719u : 1146u;
        }
    }
    assert_true(timer_at(c, t + 4000));
    assert_pdu(c, 5, "03 00 50 00 02");
    modcp_link_done(&c->l);

    /* 1 us more: (08)06H, discarded, no (08)36H */
    t += 100000;
    for (size_t i = 0; i < 8; i++) {
        byte_at(c, req[i], t);
        if (i < 7) {
            t += (i == 3) ? 1146u + 1719u + 1u : 1146u;
        }
    }
    assert_false(timer_at(c, t + 4000));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.t15_discards, 1);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_ZVZ);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 1); /* Serial Line §6.1: char level */

    /* interference suppression: discarded and counted, no event */
    c->p.opmode = MODCP_OPMODE_SUPPRESS;
    configure(c);
    t += 100000;
    for (size_t i = 0; i < 8; i++) {
        byte_at(c, req[i], t);
        if (i < 7) {
            t += (i == 3) ? 1146u + 2000u : 1146u;
        }
    }
    assert_false(timer_at(c, t + 4000));
    assert_int_equal(c->d.t15_discards, 2);
    assert_int_equal(c->d.buffer_len, 1);

    /* without the check (manual default) the same gap is accepted */
    c->p.t15_check = 0;
    configure(c);
    t += 100000;
    for (size_t i = 0; i < 8; i++) {
        byte_at(c, req[i], t);
        if (i < 7) {
            t += (i == 3) ? 1146u + 2800u : 1146u;
        }
    }
    assert_true(timer_at(c, t + 4000));
    assert_int_equal(c->d.t15_discards, 2);
}

/* ------------------------------------------------------------------------------ */
/* line errors                                                                      */

/* FC03 request with a parity error in place of its 4th character */
static bool frame_with_error(ctx_t *c, uint8_t flags, uint32_t t0, uint32_t *end)
{
    uint8_t req[8];
    hex_frame(FC03_REQ, req, sizeof req);
    uint32_t t = t0;
    for (size_t i = 0; i < 8; i++) {
        if (i == 3) {
            error_at(c, flags, t);
        } else {
            byte_at(c, req[i], t);
        }
        t += 1146;
    }
    t -= 1146;
    *end = t + 4000;
    return timer_at(c, *end);
}

static void test_parity_error_normal_mode(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    /* [RTU-2003] §2.2 normal operation: (08)0CH, the frame is discarded, no (08)36H */
    assert_false(frame_with_error(c, MODCP_LINE_PARITY, 500, &end));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_CHAR_ERROR);
    assert_int_equal(c->d.char_errors, 1);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 1); /* Serial Line §6.1: char level */
    assert_int_equal(c->d.counters[MODCP_CNT_CHAR_OVERRUN], 0);
    assert_int_equal(c->f.tx_calls, 0);

    /* overrun: (08)0CH and the serial-line overrun counter */
    assert_false(frame_with_error(c, MODCP_LINE_OVERRUN, end + 10000, &end));
    assert_int_equal(c->d.buffer_len, 2);
    assert_int_equal(c->d.char_errors, 2);
    assert_int_equal(c->d.counters[MODCP_CNT_CHAR_OVERRUN], 1);

    /* BREAK inside the frame: (08)0DH, newest first */
    assert_false(frame_with_error(c, MODCP_LINE_BREAK | MODCP_LINE_FRAMING, end + 10000, &end));
    assert_int_equal(c->d.buffer_len, 3);
    assert_int_equal(c->d.buffer[0], MODCP_EV_BREAK);
    assert_int_equal(c->d.buffer[1], MODCP_EV_CHAR_ERROR);
    assert_int_equal(c->d.buffer[2], MODCP_EV_CHAR_ERROR);
    assert_int_equal(c->d.breaks, 1);
    assert_int_equal(c->d.char_errors, 2);
}

static void test_parity_error_suppression_mode(void **state)
{
    ctx_t *c = *state;
    c->p.opmode = MODCP_OPMODE_SUPPRESS;
    configure(c);
    assert_true(c->l.suppress);
    uint32_t end;
    /* [RTU-2003] §2.2 interference suppression: the frame is discarded silently */
    assert_false(frame_with_error(c, MODCP_LINE_PARITY, 500, &end));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.char_errors, 1);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 1); /* counted, though silent */
    assert_false(frame_with_error(c, MODCP_LINE_BREAK, end + 10000, &end));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.breaks, 1);
    /* the next clean request is served */
    assert_true(frame_hex(c, FC03_REQ, end + 10000, NULL));
}

static void test_break_idle(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    /* [RTU-2003] §2.2 normal: BREAK before a message -> (08)0DH; the message after t3.5 is
     * served */
    error_at(c, MODCP_LINE_BREAK, 500);
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_BREAK);
    assert_int_equal(c->d.breaks, 1);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 4000); /* counts as a character */
    assert_false(timer_at(c, 4500));
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_true(frame_hex(c, FC03_REQ, 5000, &end));
    modcp_link_done(&c->l);
    /* a parity error on the idle line: (08)0CH */
    error_at(c, MODCP_LINE_PARITY, end + 1000);
    assert_int_equal(c->d.buffer_len, 2);
    assert_int_equal(c->d.buffer[0], MODCP_EV_CHAR_ERROR);
    assert_int_equal(c->d.buffer[1], MODCP_EV_BREAK);

    /* interference suppression: nothing */
    c->p.opmode = MODCP_OPMODE_SUPPRESS;
    configure(c);
    modcp_diag_init(&c->d);
    error_at(c, MODCP_LINE_BREAK, 100000);
    assert_false(timer_at(c, 104000));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.breaks, 1);

    /* RS485 two-wire behaves like interference suppression ([RTU-2003] §2.3) */
    c->p.opmode = MODCP_OPMODE_NORMAL;
    c->p.iface = MODCP_IFACE_RS485;
    configure(c);
    assert_true(c->l.suppress);
    error_at(c, MODCP_LINE_BREAK, 200000);
    assert_false(timer_at(c, 204000));
    assert_true(frame_hex(c, FC03_REQ, 210000, NULL));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.breaks, 2);
}

static void test_error_after_crc(void **state)
{
    ctx_t *c = *state;
    c->p.iface = MODCP_IFACE_RS485;
    configure(c);
    /* [RTU-2003] §2.2/§2.3: a framing error right after the CRC (the master releasing the
     * RS485 line) is ignored; the request is served */
    uint32_t last = feed_hex(c, FC03_REQ, 500);
    error_at(c, MODCP_LINE_FRAMING, last + 300);
    assert_true(timer_at(c, last + 4000)); /* the error did not restart t3.5 */
    assert_pdu(c, 5, "03 00 50 00 02");
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.char_errors, 1);
    modcp_link_done(&c->l);

    /* normal mode RS422: reported (after the message), the request is still served */
    c->p.iface = MODCP_IFACE_RS422;
    configure(c);
    last = feed_hex(c, FC03_REQ, 100000);
    error_at(c, MODCP_LINE_FRAMING, last + 300);
    assert_true(timer_at(c, last + 4000));
    assert_int_equal(c->d.buffer_len, 1);
    assert_int_equal(c->d.buffer[0], MODCP_EV_CHAR_ERROR);
}

/* ------------------------------------------------------------------------------ */
/* transmit                                                                         */

static void test_reply_fc03(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    fake_hal_log_clear(&c->f);
    /* [RTU-2003] §6.3 FC03 response with the [RTU-2003] §9 CRC */
    uint8_t rsp[] = {0x03, 0x04, 0x87, 0x65, 0x43, 0x21};
    memcpy(c->fr.pdu, rsp, sizeof rsp);
    c->f.now = end + 50;
    modcp_link_reply(&c->l, sizeof rsp, false, end + 50);
    assert_int_equal(c->l.state, MODCP_LINK_TX);
    assert_int_equal(c->f.tx_calls, 1);
    assert_tx(c, FC03_RSP);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 0); /* RS232: no direction */
    assert_int_equal(fake_hal_log_count(&c->f, FHL_ARM), 0);
    c->f.now = end + 50 + 9 * 1146;
    modcp_link_on_tx_done(&c->l, c->f.now);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 0);
}

static void test_reply_exception(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    /* [RTU-2003] §6.5 FC05 request; [RTU-2003] §5.4 exception reply 05 85 02 ([RTU-2003] §9 CRC) */
    assert_true(frame_hex(c, "05 05 08 09 FF 00 5F DC", 500, &end));
    assert_pdu(c, 5, "05 08 09 FF 00");
    c->fr.pdu[0] = 0x85;
    c->fr.pdu[1] = 0x02;
    modcp_link_reply(&c->l, 2, false, end);
    assert_tx(c, "05 85 02 82 90");
}

static void test_reply_too_long(void **state)
{
    ctx_t *c = *state;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    modcp_link_reply(&c->l, MODCP_ADU_MAX - 2, false, end); /* 1 byte too many */
    assert_int_equal(c->f.tx_calls, 0);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->d.buffer[0], MODCP_EV_INTERNAL_SEND);
    assert_canary(c);
    /* the largest reply fits: FC01 2040 bits (docs/mapping.md) */
    assert_true(frame_hex(c, FC03_REQ, end + 10000, &end));
    modcp_link_reply(&c->l, MODCP_ADU_MAX - 3, false, end);
    assert_int_equal(c->f.tx_calls, 1);
    assert_int_equal(c->f.tx_len, MODCP_ADU_MAX);
    assert_int_equal(modcp_crc16(c->f.tx, MODCP_ADU_MAX), 0);
    assert_canary(c);
}

static void test_rs485_de_without_turnaround(void **state)
{
    ctx_t *c = *state;
    c->p.iface = MODCP_IFACE_RS485;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    fake_hal_log_clear(&c->f);
    uint8_t rsp[] = {0x03, 0x04, 0x87, 0x65, 0x43, 0x21};
    memcpy(c->fr.pdu, rsp, sizeof rsp);
    c->f.now = end + 10;
    modcp_link_reply(&c->l, sizeof rsp, false, end + 10);
    /* docs/diagnostics.md: DE on before the first byte */
    long de_on = fake_hal_log_find(&c->f, FHL_DE, 0);
    long tx = fake_hal_log_find(&c->f, FHL_TX, 0);
    assert_true(de_on >= 0 && tx >= 0);
    assert_true(de_on < tx);
    assert_int_equal(c->f.log[de_on].value, 1);
    assert_int_equal(c->f.log[de_on].at, end + 10);
    assert_tx(c, FC03_RSP);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 1);
    assert_true(c->f.de);

    /* our own echo on the two-wire line is ignored (no (08)37H) */
    feed_hex(c, FC03_RSP, end + 1200);
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 1); /* still driving */
    assert_true(c->f.de);
    /* released on transmission complete, not before */
    uint32_t tdone = end + 10 + 9 * 1146;
    c->f.now = tdone;
    modcp_link_on_tx_done(&c->l, tdone);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 2);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_DE)->value, 0);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_DE)->at, tdone);
    assert_false(c->f.de);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    /* a second tx_done does nothing */
    modcp_link_on_tx_done(&c->l, tdone + 5);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 2);
}

static void test_rs485_turnaround(void **state)
{
    ctx_t *c = *state;
    c->p.iface = MODCP_IFACE_RS485;
    c->p.turnaround_ms = 5;
    configure(c);
    assert_int_equal(c->l.turnaround_us, 5000);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    fake_hal_log_clear(&c->f);
    uint8_t rsp[] = {0x03, 0x04, 0x87, 0x65, 0x43, 0x21};
    memcpy(c->fr.pdu, rsp, sizeof rsp);
    uint32_t t = end + 20;
    c->f.now = t;
    modcp_link_reply(&c->l, sizeof rsp, false, t);
    assert_int_equal(c->l.state, MODCP_LINK_TURNAROUND);
    assert_int_equal(c->f.n, 2);
    assert_int_equal(c->f.log[0].kind, FHL_DE);
    assert_int_equal(c->f.log[0].value, 1);
    assert_int_equal(c->f.log[1].kind, FHL_ARM);
    assert_int_equal(c->f.log[1].value, 5000);
    assert_int_equal(c->f.tx_calls, 0); /* not before the turnaround expiry */
    assert_false(timer_at(c, t + 5000));
    assert_int_equal(c->l.state, MODCP_LINK_TX);
    assert_int_equal(c->f.tx_calls, 1);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_TX)->at, t + 5000);
    assert_tx(c, FC03_RSP);
    assert_true(c->f.de);
    c->f.now = t + 5000 + 9 * 1146;
    modcp_link_on_tx_done(&c->l, c->f.now);
    assert_false(c->f.de);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_DE)->at, t + 5000 + 9 * 1146);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 2);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);

    /* turnaround applies to RS485 only */
    c->p.iface = MODCP_IFACE_RS422;
    configure(c);
    assert_int_equal(c->l.turnaround_us, 0);
}

static void test_rs485_null_de(void **state)
{
    ctx_t *c = *state;
    /* a port without DE / LED / signal callbacks (NULL) */
    fake_hal_log_init(&c->f, &c->hal, false);
    c->p.iface = MODCP_IFACE_RS485;
    c->p.turnaround_ms = 1;
    configure(c);
    uint32_t end;
    assert_true(frame_hex(c, FC03_REQ, 500, &end));
    uint8_t rsp[] = {0x03, 0x04, 0x87, 0x65, 0x43, 0x21};
    memcpy(c->fr.pdu, rsp, sizeof rsp);
    modcp_link_reply(&c->l, sizeof rsp, false, end);
    assert_false(timer_at(c, end + 1000));
    assert_tx(c, FC03_RSP);
    modcp_link_on_tx_done(&c->l, end + 20000);
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(fake_hal_log_count(&c->f, FHL_DE), 0);
}

/* ------------------------------------------------------------------------------ */
/* enable / disable                                                                 */

static void test_disabled_link_ignores_line(void **state)
{
    ctx_t *c = *state;
    /* not configured */
    feed_hex(c, FC03_REQ, 500);
    error_at(c, MODCP_LINE_BREAK, 20000);
    assert_false(timer_at(c, 30000));
    assert_int_equal(c->f.n, 0);
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.breaks, 0);
    assert_int_equal(c->buf[0], CANARY);

    /* configured, then disabled (CP not ready) */
    configure(c);
    uint32_t last = feed_hex(c, "05 03 00", 40000);
    modcp_link_disable(&c->l);
    assert_int_equal(fake_hal_log_last(&c->f, FHL_ARM)->value, 0); /* disarmed */
    assert_false(c->l.enabled);
    last = feed_hex(c, FC03_REQ, last + 10000);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(c->d.buffer_len, 0);
    assert_int_equal(c->d.counters[MODCP_CNT_BUS_CRC], 0);

    /* ASCII framing (ascii.c): an RTU frame is no request there (wrong start
     * character (08)38H, nothing sent; test_ascii.c has the rest) */
    c->p.framing = MODCP_FRAMING_ASCII;
    configure(c);
    assert_true(c->l.enabled);
    last = feed_hex(c, FC03_REQ, last + 10000);
    assert_false(timer_at(c, last + 4000));
    assert_int_equal(fake_hal_log_count(&c->f, FHL_TX), 0);
    assert_int_equal(c->d.buffer[0], MODCP_EV_ASCII_START);

    /* reconfigured for RTU: served again */
    c->p.framing = MODCP_FRAMING_RTU;
    configure(c);
    assert_true(c->l.enabled);
    assert_int_equal(c->l.own_addr, 5);
    assert_true(frame_hex(c, FC03_REQ, last + 20000, NULL));
}

static void test_configure_fields(void **state)
{
    ctx_t *c = *state;
    c->p.slave_addr = 222;
    c->p.baud = 19200;
    c->p.f_mul = 3;
    c->p.t15_check = 1;
    c->p.ascii_timeout_ms = 6500;
    c->p.turnaround_ms = 7; /* RS232: ignored */
    modcp_link_configure(&c->l, &c->p);
    assert_true(c->l.enabled);
    assert_int_equal(c->l.own_addr, 222);
    assert_false(c->l.suppress);
    assert_false(c->l.rs485);
    assert_int_equal(c->l.t35_us, 6000);
    assert_int_equal(c->l.t15_us, 860);
    assert_int_equal(c->l.char_us, 573);
    assert_int_equal(c->l.turnaround_us, 0);
    assert_int_equal(c->l.silence_us, 6000); /* RTU: t3.5 (the ASCII timeout is ASCII's) */
    assert_int_equal(c->l.state, MODCP_LINK_IDLE);
    assert_int_equal(c->f.log[0].kind, FHL_ARM);
    assert_int_equal(c->f.log[0].value, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_timing_manual_table),
        cmocka_unit_test(test_timing_modbus_rule),
        cmocka_unit_test(test_timing_t15_and_char),
        cmocka_unit_test_setup_teardown(test_eof_thresholds_manual, setup, teardown),
        cmocka_unit_test_setup_teardown(test_eof_thresholds_modbus, setup, teardown),
        cmocka_unit_test_setup_teardown(test_stale_expiry_and_time_wrap, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fc03_request_delivered, setup, teardown),
        cmocka_unit_test_setup_teardown(test_crc_error, setup, teardown),
        cmocka_unit_test_setup_teardown(test_other_address_ignored, setup, teardown),
        cmocka_unit_test_setup_teardown(test_own_address_inside_other_frame, setup, teardown),
        cmocka_unit_test_setup_teardown(test_late_timer_other_address, setup, teardown),
        cmocka_unit_test_setup_teardown(test_broadcast_delivered, setup, teardown),
        cmocka_unit_test_setup_teardown(test_frame_too_long, setup, teardown),
        cmocka_unit_test_setup_teardown(test_sequence_error_while_busy, setup, teardown),
        cmocka_unit_test_setup_teardown(test_done_then_next_frame_without_timer, setup, teardown),
        cmocka_unit_test_setup_teardown(test_tail_after_tx_done_skipped, setup, teardown),
        cmocka_unit_test_setup_teardown(test_hot_path_store, setup, teardown),
        cmocka_unit_test_setup_teardown(test_t15_check, setup, teardown),
        cmocka_unit_test_setup_teardown(test_parity_error_normal_mode, setup, teardown),
        cmocka_unit_test_setup_teardown(test_parity_error_suppression_mode, setup, teardown),
        cmocka_unit_test_setup_teardown(test_break_idle, setup, teardown),
        cmocka_unit_test_setup_teardown(test_error_after_crc, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reply_fc03, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reply_exception, setup, teardown),
        cmocka_unit_test_setup_teardown(test_reply_too_long, setup, teardown),
        cmocka_unit_test_setup_teardown(test_rs485_de_without_turnaround, setup, teardown),
        cmocka_unit_test_setup_teardown(test_rs485_turnaround, setup, teardown),
        cmocka_unit_test_setup_teardown(test_rs485_null_de, setup, teardown),
        cmocka_unit_test_setup_teardown(test_disabled_link_ignores_line, setup, teardown),
        cmocka_unit_test_setup_teardown(test_configure_fields, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
