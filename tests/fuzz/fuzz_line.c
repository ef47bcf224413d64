/* SPDX-License-Identifier: Apache-2.0 */
/* Fuzz target: arbitrary bytes, gaps and line errors on the serial line of a running
 * CP + FB, under a parameter set and a controller memory the input builds.
 * Invariants checked after every input:
 *   - every transmitted frame is a well-formed reply: our address, valid CRC,
 *     length <= 264, function code = request's or | 0x80 with code 1..4;
 *   - nothing outside the writable windows and limits changes: I, T, C, the work DB,
 *     M, Q and DBs outside the set's write limits (the manual's example: MB 1000..1255,
 *     QB 256..319, DB 800..899);
 *   - the parameter record decodes to the set it was encoded from;
 *   - the CP keeps answering a good request afterwards.
 * Input encoding: in the fuzz targets the first FUZZ_CFG_BYTES bytes build the CP's
 * parameter set and the controller's memory field by field (fuzz_cfg.c: character
 * frame, normal or modem mode, RS485 / RS232 signals, t1.5, windows and their bases,
 * write limits, 32-bit ranges, function set, quantity limits, job limit, timing,
 * scanner, DBs, ID strings); what the core's validation refuses falls back to the base
 * set, the manual's example (all bytes 0; tests/fuzz/make_seeds.py has the headers of
 * the five sets the targets once had fixed). Each further byte b is a line event:
 *   0xF0..0xF6  a gap of (b & 7) quarters of t3.5, 0xF0 five quarters (end of frame;
 *               at 9600 baud with f_MUL 1: 1..6 ms and 5 ms)
 *   0xF7        a long silence (longer than the comm-loss time, the CPU job timeout and
 *               the ASCII timeout), then the CP polls without an FB call in between
 *               (a stalled CPU side)
 *   0xF8        parity error, 0xF9 framing error, 0xFA overrun, 0xFB BREAK; with RS232
 *               automatic secondary signals (DSR ON, CTS following RTS, or always ON
 *               with a data output waiting time of 0) 0xF8 toggles "CTS stuck OFF"
 *               and 0xF9 DSR instead (both are ON again before the closing request)
 *   0xFC        run one FB cycle (1 ms), 0xFD next byte is a literal
 *   0xFE        the frame's check: RTU: the CRC of the bytes received since the last
 *               gap or line error; ASCII: the LRC of the hex pairs since the last ':'
 *               as two hex digits, then CR LF (so mutations reach the PDU, not only
 *               the CRC / LRC check)
 *   anything else: a received byte, one character time after the previous one; in an
 *               input of odd length the received bytes between two other events arrive
 *               as one block instead (modcp_cp_on_rx_block: DMA / FIFO, up to 64
 *               characters back to back; a timer due meanwhile fires late, after the
 *               block), so that the block path runs too.
 * Both framings: built with MODCP_FUZZ_FRAMING = 0 (RTU: fuzz_rtu) or 1 (ASCII:
 * fuzz_ascii) the whole input is one framing -- as libFuzzer targets with clang
 * (-DMODCP_FUZZ=ON) and as replays of tests/fuzz/corpus/<target> (replay_main.c).
 * Without MODCP_FUZZ_FRAMING it is the deterministic generator fuzz_replay, which runs
 * every kind of input in RTU and in ASCII under the base set; ctest runs it on every
 * build. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp/backplane.h"
#include "modcp/cp.h"
#include "modcp/crc.h"
#include "modcp/fb.h"
#include "modcp/params.h"
#include "modcp/plcmem.h"
#include "fuzz_cfg.h"

#define NDB 5
static const uint16_t db_numbers[NDB] = {80, 700, 800, 801, 900};

typedef struct {
    modcp_backplane_t bp;
    modcp_cp_t cp;
    modcp_fb_t fb;
    modcp_plcmem_t plc;
    modcp_db_t dbs[NDB];
    uint8_t db_data[NDB][1024];
    uint8_t i[256], q[320], m[2600];
    uint16_t t[240], c[240];
    modcp_hal_t hal;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    uint16_t record_len;
    uint32_t now_us;
    uint32_t timer_at; /* 0 = disarmed */
    uint8_t last_req_fc;
    unsigned replies;
    uint8_t tx[600];
    uint16_t tx_len;
    int tx_pending;
    int rts, cts_stuck_off, dsr_off, signals_changed; /* RS232 automatic signals */
    modcp_params_t p; /* the parameter set the CP runs */
    fuzz_mem_t mem;   /* DB sizes, M size, work DB */
    uint32_t char_us, t35_us;
    unsigned fb_calls; /* FB cycles the input asked for (CP_START drops: mem.restart_every) */
} fworld_t;

static fworld_t W;
static fworld_t SNAP; /* memory image before the input */
static int target_ascii; /* the target's framing (the base set's): ASCII instead of RTU */
static int ascii_mode;   /* the framing of the set in force (W.p.framing) */
static uint8_t cfg_bytes[FUZZ_CFG_BYTES]; /* the input's parameter bytes (0: the example) */

static int hexval(uint8_t c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* ':' + hex pairs + LRC + CR LF -> binary (without the LRC); 0 if malformed. */
static size_t ascii_decode(const uint8_t *a, size_t n, uint8_t *out)
{
    if (n < 9u || a[0] != ':' || a[n - 2] != '\r' || a[n - 1] != '\n' || (n - 3u) % 2u != 0u) {
        return 0;
    }
    size_t m = 0;
    uint8_t sum = 0;
    for (size_t k = 1; k + 2 < n; k += 2) {
        int hi = hexval(a[k]), lo = hexval(a[k + 1]);
        if (hi < 0 || lo < 0) return 0;
        out[m] = (uint8_t)(hi * 16 + lo);
        sum = (uint8_t)(sum + out[m++]);
    }
    return sum == 0u ? m - 1u : 0u;
}

static size_t ascii_encode(const uint8_t *b, size_t n, uint8_t *out)
{
    static const char hx[] = "0123456789ABCDEF";
    size_t m = 0;
    uint8_t sum = 0;
    out[m++] = ':';
    for (size_t k = 0; k <= n; k++) {
        uint8_t v = k < n ? b[k] : (uint8_t)(0u - sum);
        if (k < n) sum = (uint8_t)(sum + v);
        out[m++] = (uint8_t)hx[v >> 4];
        out[m++] = (uint8_t)hx[v & 15u];
    }
    out[m++] = '\r';
    out[m++] = '\n';
    return m;
}

static void die(const char *what)
{
    fprintf(stderr, "fuzz invariant violated: %s\n", what);
    abort();
}

static void f_tx(void *ctx, const uint8_t *buf, uint16_t len)
{
    fworld_t *w = ctx;
    if (ascii_mode) {
        uint8_t bin[300];
        if (len > 2u * 260u + 5u) {
            die("ASCII reply length");
        }
        size_t m = ascii_decode(buf, len, bin);
        if (m < 2u || bin[0] != 5 || ((bin[1] & 0x80u) && (m != 3u || bin[2] < 1u || bin[2] > 4u))) {
            die("ASCII reply format / LRC / address");
        }
        memcpy(w->tx, buf, len);
        w->tx_len = len;
        w->tx_pending = 1;
        w->replies++;
        return;
    }
    if (len > 264u || len < 5u) {
        die("reply length");
    }
    if (buf[0] != 5) {
        die("reply address");
    }
    if (modcp_crc16(buf, len) != 0) {
        die("reply CRC");
    }
    if (buf[1] & 0x80u) {
        if (len != 5u || buf[2] < 1u || buf[2] > 4u) {
            die("exception format");
        }
    }
    memcpy(w->tx, buf, len);
    w->tx_len = len;
    w->tx_pending = 1;
    w->replies++;
}

static void f_arm(void *ctx, uint32_t us)
{
    fworld_t *w = ctx;
    w->timer_at = us ? w->now_us + us : 0;
    if (us != 0 && w->timer_at == 0) {
        w->timer_at = 1;
    }
}

static void f_signal(void *ctx, modcp_signal_t sig, bool on)
{
    fworld_t *w = ctx;
    if (sig == MODCP_SIG_RTS) {
        w->rts = on;
        w->signals_changed = 1;
    }
}

/* RS232 automatic signals: the modem's CTS follows RTS (one step later) -- or, with a
 * data output waiting time of 0, is always ON (a partner that is always ready: nothing
 * else can work without a waiting time) -- and DSR is ON, unless the input says
 * otherwise. */
static void signals(void)
{
    if (W.signals_changed) {
        W.signals_changed = 0;
        bool cts = (W.p.rts_on_delay_ms == 0u || W.rts) && !W.cts_stuck_off;
        modcp_cp_on_signals(&W.cp, cts, !W.dsr_off, W.now_us);
    }
}

static void setup_world(void)
{
    memset(&W, 0, sizeof W);
    modcp_params_t base;
    fuzz_cfg_base(&base, target_ascii != 0);
    fuzz_cfg_stats_t st;
    fuzz_cfg_build(cfg_bytes, &base, &W.p, &W.mem, &st);
    const modcp_params_t *p = &W.p;
    W.char_us = modcp_params_char_us(p);
    W.t35_us = modcp_params_t35_us(p);
    uint16_t ndb = 0;
    for (unsigned k = 0; k < NDB; k++) {
        if (W.mem.db_size[k] != 0u) {
            W.dbs[ndb++] = (modcp_db_t){db_numbers[k], W.mem.db_size[k], W.db_data[k]};
        }
    }
    W.plc = (modcp_plcmem_t){.i = W.i, .q = W.q, .m = W.m, .t = W.t, .c = W.c,
                             .i_size = sizeof W.i, .q_size = sizeof W.q, .m_size = W.mem.m_size,
                             .t_count = 240, .c_count = 240, .dbs = W.dbs, .db_count = ndb};
    W.hal = (modcp_hal_t){.ctx = &W, .uart_tx = f_tx, .timer_arm = f_arm, .set_signal = f_signal};
    W.record_len = (uint16_t)modcp_params_encode(p, W.record, sizeof W.record);
    modcp_params_t back;
    if (W.record_len == 0u || modcp_params_decode(W.record, W.record_len, &back) != MODCP_EV_NONE ||
        memcmp(&back, p, sizeof back) != 0) {
        die("the parameter record does not decode to the set it was encoded from");
    }
    modcp_bp_init(&W.bp);
    modcp_fb_init(&W.fb, &W.bp, &W.plc, W.record, W.record_len, W.mem.work_db, 5000);
    modcp_cp_init(&W.cp, &W.hal, &W.bp);
    W.now_us = 5000000;
    modcp_cp_on_signals(&W.cp, false, true, W.now_us); /* CTS OFF (RTS is), DSR ON */
    /* recognisable memory contents */
    for (unsigned k = 0; k < sizeof W.m; k++) W.m[k] = (uint8_t)(k * 7u);
    for (unsigned k = 0; k < sizeof W.i; k++) W.i[k] = (uint8_t)(k * 3u);
    for (unsigned k = 0; k < sizeof W.q; k++) W.q[k] = (uint8_t)(k * 5u);
    for (unsigned k = 0; k < 240; k++) { W.t[k] = (uint16_t)(k * 257u); W.c[k] = (uint16_t)~k; }
    for (unsigned d = 0; d < NDB; d++)
        for (unsigned k = 0; k < sizeof W.db_data[d]; k++) W.db_data[d][k] = (uint8_t)(k ^ d);
    modcp_fb_in_t in = {true};
    modcp_fb_out_t out;
    for (int k = 0; k < 50 && !modcp_cp_ready(&W.cp); k++) {
        modcp_fb_call(&W.fb, &in, &out, W.now_us / 1000u);
        modcp_cp_poll(&W.cp, W.now_us);
        W.now_us += 1000;
    }
    if (!modcp_cp_ready(&W.cp)) {
        die("CP did not start");
    }
    W.signals_changed = 1; /* the partner's CTS and DSR as the model says */
}

/* Started worlds, the last few parameter sets (an input's mutations mostly keep its
 * set), copied into W: every pointer in W points into W itself (HAL context, memory
 * areas, record), so a copy is the same world. */
#define NCACHE 8
static struct {
    int used, ascii;
    uint8_t key[FUZZ_CFG_BYTES];
    fworld_t w;
} cache[NCACHE];
static unsigned cache_next;

static void setup(void)
{
    for (unsigned k = 0; k < NCACHE; k++) {
        if (cache[k].used && cache[k].ascii == target_ascii &&
            memcmp(cache[k].key, cfg_bytes, sizeof cfg_bytes) == 0) {
            W = cache[k].w;
            ascii_mode = W.p.framing == MODCP_FRAMING_ASCII;
            return;
        }
    }
    setup_world();
    unsigned k = cache_next++ % NCACHE;
    cache[k].used = 1;
    cache[k].ascii = target_ascii;
    memcpy(cache[k].key, cfg_bytes, sizeof cfg_bytes);
    cache[k].w = W;
    ascii_mode = W.p.framing == MODCP_FRAMING_ASCII;
}

static void advance(uint32_t us)
{
    uint32_t end = W.now_us + us;
    while ((int32_t)(end - W.now_us) > 0) {
        signals();
        if (W.timer_at != 0 && (int32_t)(W.timer_at - end) <= 0) {
            W.now_us = W.timer_at;
            W.timer_at = 0;
            modcp_cp_on_timer(&W.cp, W.now_us);
        } else {
            W.now_us = end;
        }
        if (W.tx_pending) {
            W.tx_pending = 0;
            modcp_cp_on_tx_done(&W.cp, W.now_us);
        }
    }
}

/* Received characters gathered for one block (inputs of odd length). */
static uint8_t blk[64];
static uint16_t blk_n;

/* The gathered characters as one block: back to back, the first ending now. */
static void flush_block(void)
{
    if (blk_n == 0u) {
        return;
    }
    uint32_t end = W.now_us + (uint32_t)(blk_n - 1u) * W.cp.link.char_us;
    if (W.timer_at != 0 && (int32_t)(W.timer_at - end) < 0) {
        W.timer_at = end; /* due during the block: the interrupt comes after it */
    }
    W.now_us = end;
    modcp_cp_on_rx_block(&W.cp, blk, blk_n, end);
    blk_n = 0;
    advance(W.char_us);
}

/* One cycle of the user program: the FB call, the CP's poll, 1 ms. True when the FB
 * reports CP_START_ERROR. */
static bool fb_call(bool cp_start)
{
    modcp_fb_in_t in = {cp_start};
    modcp_fb_out_t out;
    modcp_fb_call(&W.fb, &in, &out, W.now_us / 1000u);
    modcp_cp_poll(&W.cp, W.now_us);
    advance(1000);
    return out.cp_start_error;
}

static void fb_cycle(void)
{
    (void)fb_call(true);
}

/* Long enough for a frame to end and its reply to be out: t3.5 twice, turnaround, RTS
 * delays, a reply's characters. */
static uint32_t quiet_us(void)
{
    const modcp_params_t *p = &W.p;
    return 40000u + 2u * W.t35_us + 30u * W.char_us +
           1000u * ((uint32_t)p->turnaround_ms + p->rts_on_delay_ms + p->rts_off_delay_ms);
}

/* The user program runs on (one FB cycle per ms) until every frame has ended, its jobs
 * are done and its reply is out (quiet_us, at least 80 cycles); after CP_START_ERROR
 * (e.g. START_TIME ran out while the input stalled the CPU side during an
 * initialisation) it starts the CP again, as the manual's programs do: CP_START low for
 * one cycle, then high. */
static void settle(void)
{
    bool low = false; /* CP_START low in this cycle */
    uint32_t cycles = 80u + quiet_us() / 1000u;
    for (uint32_t k = 0; k < cycles; k++) {
        bool error = fb_call(!low);
        low = error && !low; /* CP_START_ERROR stays set until the next rising edge */
    }
}

static int writable(const modcp_limit_t *l, unsigned k)
{
    return l->max != 0u && k >= l->min && k <= l->max;
}

/* In 32-bit mode the DB limits are standard mode's: the 32-bit ranges' DBs stay writable
 * unless [limits] db_in_32bit_mode (r32_lim_db) keeps them ([ASCII-32] §3.7, §5.4). */
static int r32_db_free(unsigned db)
{
    if (W.p.regs32 == 0u || W.p.r32_lim_db != 0u) return 0;
    for (unsigned k = 0; k < 3u; k++)
        if (W.p.r32[k].db == db) return 1;
    return 0;
}

static void check_memory(void)
{
    if (memcmp(W.i, SNAP.i, sizeof W.i) != 0) die("I changed");
    if (memcmp(W.t, SNAP.t, sizeof W.t) != 0) die("T changed");
    if (memcmp(W.c, SNAP.c, sizeof W.c) != 0) die("C changed");
    for (unsigned k = 0; k < sizeof W.m; k++)
        if (!writable(&W.p.lim_m, k) && W.m[k] != SNAP.m[k]) die("M outside limits changed");
    for (unsigned k = 0; k < sizeof W.q; k++)
        if (!writable(&W.p.lim_q, k) && W.q[k] != SNAP.q[k]) die("Q outside limits changed");
    for (unsigned d = 0; d < NDB; d++)
        if ((!(writable(&W.p.lim_db, db_numbers[d]) || r32_db_free(db_numbers[d])) ||
             db_numbers[d] == W.mem.work_db) &&
            memcmp(W.db_data[d], SNAP.db_data[d], sizeof W.db_data[d]) != 0)
            die("DB outside limits (or the work DB) changed");
}

/* Send a diagnostic request FC08 with sub-function sub and data. */
static size_t send_fc08(uint16_t sub, uint16_t data, uint8_t *req)
{
    uint8_t bin[8] = {5, 0x08, (uint8_t)(sub >> 8), (uint8_t)sub, (uint8_t)(data >> 8), (uint8_t)data};
    size_t n = 8;
    if (ascii_mode) {
        n = ascii_encode(bin, 6, req);
        req[n - 1] = W.cp.link.ascii_delim; /* LF, or what FC08/0003 made it */
    } else {
        uint16_t crc = modcp_crc16(bin, 6);
        bin[6] = (uint8_t)crc;
        bin[7] = (uint8_t)(crc >> 8);
        memcpy(req, bin, 8);
    }
    advance(quiet_us()); /* silence: whatever was going on is over */
    fb_cycle();
    for (size_t k = 0; k < n; k++) {
        modcp_cp_on_rx(&W.cp, req[k], W.now_us);
        advance(W.char_us);
    }
    advance(quiet_us()); /* end of frame, turnaround, RTS delays: the reply is out */
    fb_cycle();
    return n;
}

/* The CP answers an echo (FC08/0000) after the input (and its jobs: settle()). With the extended function set
 * the input may have forced listen-only mode (FC08/0004) or changed the ASCII input
 * delimiter (FC08/0003): a restart (FC08/0001, processed without a reply in listen-only
 * mode; ended by the delimiter in force) comes first, then the echo ends with CR LF. */
static void good_request_answered(void)
{
    uint8_t req[32];
    W.cts_stuck_off = 0;
    W.dsr_off = 0;
    W.signals_changed = 1;
    if (W.p.fset != MODCP_FSET_CP341) {
        (void)send_fc08(0x0001, 0x0000, req);
    }
    unsigned before = W.replies;
    size_t n = send_fc08(0x0000, 0x1234, req);
    if (W.replies != before + 1 || W.tx_len != n || memcmp(W.tx, req, n) != 0) {
        die("good request not answered after the input");
    }
}

/* 0xFE: the CRC (RTU) or LRC + CR LF (ASCII) of the frame so far, received. */
static void send_check(uint8_t *fr, size_t *fr_len, size_t cap)
{
    uint8_t chk[4];
    size_t n;
    if (ascii_mode) {
        static const char hx[] = "0123456789ABCDEF";
        uint8_t sum = 0;
        size_t j = *fr_len > 0 && fr[0] == ':' ? 1u : 0u;
        for (; j + 1 < *fr_len; j += 2) {
            int hi = hexval(fr[j]), lo = hexval(fr[j + 1]);
            sum = (uint8_t)(sum + (uint8_t)((hi < 0 ? 0 : hi) * 16 + (lo < 0 ? 0 : lo)));
        }
        sum = (uint8_t)(0u - sum);
        chk[0] = (uint8_t)hx[sum >> 4];
        chk[1] = (uint8_t)hx[sum & 15u];
        chk[2] = '\r';
        chk[3] = '\n';
        n = 4;
    } else {
        uint16_t crc = modcp_crc16(fr, *fr_len);
        chk[0] = (uint8_t)crc;
        chk[1] = (uint8_t)(crc >> 8);
        n = 2;
    }
    for (size_t j = 0; j < n; j++) {
        modcp_cp_on_rx(&W.cp, chk[j], W.now_us);
        advance(W.char_us);
        if (*fr_len < cap) {
            fr[(*fr_len)++] = chk[j];
        }
    }
}

/* Silence longer than every timeout of the set, then the CP's poll without an FB call. */
static void long_silence(void)
{
    const modcp_params_t *p = &W.p;
    uint32_t ms = p->commloss_ms > p->cpu_timeout_ms ? p->commloss_ms : p->cpu_timeout_ms;
    ms = p->ascii_timeout_ms > ms ? p->ascii_timeout_ms : ms;
    advance(ms * 1000u + W.t35_us + 1000u);
    modcp_cp_poll(&W.cp, W.now_us);
}

/* An input byte 0xF0..0xFC other than 0xFE: gap, long silence, RS232 signal, line
 * error or FB cycle. */
static void event(uint8_t b, size_t *fr_len)
{
    if (b == 0xF7) {
        *fr_len = 0;
        long_silence();
    } else if (b <= 0xF6) {
        *fr_len = 0;
        advance((b == 0xF0 ? 5u : (uint32_t)(b & 7u)) * (W.t35_us / 4u));
    } else if (W.p.rs232_auto && (b == 0xF8 || b == 0xF9)) {
        if (b == 0xF8) {
            W.cts_stuck_off = !W.cts_stuck_off;
        } else {
            W.dsr_off = !W.dsr_off;
        }
        W.signals_changed = 1;
        advance(100);
    } else if (b <= 0xFB) {
        static const uint8_t errs[4] = {MODCP_LINE_PARITY, MODCP_LINE_FRAMING,
                                        MODCP_LINE_OVERRUN, MODCP_LINE_BREAK};
        *fr_len = 0;
        modcp_cp_on_line_error(&W.cp, errs[b - 0xF8], W.now_us);
        advance(W.char_us);
    } else { /* 0xFC: CP_START dropped in every n-th cycle, raised again in the next */
        W.fb_calls++;
        fb_call(W.mem.restart_every == 0u || W.fb_calls % W.mem.restart_every != 0u);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
#ifdef MODCP_FUZZ_FRAMING
    target_ascii = MODCP_FUZZ_FRAMING;
    size_t nh = size < FUZZ_CFG_BYTES ? size : FUZZ_CFG_BYTES;
    memset(cfg_bytes, 0, sizeof cfg_bytes);
    memcpy(cfg_bytes, data, nh);
    data += nh;
    size -= nh;
#endif
    setup();
    SNAP = W;
    uint8_t fr[600]; /* the frame so far, for 0xFE */
    size_t fr_len = 0;
    const int blocks = (size & 1u) != 0u; /* received bytes as blocks */
    blk_n = 0;
    for (size_t k = 0; k < size; k++) {
        uint8_t b = data[k];
        int literal = b < 0xF0;
        if (b == 0xFD) {
            literal = 1;
            if (k + 1 < size) {
                b = data[++k];
            }
        }
        if (!literal || (blocks && blk_n == sizeof blk)) {
            flush_block(); /* the block ends before any other event */
        }
        if (literal) { /* a received byte */
            if (ascii_mode && b == ':') {
                fr_len = 0;
            }
            if (fr_len < sizeof fr) {
                fr[fr_len++] = b;
            }
            if (blocks) {
                blk[blk_n++] = b;
            } else {
                modcp_cp_on_rx(&W.cp, b, W.now_us);
                advance(W.char_us);
            }
        } else if (b == 0xFE) {
            send_check(fr, &fr_len, sizeof fr);
        } else {
            event(b, &fr_len);
        }
    }
    flush_block();
    settle();
    check_memory();
    good_request_answered();
    return 0;
}

#ifndef MODCP_FUZZ_FRAMING
/* Deterministic replay: the manual's frames, mutations of them, and random noise. */
static uint32_t rng = 0x12345678u;
static uint32_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

static size_t with_crc(const uint8_t *f, size_t n, uint8_t *out)
{
    memcpy(out, f, n);
    uint16_t crc = modcp_crc16(f, n);
    out[n] = (uint8_t)crc;
    out[n + 1] = (uint8_t)(crc >> 8);
    return n + 2;
}

int main(int argc, char **argv)
{
    unsigned iterations = argc > 1 ? (unsigned)strtoul(argv[1], NULL, 0) : 3000u;
    static const uint8_t seeds[][16] = {
        {6, 5, 1, 0x00, 0x40, 0x00, 0x20},
        {6, 5, 2, 0x10, 0x30, 0x00, 0x18},
        {6, 5, 3, 0x00, 0x50, 0x00, 0x02},
        {6, 5, 4, 0x02, 0xC0, 0x00, 0x03},
        {6, 5, 5, 0x08, 0x09, 0xFF, 0x00},
        {6, 5, 6, 0x01, 0x80, 0x2B, 0x1A},
        {9, 5, 15, 0x04, 0x80, 0x00, 0x0C, 0x02, 0xCD, 0x09},
        {13, 5, 16, 0x00, 0x32, 0x00, 0x03, 0x06, 0xCD, 0x09, 0xDE, 0x1A, 0xEF, 0x2B},
        {6, 0, 6, 0x00, 0x10, 0xAA, 0x55},
    };
    uint8_t in[1400];
    unsigned runs = 0, m_changed = 0;
    unsigned long total_replies = 0, ascii_replies = 0;
    for (unsigned it = 0; it < 2u * iterations; it++) {
        target_ascii = ascii_mode = it >= iterations; /* first RTU, then the same in ASCII */
        size_t n = 0;
        unsigned frames = 1 + next() % 4;
        for (unsigned f = 0; f < frames && n < 600; f++) {
            uint32_t kind = next() % 4;
            if (kind == 0) { /* noise */
                unsigned len = next() % 40;
                for (unsigned k = 0; k < len; k++) in[n++] = (uint8_t)next();
            } else { /* a seed frame with its CRC, mutated or not */
                const uint8_t *s = seeds[next() % (sizeof seeds / sizeof seeds[0])];
                uint8_t fr[40];
                size_t len;
                if (ascii_mode) {
                    len = ascii_encode(s + 1, s[0], fr);
                } else {
                    len = with_crc(s + 1, s[0], fr);
                }
                if (kind == 2) fr[next() % len] ^= (uint8_t)(1u << (next() % 8));
                if (kind == 3) fr[1 + next() % (len - 1)] = (uint8_t)next();
                for (size_t k = 0; k < len; k++) {
                    if (fr[k] >= 0xF0) in[n++] = 0xFD;
                    in[n++] = fr[k];
                }
            }
            in[n++] = (uint8_t)(0xF0 + next() % 8); /* a gap of some length */
            if (next() % 3 == 0) in[n++] = 0xFC;
        }
        LLVMFuzzerTestOneInput(in, n);
        runs++;
        total_replies += W.replies - 1u; /* minus the closing good request */
        ascii_replies += ascii_mode ? W.replies - 1u : 0u;
        m_changed += memcmp(W.m, SNAP.m, sizeof W.m) != 0;
    }
    printf("fuzz replay: %u inputs (RTU and ASCII), %lu replies (%lu in ASCII), %u inputs wrote M,"
           " invariants held\n", runs, total_replies, ascii_replies, m_changed);
    if (total_replies == ascii_replies || ascii_replies == 0 || m_changed == 0) {
        die("the replay exercised nothing");
    }
    return 0;
}
#endif
