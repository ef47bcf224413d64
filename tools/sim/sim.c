/* modcp-sim — the modcp slave on a pseudo-terminal (or a real serial device).
 *
 *   modcp-sim CONFIG.ini [--pty-link PATH] [--device /dev/ttyX] [--trace]
 *             [--script FILE] [--cycle-ms N] [--set section.key=value]... [--control FIFO]
 *
 * Two threads joined only by the backplane (modcp_backplane_t):
 *   CP thread   the CP side: waits on the UART, the one-shot timer and the paced
 *               reply bytes (POSIX HAL) and feeds modcp_cp_on_rx / _on_timer /
 *               _on_tx_done / _poll with CLOCK_MONOTONIC microseconds. It sleeps until
 *               one of those events or a wake-up from the CPU thread; a supervision
 *               tick (1 ms while a job runs, else 5 ms) only drives job timeouts,
 *               comm-loss supervision and the LEDs.
 *   CPU thread  the controller: a cyclic user program that calls modcp_fb_call every
 *               cycle_ms (CP_START set from the first cycle on, like OB100) and executes
 *               queued console commands between two calls. When an FB call moved
 *               blocks on the backplane (a reply or parameters put, job blocks taken)
 *               it wakes the CP thread (modcp_posix_wake).
 * The parameter record travels from the CPU side to the CP over the backplane (the FB
 * sends it); the main thread reads the console (stdin, --script, --control FIFO). The
 * tool keeps a mutex-protected snapshot of the CP's diagnostics for the console. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "modcp/backplane.h"
#include "modcp/console.h"
#include "modcp/cp.h"
#include "modcp/fb.h"
#include "modcp/hal_posix.h"
#include "modcp_conf.h"
#include "trace.h"

#define MAX_SETS 32
#define RX_CHUNK 512
#define CMD_OUT_MAX 8192
/* Supervision ticks of the CP thread; nothing on a request's path waits for them. */
#define IDLE_TICK_US 5000u
#define BUSY_TICK_US 1000u

typedef struct {
    /* options */
    const char *config;
    const char *pty_link;
    const char *device;
    const char *script;
    const char *control;
    const char *sets[MAX_SETS];
    size_t set_count;
    long cycle_override;
    /* configuration */
    modcp_conf_t *conf;
    modcp_conf_memory_t memory;
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    uint16_t record_len;
    uint32_t cycle_ms;
    /* the only thing both sides share */
    modcp_backplane_t bp;
    atomic_bool stop;
    atomic_bool trace_on;
    uint64_t t0_us64;
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
    /* output */
    pthread_mutex_t print_mu;
} sim_t;

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
    print_line(user, line);
}

static uint64_t since_start(const sim_t *s)
{
    return modcp_posix_now_us64() - s->t0_us64;
}

static void on_tx(void *user, const uint8_t *buf, uint16_t len, uint32_t now_us)
{
    sim_t *s = user;
    (void)now_us;
    if (atomic_load(&s->trace_on)) {
        sim_trace_tx(&s->tr, buf, len, since_start(s));
    }
}

/* ---- CP thread ----------------------------------------------------------------- */

static void cp_snapshot(sim_t *s)
{
    pthread_mutex_lock(&s->snap_mu);
    s->snap_diag = s->cp.diag;
    s->snap_configured = s->cp.configured;
    s->snap_ready = modcp_cp_ready(&s->cp);
    s->snap_param_event = s->cp.param_event;
    pthread_mutex_unlock(&s->snap_mu);
}

static void trace_events(sim_t *s)
{
    uint32_t total = s->cp.diag.events_total;
    if (total == s->events_seen) {
        return;
    }
    uint32_t n = total - s->events_seen;
    s->events_seen = total;
    if (!atomic_load(&s->trace_on)) {
        return;
    }
    if (n > s->cp.diag.buffer_len) {
        n = s->cp.diag.buffer_len;
    }
    uint64_t t = since_start(s);
    for (uint32_t i = n; i > 0u; i--) {
        sim_trace_event(&s->tr, s->cp.diag.buffer[i - 1u], t);
    }
}

static void *cp_thread(void *arg)
{
    sim_t *s = arg;
    static modcp_posix_rx_t rx[RX_CHUNK];
    while (!atomic_load(&s->stop)) {
        bool idle = modcp_cp_ready(&s->cp) && !modcp_job_busy(&s->cp.job) && !s->cp.request_pending;
        bool tx_done = false, timer = false;
        uint32_t now = 0;
        int n = modcp_posix_wait(&s->port, idle ? IDLE_TICK_US : BUSY_TICK_US, rx, RX_CHUNK,
                                 &tx_done, &timer, &now);
        if (n < 0) {
            printf_line(s, "modcp-sim: read error on %s: %s", s->port.path, strerror(-n));
            atomic_store(&s->stop, true);
            break;
        }
        bool tr = atomic_load(&s->trace_on);
        /* the trace's time is exactly the core's `now` (widened to 64 bits), so its
         * t3.5 frame cut agrees with the core's timer: a frame is printed before the
         * events its end raises */
        uint64_t n64 = modcp_posix_now_us64();
        uint64_t t = n64 - (uint32_t)((uint32_t)n64 - now) - s->t0_us64;
        s->port.now_us = now;
        bool cts = true, dsr = true;
        if (modcp_posix_modem_inputs(&s->port, &cts, &dsr)) {
            modcp_cp_on_signals(&s->cp, cts, dsr, now);
        }
        if (tx_done) {
            modcp_cp_on_tx_done(&s->cp, now);
        }
        if (timer) {
            modcp_cp_on_timer(&s->cp, now);
        }
        for (int i = 0; i < n; i++) {
            if (tr) {
                sim_trace_rx(&s->tr, rx[i].byte, rx[i].errors, t);
            }
            if (rx[i].errors != 0u) {
                modcp_cp_on_line_error(&s->cp, rx[i].errors, now);
            } else {
                modcp_cp_on_rx(&s->cp, rx[i].byte, now);
            }
        }
        modcp_cp_poll(&s->cp, now);
        if (tr) {
            sim_trace_poll(&s->tr, t);
        }
        trace_events(s);
        cp_snapshot(s);
    }
    return NULL;
}

/* ---- CPU thread ------------------------------------------------------------------- */

static void exec_console(sim_t *s)
{
    modcp_console_env_t env;
    modcp_diag_t diag;
    memset(&env, 0, sizeof env);
    pthread_mutex_lock(&s->snap_mu);
    diag = s->snap_diag;
    env.cp_configured = s->snap_configured;
    env.cp_ready = s->snap_ready;
    env.cp_param_event = s->snap_param_event;
    pthread_mutex_unlock(&s->snap_mu);
    env.mem = &s->memory.mem;
    env.diag = &diag;
    env.fb = &s->fb;
    env.paused = &s->paused;
    env.cp_start = &s->fb_in.cp_start;
    env.cycles = s->cycles;
    /* the CP's status area, read from the backplane like any user program would */
    modcp_cp_status_t cst;
    for (int k = 0; k < 100; k++) {
        if (modcp_bp_read_status(&s->bp, &cst)) {
            env.cp_status = &cst;
            break;
        }
    }
    (void)modcp_console_exec(&env, s->cmd_line, s->cmd_out, sizeof s->cmd_out);
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

static void *cpu_thread(void *arg)
{
    sim_t *s = arg;
    uint64_t next = modcp_posix_now_us64();
    uint8_t last_state = 0xFF;
    bool ready_printed = false;
    s->fb_in.cp_start = true; /* OB100: CP_START set at start-up */
    while (!atomic_load(&s->stop)) {
        pthread_mutex_lock(&s->cmd_mu);
        for (;;) {
            if (atomic_load(&s->stop)) {
                break;
            }
            if (s->cmd_pending) {
                exec_console(s);
                s->cmd_pending = false;
                s->cmd_done = true;
                pthread_cond_broadcast(&s->cmd_cv);
                continue;
            }
            if (modcp_posix_now_us64() >= next) {
                break;
            }
            struct timespec ts;
            timespec_of(next, &ts);
            (void)pthread_cond_timedwait(&s->cmd_cv, &s->cmd_mu, &ts);
        }
        pthread_mutex_unlock(&s->cmd_mu);
        if (atomic_load(&s->stop)) {
            break;
        }
        if (!s->paused) {
            modcp_fb_out_t out;
            uint32_t moved0 = bp_moves(&s->bp);
            modcp_fb_call(&s->fb, &s->fb_in, &out, modcp_posix_now_ms());
            if (bp_moves(&s->bp) != moved0) {
                modcp_posix_wake(&s->port); /* the CP has blocks to take or room to put */
            }
            s->cycles++;
            if (s->fb.state != last_state) {
                last_state = s->fb.state;
                atomic_store(&s->fb_state, last_state);
                if (last_state == MODCP_FBST_RUN && out.cp_start_ok && !ready_printed) {
                    ready_printed = true;
                    printf_line(s, "modcp-sim: ready");
                } else if (last_state == MODCP_FBST_FAILED) {
                    char en[16];
                    modcp_console_event_name((modcp_event_t)out.error_info, en, sizeof en);
                    printf_line(s,
                                "modcp-sim: CP_START_ERROR, ERROR_NR %u ERROR_INFO 0x%04X %s (%s)",
                                (unsigned)out.error_nr, (unsigned)out.error_info, en,
                                modcp_event_text((modcp_event_t)out.error_info));
                    ready_printed = false;
                } else if (last_state != MODCP_FBST_RUN) {
                    ready_printed = false;
                }
            }
        }
        uint64_t period = (uint64_t)s->cycle_ms * 1000u;
        next += period;
        uint64_t now = modcp_posix_now_us64();
        if (next + period < now) {
            next = now + period; /* overrun: do not catch up with a burst of cycles */
        }
    }
    return NULL;
}

/* ---- console input (main thread) ----------------------------------------------------- */

static void submit(sim_t *s, const char *line, char *out, size_t cap)
{
    pthread_mutex_lock(&s->cmd_mu);
    snprintf(s->cmd_line, sizeof s->cmd_line, "%s", line);
    s->cmd_pending = true;
    s->cmd_done = false;
    pthread_cond_broadcast(&s->cmd_cv);
    while (!s->cmd_done && !atomic_load(&s->stop)) {
        struct timespec ts;
        timespec_of(modcp_posix_now_us64() + 100000u, &ts);
        (void)pthread_cond_timedwait(&s->cmd_cv, &s->cmd_mu, &ts);
    }
    snprintf(out, cap, "%s", s->cmd_done ? s->cmd_out : "error: stopped");
    pthread_mutex_unlock(&s->cmd_mu);
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

/* One console line; returns false when the simulator should stop. */
static bool handle_line(sim_t *s, const char *line)
{
    char cmd[32] = "";
    char arg[64] = "";
    int k = sscanf(line, " %31s %63s", cmd, arg);
    if (k >= 1) {
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
                printf_line(s, "trace %s", arg);
            } else {
                print_line(s, "error: usage: trace on|off");
            }
            return true;
        }
    }
    char out[CMD_OUT_MAX];
    submit(s, line, out, sizeof out);
    if (out[0] != '\0') {
        print_line(s, out);
    }
    if (k >= 1 && (strcasecmp(cmd, "help") == 0 || strcmp(cmd, "?") == 0)) {
        print_line(s, "  trace on|off        frame trace (simulator)");
        print_line(s, "  sleep MS            wait (simulator, for scripts)");
        print_line(s, "  quit                stop the simulator");
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
    uint64_t limit = modcp_posix_now_us64() +
                     ((uint64_t)s->conf->params.start_time_ms + 2000u) * 1000u;
    while (!atomic_load(&s->stop) && g_signal == 0 && modcp_posix_now_us64() < limit) {
        int st = atomic_load(&s->fb_state);
        if (st == MODCP_FBST_RUN || st == MODCP_FBST_FAILED) {
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
            "usage: modcp-sim CONFIG.ini [--pty-link PATH] [--device /dev/ttyX] [--trace]\n"
            "                 [--script FILE] [--cycle-ms N] [--set section.key=value]...\n"
            "                 [--control FIFO]\n"
            "  --pty-link PATH   also make PATH a symlink to the pseudo-terminal\n"
            "  --device PATH     use a real serial device (termios from the parameters)\n"
            "  --trace           print every frame received and sent, and every event\n"
            "  --script FILE     run console commands from FILE once the FB is initialised\n"
            "  --cycle-ms N      cycle time of the user program (default: [cpu] cycle_ms)\n"
            "  --set S.K=V       override a key of the configuration (e.g. serial.baud=115200)\n"
            "  --control FIFO    also read console commands from a named pipe (made if missing)\n"
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
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool has = i + 1 < argc;
        const char *needs = option_value(a);
        if (needs != NULL && (!has || (argv[i + 1][0] == '-' && argv[i + 1][1] == '-'))) {
            fprintf(stderr, "modcp-sim: %s needs a value (%s)\n", a, needs);
            return 1;
        }
        if (strcmp(a, "--pty-link") == 0 && has) {
            s->pty_link = argv[++i];
        } else if (strcmp(a, "--device") == 0 && has) {
            s->device = argv[++i];
        } else if (strcmp(a, "--trace") == 0) {
            atomic_store(&s->trace_on, true);
        } else if (strcmp(a, "--script") == 0 && has) {
            s->script = argv[++i];
        } else if (strcmp(a, "--control") == 0 && has) {
            s->control = argv[++i];
        } else if (strcmp(a, "--cycle-ms") == 0 && has) {
            char *end = NULL;
            long v = strtol(argv[++i], &end, 10);
            if (*end != '\0' || v < 1 || v > 60000) {
                fprintf(stderr, "modcp-sim: --cycle-ms must be 1..60000\n");
                return 1;
            }
            s->cycle_override = v;
        } else if (strcmp(a, "--set") == 0 && has) {
            if (s->set_count >= MAX_SETS) {
                fprintf(stderr, "modcp-sim: too many --set\n");
                return 1;
            }
            s->sets[s->set_count++] = argv[++i];
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            return usage();
        } else if (a[0] == '-' || s->config != NULL) {
            fprintf(stderr, "modcp-sim: unexpected argument '%s'\n", a);
            return usage();
        } else {
            s->config = a;
        }
    }
    return s->config == NULL ? usage() : 0;
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
static size_t print_problems(const modcp_conf_t *c, const char *const *sets, size_t nsets)
{
    size_t shown = c->problem_count < MODCP_CONF_MAX_PROBLEMS ? c->problem_count
                                                              : MODCP_CONF_MAX_PROBLEMS;
    size_t from_set = 0;
    for (size_t i = 0; i < shown; i++) {
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
            fprintf(stderr, "--set %s: %s\n", arg, rest);
            if (c->problems[i].fatal) {
                from_set++;
            }
        } else {
            fprintf(stderr, "%s\n", txt);
        }
    }
    return from_set;
}

int main(int argc, char **argv)
{
    sim_t *s = calloc(1, sizeof *s);
    if (s == NULL) {
        return 1;
    }
    atomic_init(&s->stop, false);
    atomic_init(&s->trace_on, false);
    atomic_init(&s->fb_state, MODCP_FBST_STOPPED);
    int rc = parse_args(s, argc, argv);
    if (rc != 0) {
        free(s);
        return rc;
    }

    /* configuration: the same code and messages as modcp-conf check */
    s->conf = malloc(sizeof *s->conf);
    if (s->conf == NULL) {
        free(s);
        return 1;
    }
    size_t fatal = modcp_conf_load_ex(s->conf, s->config, s->sets, s->set_count);
    size_t from_set = print_problems(s->conf, s->sets, s->set_count);
    if (fatal > 0u) {
        if (from_set == fatal) {
            fprintf(stderr, "modcp-sim: --set: %zu problem%s, not started\n", fatal,
                    fatal == 1u ? "" : "s");
        } else {
            fprintf(stderr, "modcp-sim: %s%s: %zu problem%s, not started\n", s->config,
                    from_set > 0u ? " and --set" : "", fatal, fatal == 1u ? "" : "s");
        }
        free(s->conf);
        free(s);
        return 2;
    }
    size_t rlen = modcp_conf_record(s->conf, s->record, sizeof s->record);
    if (rlen == 0u || !modcp_conf_memory_alloc(s->conf, &s->memory)) {
        fprintf(stderr, "modcp-sim: cannot build the parameter record / memory\n");
        free(s->conf);
        free(s);
        return 1;
    }
    s->record_len = (uint16_t)rlen;
    s->cycle_ms = s->cycle_override > 0 ? (uint32_t)s->cycle_override : s->conf->cycle_ms;
    const modcp_params_t *p = &s->conf->params;
    uint32_t char_us = modcp_params_char_us(p);

    /* the line */
    int orc = s->device != NULL
                  ? modcp_posix_open_device(&s->port, s->device, p->baud, p->data_bits, p->parity,
                                            p->stop_bits, char_us)
                  : modcp_posix_open_pty(&s->port, s->pty_link, char_us);
    if (orc != 0) {
        open_failed(s->device, s->pty_link, orc);
        modcp_conf_memory_free(&s->memory);
        free(s->conf);
        free(s);
        return 1;
    }
    s->port.on_tx = on_tx;
    s->port.on_tx_user = s;
    s->port.now_us = modcp_posix_now_us();
    modcp_posix_hal(&s->port, &s->hal);

    /* the two sides and the interface between them */
    pthread_mutex_init(&s->snap_mu, NULL);
    pthread_mutex_init(&s->cmd_mu, NULL);
    pthread_mutex_init(&s->print_mu, NULL);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&s->cmd_cv, &ca);
    pthread_condattr_destroy(&ca);
    s->t0_us64 = modcp_posix_now_us64();
    modcp_bp_init(&s->bp);
    modcp_cp_init(&s->cp, &s->hal, &s->bp);
    modcp_fb_init(&s->fb, &s->bp, &s->memory.mem, s->record, s->record_len, s->conf->work_db,
                  p->start_time_ms);
    bool ascii = p->framing == MODCP_FRAMING_ASCII;
    uint64_t gap = ascii ? (uint64_t)p->ascii_timeout_ms * 1000u : modcp_params_t35_us(p);
    sim_trace_init(&s->tr, p->slave_addr, ascii, gap, trace_print, s);
    cp_snapshot(s);

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
    modcp_conf_line_settings(p, settings, sizeof settings);
    printf_line(s, "modcp-sim: slave %u on %s (%s)", (unsigned)p->slave_addr, s->port.path, settings);
    if (s->port.link[0] != '\0') {
        printf_line(s, "modcp-sim: link %s -> %s", s->port.link, s->port.path);
    }

    modcp_posix_thread_t t_cp, t_cpu;
    if (modcp_posix_thread_start(&t_cp, cp_thread, s) != 0 ||
        modcp_posix_thread_start(&t_cpu, cpu_thread, s) != 0) {
        fprintf(stderr, "modcp-sim: cannot start threads\n");
        modcp_posix_close(&s->port);
        return 1;
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);

    bool go_on = true;
    if (s->script != NULL) {
        go_on = run_script(s);
    }
    if (go_on) {
        console_loop(s, control_fd);
    }

    atomic_store(&s->stop, true);
    modcp_posix_wake(&s->port);
    pthread_mutex_lock(&s->cmd_mu);
    pthread_cond_broadcast(&s->cmd_cv);
    pthread_mutex_unlock(&s->cmd_mu);
    modcp_posix_thread_join(&t_cpu);
    modcp_posix_thread_join(&t_cp);
    modcp_posix_close(&s->port);
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
    modcp_conf_memory_free(&s->memory);
    free(s->conf);
    free(s);
    return 0;
}
