/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the modcp slave on a pseudo-terminal (or a real serial device), or
 * several slaves on one line (a bus, see bus.h).
 *
 *   modcp-sim CONFIG.ini [CONFIG2.ini ...] [--pty-link PATH] [--device /dev/ttyX] [--trace]
 *             [--script FILE] [--cycle-ms N] [--set section.key=value]... [--control FIFO]
 *             [--bus] [--fault [@M:]KIND=VALUE]... [--seed N] [--qemu-member PTY]...
 *
 * Every slave (member) is one modcp_cp_t + modcp_fb_t with its own threads below; with
 * one config and no --bus / --fault it owns the pty itself, else each member gets a pty
 * of its own and a bus thread joins them, any --qemu-member board's UART pty and the
 * master's pty into one line.
 *
 * Two threads joined only by the backplane (modcp_backplane_t):
 *   CP thread   the CP side: waits on the UART, the one-shot timer and the paced
 *               reply bytes (POSIX HAL) and feeds modcp_cp_on_rx / _on_timer /
 *               _on_tx_done / _poll with CLOCK_MONOTONIC microseconds. It sleeps until
 *               one of those events or a wake-up from the CPU thread; a supervision
 *               tick (1 ms while a job runs, else 5 ms) only drives job timeouts,
 *               comm-loss supervision and the LEDs. While a job is out it watches
 *               for the reply around the CPU thread's next FB call (port.expect_us);
 *               when it put blocks for the CPU side it signals the CPU thread
 *               (cpu_irq, the "backplane interrupt").
 *   CPU thread  the controller: a cyclic user program that calls modcp_fb_call every
 *               cycle_ms (CP_START set from the first cycle on, like OB100) and executes
 *               queued console commands between two calls; with blocks from the CP
 *               waiting it watches the clock for the last CPU_SPIN_US before the
 *               call. When an FB call moved blocks on the backplane (a reply or
 *               parameters put, job blocks taken) it wakes the CP thread
 *               (modcp_posix_wake).
 * The parameter record travels from the CPU side to the CP over the backplane (the FB
 * sends it); the main thread reads the console (stdin, --script, --control FIFO). The
 * tool keeps a mutex-protected snapshot of the CP's diagnostics for the console. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "modcp/backplane.h"
#include "modcp/console.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/hal_posix.h"
#include "modcp_conf.h"
#include "bus.h"
#include "latlog.h"
#include "trace.h"

#define MAX_SETS 32
#define RX_CHUNK 512
#define CMD_OUT_MAX 8192
/* Supervision ticks of the CP thread; nothing on a request's path waits for them. */
#define IDLE_TICK_US 5000u
#define BUSY_TICK_US 1000u
/* The CPU thread watches the clock for the last CPU_SPIN_US before an FB call that
 * blocks from the CP wait for (only then). */
#define CPU_SPIN_US 50u

#define MAX_MEMBERS SIM_BUS_MAX_MEMBERS
#define MAX_FAULTS 64

typedef struct sim sim_t;

/* One slave: its configuration, CP, FB and the threads that run them. */
typedef struct {
    sim_t *sim;
    size_t index;
    char name[24];      /* "a" for a.ini; addressed as @a or @1 on the console */
    const char *config;
    /* configuration */
    modcp_conf_t *conf;
    modcp_conf_memory_t memory;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    uint16_t record_len;
    uint32_t cycle_ms;
    /* the only thing both sides share */
    modcp_backplane_t bp;
    /* CP side (CP thread) */
    modcp_cp_t cp;
    modcp_posix_port_t port;
    modcp_hal_t hal;
    sim_trace_t tr;
    uint32_t events_seen;
    /* snapshot of the CP's diagnostics for the console (tool-level) */
    pthread_mutex_t snap_mu;
    modcp_diag_t snap_diag;
    bool snap_configured, snap_ready;
    modcp_event_t snap_param_event;
    /* CPU side (CPU thread) */
    modcp_fb_t fb;
    modcp_fb_in_t fb_in;
    bool paused;
    uint32_t cycles;
    atomic_int fb_state;
    /* console command slot (main -> CPU thread) */
    pthread_mutex_t cmd_mu;
    pthread_cond_t cmd_cv;
    char cmd_line[512];
    char cmd_out[CMD_OUT_MAX];
    bool cmd_pending;
    bool cmd_done;
    modcp_posix_thread_t t_cp, t_cpu;
    /* the CPU thread's wake-up: a console command, the stop, or the CP side's
     * "backplane interrupt" (the CP put blocks for the CPU side) */
    modcp_posix_event_t cpu_irq;
    uint32_t cp_put_seen; /* CP thread: to_cpu.head when it last interrupted */
    atomic_uint cpu_due; /* CPU thread: when its next FB call is due (us, low 32 bits) */
    atomic_int cpu_core; /* CPU thread: the processor it last ran on (-1: unknown) */
    atomic_bool cpu_calls; /* CPU thread: the FB is called (not paused) */
    uint32_t core_t; /* on a bus: the last time passed to the core */
    sim_latlog_t lat; /* MODCP_SIM_LATLOG: stage time stamps of every reply */
} member_t;

struct sim {
    /* options */
    const char *configs[MAX_MEMBERS];
    size_t n;
    const char *pty_link;
    const char *device;
    const char *script;
    const char *control;
    const char *sets[MAX_SETS];
    size_t set_count;
    const char *faults[MAX_FAULTS];
    size_t fault_count;
    const char *ext_tty[MAX_MEMBERS]; /* --qemu-member PTY: external members */
    size_t n_ext;
    int ext_fd[MAX_MEMBERS];
    char ext_name[MAX_MEMBERS][24];
    long cycle_override;
    bool bus_mode;
    uint32_t seed;
    atomic_bool stop;
    atomic_bool trace_on;
    uint64_t t0_us64;
    uint64_t cpu_t0_us64; /* all CPU threads cycle in phase from here */
    atomic_int ready_count;
    member_t m[MAX_MEMBERS];
    /* the bus (bus_mode): the master's pty and the line */
    modcp_posix_port_t line_port;
    sim_bus_t *bus;
    /* output */
    pthread_mutex_t print_mu;
};

static volatile sig_atomic_t g_signal;
static int g_sigpipe[2] = {-1, -1};

static void on_signal(int sig)
{
    g_signal = sig;
    if (g_sigpipe[1] >= 0) {
        char c = 's';
        ssize_t r = write(g_sigpipe[1], &c, 1);
        (void)r;
    }
}

static void print_line(sim_t *s, const char *line)
{
    pthread_mutex_lock(&s->print_mu);
    fputs(line, stdout);
    fputc('\n', stdout);
    fflush(stdout);
    pthread_mutex_unlock(&s->print_mu);
}

static void printf_line(sim_t *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void printf_line(sim_t *s, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    print_line(s, buf);
}

static void trace_print(void *user, const char *line)
{
    member_t *m = user;
    print_line(m->sim, line);
}

static uint64_t since_start(const sim_t *s)
{
    return modcp_posix_now_us64() - s->t0_us64;
}

static void on_tx(void *user, const uint8_t *buf, uint16_t len, uint32_t now_us)
{
    member_t *m = user;
    sim_t *s = m->sim;
    if (s->bus != NULL) {
        sim_bus_tx(s->bus, m->index, buf, len, now_us); /* the bus traces the line */
    } else if (atomic_load(&s->trace_on)) {
        sim_trace_tx(&m->tr, buf, len, since_start(s));
    }
}

/* ---- CP thread ----------------------------------------------------------------- */

static void cp_snapshot(member_t *m)
{
    pthread_mutex_lock(&m->snap_mu);
    m->snap_diag = m->cp.diag;
    m->snap_configured = m->cp.configured;
    m->snap_ready = modcp_cp_ready(&m->cp);
    m->snap_param_event = m->cp.param_event;
    pthread_mutex_unlock(&m->snap_mu);
}

static void trace_events(member_t *m)
{
    uint32_t total = m->cp.diag.events_total;
    if (total == m->events_seen) {
        return;
    }
    uint32_t n = total - m->events_seen;
    m->events_seen = total;
    if (!atomic_load(&m->sim->trace_on)) {
        return;
    }
    if (n > m->cp.diag.buffer_len) {
        n = m->cp.diag.buffer_len;
    }
    uint64_t t = since_start(m->sim);
    for (uint32_t i = n; i > 0u; i--) {
        sim_trace_event(&m->tr, m->cp.diag.buffer[i - 1u], t);
    }
}

/* This thread's processor, -1 when unknown. */
static int this_core(void)
{
#ifdef __linux__
    return sched_getcpu();
#else
    return -1;
#endif
}

/* The calling thread last ran on processor `core` too. Two threads that watch the
 * clock on one processor take turns: the CP thread watching for the reply there would
 * hold off the very FB call that makes it (until the scheduler preempts it, ~50 us). */
static bool same_core(int core)
{
    return core >= 0 && core == this_core();
}

/* Blocks published on a ring and not yet taken by its consumer. */
static bool ring_pending(const modcp_ring_t *r)
{
    return atomic_load_explicit(&r->head, memory_order_acquire) !=
           atomic_load_explicit(&r->tail, memory_order_relaxed);
}

static void *cp_thread(void *arg)
{
    member_t *m = arg;
    sim_t *s = m->sim;
    modcp_posix_rx_t rx[RX_CHUNK];
    /* on a bus, the bus traces the line; MODCP_SIM_MEMBER_RX=1 adds what each member
     * heard (a debugging aid: "@b heard ...") */
    bool line_trace = s->bus == NULL || getenv("MODCP_SIM_MEMBER_RX") != NULL;
    if (s->bus != NULL) {
        char l[32];
        snprintf(l, sizeof l, "@%s heard", m->name);
        sim_trace_labels(&m->tr, l, NULL, NULL);
    }
    while (!atomic_load(&s->stop)) {
        bool idle = modcp_cp_ready(&m->cp) && !modcp_job_busy(&m->cp.job) && !m->cp.request_pending;
        bool tx_done = false, timer = false;
        uint32_t now = 0;
        /* a job on the backplane: its reply comes at the CPU side's next FB call,
         * watched for (the backplane interrupt is immediate on a real CP) */
        m->port.expect_armed = m->cp.request_pending && !ring_pending(&m->bp.to_cp) &&
                               atomic_load_explicit(&m->cpu_calls, memory_order_relaxed) &&
                               !same_core(atomic_load_explicit(&m->cpu_core, memory_order_relaxed));
        m->port.expect_us = atomic_load_explicit(&m->cpu_due, memory_order_relaxed);
        sim_latlog_before_wait(&m->lat, &m->port);
        int n = modcp_posix_wait(&m->port, idle ? IDLE_TICK_US : BUSY_TICK_US, rx, RX_CHUNK,
                                 &tx_done, &timer, &now);
        sim_latlog_after_wait(&m->lat, &m->port, n, timer, now);
        if (n < 0) {
            printf_line(s, "modcp-sim: read error on %s: %s", m->port.path, strerror(-n));
            atomic_store(&s->stop, true);
            break;
        }
        bool tr = line_trace && atomic_load(&s->trace_on);
        /* the trace's time is exactly the core's `now` (widened to 64 bits), so its
         * t3.5 frame cut agrees with the core's timer: a frame is printed before the
         * events its end raises */
        uint64_t n64 = modcp_posix_now_us64();
        uint64_t t = n64 - (uint32_t)((uint32_t)n64 - now) - s->t0_us64;
        if (s->bus != NULL) {
            /* on a bus: the characters heard, each at its time on the line, and the
             * timer between them when it fell due first */
            if (timer) {
                m->port.timer_armed = true; /* ordered with the characters below */
                timer = false;
            }
            if (tx_done) {
                /* our reply ended before anything heard after it (we were deaf while
                 * sending): its end first, at its time on the line */
                uint32_t end = m->port.tx_t0_us + (uint32_t)m->port.tx_len * m->port.char_us;
                if ((int32_t)(end - m->core_t) < 0) {
                    end = m->core_t;
                }
                if ((int32_t)(now - end) < 0) {
                    end = now;
                }
                m->port.now_us = end;
                modcp_cp_on_tx_done(&m->cp, end);
                m->core_t = end;
                tx_done = false;
            }
            uint8_t bb[RX_CHUNK];
            uint32_t bt[RX_CHUNK];
            bool more = false;
            size_t k = sim_bus_take(s->bus, m->index, bb, bt, RX_CHUNK, now, &more);
            if (more) {
                /* characters that arrived after `now` was read: the next turn takes
                 * them (pulled back to `now` they could precede the end of our own
                 * reply: (08)37H, the request lost) */
                modcp_posix_wake(&m->port);
            }
            for (size_t i = 0; i < k; i++) {
                uint32_t ti = bt[i];
                if ((int32_t)(ti - m->core_t) < 0) {
                    ti = m->core_t; /* never back in time for the core */
                }
                if ((int32_t)(now - ti) < 0) {
                    ti = now;
                }
                while (m->port.timer_armed && (int32_t)(ti - m->port.timer_deadline_us) >= 0) {
                    uint32_t d = m->port.timer_deadline_us;
                    if ((int32_t)(d - m->core_t) < 0) {
                        d = m->core_t;
                    }
                    m->port.timer_armed = false;
                    m->port.now_us = d;
                    modcp_cp_on_timer(&m->cp, d);
                    m->core_t = d;
                }
                m->port.now_us = ti;
                if (tr) {
                    uint64_t tb = n64 - (uint32_t)((uint32_t)n64 - ti) - s->t0_us64;
                    sim_trace_rx(&m->tr, bb[i], 0, tb);
                }
                modcp_cp_on_rx(&m->cp, bb[i], ti);
                m->core_t = ti;
            }
            if (m->port.timer_armed && (int32_t)(now - m->port.timer_deadline_us) >= 0) {
                m->port.timer_armed = false;
                timer = true;
            }
            m->core_t = now;
        }
        m->port.now_us = now;
        bool cts = true, dsr = true;
        if (modcp_posix_modem_inputs(&m->port, &cts, &dsr)) {
            modcp_cp_on_signals(&m->cp, cts, dsr, now);
        }
        if (tx_done) {
            modcp_cp_on_tx_done(&m->cp, now);
        }
        if (timer) {
            modcp_cp_on_timer(&m->cp, now);
        }
        for (int i = 0; i < n; i++) {
            if (tr) {
                sim_trace_rx(&m->tr, rx[i].byte, rx[i].errors, t);
            }
            if (rx[i].errors != 0u) {
                modcp_cp_on_line_error(&m->cp, rx[i].errors, now);
            } else {
                modcp_cp_on_rx(&m->cp, rx[i].byte, now);
            }
        }
        modcp_cp_poll(&m->cp, now);
        sim_latlog_after_core(&m->lat, &m->cp, &m->port, now);
        uint32_t put = atomic_load_explicit(&m->bp.to_cpu.head, memory_order_relaxed);
        if (put != m->cp_put_seen) {
            m->cp_put_seen = put;
            modcp_posix_event_signal(&m->cpu_irq); /* the backplane interrupt */
        }
        if (tr) {
            sim_trace_poll(&m->tr, t);
        }
        trace_events(m);
        cp_snapshot(m);
    }
    return NULL;
}

/* ---- CPU thread ------------------------------------------------------------------- */

static void exec_console(member_t *m)
{
    modcp_console_env_t env;
    modcp_diag_t diag;
    memset(&env, 0, sizeof env);
    pthread_mutex_lock(&m->snap_mu);
    diag = m->snap_diag;
    env.cp_configured = m->snap_configured;
    env.cp_ready = m->snap_ready;
    env.cp_param_event = m->snap_param_event;
    pthread_mutex_unlock(&m->snap_mu);
    env.mem = &m->memory.mem;
    env.diag = &diag;
    env.fb = &m->fb;
    env.paused = &m->paused;
    env.cp_start = &m->fb_in.cp_start;
    env.bp = &m->bp;
    env.cycles = m->cycles;
    /* the CP's status area, read from the backplane like any user program would */
    modcp_cp_status_t cst;
    for (int k = 0; k < 100; k++) {
        if (modcp_bp_read_status(&m->bp, &cst)) {
            env.cp_status = &cst;
            break;
        }
    }
    (void)modcp_console_exec(&env, m->cmd_line, m->cmd_out, sizeof m->cmd_out);
}

/* Blocks the CPU side has put (to the CP) plus blocks it has taken (from the CP): it
 * changes whenever an FB call gives the CP something to do. Read on the CPU thread,
 * which is the only writer of both counters. */
static uint32_t bp_moves(const modcp_backplane_t *bp)
{
    return atomic_load_explicit(&bp->to_cp.head, memory_order_relaxed) +
           atomic_load_explicit(&bp->to_cpu.tail, memory_order_relaxed);
}

static void timespec_of(uint64_t us, struct timespec *ts)
{
    ts->tv_sec = (time_t)(us / 1000000u);
    ts->tv_nsec = (long)((us % 1000000u) * 1000u);
}

/* "modcp-sim: " or "modcp-sim: @b " */
static const char *who(const member_t *m, char *buf, size_t cap)
{
    if (m->sim->bus != NULL) {
        snprintf(buf, cap, "@%s ", m->name);
    } else {
        buf[0] = '\0';
    }
    return buf;
}

static void *cpu_thread(void *arg)
{
    member_t *m = arg;
    sim_t *s = m->sim;
    uint64_t next = s->cpu_t0_us64; /* every member's cycle in phase (two at one address
                                       answer at once, as two PLCs polled alike would) */
    uint8_t last_state = 0xFF;
    bool ready_printed = false, counted = false;
    char wb[32];
    m->fb_in.cp_start = true; /* OB100: CP_START set at start-up */
    atomic_store(&m->cpu_due, (unsigned)(next & 0xFFFFFFFFu));
    atomic_store(&m->cpu_core, -1);
    atomic_store(&m->cpu_calls, true);
    while (!atomic_load(&s->stop)) {
        for (;;) {
            if (atomic_load(&s->stop)) {
                break;
            }
            pthread_mutex_lock(&m->cmd_mu);
            bool cmd = m->cmd_pending;
            if (cmd) {
                exec_console(m);
                m->cmd_pending = false;
                m->cmd_done = true;
                pthread_cond_broadcast(&m->cmd_cv);
            }
            pthread_mutex_unlock(&m->cmd_mu);
            if (cmd) {
                continue;
            }
            uint64_t now = modcp_posix_now_us64();
            if (now >= next) {
                break;
            }
            /* blocks from the CP wait for this FB call: it starts on time, not a
             * wake-up late (the last CPU_SPIN_US are spent watching the clock) */
            const bool blocks_wait = !m->paused && ring_pending(&m->bp.to_cpu);
            if (blocks_wait && next - now <= CPU_SPIN_US) {
                modcp_posix_spin_until_us64(next);
                break;
            }
            uint64_t at = blocks_wait ? next - CPU_SPIN_US : next;
            (void)modcp_posix_event_wait_until(&m->cpu_irq, at);
        }
        if (atomic_load(&s->stop)) {
            break;
        }
        if (!m->paused) {
            modcp_fb_out_t out = {0}; /* ERROR_NR / INFO read only when the FB wrote them */
            uint32_t moved0 = bp_moves(&m->bp);
            uint32_t fb_t0 = modcp_posix_now_us();
            atomic_store_explicit(&m->cpu_core, this_core(), memory_order_relaxed);
            modcp_fb_call(&m->fb, &m->fb_in, &out, modcp_posix_now_ms());
            if (bp_moves(&m->bp) != moved0) {
                sim_latlog_fb(&m->lat, next, fb_t0, modcp_posix_now_us());
                modcp_posix_wake(&m->port); /* the CP has blocks to take or room to put */
            }
            m->cycles++;
            if (m->fb.state != last_state) {
                last_state = m->fb.state;
                atomic_store(&m->fb_state, last_state);
                if (last_state == MODCP_FBST_RUN && out.cp_start_ok && !ready_printed) {
                    ready_printed = true;
                    if (s->bus == NULL) {
                        printf_line(s, "modcp-sim: ready");
                    } else {
                        printf_line(s, "modcp-sim: @%s ready", m->name);
                        if (!counted) {
                            counted = true;
                            if (atomic_fetch_add(&s->ready_count, 1) + 1 == (int)s->n) {
                                printf_line(s, "modcp-sim: ready");
                            }
                        }
                    }
                } else if (last_state == MODCP_FBST_FAILED) {
                    char en[16];
                    modcp_console_event_name((modcp_event_t)out.error_info, en, sizeof en);
                    printf_line(s,
                                "modcp-sim: %sCP_START_ERROR, ERROR_NR %u ERROR_INFO 0x%04X %s (%s)",
                                who(m, wb, sizeof wb), (unsigned)out.error_nr,
                                (unsigned)out.error_info, en,
                                modcp_event_text((modcp_event_t)out.error_info));
                    ready_printed = false;
                } else if (last_state != MODCP_FBST_RUN) {
                    ready_printed = false;
                }
            }
        }
        uint64_t period = (uint64_t)m->cycle_ms * 1000u;
        next += period;
        uint64_t now = modcp_posix_now_us64();
        if (next + period < now) {
            /* overrun: do not catch up with a burst of cycles; stay in phase */
            next += ((now - next) / period + 1u) * period;
        }
        atomic_store_explicit(&m->cpu_due, (unsigned)(next & 0xFFFFFFFFu), memory_order_relaxed);
        atomic_store_explicit(&m->cpu_calls, !m->paused, memory_order_relaxed);
    }
    return NULL;
}

/* ---- console input (main thread) ----------------------------------------------------- */

static void submit(member_t *m, const char *line, char *out, size_t cap)
{
    sim_t *s = m->sim;
    pthread_mutex_lock(&m->cmd_mu);
    snprintf(m->cmd_line, sizeof m->cmd_line, "%s", line);
    m->cmd_pending = true;
    m->cmd_done = false;
    modcp_posix_event_signal(&m->cpu_irq);
    while (!m->cmd_done && !atomic_load(&s->stop)) {
        struct timespec ts;
        timespec_of(modcp_posix_now_us64() + 100000u, &ts);
        (void)pthread_cond_timedwait(&m->cmd_cv, &m->cmd_mu, &ts);
    }
    snprintf(out, cap, "%s", m->cmd_done ? m->cmd_out : "error: stopped");
    pthread_mutex_unlock(&m->cmd_mu);
}

static bool sleep_ms(sim_t *s, long ms)
{
    uint64_t end = modcp_posix_now_us64() + (uint64_t)ms * 1000u;
    while (!atomic_load(&s->stop) && g_signal == 0) {
        uint64_t now = modcp_posix_now_us64();
        if (now >= end) {
            return true;
        }
        uint64_t step = end - now > 50000u ? 50000u : end - now;
        modcp_posix_sleep_until_us64(now + step);
    }
    return false;
}

/* "@b" / "@2" -> member index; -1 = none such; MAX_MEMBERS = all ("@*"). */
static int find_member(const sim_t *s, const char *name)
{
    if (strcmp(name, "*") == 0) {
        return MAX_MEMBERS;
    }
    for (size_t i = 0; i < s->n; i++) {
        if (strcmp(s->m[i].name, name) == 0) {
            return (int)i;
        }
    }
    char *end = NULL;
    long k = strtol(name, &end, 10);
    if (*name != '\0' && *end == '\0' && k >= 1 && (size_t)k <= s->n) {
        return (int)(k - 1);
    }
    return -1;
}

/* `fault [KIND=VALUE|off]...` for member m. */
static void fault_cmd(member_t *m, const char *args, bool prefix)
{
    sim_t *s = m->sim;
    char out[512];
    char pre[32] = "";
    if (prefix) {
        snprintf(pre, sizeof pre, "@%s ", m->name);
    }
    char buf[256];
    snprintf(buf, sizeof buf, "%s", args);
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t", &save); tok != NULL; tok = strtok_r(NULL, " \t", &save)) {
        char err[160];
        if (!sim_bus_fault_set(s->bus, m->index, tok, err, sizeof err)) {
            printf_line(s, "%serror: fault %s", pre, err);
            return;
        }
    }
    sim_bus_fault_describe(s->bus, m->index, out, sizeof out);
    printf_line(s, "%s%s", pre, out);
}

/* One console command for member m (prefix: name it in each output line). */
static void member_cmd(member_t *m, const char *line, const char *cmd, bool prefix)
{
    sim_t *s = m->sim;
    if (strcasecmp(cmd, "fault") == 0 || strcasecmp(cmd, "faults") == 0) {
        const char *args = line;
        while (*args == ' ' || *args == '\t') {
            args++;
        }
        args += strlen(cmd);
        if (s->bus == NULL) {
            print_line(s, "error: faults are injected by the bus: start modcp-sim with --bus "
                          "(or --fault)");
            return;
        }
        fault_cmd(m, args, prefix);
        return;
    }
    char out[CMD_OUT_MAX];
    submit(m, line, out, sizeof out);
    if (out[0] == '\0') {
        return;
    }
    if (!prefix) {
        print_line(s, out);
    } else {
        /* every line of the answer named by its member */
        char *save = NULL;
        for (char *l = strtok_r(out, "\n", &save); l != NULL; l = strtok_r(NULL, "\n", &save)) {
            printf_line(s, "@%s %s", m->name, l);
        }
    }
    if (s->bus != NULL && strcasecmp(cmd, "status") == 0) {
        char f[512];
        sim_bus_fault_describe(s->bus, m->index, f, sizeof f);
        if (prefix) {
            printf_line(s, "@%s %s", m->name, f);
        } else {
            print_line(s, f);
        }
    }
}

/* One console line; returns false when the simulator should stop. */
static bool handle_line(sim_t *s, const char *line)
{
    char cmd[32] = "";
    char arg[64] = "";
    const char *rest = line;
    int target = -2; /* -2: no prefix */
    while (*rest == ' ' || *rest == '\t') {
        rest++;
    }
    if (*rest == '@') {
        char name[32];
        size_t k = 0;
        rest++;
        while (*rest != '\0' && *rest != ' ' && *rest != '\t' && k + 1u < sizeof name) {
            name[k++] = *rest++;
        }
        name[k] = '\0';
        target = find_member(s, name);
        if (target < 0) {
            printf_line(s, "error: no member @%s; members:", name);
            for (size_t i = 0; i < s->n; i++) {
                printf_line(s, "  @%s = @%zu  slave %u  %s", s->m[i].name, i + 1u,
                            (unsigned)s->m[i].conf->params.slave_addr, s->m[i].config);
            }
            return true;
        }
    }
    int k = sscanf(rest, " %31s %63s", cmd, arg);
    if (k >= 1 && target == -2) {
        if (strcasecmp(cmd, "quit") == 0 || strcasecmp(cmd, "exit") == 0) {
            return false;
        }
        if (strcasecmp(cmd, "sleep") == 0) {
            char *end = NULL;
            long ms = strtol(arg, &end, 10);
            if (k < 2 || *end != '\0' || ms < 0 || ms > 3600000L) {
                print_line(s, "error: usage: sleep MS");
            } else {
                (void)sleep_ms(s, ms);
            }
            return true;
        }
        if (strcasecmp(cmd, "trace") == 0) {
            if (k == 2 && (strcasecmp(arg, "on") == 0 || strcasecmp(arg, "off") == 0)) {
                atomic_store(&s->trace_on, strcasecmp(arg, "on") == 0);
                if (s->bus != NULL) {
                    sim_bus_trace(s->bus, strcasecmp(arg, "on") == 0);
                }
                printf_line(s, "trace %s", arg);
            } else {
                print_line(s, "error: usage: trace on|off");
            }
            return true;
        }
        if (strcasecmp(cmd, "members") == 0) {
            for (size_t i = 0; i < s->n; i++) {
                printf_line(s, "@%s = @%zu  slave %u  %s", s->m[i].name, i + 1u,
                            (unsigned)s->m[i].conf->params.slave_addr, s->m[i].config);
            }
            return true;
        }
    }
    if (k < 1 && target != -2) {
        print_line(s, "error: @MEMBER needs a command (e.g. @b status)");
        return true;
    }
    /* which members: a prefix names one (or @* all); without one, status / diag /
     * fault go to every member, everything else to the first */
    bool all = target == MAX_MEMBERS;
    if (target == -2) {
        all = s->n > 1u && k >= 1 &&
              (strcasecmp(cmd, "status") == 0 || strcasecmp(cmd, "diag") == 0 ||
               ((strcasecmp(cmd, "fault") == 0 || strcasecmp(cmd, "faults") == 0) && k == 1));
        target = 0;
    }
    if (all) {
        for (size_t i = 0; i < s->n; i++) {
            member_cmd(&s->m[i], rest, cmd, true);
        }
    } else {
        member_cmd(&s->m[target], rest, cmd, false);
    }
    if (k >= 1 && (strcasecmp(cmd, "help") == 0 || strcmp(cmd, "?") == 0)) {
        print_line(s, "  trace on|off        frame trace (simulator)");
        print_line(s, "  sleep MS            wait (simulator, for scripts)");
        print_line(s, "  quit                stop the simulator");
        if (s->bus != NULL) {
            print_line(s, "  members             the bus's members (@name = @index, address, config)");
            print_line(s, "  @M COMMAND          run COMMAND on member M (@b, @2; @* = all); without");
            print_line(s, "                      @M: status, diag and fault on all, the rest on the first");
            print_line(s, "  fault [SPEC]...     faults of a member's replies: drop=P crc=P exc06=P");
            print_line(s, "                      exc04=P (P in %), delay=MS|MIN-MAX, silent=N, noise=N,");
            print_line(s, "                      off; without SPEC: settings and counters");
        }
    }
    return true;
}

typedef struct {
    int fd;
    char buf[1024];
    size_t len;
    bool eof;
} line_reader_t;

/* Read what is available; call handle_line per complete line. false = stop. */
static bool pump(sim_t *s, line_reader_t *r)
{
    ssize_t n = read(r->fd, r->buf + r->len, sizeof r->buf - 1u - r->len);
    if (n == 0) {
        r->eof = true;
        if (r->len > 0u) {
            r->buf[r->len] = '\0';
            r->len = 0;
            return handle_line(s, r->buf);
        }
        return true;
    }
    if (n < 0) {
        if (errno != EAGAIN && errno != EINTR) {
            r->eof = true;
        }
        return true;
    }
    r->len += (size_t)n;
    for (;;) {
        char *nl = memchr(r->buf, '\n', r->len);
        if (nl == NULL) {
            if (r->len >= sizeof r->buf - 1u) { /* over-long line: take it as it is */
                r->buf[r->len] = '\0';
                r->len = 0;
                if (!handle_line(s, r->buf)) {
                    return false;
                }
            }
            return true;
        }
        *nl = '\0';
        size_t used = (size_t)(nl - r->buf) + 1u;
        char line[1024];
        memcpy(line, r->buf, used);
        memmove(r->buf, r->buf + used, r->len - used);
        r->len -= used;
        if (!handle_line(s, line)) {
            return false;
        }
    }
}

static bool run_script(sim_t *s)
{
    /* after the FB's init has finished (ready or CP_START_ERROR) */
    uint32_t start_ms = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (s->m[i].conf->params.start_time_ms > start_ms) {
            start_ms = s->m[i].conf->params.start_time_ms;
        }
    }
    uint64_t limit = modcp_posix_now_us64() + ((uint64_t)start_ms + 2000u) * 1000u;
    while (!atomic_load(&s->stop) && g_signal == 0 && modcp_posix_now_us64() < limit) {
        size_t done = 0;
        for (size_t i = 0; i < s->n; i++) {
            int st = atomic_load(&s->m[i].fb_state);
            done += (st == MODCP_FBST_RUN || st == MODCP_FBST_FAILED) ? 1u : 0u;
        }
        if (done == s->n) {
            break;
        }
        (void)sleep_ms(s, 10);
    }
    FILE *f = fopen(s->script, "r");
    if (f == NULL) {
        printf_line(s, "modcp-sim: cannot open script %s: %s", s->script, strerror(errno));
        return true;
    }
    char line[1024];
    bool go_on = true;
    while (go_on && fgets(line, sizeof line, f) != NULL && g_signal == 0 &&
           !atomic_load(&s->stop)) {
        line[strcspn(line, "\r\n")] = '\0';
        go_on = handle_line(s, line);
    }
    fclose(f);
    return go_on;
}

static void console_loop(sim_t *s, int control_fd)
{
    line_reader_t in = {STDIN_FILENO, "", 0, false};
    line_reader_t ctl = {control_fd, "", 0, control_fd < 0};
    bool tty = isatty(STDIN_FILENO) != 0;
    while (!atomic_load(&s->stop) && g_signal == 0) {
        struct pollfd pf[3];
        nfds_t n = 0;
        pf[n++] = (struct pollfd){g_sigpipe[0], POLLIN, 0};
        int in_ix = -1, ctl_ix = -1;
        if (!in.eof) {
            in_ix = (int)n;
            pf[n++] = (struct pollfd){in.fd, POLLIN, 0};
        }
        if (!ctl.eof) {
            ctl_ix = (int)n;
            pf[n++] = (struct pollfd){ctl.fd, POLLIN, 0};
        }
        int r = poll(pf, n, 200);
        if (r <= 0) {
            continue;
        }
        if ((pf[0].revents & POLLIN) != 0) {
            break;
        }
        if (in_ix >= 0 && (pf[in_ix].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
            if (!pump(s, &in)) {
                break;
            }
            if (in.eof && tty) {
                break; /* Ctrl-D on a terminal */
            }
        }
        if (ctl_ix >= 0 && (pf[ctl_ix].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
            if (!pump(s, &ctl)) {
                break;
            }
        }
    }
}

/* ---- start-up ------------------------------------------------------------------------------ */

static int usage(void)
{
    fprintf(stderr,
            "usage: modcp-sim CONFIG.ini [CONFIG2.ini ...] [--pty-link PATH] [--device /dev/ttyX]\n"
            "                 [--trace] [--script FILE] [--cycle-ms N] [--set section.key=value]...\n"
            "                 [--control FIFO] [--bus] [--fault [@M:]KIND=VALUE]... [--seed N]\n"
            "                 [--qemu-member PTY]...\n"
            "  --pty-link PATH   also make PATH a symlink to the pseudo-terminal\n"
            "  --device PATH     use a real serial device (termios from the parameters)\n"
            "  --trace           print every frame received and sent, and every event\n"
            "  --script FILE     run console commands from FILE once the FB is initialised\n"
            "  --cycle-ms N      cycle time of the user program (default: [cpu] cycle_ms)\n"
            "  --set [@M:]S.K=V  override a key of the configuration (e.g. serial.baud=115200);\n"
            "                    on a bus, of every member, or of member M (@2:, @name:)\n"
            "  --control FIFO    also read console commands from a named pipe (made if missing)\n"
            "  --bus             run even one config as a bus member (for --fault / fault)\n"
            "  --fault [@M:]K=V  a fault of member M's replies (default: every member); K: drop,\n"
            "                    crc, exc06, exc04 (V in %%), delay (MS or MIN-MAX), silent (N\n"
            "                    requests), noise (N bytes after each reply); implies --bus\n"
            "  --seed N          seed of the faults' random choices (default 1)\n"
            "  --qemu-member PTY a QEMU board's Modbus pty (tools/run-qemu) as a member of the\n"
            "                    bus (@qemu; its console is its own); implies --bus\n"
            "Several configs: one line (bus), one pty for the master, every member on it.\n"
            "The console reads stdin; type help. Ctrl-C or SIGTERM stops.\n");
    return 1;
}

/* What the value of an option is, for "needs a value" (NULL: the option takes none). */
static const char *option_value(const char *a)
{
    static const char *const opts[][2] = {
        {"--pty-link", "a path for the symlink to the pty"},
        {"--device", "a serial device, e.g. /dev/ttyUSB0"},
        {"--script", "a file of console commands"},
        {"--control", "a path for the console FIFO"},
        {"--cycle-ms", "the user program's cycle in ms, 1..60000"},
        {"--set", "section.key=value"},
        {"--fault", "[@MEMBER:]KIND=VALUE, e.g. drop=30 or @b:delay=5-20"},
        {"--seed", "a number"},
        {"--qemu-member", "the Modbus pty of a QEMU board (tools/run-qemu's MODBUS_TTY)"},
    };
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++) {
        if (strcmp(a, opts[i][0]) == 0) {
            return opts[i][1];
        }
    }
    return NULL;
}

static int parse_args(sim_t *s, int argc, char **argv)
{
    s->cycle_override = -1;
    s->seed = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *needs = option_value(a);
        if (needs != NULL && (i + 1 >= argc || (argv[i + 1][0] == '-' && argv[i + 1][1] == '-'))) {
            fprintf(stderr, "modcp-sim: %s needs a value (%s)\n", a, needs);
            return 1;
        }
        if (strcmp(a, "--pty-link") == 0) {
            s->pty_link = argv[++i];
        } else if (strcmp(a, "--device") == 0) {
            s->device = argv[++i];
        } else if (strcmp(a, "--trace") == 0) {
            atomic_store(&s->trace_on, true);
        } else if (strcmp(a, "--bus") == 0) {
            s->bus_mode = true;
        } else if (strcmp(a, "--script") == 0) {
            s->script = argv[++i];
        } else if (strcmp(a, "--control") == 0) {
            s->control = argv[++i];
        } else if (strcmp(a, "--cycle-ms") == 0) {
            char *end = NULL;
            long v = strtol(argv[++i], &end, 10);
            if (*end != '\0' || v < 1 || v > 60000) {
                fprintf(stderr, "modcp-sim: --cycle-ms %s: must be 1..60000\n", argv[i]);
                return 1;
            }
            s->cycle_override = v;
        } else if (strcmp(a, "--seed") == 0) {
            char *end = NULL;
            unsigned long v = strtoul(argv[++i], &end, 10);
            if (*end != '\0' || v > 0xFFFFFFFFul) {
                fprintf(stderr, "modcp-sim: --seed %s: must be a number\n", argv[i]);
                return 1;
            }
            s->seed = (uint32_t)v;
        } else if (strcmp(a, "--set") == 0) {
            if (s->set_count >= MAX_SETS) {
                fprintf(stderr, "modcp-sim: too many --set\n");
                return 1;
            }
            s->sets[s->set_count++] = argv[++i];
        } else if (strcmp(a, "--fault") == 0) {
            if (s->fault_count >= MAX_FAULTS) {
                fprintf(stderr, "modcp-sim: too many --fault\n");
                return 1;
            }
            s->faults[s->fault_count++] = argv[++i];
            s->bus_mode = true;
        } else if (strcmp(a, "--qemu-member") == 0) {
            if (s->n_ext >= MAX_MEMBERS) {
                fprintf(stderr, "modcp-sim: too many --qemu-member\n");
                return 1;
            }
            s->ext_tty[s->n_ext++] = argv[++i];
            s->bus_mode = true;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            return usage();
        } else if (a[0] == '-') {
            fprintf(stderr, "modcp-sim: unexpected argument '%s'\n", a);
            return usage();
        } else {
            if (s->n >= MAX_MEMBERS) {
                fprintf(stderr, "modcp-sim: at most %d configs (members of one bus)\n",
                        MAX_MEMBERS);
                return 1;
            }
            s->configs[s->n++] = a;
        }
    }
    if (s->n == 0u) {
        return usage();
    }
    if (s->n + s->n_ext > MAX_MEMBERS) {
        fprintf(stderr, "modcp-sim: at most %d members on one bus\n", MAX_MEMBERS);
        return 1;
    }
    if (s->n > 1u) {
        s->bus_mode = true;
    }
    if (s->bus_mode && s->device != NULL) {
        fprintf(stderr, "modcp-sim: --device works with one slave; a bus runs on a pty\n");
        return 1;
    }
    return 0;
}

/* A process holding dev open (not us): its PID and name; 0 if none. */
static long holder_of(const char *dev, char *comm, size_t cap)
{
    DIR *proc = opendir("/proc");
    if (proc == NULL) {
        return 0;
    }
    long found = 0;
    long self = (long)getpid();
    struct dirent *de;
    while (found == 0 && (de = readdir(proc)) != NULL) {
        char *end = NULL;
        long pid = strtol(de->d_name, &end, 10);
        if (*end != '\0' || pid <= 0 || pid == self) {
            continue;
        }
        char fdpath[64];
        snprintf(fdpath, sizeof fdpath, "/proc/%ld/fd", pid);
        DIR *fds = opendir(fdpath);
        if (fds == NULL) {
            continue;
        }
        struct dirent *fe;
        while ((fe = readdir(fds)) != NULL) {
            char lp[320], target[256];
            snprintf(lp, sizeof lp, "%s/%s", fdpath, fe->d_name);
            ssize_t n = readlink(lp, target, sizeof target - 1u);
            if (n > 0) {
                target[n] = '\0';
                if (strcmp(target, dev) == 0) {
                    found = pid;
                    break;
                }
            }
        }
        closedir(fds);
    }
    closedir(proc);
    if (found != 0) {
        char cp[64];
        snprintf(cp, sizeof cp, "/proc/%ld/comm", found);
        FILE *f = fopen(cp, "r");
        comm[0] = '\0';
        if (f != NULL) {
            if (fgets(comm, (int)cap, f) != NULL) {
                comm[strcspn(comm, "\n")] = '\0';
            }
            fclose(f);
        }
    }
    return found;
}

/* Why the line could not be opened, in words. */
static void open_failed(const char *device, const char *link, int orc)
{
    if (device != NULL) {
        struct stat st;
        if (orc == -ENOTTY || (stat(device, &st) == 0 && !S_ISCHR(st.st_mode))) {
            fprintf(stderr, "modcp-sim: --device %s: not a serial device\n", device);
        } else {
            fprintf(stderr, "modcp-sim: --device %s: %s\n", device, strerror(-orc));
        }
        return;
    }
    if (link != NULL && orc == -EBUSY) {
        char target[256] = "?", comm[64] = "";
        ssize_t n = readlink(link, target, sizeof target - 1u);
        if (n > 0) {
            target[n] = '\0';
        }
        long pid = holder_of(target, comm, sizeof comm);
        if (pid != 0) {
            fprintf(stderr,
                    "modcp-sim: --pty-link %s is in use: it points at %s, held by PID %ld (%s); "
                    "not replaced (stop that instance or choose another path)\n",
                    link, target, pid, comm);
        } else {
            fprintf(stderr,
                    "modcp-sim: --pty-link %s exists and points at %s, which no process holds; "
                    "not replaced (remove it or choose another path)\n",
                    link, target);
        }
        return;
    }
    if (link != NULL && orc == -EEXIST) {
        fprintf(stderr, "modcp-sim: --pty-link %s exists and is not a symbolic link; not replaced\n",
                link);
        return;
    }
    fprintf(stderr, "modcp-sim: cannot open %s: %s\n", link != NULL ? link : "a pty",
            strerror(-orc));
}

/* Problems of the configuration; one from --set N is blamed on that option:
 * "--set serial.baud=7: must be one of ...". Returns the fatal ones from --set. */
static size_t print_problems(const modcp_conf_t *c, const char *const *sets,
                             const char *const *shown, size_t nsets)
{
    size_t count = c->problem_count < MODCP_CONF_MAX_PROBLEMS ? c->problem_count
                                                              : MODCP_CONF_MAX_PROBLEMS;
    size_t from_set = 0;
    for (size_t i = 0; i < count; i++) {
        const char *txt = c->problems[i].text;
        unsigned long k = 0;
        int used = 0;
        if (sscanf(txt, "--set:%lu: %n", &k, &used) == 1 && used > 0 && k >= 1u && k <= nsets) {
            const char *rest = txt + used;
            const char *arg = sets[k - 1u];
            const char *eq = strchr(arg, '=');
            size_t keylen = eq != NULL ? (size_t)(eq - arg) : strlen(arg);
            /* drop the "section.key = value: " the rule is prefixed with */
            if (strncmp(rest, arg, keylen) == 0 && strncmp(rest + keylen, " = ", 3) == 0) {
                const char *colon = strstr(rest + keylen + 3u, ": ");
                if (colon != NULL) {
                    rest = colon + 2;
                }
            }
            fprintf(stderr, "--set %s: %s\n", shown[k - 1u], rest);
            if (c->problems[i].fatal) {
                from_set++;
            }
        } else {
            fprintf(stderr, "%s\n", txt);
        }
    }
    return from_set;
}

/* "a" for "configs/a.ini"; "a-2" when an earlier member has the name already. */
static void member_name(sim_t *s, size_t i)
{
    member_t *m = &s->m[i];
    const char *base = strrchr(m->config, '/');
    base = base != NULL ? base + 1 : m->config;
    size_t len = strcspn(base, ".");
    if (len == 0u) {
        len = strlen(base);
    }
    if (len > 16u) {
        len = 16u;
    }
    char name[17];
    memcpy(name, base, len);
    name[len] = '\0';
    bool dup = false;
    for (size_t k = 0; k < i; k++) {
        dup = dup || strcmp(s->m[k].name, name) == 0;
    }
    if (dup) {
        snprintf(m->name, sizeof m->name, "%s-%u", name, (unsigned)(i + 1u) % 100u);
    } else {
        snprintf(m->name, sizeof m->name, "%s", name);
    }
}

static void free_members(sim_t *s)
{
    for (size_t i = 0; i < s->n; i++) {
        member_t *m = &s->m[i];
        if (m->conf != NULL) {
            modcp_conf_memory_free(&m->memory);
            free(m->conf);
            m->conf = NULL;
        }
    }
}

/* Configuration of member m: the same code and messages as modcp-conf check.
 * 0, or the exit code. */
static int load_member(sim_t *s, member_t *m)
{
    m->conf = malloc(sizeof *m->conf);
    if (m->conf == NULL) {
        return 1;
    }
    memset(&m->memory, 0, sizeof m->memory);
    /* --set S.K=V for every member, --set @M:S.K=V for member M (name or index) only */
    const char *mine[MAX_SETS], *shown[MAX_SETS];
    size_t nmine = 0;
    for (size_t k = 0; k < s->set_count; k++) {
        const char *a = s->sets[k];
        if (a[0] == '@') {
            const char *colon = strchr(a, ':');
            char name[32];
            size_t len = colon != NULL ? (size_t)(colon - a - 1) : 0u;
            if (colon == NULL || len == 0u || len >= sizeof name) {
                fprintf(stderr, "modcp-sim: --set %s: expected @MEMBER:section.key=value\n", a);
                free(m->conf);
                m->conf = NULL;
                return 1;
            }
            memcpy(name, a + 1, len);
            name[len] = '\0';
            int target = find_member(s, name);
            if (target < 0 || target == MAX_MEMBERS) {
                fprintf(stderr, "modcp-sim: --set %s: no member @%s\n", a, name);
                free(m->conf);
                m->conf = NULL;
                return 1;
            }
            if ((size_t)target != m->index) {
                continue;
            }
            mine[nmine] = colon + 1;
        } else {
            mine[nmine] = a;
        }
        shown[nmine++] = a;
    }
    size_t fatal = modcp_conf_load_ex(m->conf, m->config, mine, nmine);
    size_t from_set = print_problems(m->conf, mine, shown, nmine);
    if (fatal > 0u) {
        if (from_set == fatal) {
            fprintf(stderr, "modcp-sim: --set: %zu problem%s, not started\n", fatal,
                    fatal == 1u ? "" : "s");
        } else {
            fprintf(stderr, "modcp-sim: %s%s: %zu problem%s, not started\n", m->config,
                    from_set > 0u ? " and --set" : "", fatal, fatal == 1u ? "" : "s");
        }
        free(m->conf);
        m->conf = NULL;
        return 2;
    }
    size_t rlen = modcp_conf_record(m->conf, m->record, sizeof m->record);
    if (rlen == 0u || !modcp_conf_memory_alloc(m->conf, &m->memory)) {
        fprintf(stderr, "modcp-sim: cannot build the parameter record / memory\n");
        free(m->conf);
        m->conf = NULL;
        return 1;
    }
    m->record_len = (uint16_t)rlen;
    m->cycle_ms = s->cycle_override > 0 ? (uint32_t)s->cycle_override : m->conf->cycle_ms;
    return 0;
}

/* Every member of one line needs the first one's line settings. */
static bool same_line(const sim_t *s)
{
    const modcp_params_t *p0 = &s->m[0].conf->params;
    static const char *const par[] = {"none", "odd", "even"};
    for (size_t i = 1; i < s->n; i++) {
        const modcp_params_t *p = &s->m[i].conf->params;
        char mine[32] = "", bus[32] = "";
        const char *field = NULL;
        if (p->baud != p0->baud) {
            field = "serial.baud";
            snprintf(mine, sizeof mine, "%u", (unsigned)p->baud);
            snprintf(bus, sizeof bus, "%u", (unsigned)p0->baud);
        } else if (p->parity != p0->parity) {
            field = "serial.parity";
            snprintf(mine, sizeof mine, "%s", par[p->parity % 3u]);
            snprintf(bus, sizeof bus, "%s", par[p0->parity % 3u]);
        } else if (p->data_bits != p0->data_bits) {
            field = "serial.data_bits";
            snprintf(mine, sizeof mine, "%u", (unsigned)p->data_bits);
            snprintf(bus, sizeof bus, "%u", (unsigned)p0->data_bits);
        } else if (p->stop_bits != p0->stop_bits) {
            field = "serial.stop_bits";
            snprintf(mine, sizeof mine, "%u", (unsigned)p->stop_bits);
            snprintf(bus, sizeof bus, "%u", (unsigned)p0->stop_bits);
        } else if (p->framing != p0->framing) {
            field = "protocol.framing";
            snprintf(mine, sizeof mine, "%s", p->framing == MODCP_FRAMING_ASCII ? "ascii" : "rtu");
            snprintf(bus, sizeof bus, "%s", p0->framing == MODCP_FRAMING_ASCII ? "ascii" : "rtu");
        }
        if (field != NULL) {
            fprintf(stderr,
                    "modcp-sim: member @%s (%s): %s = %s, but the bus runs %s = %s (@%s, %s); "
                    "all members of one line need the same baud, parity, data bits, stop bits "
                    "and framing, not started\n",
                    s->m[i].name, s->m[i].config, field, mine, field, bus, s->m[0].name,
                    s->m[0].config);
            return false;
        }
    }
    return true;
}

/* --fault [@M:]KIND=VALUE from the command line. */
static bool apply_cli_faults(sim_t *s)
{
    for (size_t k = 0; k < s->fault_count; k++) {
        const char *spec = s->faults[k];
        int target = MAX_MEMBERS;
        if (spec[0] == '@') {
            const char *colon = strchr(spec, ':');
            char name[32];
            size_t len = colon != NULL ? (size_t)(colon - spec - 1) : 0u;
            if (colon == NULL || len == 0u || len >= sizeof name) {
                fprintf(stderr, "modcp-sim: --fault %s: expected @MEMBER:KIND=VALUE\n", spec);
                return false;
            }
            memcpy(name, spec + 1, len);
            name[len] = '\0';
            target = find_member(s, name);
            if (target < 0) {
                fprintf(stderr, "modcp-sim: --fault %s: no member @%s\n", spec, name);
                return false;
            }
            spec = colon + 1;
        }
        for (size_t i = 0; i < s->n; i++) {
            if (target != MAX_MEMBERS && (size_t)target != i) {
                continue;
            }
            char err[160];
            if (!sim_bus_fault_set(s->bus, i, spec, err, sizeof err)) {
                fprintf(stderr, "modcp-sim: --fault %s: %s\n", s->faults[k], err);
                return false;
            }
        }
    }
    return true;
}

static void bus_print(void *user, const char *line)
{
    print_line(user, line);
}

int main(int argc, char **argv)
{
    sim_t *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return 1;
    }
    atomic_init(&s->stop, false);
    atomic_init(&s->trace_on, false);
    atomic_init(&s->ready_count, 0);
    int rc = parse_args(s, argc, argv);
    if (rc != 0) {
        free(s);
        return rc;
    }
    pthread_mutex_init(&s->print_mu, NULL);

    /* configurations */
    for (size_t i = 0; i < s->n; i++) {
        member_t *m = &s->m[i];
        m->sim = s;
        m->index = i;
        m->config = s->configs[i];
        atomic_init(&m->fb_state, MODCP_FBST_STOPPED);
        member_name(s, i);
    }
    for (size_t i = 0; i < s->n; i++) {
        member_t *m = &s->m[i];
        rc = load_member(s, m);
        if (rc != 0) {
            free_members(s);
            free(s);
            return rc;
        }
    }
    if (s->bus_mode && !same_line(s)) {
        free_members(s);
        free(s);
        return 2;
    }
    const modcp_params_t *p0 = &s->m[0].conf->params;
    uint32_t char_us = modcp_params_char_us(p0);

    /* the line: the first member's port (one slave), or the master's pty of the bus and
     * one pty per member */
    int orc;
    if (!s->bus_mode) {
        orc = s->device != NULL
                  ? modcp_posix_open_device(&s->m[0].port, s->device, p0->baud, p0->data_bits,
                                            p0->parity, p0->stop_bits, char_us)
                  : modcp_posix_open_pty(&s->m[0].port, s->pty_link, char_us);
    } else {
        orc = modcp_posix_open_pty(&s->line_port, s->pty_link, char_us);
        for (size_t i = 0; orc == 0 && i < s->n; i++) {
            orc = modcp_posix_open_pty(&s->m[i].port, NULL, char_us);
        }
        for (size_t i = 0; orc == 0 && i < s->n_ext; i++) {
            s->ext_fd[i] = open(s->ext_tty[i], O_RDWR | O_NOCTTY | O_NONBLOCK);
            struct termios tio;
            if (s->ext_fd[i] < 0 || tcgetattr(s->ext_fd[i], &tio) != 0) {
                fprintf(stderr, "modcp-sim: --qemu-member %s: %s\n", s->ext_tty[i],
                        s->ext_fd[i] < 0 ? strerror(errno) : "not a serial device");
                return 1;
            }
            cfmakeraw(&tio);
            (void)tcsetattr(s->ext_fd[i], TCSANOW, &tio);
            snprintf(s->ext_name[i], sizeof s->ext_name[i], i == 0u ? "qemu" : "qemu-%u",
                     (unsigned)(i + 1u) % 100u);
        }
    }
    if (orc != 0) {
        open_failed(s->device, s->pty_link, orc);
        if (s->bus_mode) {
            modcp_posix_close(&s->line_port);
            for (size_t i = 0; i < s->n; i++) {
                modcp_posix_close(&s->m[i].port);
            }
        }
        free_members(s);
        free(s);
        return 1;
    }
    s->t0_us64 = modcp_posix_now_us64();
    const char *line_path = s->bus_mode ? s->line_port.path : s->m[0].port.path;
    const char *line_link = s->bus_mode ? s->line_port.link : s->m[0].port.link;
    if (s->bus_mode) {
        sim_line_t line = {p0->data_bits, p0->parity, p0->stop_bits,
                           p0->framing == MODCP_FRAMING_ASCII, char_us,
                           p0->framing == MODCP_FRAMING_ASCII ? p0->ascii_timeout_ms * 1000u
                                                              : modcp_params_t35_us(p0)};
        const char *names[MAX_MEMBERS];
        uint8_t addr[MAX_MEMBERS];
        int fds[MAX_MEMBERS], wakes[MAX_MEMBERS];
        for (size_t i = 0; i < s->n; i++) {
            names[i] = s->m[i].name;
            addr[i] = s->m[i].conf->params.slave_addr;
            fds[i] = s->m[i].port.slave_fd;
            wakes[i] = s->m[i].port.wake.wr;
        }
        for (size_t i = 0; i < s->n_ext; i++) {
            names[s->n + i] = s->ext_name[i];
            addr[s->n + i] = 0;
            fds[s->n + i] = s->ext_fd[i];
            wakes[s->n + i] = -1;
        }
        s->bus = sim_bus_new(&line, s->n + s->n_ext, names, addr, s->line_port.fd, fds, wakes,
                             s->t0_us64, bus_print, s, s->seed);
        if (s->bus == NULL || !apply_cli_faults(s)) {
            if (s->bus == NULL) {
                fprintf(stderr, "modcp-sim: cannot set up the bus\n");
            }
            sim_bus_free(s->bus);
            modcp_posix_close(&s->line_port);
            for (size_t i = 0; i < s->n; i++) {
                modcp_posix_close(&s->m[i].port);
            }
            free_members(s);
            free(s);
            return 1;
        }
        sim_bus_trace(s->bus, atomic_load(&s->trace_on));
    }

    /* each member: the two sides and the interface between them */
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    for (size_t i = 0; i < s->n; i++) {
        member_t *m = &s->m[i];
        const modcp_params_t *p = &m->conf->params;
        m->port.on_tx = on_tx;
        m->port.on_tx_user = m;
        m->port.now_us = modcp_posix_now_us();
        m->core_t = m->port.now_us;
        modcp_posix_hal(&m->port, &m->hal);
        pthread_mutex_init(&m->snap_mu, NULL);
        pthread_mutex_init(&m->cmd_mu, NULL);
        pthread_cond_init(&m->cmd_cv, &ca);
        if (modcp_posix_event_open(&m->cpu_irq) != 0) {
            fprintf(stderr, "modcp-sim: cannot make a pipe\n");
            return 1;
        }
        modcp_bp_init(&m->bp);
        modcp_cp_init(&m->cp, &m->hal, &m->bp);
        modcp_fb_init(&m->fb, &m->bp, &m->memory.mem, m->record, m->record_len,
                      m->conf->work_db, p->start_time_ms);
        bool ascii = p->framing == MODCP_FRAMING_ASCII;
        uint64_t gap = ascii ? (uint64_t)p->ascii_timeout_ms * 1000u : modcp_params_t35_us(p);
        sim_trace_init(&m->tr, p->slave_addr, ascii, gap, trace_print, m);
        if (s->bus_mode) {
            char ev[32];
            snprintf(ev, sizeof ev, "@%s ", m->name);
            sim_trace_labels(&m->tr, NULL, NULL, ev);
        }
        if (s->bus == NULL) {
            sim_latlog_open(&m->lat);
        }
        cp_snapshot(m);
    }
    pthread_condattr_destroy(&ca);

    /* console FIFO */
    int control_fd = -1, control_wfd = -1;
    bool made_fifo = false;
    if (s->control != NULL) {
        struct stat st;
        if (stat(s->control, &st) != 0) {
            if (mkfifo(s->control, 0600) == 0) {
                made_fifo = true;
            }
        }
        control_fd = open(s->control, O_RDONLY | O_NONBLOCK);
        if (control_fd >= 0) {
            control_wfd = open(s->control, O_WRONLY | O_NONBLOCK); /* never see EOF */
        } else {
            fprintf(stderr, "modcp-sim: cannot open %s: %s\n", s->control, strerror(errno));
        }
    }

    /* signals: handled by the main thread only */
    if (pipe(g_sigpipe) != 0) {
        return 1;
    }
    (void)fcntl(g_sigpipe[1], F_SETFL, O_NONBLOCK);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, &old);

    char settings[48];
    modcp_conf_line_settings(p0, settings, sizeof settings);
    if (!s->bus_mode) {
        printf_line(s, "modcp-sim: slave %u on %s (%s)", (unsigned)p0->slave_addr, line_path,
                    settings);
    } else {
        printf_line(s, "modcp-sim: bus on %s (%s), %zu member%s", line_path, settings, s->n,
                    s->n == 1u ? "" : "s");
        for (size_t i = 0; i < s->n; i++) {
            printf_line(s, "modcp-sim: slave %u on %s (%s) member @%s, %s",
                        (unsigned)s->m[i].conf->params.slave_addr, line_path, settings,
                        s->m[i].name, s->m[i].config);
        }
    }
    for (size_t i = 0; i < s->n_ext; i++) {
        printf_line(s, "modcp-sim: member @%s on %s (external: a QEMU board's UART)",
                    s->ext_name[i], s->ext_tty[i]);
    }
    if (line_link[0] != '\0') {
        printf_line(s, "modcp-sim: link %s -> %s", line_link, line_path);
    }

    modcp_posix_thread_t t_bus;
    bool ok = true;
    if (s->bus != NULL) {
        ok = modcp_posix_thread_start(&t_bus, sim_bus_thread, s->bus) == 0;
    }
    s->cpu_t0_us64 = modcp_posix_now_us64();
    size_t started = 0;
    for (size_t i = 0; ok && i < s->n; i++) {
        member_t *m = &s->m[i];
        ok = modcp_posix_thread_start(&m->t_cp, cp_thread, m) == 0;
        if (ok) {
            ok = modcp_posix_thread_start(&m->t_cpu, cpu_thread, m) == 0;
            if (!ok) {
                atomic_store(&s->stop, true);
                modcp_posix_thread_join(&m->t_cp);
            }
        }
        if (ok) {
            started++;
        }
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);

    bool go_on = ok;
    if (!ok) {
        fprintf(stderr, "modcp-sim: cannot start threads\n");
    }
    if (go_on && s->script != NULL) {
        go_on = run_script(s);
    }
    if (go_on) {
        console_loop(s, control_fd);
    }

    atomic_store(&s->stop, true);
    for (size_t i = 0; i < started; i++) {
        member_t *m = &s->m[i];
        modcp_posix_wake(&m->port);
        modcp_posix_event_signal(&m->cpu_irq);
        pthread_mutex_lock(&m->cmd_mu);
        pthread_cond_broadcast(&m->cmd_cv);
        pthread_mutex_unlock(&m->cmd_mu);
    }
    for (size_t i = 0; i < started; i++) {
        modcp_posix_thread_join(&s->m[i].t_cpu);
        modcp_posix_thread_join(&s->m[i].t_cp);
    }
    if (s->bus != NULL) {
        sim_bus_stop(s->bus);
        modcp_posix_thread_join(&t_bus);
        sim_bus_free(s->bus);
        s->bus = NULL;
        modcp_posix_close(&s->line_port);
    }
    for (size_t i = 0; i < s->n; i++) {
        modcp_posix_close(&s->m[i].port);
        modcp_posix_event_close(&s->m[i].cpu_irq);
        sim_latlog_close(&s->m[i].lat);
    }
    if (control_fd >= 0) {
        close(control_fd);
    }
    if (control_wfd >= 0) {
        close(control_wfd);
    }
    if (made_fifo) {
        (void)unlink(s->control);
    }
    if (g_signal != 0) {
        printf_line(s, "modcp-sim: stopped (%s)", g_signal == SIGINT ? "SIGINT"
                                                   : g_signal == SIGTERM ? "SIGTERM"
                                                                         : "SIGHUP");
    } else {
        printf_line(s, "modcp-sim: stopped");
    }
    free_members(s);
    free(s);
    return ok ? 0 : 1;
}
