/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the waveform (--vcd FILE.vcd), an observer of the line.
 *
 * A Value Change Dump (IEEE 1364) at bit level, timescale 100 ns (a bit at 115200 baud
 * is 86.8 ticks), time 0 = the simulator's start, idle gaps kept. Signals (1 bit each):
 *   line          the bus: the wired AND of every transmitter (idle 1)
 *   master_tx     what the master sends
 *   slaves        the wired AND of the members' transmitters and the noise: what the
 *                 master receives
 *   <m>_tx <m>_de each member's transmitter and its RS485 driver enable (1 = driving)
 *   noise_tx      the noise fault's characters
 * A bit's edges are at t + i * (1 / baud) from the start bit's falling edge (exact, not
 * rounded to the character time). DE is on from a frame's first start bit to the end
 * of its last stop bit (or where a "DE released early" fault cuts it). */
#define _GNU_SOURCE
#include "vcd.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_SIG (4 + 2 * SIM_LINE_MAX_MEMBERS)
#define MAX_EDGES 8192
#define SIG_LINE 0
#define SIG_MASTER 1
#define SIG_NOISE 2
#define SIG_SLAVES 3
#define SIG_MEMBER0 4u
#define TICKS_PER_US 10u

typedef struct {
    uint64_t t; /* ticks */
    uint16_t sig; /* up to MAX_SIG */
    uint8_t v;
} edge_t;

struct sim_vcd {
    sim_observer_t obs; /* first: the line calls it */
    const sim_line_t *line;
    FILE *f;
    size_t nsig;
    uint8_t level[MAX_SIG];
    edge_t e[MAX_EDGES]; /* pending, sorted by t */
    size_t ne;
    uint64_t written; /* the last time written */
    uint64_t de_until[SIM_LINE_MAX_MEMBERS]; /* ticks; 0: DE off */
    double bit_ticks;
};

static unsigned sig_tx(int src)
{
    return src == SIM_SRC_MASTER ? SIG_MASTER : src < 0 ? SIG_NOISE : SIG_MEMBER0 + 2u * (unsigned)src;
}

static unsigned sig_de(int src)
{
    return SIG_MEMBER0 + 1u + 2u * (unsigned)src;
}

/* A signal's identifier: printable characters '!'..'~' (94), one for the first 94
 * signals, more after (the VCD format allows any length): 247 members have 498. */
#define ID_MAX 4
static void id_of(unsigned sig, char *id)
{
    size_t n = 0;
    do {
        id[n++] = (char)('!' + sig % 94u);
        sig /= 94u;
    } while (sig > 0u && n < ID_MAX - 1u);
    id[n] = '\0';
}

static void add_edge(sim_vcd_t *v, uint64_t t, unsigned sig, int val)
{
    if (v->ne == MAX_EDGES) {
        return; /* more than that pending: a fault's run-away; the rest is lost */
    }
    size_t i = v->ne;
    while (i > 0u && v->e[i - 1u].t > t) {
        i--;
    }
    memmove(&v->e[i + 1u], &v->e[i], (v->ne - i) * sizeof v->e[0]);
    v->e[i] = (edge_t){t, (uint16_t)sig, (uint8_t)val};
    v->ne++;
}

static bool is_de(size_t s)
{
    return s >= SIG_MEMBER0 && (s - SIG_MEMBER0) % 2u == 1u;
}

/* The wired AND of the transmitters: with the master (line) or without (slaves). */
static int wired_and(const sim_vcd_t *v, bool master)
{
    for (size_t s = SIG_MASTER; s < v->nsig; s++) {
        bool tx = (s == SIG_MASTER && master) || s == SIG_NOISE ||
                  (s >= SIG_MEMBER0 && !is_de(s));
        if (tx && v->level[s] == 0u) {
            return 0;
        }
    }
    return 1;
}

/* Writes the edges before `until` (ticks), one time section per distinct time. */
static void write_until(sim_vcd_t *v, uint64_t until)
{
    size_t i = 0;
    while (i < v->ne && v->e[i].t < until) {
        uint64_t t = v->e[i].t < v->written ? v->written : v->e[i].t;
        if (t != v->written) {
            fprintf(v->f, "#%llu\n", (unsigned long long)t);
        }
        uint64_t at = v->e[i].t;
        for (; i < v->ne && v->e[i].t == at; i++) {
            char id[ID_MAX];
            if (v->level[v->e[i].sig] != v->e[i].v) {
                v->level[v->e[i].sig] = v->e[i].v;
                id_of(v->e[i].sig, id);
                fprintf(v->f, "%u%s\n", (unsigned)v->e[i].v, id);
            }
        }
        for (unsigned s = SIG_LINE; s <= SIG_SLAVES; s += SIG_SLAVES) {
            int lv = wired_and(v, s == SIG_LINE);
            if (lv != v->level[s]) {
                char id[ID_MAX];
                v->level[s] = (uint8_t)lv;
                id_of(s, id);
                fprintf(v->f, "%d%s\n", lv, id);
            }
        }
        v->written = t;
    }
    memmove(&v->e[0], &v->e[i], (v->ne - i) * sizeof v->e[0]);
    v->ne -= i;
}

static void char_edges(sim_vcd_t *v, const sim_char_t *c, uint64_t t0, unsigned tx)
{
    if ((c->flags & SIM_CH_BREAK) != 0u) {
        add_edge(v, t0, tx, 0);
        add_edge(v, t0 + (uint64_t)c->len_us * TICKS_PER_US, tx, 1);
        return;
    }
    const sim_line_cfg_t *cfg = &v->line->cfg;
    unsigned nb = sim_line_nbits(cfg);
    unsigned parity_bit = cfg->parity != 0u ? 1u + cfg->data_bits : 0u;
    for (unsigned i = 0; i < nb; i++) {
        int lv = sim_line_bit(cfg, c->byte, i);
        if (i == parity_bit && parity_bit != 0u && (c->flags & SIM_CH_PARITY) != 0u) {
            lv ^= 1;
        }
        if (i == nb - cfg->stop_bits && (c->flags & SIM_CH_FRAMING) != 0u) {
            lv = 0;
        }
        add_edge(v, t0 + (uint64_t)((double)i * v->bit_ticks + 0.5), tx, lv);
    }
    add_edge(v, t0 + (uint64_t)((double)nb * v->bit_ticks + 0.5), tx, 1);
}

static void on_char(sim_observer_t *o, const sim_char_t *c)
{
    sim_vcd_t *v = (sim_vcd_t *)o;
    uint64_t t0 = c->t_us * TICKS_PER_US;
    write_until(v, t0);
    unsigned tx = sig_tx(c->src);
    if (c->src >= 0 && (size_t)c->src < v->line->n_members) {
        size_t m = (size_t)c->src;
        unsigned de = sig_de(c->src);
        /* DE: one frame is characters back to back (within half a bit) */
        if (v->de_until[m] == 0u || t0 > v->de_until[m] + (uint64_t)(v->bit_ticks / 2.0)) {
            add_edge(v, t0, de, 1);
        } else {
            /* still on: take back the off edge of the previous character */
            for (size_t i = 0; i < v->ne; i++) {
                if (v->e[i].sig == de && v->e[i].v == 0u && v->e[i].t == v->de_until[m]) {
                    memmove(&v->e[i], &v->e[i + 1u], (v->ne - i - 1u) * sizeof v->e[0]);
                    v->ne--;
                    break;
                }
            }
        }
        uint64_t end = t0 + (uint64_t)c->len_us * TICKS_PER_US;
        if ((c->flags & SIM_CH_DE_CUT) != 0u) {
            end = t0 + (uint64_t)c->de_off_us * TICKS_PER_US;
        }
        add_edge(v, end, de, 0);
        v->de_until[m] = end;
        if ((c->flags & SIM_CH_DE_CUT) != 0u) {
            /* the driver is off: the rest of the character does not reach the line */
            char_edges(v, c, t0, tx);
            for (size_t i = 0; i < v->ne; i++) {
                if (v->e[i].sig == tx && v->e[i].t >= end) {
                    v->e[i].v = 1;
                }
            }
            return;
        }
    }
    char_edges(v, c, t0, tx);
}

static void on_close(sim_observer_t *o)
{
    sim_vcd_t *v = (sim_vcd_t *)o;
    write_until(v, UINT64_MAX);
    fprintf(v->f, "#%llu\n", (unsigned long long)(v->written + 10u * TICKS_PER_US));
    fflush(v->f);
}

static void declare(sim_vcd_t *v, unsigned sig, const char *name)
{
    char id[ID_MAX];
    id_of(sig, id);
    fprintf(v->f, "$var wire 1 %s %s $end\n", id, name);
}

sim_vcd_t *sim_vcd_open(const sim_line_t *line, const char *path, char *err, size_t cap)
{
    sim_vcd_t *v = calloc(1, sizeof *v);
    if (v == NULL) {
        snprintf(err, cap, "out of memory");
        return NULL;
    }
    v->f = fopen(path, "w");
    if (v->f == NULL) {
        snprintf(err, cap, "cannot write %s: %s", path, strerror(errno));
        free(v);
        return NULL;
    }
    v->obs.on_char = on_char;
    v->obs.on_close = on_close;
    v->line = line;
    v->nsig = SIG_MEMBER0 + 2u * line->n_members;
    v->bit_ticks = 1e6 * TICKS_PER_US / (double)(line->cfg.baud != 0u ? line->cfg.baud : 9600u);
    fprintf(v->f, "$comment modcp-sim line, %u baud $end\n$timescale 100 ns $end\n",
            (unsigned)line->cfg.baud);
    fprintf(v->f, "$scope module modbus $end\n");
    declare(v, SIG_LINE, "line");
    declare(v, SIG_MASTER, "master_tx");
    declare(v, SIG_NOISE, "noise_tx");
    declare(v, SIG_SLAVES, "slaves");
    for (size_t m = 0; m < line->n_members; m++) {
        char name[40];
        snprintf(name, sizeof name, "%s_tx", line->names[m]);
        declare(v, sig_tx((int)m), name);
        snprintf(name, sizeof name, "%s_de", line->names[m]);
        declare(v, sig_de((int)m), name);
    }
    fprintf(v->f, "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n");
    for (size_t s = 0; s < v->nsig; s++) {
        v->level[s] = (uint8_t)(is_de(s) ? 0u : 1u);
        char id[ID_MAX];
        id_of((unsigned)s, id);
        fprintf(v->f, "%u%s\n", (unsigned)v->level[s], id);
    }
    fprintf(v->f, "$end\n");
    return v;
}

sim_observer_t *sim_vcd_observer(sim_vcd_t *v)
{
    return &v->obs;
}

void sim_vcd_close(sim_vcd_t *v)
{
    if (v != NULL) {
        fclose(v->f);
        free(v);
    }
}
