/* SPDX-License-Identifier: Apache-2.0 */
/* The line fuzz targets' parameter set, built field by field from the input's first
 * FUZZ_CFG_BYTES bytes. In every byte (or bit group) 0 keeps the base set's value.
 *
 *  byte  bits   field
 *   0    0-3    baud: 1..11 = 300, 600, 1200, 2400, 4800, 9600, 19200, 38400, 57600,
 *               76800, 115200 (12..15 keep)
 *        4-5    parity: 1 none, 2 odd, 3 even
 *        6      stop bits 2
 *        7      data bits: 8 in ASCII, 7 in RTU (refused there: falls back)
 *   1    0-3    f_MUL 1..15 (11..15 out of range: the CP warns and runs with 1)
 *        4      end of frame by the Modbus rule; 5 t1.5 check; 6 interference
 *               suppression (modem mode); 7 RS485 mode selection ([RTU-2009] Table 5-2)
 *   2    0-1    interface: 1 RS422, 2 RS485, 3 RS232
 *        2      RS232 automatic secondary signals
 *        3-5    RS485 turnaround 0, 1, 2, 3, 5, 10, 50, 100 ms
 *        6-7    RTS on / off delays 0, 1, 2, 20 ms
 *   3    0      function set cp341; 1 quantity limits of the Modbus spec; 2 CPU model
 *               CP 441; 3-5 job limit: model's, 32, 33, 64, 100, 256, 450, 1024 bytes;
 *        6      32-bit registers; 7 diagnostic interrupt records
 *   4    0-2    CPU job timeout 50, 5, 10, 20, 100, 300, 1000, 65535 ms
 *        3-5    comm-loss supervision off, 100, 101, 150, 300, 1000, 5000, 30000 ms
 *        6-7    ASCII inter-character timeout 20, 3, 8, 100 ms
 *   5    0-4    scanner entries 0..31 (over 16: refused)
 *        5-7    scanner start 40000, 0, 1, 100, 1000, 65520, 65535, 30000
 *   6           scanner entries: entry k is refs[(k + byte) % NREFS]
 *   7, 8        write limits M, Q: 0xFF off; else MIN = (b & 15) x step, MAX = MIN +
 *               ((b >> 4) + 1) x step - 1 (step 160 bytes M, 20 bytes Q)
 *   9           write limits DB: 0xFF off; else MIN, MAX = dbs[b & 7], dbs[(b >> 3) & 7]
 *   10, 11      base DB of FC03/06/16, FC04: dbs[b & 7] + (b >> 3)
 *   12..14      32-bit ranges int16, int32, float: FROM = (b & 31) x 2048, length 1, 16,
 *               200, 400 registers by bits 5-6, bit 7: on the DB of the next range
 *   15..32      coil windows 0..5, 33..44 input windows 0..3, 3 bytes each:
 *               a: bits 0-2 area (1 none, 2 M, 3 Q (coils) / I (inputs), 4 T, 5 C,
 *                  6 DB 800, 7 DB 900), bits 3-7 FROM = value x 2048
 *               b: number of bits ((b & 127) + 1) x (16 if b & 128 else 8)
 *               c: START = c x 10 (M), c (I, Q, T, C), c x 4 (DB)
 *   45   0      DB 700 missing; 1 DB 801 100 bytes; 2 DB 900 missing; 3 no work DB;
 *        4      M 100 bytes; 5 DB 800 300 bytes; 6-7 unused
 *   46          ID strings vendor, product, revision, app_name (2 bits each): keep,
 *               empty, 7, 16 characters
 *   47   0      the other framing (RTU <-> ASCII; ASCII: 7 data bits, timeout 20 ms)
 *        1-3    the user program drops CP_START in every n-th FB cycle of the input (and
 *               raises it in the next: the FB initialises the CP again), 0 never
 * Then modcp_params_validate decides: each field with a fatal issue falls back to the
 * base set's value (a window or range that already has it: off), until the set is
 * accepted; after 8 rounds the whole base set. An ASCII inter-character timeout shorter
 * than two characters (no frame could arrive) becomes three characters. */
#include "fuzz_cfg.h"

#include <string.h>

#include "params_internal.h"
#include "../unit/support/example_params.h"

static const uint32_t rates[11] = {300,   600,   1200,  2400,  4800,  9600,
                                   19200, 38400, 57600, 76800, 115200};
static const uint16_t dbs[8] = {1, 80, 700, 800, 801, 900, 65535, 899};
static const uint16_t world_dbs[5] = {80, 700, 800, 801, 900}; /* fuzz_line.c's */

/* Word operands the scanner can point at: the manual-like ones first (the old parameter
 * set 1), then edges: missing DB, offsets at and beyond the areas, DB 0, no area. */
static const modcp_operand_ref_t refs[] = {
    {MODCP_AREA_M, 0, 1000},   {MODCP_AREA_I, 0, 4},      {MODCP_AREA_DB, 800, 10},
    {MODCP_AREA_T, 0, 7},      {MODCP_AREA_Q, 0, 256},    {MODCP_AREA_C, 0, 239},
    {MODCP_AREA_DB, 801, 1022}, {MODCP_AREA_DB, 701, 0},  {MODCP_AREA_M, 0, 2599},
    {MODCP_AREA_Q, 0, 319},    {MODCP_AREA_I, 0, 255},    {MODCP_AREA_T, 0, 240},
    {MODCP_AREA_DB, 0, 4},     {MODCP_AREA_NONE, 0, 0},   {MODCP_AREA_DB, 900, 65534},
    {MODCP_AREA_DB, 80, 2},    {MODCP_AREA_M, 0, 65535},  {MODCP_AREA_DB, 700, 100},
};
#define NREFS (sizeof refs / sizeof refs[0])

static uint16_t pick16(const uint16_t *table, unsigned idx, uint16_t keep)
{
    return idx == 0u ? keep : table[idx];
}

static void frame_and_protocol(const uint8_t *h, modcp_params_t *p)
{
    unsigned b = h[0] & 15u;
    if (b >= 1u && b <= 11u) {
        p->baud = rates[b - 1u];
    }
    static const uint8_t parities[4] = {0, MODCP_PARITY_NONE, MODCP_PARITY_ODD, MODCP_PARITY_EVEN};
    p->parity = (h[0] >> 4) & 3u ? parities[(h[0] >> 4) & 3u] : p->parity;
    p->stop_bits = (h[0] & 0x40u) ? 2u : p->stop_bits;
    p->data_bits = (h[0] & 0x80u) ? (p->framing == MODCP_FRAMING_ASCII ? 8u : 7u) : p->data_bits;
    p->f_mul = (h[1] & 15u) ? (uint8_t)(h[1] & 15u) : p->f_mul;
    p->eof_timing = (h[1] & 0x10u) ? MODCP_EOF_MODBUS : p->eof_timing;
    p->t15_check = (h[1] & 0x20u) ? 1u : p->t15_check;
    p->opmode = (h[1] & 0x40u) ? MODCP_OPMODE_SUPPRESS : p->opmode;
    p->rs485_sel = (h[1] & 0x80u) ? 1u : p->rs485_sel;
    static const uint8_t ifaces[4] = {0, MODCP_IFACE_RS422, MODCP_IFACE_RS485, MODCP_IFACE_RS232};
    p->iface = (h[2] & 3u) ? ifaces[h[2] & 3u] : p->iface;
    p->rs232_auto = (h[2] & 4u) ? 1u : p->rs232_auto;
    static const uint16_t turnarounds[8] = {0, 1, 2, 3, 5, 10, 50, 100};
    p->turnaround_ms = pick16(turnarounds, (h[2] >> 3) & 7u, p->turnaround_ms);
    static const uint16_t rts[4] = {0, 1, 2, 20};
    p->rts_on_delay_ms = pick16(rts, h[2] >> 6, p->rts_on_delay_ms);
    p->rts_off_delay_ms = pick16(rts, h[2] >> 6, p->rts_off_delay_ms);
}

static void functions_and_cpu(const uint8_t *h, modcp_params_t *p)
{
    p->fset = (h[3] & 1u) ? MODCP_FSET_CP341 : p->fset;
    p->qty_limits = (h[3] & 2u) ? MODCP_QLIMITS_SPEC : p->qty_limits;
    p->cpu_model = (h[3] & 4u) ? MODCP_CPU_CP441 : p->cpu_model;
    static const uint16_t job_limits[8] = {0, 32, 33, 64, 100, 256, 450, 1024};
    p->job_limit = pick16(job_limits, (h[3] >> 3) & 7u, p->job_limit);
    p->regs32 = (h[3] & 0x40u) ? 1u : p->regs32;
    p->diag_irq = (h[3] & 0x80u) ? 1u : p->diag_irq;
    static const uint16_t timeouts[8] = {0, 5, 10, 20, 100, 300, 1000, 65535};
    p->cpu_timeout_ms = pick16(timeouts, h[4] & 7u, p->cpu_timeout_ms);
    static const uint16_t commloss[8] = {0, 100, 101, 150, 300, 1000, 5000, 30000};
    p->commloss_ms = pick16(commloss, (h[4] >> 3) & 7u, p->commloss_ms);
    static const uint16_t ascii_to[4] = {0, 3, 8, 100};
    p->ascii_timeout_ms = pick16(ascii_to, h[4] >> 6, p->ascii_timeout_ms);
}

static void scanner(const uint8_t *h, modcp_params_t *p)
{
#if MODCP_WITH_EXTENDED
    if (h[5] & 31u) {
        p->scan_count = (uint8_t)(h[5] & 31u);
    }
    static const uint16_t starts[8] = {0, 0, 1, 100, 1000, 65520, 65535, 30000};
    p->scan_start = pick16(starts, h[5] >> 5, p->scan_start);
    if (h[6] != 0u) {
        for (unsigned k = 0; k < MODCP_SCANNER_MAX; k++) {
            p->scan[k] = refs[(k + h[6]) % NREFS];
        }
    }
#else
    (void)h;
    (void)p;
#endif
}

static void limit(uint8_t b, uint16_t step, modcp_limit_t *l)
{
    if (b == 0xFFu) {
        *l = (modcp_limit_t){0, 0};
    } else if (b != 0u) {
        uint32_t min = (uint32_t)(b & 15u) * step;
        uint32_t max = min + ((uint32_t)(b >> 4) + 1u) * step - 1u;
        *l = (modcp_limit_t){(uint16_t)min, (uint16_t)(max > 0xFFFFu ? 0xFFFFu : max)};
    }
}

static void mapping(const uint8_t *h, modcp_params_t *p)
{
    limit(h[7], 160, &p->lim_m);
    limit(h[8], 20, &p->lim_q);
    if (h[9] == 0xFFu) {
        p->lim_db = (modcp_limit_t){0, 0};
    } else if (h[9] != 0u) {
        p->lim_db = (modcp_limit_t){dbs[h[9] & 7u], dbs[(h[9] >> 3) & 7u]};
    }
    p->hr_base_db = h[10] ? (uint16_t)(dbs[h[10] & 7u] + (h[10] >> 3)) : p->hr_base_db;
    p->ir_base_db = h[11] ? (uint16_t)(dbs[h[11] & 7u] + (h[11] >> 3)) : p->ir_base_db;
    static const uint16_t lengths[4] = {1, 16, 200, 400};
    for (unsigned k = 0; k < 3u; k++) {
        uint8_t b = h[12 + k];
        if (b != 0u) {
            uint32_t from = (uint32_t)(b & 31u) * 2048u;
            uint32_t to = from + lengths[(b >> 5) & 3u] - 1u;
            uint16_t db = p->r32[(k + (b >> 7)) % 3u].db;
            to = to > 0xFFFFu ? 0xFFFFu : to;
            p->r32[k] = (modcp_r32range_t){(uint16_t)from, (uint16_t)to, db};
        }
    }
}

/* One window from three bytes (coils: Q at area code 3, inputs: I). */
static void window(const uint8_t *h, int coils, modcp_bitwin_t *w)
{
    static const uint8_t areas[8] = {0, MODCP_AREA_NONE, MODCP_AREA_M, 0, MODCP_AREA_T,
                                     MODCP_AREA_C, MODCP_AREA_DB, MODCP_AREA_DB};
    static const uint16_t start_step[8] = {0, 0, 10, 1, 1, 1, 4, 4};
    unsigned code = h[0] & 7u;
    if (code == 0u) {
        return;
    }
    uint8_t area = code == 3u ? (coils ? MODCP_AREA_Q : MODCP_AREA_I) : areas[code];
    uint32_t from = (uint32_t)(h[0] >> 3) * 2048u;
    uint32_t bits = ((uint32_t)(h[1] & 127u) + 1u) * ((h[1] & 128u) ? 16u : 8u);
    uint32_t to = from + bits - 1u;
    w->area = area;
    w->from = (uint16_t)from;
    w->to = (uint16_t)(to > 0xFFFFu ? 0xFFFFu : to);
    w->start = (uint16_t)(h[2] * start_step[code]);
    w->db = code == 6u ? 800u : (code == 7u ? 900u : 0u);
}

/* The other framing than the base's (byte 47 bit 0). */
static void framing(const uint8_t *h, modcp_params_t *p)
{
    if ((h[47] & 1u) == 0u) {
        return;
    }
    if (p->framing == MODCP_FRAMING_ASCII) {
        p->framing = MODCP_FRAMING_RTU;
        p->data_bits = 8;
    } else {
        p->framing = MODCP_FRAMING_ASCII;
        p->data_bits = 7;
        p->ascii_timeout_ms = 20;
    }
}

static void memory(const uint8_t *h, modcp_params_t *p, fuzz_mem_t *mem)
{
    static const uint16_t sizes[5] = {64, 1024, 1024, 1024, 1024};
    memcpy(mem->db_size, sizes, sizeof sizes);
    uint8_t b = h[45];
    mem->db_size[1] = (b & 1u) ? 0u : mem->db_size[1];
    mem->db_size[3] = (b & 2u) ? 100u : mem->db_size[3];
    mem->db_size[4] = (b & 4u) ? 0u : mem->db_size[4];
    mem->work_db = (b & 8u) ? 0u : world_dbs[0];
    mem->m_size = (b & 16u) ? 100u : 2600u;
    mem->db_size[2] = (b & 32u) ? 300u : mem->db_size[2];
    mem->restart_every = (uint8_t)((h[47] >> 1) & 7u);
#if MODCP_WITH_EXTENDED
    static const char text[] = "modcp-fuzz-0123456789";
    char *strings[4] = {p->vendor, p->product, p->revision, p->app_name};
    static const uint8_t lens[4] = {0, 0, 7, 16};
    for (unsigned k = 0; k < 4u; k++) {
        unsigned sel = (h[46] >> (2u * k)) & 3u;
        if (sel != 0u) {
            memset(strings[k], 0, MODCP_ID_STRING_MAX + 1u);
            memcpy(strings[k], text + k, lens[sel]);
        }
    }
#else
    (void)p;
#endif
}

/* A window back to its base value; one that has it already: off. */
static void window_back(modcp_bitwin_t *w, const modcp_bitwin_t *base)
{
    if (memcmp(w, base, sizeof *w) != 0) {
        *w = *base;
    } else {
        memset(w, 0, sizeof *w);
    }
}

/* A field with a fatal issue back to base; false when it had the base value already. */
static int fall_back(modcp_params_t *p, const modcp_params_t *base,
                     const modcp_param_issue_t *is)
{
    unsigned i = is->index;
    modcp_params_t old = *p;
    switch (is->field) {
    case MODCP_PF_COILS:
        window_back(&p->coils[i % MODCP_COIL_WINDOWS], &base->coils[i % MODCP_COIL_WINDOWS]);
        break;
    case MODCP_PF_INPUTS:
        window_back(&p->inputs[i % MODCP_INPUT_WINDOWS], &base->inputs[i % MODCP_INPUT_WINDOWS]);
        break;
    case MODCP_PF_R32: p->r32[i % 3u] = base->r32[i % 3u]; break;
    case MODCP_PF_LIM_DB: p->lim_db = base->lim_db; break;
    case MODCP_PF_LIM_M: p->lim_m = base->lim_m; break;
    case MODCP_PF_LIM_Q: p->lim_q = base->lim_q; break;
    case MODCP_PF_SCANNER: p->scan_count = 0; break;
    case MODCP_PF_BAUD: p->baud = base->baud; break;
    case MODCP_PF_DATA_BITS: p->data_bits = 8u; break; /* RTU and ASCII */
    case MODCP_PF_PARITY: p->parity = base->parity; break;
    case MODCP_PF_STOP_BITS: /* ASCII: 7E1, 7O1, 7N2 */
        p->stop_bits =
            p->framing == MODCP_FRAMING_ASCII && p->parity == MODCP_PARITY_NONE ? 2u : 1u;
        break;
    case MODCP_PF_OPMODE: p->opmode = MODCP_OPMODE_SUPPRESS; break; /* RS485 without selection */
    case MODCP_PF_IFACE: p->iface = base->iface; break;
    case MODCP_PF_RS232_AUTO: p->rs232_auto = 0; break; /* only with RS232 */
    case MODCP_PF_HR_BASE: p->hr_base_db = base->hr_base_db; break;
    case MODCP_PF_IR_BASE: p->ir_base_db = base->ir_base_db; break;
    case MODCP_PF_JOB_LIMIT: p->job_limit = 0; break; /* the model's limit */
    case MODCP_PF_COMMLOSS: p->commloss_ms = 0; break;
    case MODCP_PF_CPU_TIMEOUT: p->cpu_timeout_ms = base->cpu_timeout_ms; break;
    default: return 0; /* not a field the input sets: no way back but the whole set */
    }
    return memcmp(&old, p, sizeof old) != 0;
}

/* A set validation accepts but on which no frame can arrive is not one users run: an
 * ASCII inter-character timeout shorter than two characters becomes three. */
static void carries_frames(modcp_params_t *p)
{
    uint32_t two = 2u * modcp_params_char_us(p);
    if (p->framing == MODCP_FRAMING_ASCII && (uint32_t)p->ascii_timeout_ms * 1000u <= two &&
        p->ascii_timeout_ms >= 1u && p->ascii_timeout_ms <= 6500u) {
        p->ascii_timeout_ms = (uint16_t)(3u * two / 2000u + 1u);
    }
}

void fuzz_cfg_build(const uint8_t *h, const modcp_params_t *base, modcp_params_t *p,
                    fuzz_mem_t *mem, fuzz_cfg_stats_t *stats)
{
    *p = *base;
    memset(stats, 0, sizeof *stats);
    framing(h, p); /* first: the frame's defaults follow it */
    frame_and_protocol(h, p);
    functions_and_cpu(h, p);
    scanner(h, p);
    mapping(h, p);
    for (unsigned k = 0; k < MODCP_COIL_WINDOWS; k++) {
        window(h + 15u + 3u * k, 1, &p->coils[k]);
    }
    for (unsigned k = 0; k < MODCP_INPUT_WINDOWS; k++) {
        window(h + 33u + 3u * k, 0, &p->inputs[k]);
    }
    memory(h, p, mem);
    for (unsigned round = 0; round < 8u; round++) {
        modcp_param_issue_t issues[16];
        size_t n = modcp_params_validate(p, issues, 16);
        int fatal = 0;
        int moved = 0;
        for (size_t k = 0; k < n && k < 16u; k++) {
            if (issues[k].fatal) {
                fatal = 1;
                moved |= fall_back(p, base, &issues[k]);
                stats->fallbacks++;
            }
        }
        stats->rounds = round + 1u;
        if (!fatal) {
            carries_frames(p);
            return;
        }
        if (!moved) {
            break;
        }
    }
    *p = *base;
    stats->whole = 1;
}

/* The base parameter set of the line targets and the differential harness: the manual's
 * example (example_params.h: slave 5, windows onto M, Q, T, C and I, input registers
 * from DB 900, write limits) with holding registers from DB 700, and the 32-bit ranges
 * and scanner entries the input can switch on. */
void fuzz_cfg_base(modcp_params_t *p, bool ascii)
{
    example_params(p);
    p->hr_base_db = 700; /* registers 0..511 -> DB 700 (not writable), 512.. -> DB 701 (missing) */
    p->cpu_timeout_ms = 50;
    p->r32[MODCP_R32_INT16] = (modcp_r32range_t){3000, 3199, 800};
    p->r32[MODCP_R32_INT32] = (modcp_r32range_t){5000, 5099, 801};
    p->r32[MODCP_R32_FLOAT] = (modcp_r32range_t){7000, 7199, 900};
#if MODCP_WITH_EXTENDED
    p->scan_start = 40000;
    static const modcp_operand_ref_t scan[5] = {{MODCP_AREA_M, 0, 1000}, {MODCP_AREA_I, 0, 4},
                                                {MODCP_AREA_DB, 800, 10}, {MODCP_AREA_T, 0, 7},
                                                {MODCP_AREA_Q, 0, 256}};
    memcpy(p->scan, scan, sizeof scan);
#endif
    if (ascii) {
        p->framing = MODCP_FRAMING_ASCII;
        p->data_bits = 7;
        p->ascii_timeout_ms = 20;
    }
}
