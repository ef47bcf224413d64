/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the text trace (--trace), an observer of the line like the capture and the
 * waveform: the same characters, at the same times (the start of a frame's first start
 * bit), in the same order, gathered into frames the same way (each source apart, a frame
 * ending at a gap of t3.5; ASCII: at LF, or at a new ':'). The notes of the line (events,
 * fault remarks, collisions, console output while the trace runs) come in the same time
 * order; a frame is printed when it has ended, and a note waits for every frame that began
 * before it: an event raised while a request is still on the line follows that request.
 * The noise fault's characters are not printed (the bus's note names them). */
#define _GNU_SOURCE
#include "trace_obs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#define NSLOT (2 + SIM_LINE_MAX_MEMBERS)
#define MAX_PENDING 64u

typedef struct {
    uint8_t b[SIM_TRACE_MAX];
    size_t n;
    uint64_t t0, end;
    bool errors;        /* a parity or framing error, a BREAK */
    bool lf;            /* ASCII: it ended at LF */
    char remark[96];    /* SIM_NOTE_FRAME: appended to its line */
    char next_remark[96]; /* for the source's next frame */
} tframe_t;

struct sim_trace_obs {
    sim_observer_t obs; /* first: the line calls it */
    const sim_line_t *line;
    const atomic_bool *on;
    bool solo;
    sim_trace_t fmt; /* formats frames and prints */
    tframe_t fr[NSLOT];
    sim_note_t pending[MAX_PENDING]; /* notes waiting for a frame that began before them */
    size_t np;
};

static size_t slot_of(int src)
{
    return src + 2 < (int)NSLOT && src + 2 >= 0 ? (size_t)(src + 2) : 0u;
}

/* "master", "slave 5" (one slave), "@b slave 6", "@qemu (external)" */
static void label_of(const sim_trace_obs_t *o, int src, char *out, size_t cap)
{
    const sim_line_t *l = o->line;
    if (src == SIM_SRC_MASTER) {
        snprintf(out, cap, "master");
    } else if (src >= 0 && (size_t)src < l->n_members && l->addr[src] == 0u) {
        snprintf(out, cap, "@%s (external)", l->names[src]);
    } else if (src >= 0 && (size_t)src < l->n_members && !o->solo) {
        snprintf(out, cap, "@%s slave %u", l->names[src], (unsigned)l->addr[src]);
    } else if (src >= 0 && (size_t)src < l->n_members) {
        snprintf(out, cap, "slave %u", (unsigned)l->addr[src]);
    } else {
        snprintf(out, cap, "noise");
    }
}

static bool frame_due(const sim_trace_obs_t *o, const tframe_t *fr, uint64_t t)
{
    return fr->n > 0u && (t == UINT64_MAX || fr->lf || t >= fr->end + o->line->cfg.t35_us);
}

static void print_frame(sim_trace_obs_t *o, size_t slot)
{
    tframe_t *fr = &o->fr[slot];
    int src = (int)slot - 2;
    if (atomic_load(o->on)) {
        char label[64];
        char line[SIM_TRACE_LINE];
        label_of(o, src, label, sizeof label);
        sim_trace_format(&o->fmt, label, fr->b, fr->n, src != SIM_SRC_MASTER, fr->errors,
                         fr->remark[0] != '\0' ? fr->remark : NULL, line, sizeof line);
        sim_trace_print(&o->fmt, line, fr->t0);
    }
    fr->n = 0;
    fr->errors = false;
    fr->lf = false;
    fr->remark[0] = '\0';
}

static void print_note(sim_trace_obs_t *o, const sim_note_t *n)
{
    if (n->kind == SIM_NOTE_OUTPUT) {
        o->fmt.print(o->fmt.user, n->text); /* printed even when the trace went off */
    } else if (atomic_load(o->on)) {
        sim_trace_print(&o->fmt, n->text, n->t_us);
    }
}

/* Prints what is complete by t (UINT64_MAX: everything) in time order: ended frames by
 * their start, notes by their time, none of them past a frame still going on. */
static void flush(sim_trace_obs_t *o, uint64_t t)
{
    for (;;) {
        uint64_t block = UINT64_MAX; /* the start of the first frame still going on */
        size_t first = NSLOT;
        for (size_t i = 0; i < NSLOT; i++) {
            const tframe_t *fr = &o->fr[i];
            if (fr->n == 0u) {
                continue;
            }
            if (!frame_due(o, fr, t)) {
                block = fr->t0 < block ? fr->t0 : block;
            } else if (first == NSLOT || fr->t0 < o->fr[first].t0) {
                first = i;
            }
        }
        bool note = o->np > 0u && o->pending[0].t_us < block &&
                    (first == NSLOT || o->pending[0].t_us <= o->fr[first].t0);
        if (note) {
            print_note(o, &o->pending[0]);
            o->np--;
            memmove(&o->pending[0], &o->pending[1], o->np * sizeof o->pending[0]);
        } else if (first != NSLOT && o->fr[first].t0 <= block) {
            print_frame(o, first);
        } else {
            return;
        }
    }
}

static void on_char(sim_observer_t *obs, const sim_char_t *ch)
{
    sim_trace_obs_t *o = (sim_trace_obs_t *)obs;
    flush(o, ch->t_us);
    if (ch->src == SIM_SRC_NOISE) {
        return;
    }
    size_t slot = slot_of(ch->src);
    tframe_t *fr = &o->fr[slot];
    if (o->line->cfg.ascii && ch->byte == ':' && fr->n > 0u) {
        print_frame(o, slot); /* a start character begins a new frame */
        flush(o, ch->t_us);
    }
    if (fr->n == 0u) {
        fr->t0 = ch->t_us;
        memcpy(fr->remark, fr->next_remark, sizeof fr->remark);
        fr->next_remark[0] = '\0';
    }
    if ((ch->flags & (SIM_CH_PARITY | SIM_CH_FRAMING | SIM_CH_BREAK)) != 0u) {
        fr->errors = true;
    }
    if ((ch->flags & SIM_CH_BREAK) == 0u && fr->n < sizeof fr->b) {
        fr->b[fr->n++] = ch->byte;
    }
    fr->end = ch->t_us + ch->len_us;
    if (o->line->cfg.ascii && ch->byte == '\n') {
        fr->lf = true;
        flush(o, ch->t_us);
    }
}

static void on_note(sim_observer_t *obs, const sim_note_t *n)
{
    sim_trace_obs_t *o = (sim_trace_obs_t *)obs;
    flush(o, n->t_us);
    if (n->kind == SIM_NOTE_FRAME) {
        char *r = o->fr[slot_of(n->src)].next_remark;
        size_t len = strnlen(n->text, sizeof o->fr[0].next_remark - 1u);
        memcpy(r, n->text, len);
        r[len] = '\0';
        return;
    }
    if (o->np == MAX_PENDING) {
        print_note(o, &o->pending[0]);
        o->np--;
        memmove(&o->pending[0], &o->pending[1], o->np * sizeof o->pending[0]);
    }
    o->pending[o->np++] = *n;
    flush(o, n->t_us);
}

static void on_time(sim_observer_t *obs, uint64_t t)
{
    flush((sim_trace_obs_t *)obs, t);
}

static void on_close(sim_observer_t *obs)
{
    flush((sim_trace_obs_t *)obs, UINT64_MAX);
}

sim_trace_obs_t *sim_trace_obs_new(const sim_line_t *line, const atomic_bool *on, bool solo,
                                   void (*print)(void *user, const char *line), void *user)
{
    sim_trace_obs_t *o = calloc(1, sizeof *o);
    if (o == NULL) {
        return NULL;
    }
    o->obs.on_char = on_char;
    o->obs.on_note = on_note;
    o->obs.on_time = on_time;
    o->obs.on_close = on_close;
    o->line = line;
    o->on = on;
    o->solo = solo;
    uint8_t own = solo && line->n_members > 0u ? line->addr[0] : 0u;
    sim_trace_init(&o->fmt, own, line->cfg.ascii, line->cfg.t35_us, print, user);
    o->fmt.any_addr = !solo;
    return o;
}

sim_observer_t *sim_trace_obs_observer(sim_trace_obs_t *o)
{
    return &o->obs;
}

void sim_trace_obs_free(sim_trace_obs_t *o)
{
    free(o);
}
