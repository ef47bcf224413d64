/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the modcp slave on a pseudo-terminal (or a real serial device), or
 * several slaves on one line (a bus, see bus.h).
 *
 *   modcp-sim CONFIG.ini [CONFIG2.ini ...] [--pty-link PATH] [--device /dev/ttyX] [--trace]
 *             [--script FILE] [--cycle-ms N] [--set section.key=value]... [--control FIFO]
 *             [--bus] [--fault [@M:]KIND=VALUE]... [--seed N] [--qemu-member PTY]...
 *
 * Every slave (member, up to 247: one per Modbus address) is one modcp_cp_t + modcp_fb_t;
 * on a pty each member (one too: a line of one, so that it takes the line's faults) gets
 * a pty of its own and a bus thread joins them, any --qemu-member board's UART pty and
 * the master's pty into one line; on --device the one slave owns the serial port.
 *
 * The two sides of a member are joined only by the backplane (modcp_backplane_t):
 *   CP thread   one per member, the CP side: waits on the UART, the one-shot timer and
 *               the paced reply bytes (POSIX HAL) and feeds modcp_cp_on_rx / _on_timer /
 *               _on_tx_done / _poll with CLOCK_MONOTONIC microseconds, holding cp_mu
 *               while it runs the core. It sleeps until one of those events or a
 *               wake-up from the scheduler; a supervision tick (1 ms while a job runs,
 *               5 ms while a request or the start-up is in progress) drives job
 *               timeouts; a quiet CP (nothing to do) sleeps until it has work, and the
 *               scheduler's shared tick polls it (comm-loss supervision, LEDs). While a
 *               job is out it watches for the reply around the member's next FB call
 *               (port.expect_us); when it put blocks for the CPU side it signals the
 *               scheduler (sched_irq, the "backplane interrupt").
 *   scheduler   one thread for every member's CPU side (sim_sched.c): each member's
 *               cyclic user program calls modcp_fb_call every cycle_ms of that member
 *               (CP_START set from the first cycle on, like OB100) and executes queued
 *               console commands between two calls; with blocks from the CP waiting it
 *               watches the clock for the last CPU_SPIN_US before the call. When an FB
 *               call moved blocks on the backplane (a reply or parameters put, job
 *               blocks taken) it wakes the member's CP thread (modcp_posix_wake).
 * The parameter record travels from the CPU side to the CP over the backplane (the FB
 * sends it); the main thread reads the console (stdin, --script, --control FIFO). The
 * tool keeps a mutex-protected snapshot of the CP's diagnostics for the console. */
#define _GNU_SOURCE
#include "sim.h"

volatile sig_atomic_t g_signal;
int g_sigpipe[2] = {-1, -1};

static void on_signal(int sig)
{
    g_signal = sig;
    if (g_sigpipe[1] >= 0) {
        char c = 's';
        ssize_t r = write(g_sigpipe[1], &c, 1);
        (void)r;
    }
}

void print_line(sim_t *s, const char *line)
{
    pthread_mutex_lock(&s->print_mu);
    fputs(line, stdout);
    fputc('\n', stdout);
    fflush(stdout);
    pthread_mutex_unlock(&s->print_mu);
}

void printf_line(sim_t *s, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    print_line(s, buf);
}

void say(sim_t *s, const char *text)
{
    if (s->trace_obs == NULL || !atomic_load(&s->trace_on)) {
        print_line(s, text);
        return;
    }
    /* after every trace line of what happened before it */
    uint64_t t = since_start(s);
    const char *p = text;
    for (;;) {
        const char *nl = strchr(p, '\n');
        int len = nl != NULL ? (int)(nl - p) : (int)strlen(p);
        sim_line_note(&s->wire, t, SIM_SRC_MASTER, SIM_NOTE_OUTPUT, "%.*s", len, p);
        if (nl == NULL || nl[1] == '\0') {
            return;
        }
        p = nl + 1;
    }
}

void sayf(sim_t *s, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    say(s, buf);
}

static void trace_print(void *user, const char *line)
{
    member_t *m = user;
    print_line(m->sim, line);
}

uint64_t since_start(const sim_t *s)
{
    return modcp_posix_now_us64() - s->t0_us64;
}

/* A 32-bit clock value (modcp_posix_now_us) as us since start. */
uint64_t since_start_of(const sim_t *s, uint32_t now_us)
{
    uint64_t n64 = modcp_posix_now_us64();
    return n64 - (uint32_t)((uint32_t)n64 - now_us) - s->t0_us64;
}

static void on_tx(void *user, const uint8_t *buf, uint16_t len, uint32_t now_us)
{
    member_t *m = user;
    sim_t *s = m->sim;
    if (s->bus == NULL) {
        /* one slave: the UART sends byte k from now + k characters on */
        sim_line_put_frame(&s->wire, (int)m->index, buf, NULL, len, since_start_of(s, now_us));
    } else {
        sim_bus_tx(s->bus, m->index, buf, len, now_us); /* the bus puts it on the line */
    }
}


static void bus_print(void *user, const char *line)
{
    print_line(user, line);
}

/* Every member's configuration; 0 or the exit code. */
static int load_members(sim_t *s)
{
    for (size_t i = 0; i < s->n; i++) {
        member_t *m = &s->m[i];
        m->sim = s;
        m->index = i;
        m->config = s->configs[i];
        atomic_init(&m->fb_state, MODCP_FBST_STOPPED);
        member_name(s, i);
    }
    for (size_t i = 0; i < s->n; i++) {
        int rc = load_member(s, &s->m[i]);
        if (rc != 0) {
            return rc;
        }
    }
    return s->bus_mode && !same_line(s) ? 2 : 0;
}

static void close_ports(sim_t *s)
{
    if (s->bus_mode) {
        modcp_posix_close(&s->line_port);
        for (size_t i = 0; i < s->n; i++) {
            modcp_posix_close(&s->m[i].port);
        }
    }
}

/* --qemu-member ttys, raw; 0 or -1 (message printed). */
static int open_external(sim_t *s)
{
    for (size_t i = 0; i < s->n_ext; i++) {
        s->ext_fd[i] = open(s->ext_tty[i], O_RDWR | O_NOCTTY | O_NONBLOCK);
        struct termios tio;
        if (s->ext_fd[i] < 0 || tcgetattr(s->ext_fd[i], &tio) != 0) {
            fprintf(stderr, "modcp-sim: --qemu-member %s: %s\n", s->ext_tty[i],
                    s->ext_fd[i] < 0 ? strerror(errno) : "not a serial device");
            return -1;
        }
        cfmakeraw(&tio);
        (void)tcsetattr(s->ext_fd[i], TCSANOW, &tio);
        snprintf(s->ext_name[i], sizeof s->ext_name[i], i == 0u ? "qemu" : "qemu-%u",
                 (unsigned)(i + 1u) % 100u);
    }
    return 0;
}

/* The line: the first member's port (one slave), or the master's pty of the bus and one
 * pty per member. 0, or the exit code (message printed). */
static int open_line(sim_t *s, const modcp_params_t *p0, uint32_t char_us)
{
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
        if (orc == 0 && open_external(s) != 0) {
            return 1;
        }
    }
    if (orc != 0) {
        open_failed(s->device, s->pty_link, orc);
        close_ports(s);
        return 1;
    }
    return 0;
}

/* The bus thread's state; false (message printed) on failure. */
static bool make_bus(sim_t *s, const modcp_params_t *p0, uint32_t char_us)
{
    bool ascii = p0->framing == MODCP_FRAMING_ASCII;
    sim_line_cfg_t line = {p0->data_bits, (uint8_t)p0->parity, p0->stop_bits, ascii, p0->baud,
                           char_us, ascii ? p0->ascii_timeout_ms * 1000u : modcp_params_t35_us(p0)};
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
    if (s->bus == NULL) {
        fprintf(stderr, "modcp-sim: cannot set up the bus\n");
        return false;
    }
    sim_bus_set_line(s->bus, &s->wire, s->solo);
    for (size_t i = 0; i < s->n; i++) {
        sim_bus_member_quiet(s->bus, i, &s->m[i].cp_quiet);
    }
    if (!apply_cli_faults(s)) {
        sim_bus_free(s->bus);
        s->bus = NULL;
        return false;
    }
    sim_bus_trace(s->bus, atomic_load(&s->trace_on));
    return true;
}

/* Each member: the two sides and the interface between them. */
static bool init_sides(sim_t *s)
{
    if (modcp_posix_event_open(&s->sched_irq) != 0) {
        fprintf(stderr, "modcp-sim: cannot make a pipe\n");
        return false;
    }
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
        pthread_mutex_init(&m->cp_mu, NULL);
        atomic_init(&m->cp_quiet, false);
        modcp_bp_init(&m->bp);
        modcp_cp_init(&m->cp, &m->hal, &m->bp);
        modcp_fb_init(&m->fb, &m->bp, &m->memory.mem, m->record, m->record_len,
                      m->conf->work_db, p->start_time_ms);
        bool ascii = p->framing == MODCP_FRAMING_ASCII;
        uint64_t gap = ascii ? (uint64_t)p->ascii_timeout_ms * 1000u : modcp_params_t35_us(p);
        sim_trace_init(&m->tr, p->slave_addr, ascii, gap, trace_print, m);
        if (!s->solo) {
            char ev[32];
            snprintf(ev, sizeof ev, "@%s ", m->name);
            sim_trace_labels(&m->tr, NULL, NULL, ev);
        }
        if (s->solo) {
            sim_latlog_open(&m->lat);
        }
        cp_snapshot(m);
    }
    pthread_condattr_destroy(&ca);
    return true;
}

typedef struct {
    int fd, wfd;
    bool made;
} control_t;

/* The console FIFO (--control). */
static void open_control(const sim_t *s, control_t *c)
{
    c->fd = -1;
    c->wfd = -1;
    c->made = false;
    if (s->control == NULL) {
        return;
    }
    struct stat st;
    if (stat(s->control, &st) != 0 && mkfifo(s->control, 0600) == 0) {
        c->made = true;
    }
    c->fd = open(s->control, O_RDONLY | O_NONBLOCK);
    if (c->fd >= 0) {
        c->wfd = open(s->control, O_WRONLY | O_NONBLOCK); /* never see EOF */
    } else {
        fprintf(stderr, "modcp-sim: cannot open %s: %s\n", s->control, strerror(errno));
    }
}

static void close_control(const sim_t *s, const control_t *c)
{
    if (c->fd >= 0) {
        close(c->fd);
    }
    if (c->wfd >= 0) {
        close(c->wfd);
    }
    if (c->made) {
        (void)unlink(s->control);
    }
}

/* Signals are handled by the main thread only: blocked here (old: the mask before), the
 * threads started then inherit the block. false: no pipe. */
static bool install_signals(sigset_t *old)
{
    if (pipe(g_sigpipe) != 0) {
        return false;
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
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, old);
    return true;
}

static void print_startup(sim_t *s, const modcp_params_t *p0)
{
    const char *line_path = s->bus_mode ? s->line_port.path : s->m[0].port.path;
    const char *line_link = s->bus_mode ? s->line_port.link : s->m[0].port.link;
    char settings[48];
    modcp_conf_line_settings(p0, settings, sizeof settings);
    if (s->solo) {
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
}

/* The bus thread, every member's CP thread and the scheduler (every member's CPU side);
 * returns how many members started (0 when the scheduler did not). */
static size_t start_threads(sim_t *s, modcp_posix_thread_t *t_bus, bool *ok)
{
    *ok = true;
    if (s->bus != NULL) {
        *ok = modcp_posix_thread_start(t_bus, sim_bus_thread, s->bus) == 0;
    }
    s->cpu_t0_us64 = modcp_posix_now_us64();
    size_t started = 0;
    for (size_t i = 0; *ok && i < s->n; i++) {
        *ok = modcp_posix_thread_start(&s->m[i].t_cp, cp_thread, &s->m[i]) == 0;
        if (*ok) {
            started++;
        }
    }
    if (*ok && modcp_posix_thread_start(&s->t_sched, sched_thread, s) != 0) {
        *ok = false;
    }
    if (!*ok) {
        atomic_store(&s->stop, true);
        for (size_t i = 0; i < started; i++) {
            modcp_posix_wake(&s->m[i].port);
            modcp_posix_thread_join(&s->m[i].t_cp);
        }
        started = 0;
    }
    return started;
}

static void stop_threads(sim_t *s, size_t started, modcp_posix_thread_t *t_bus)
{
    atomic_store(&s->stop, true);
    if (started > 0u) {
        modcp_posix_event_signal(&s->sched_irq);
        modcp_posix_thread_join(&s->t_sched);
    }
    for (size_t i = 0; i < started; i++) {
        member_t *m = &s->m[i];
        modcp_posix_wake(&m->port);
        pthread_mutex_lock(&m->cmd_mu);
        pthread_cond_broadcast(&m->cmd_cv);
        pthread_mutex_unlock(&m->cmd_mu);
    }
    for (size_t i = 0; i < started; i++) {
        modcp_posix_thread_join(&s->m[i].t_cp);
    }
    if (s->bus != NULL) {
        sim_bus_stop(s->bus);
        modcp_posix_thread_join(t_bus);
        sim_bus_free(s->bus);
        s->bus = NULL;
        modcp_posix_close(&s->line_port);
    }
    for (size_t i = 0; i < s->n; i++) {
        modcp_posix_close(&s->m[i].port);
        sim_latlog_close(&s->m[i].lat);
    }
    modcp_posix_event_close(&s->sched_irq);
}

/* Everything opened and set up; 0 or the exit code (cleaned up but s). */
static int set_up(sim_t *s)
{
    int rc = load_members(s);
    if (rc != 0) {
        free_members(s);
        return rc;
    }
    const modcp_params_t *p0 = &s->m[0].conf->params;
    uint32_t char_us = modcp_params_char_us(p0);
    rc = open_line(s, p0, char_us);
    if (rc != 0) {
        free_members(s);
        return rc;
    }
    s->t0_us64 = modcp_posix_now_us64();
    if (!load_replay(s) || !listen_tcp(s) || !open_observers(s, p0) ||
        (s->bus_mode && !make_bus(s, p0, char_us)) || !init_sides(s)) {
        join_tcp(s);
        close_observers(s);
        close_ports(s);
        free_members(s);
        return 1;
    }
    return 0;
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
    atomic_init(&s->cmds, false);
    int rc = parse_args(s, argc, argv);
    if (rc == 0) {
        pthread_mutex_init(&s->print_mu, NULL);
        rc = set_up(s);
    }
    if (rc != 0) {
        free(s->sets);
        free(s->faults);
        free(s);
        return rc < 0 ? 0 : rc; /* -1: --version printed */
    }
    control_t ctl;
    open_control(s, &ctl);
    sigset_t old;
    if (!install_signals(&old)) {
        return 1;
    }
    print_startup(s, &s->m[0].conf->params);
    start_tcp(s);
    modcp_posix_thread_t t_bus;
    bool ok = true;
    size_t started = start_threads(s, &t_bus, &ok);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    bool go_on = ok;
    if (!ok) {
        fprintf(stderr, "modcp-sim: cannot start threads\n");
    }
    if (go_on && s->script != NULL) {
        go_on = run_script(s);
    }
    if (go_on) {
        start_replay(s);
        console_loop(s, ctl.fd);
    }
    atomic_store(&s->stop, true);
    join_replay(s);
    join_tcp(s);
    stop_threads(s, started, &t_bus);
    close_observers(s);
    close_control(s, &ctl);
    if (g_signal != 0) {
        printf_line(s, "modcp-sim: stopped (%s)", g_signal == SIGINT ? "SIGINT"
                                                   : g_signal == SIGTERM ? "SIGTERM"
                                                                         : "SIGHUP");
    } else {
        printf_line(s, "modcp-sim: stopped");
    }
    free_members(s);
    int rc_end = !ok ? 1 : s->replay.differ > 0u ? 3 : 0;
    free(s->sets);
    free(s->faults);
    free(s);
    return rc_end;
}
