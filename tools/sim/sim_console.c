/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the console: stdin, --script and --control lines, @member prefixes, simulator commands. */
#define _GNU_SOURCE
#include "sim.h"

/* ---- console input (main thread) ----------------------------------------------------- */

static void submit(member_t *m, const char *line, char *out, size_t cap)
{
    sim_t *s = m->sim;
    pthread_mutex_lock(&m->cmd_mu);
    snprintf(m->cmd_line, sizeof m->cmd_line, "%s", line);
    m->cmd_pending = true;
    m->cmd_done = false;
    atomic_store(&s->cmds, true);
    modcp_posix_event_signal(&s->sched_irq);
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
int find_member(const sim_t *s, const char *name)
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
            sayf(s, "%serror: fault %s", pre, err);
            return;
        }
    }
    sim_bus_fault_describe(s->bus, m->index, out, sizeof out);
    sayf(s, "%s%s", pre, out);
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
            say(s, "error: faults are made by the simulated line, which runs on a pty, "
                   "not on --device");
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
        say(s, out);
    } else {
        /* every line of the answer named by its member */
        char *save = NULL;
        for (char *l = strtok_r(out, "\n", &save); l != NULL; l = strtok_r(NULL, "\n", &save)) {
            sayf(s, "@%s %s", m->name, l);
        }
    }
    /* one slave: its faults' line once it had a fault (its status line last otherwise) */
    if (s->bus != NULL && strcasecmp(cmd, "status") == 0 &&
        (!s->solo || sim_bus_fault_get(s->bus, m->index).used)) {
        char f[512];
        sim_bus_fault_describe(s->bus, m->index, f, sizeof f);
        if (prefix) {
            sayf(s, "@%s %s", m->name, f);
        } else {
            say(s, f);
        }
    }
}

static void list_members(sim_t *s, const char *indent)
{
    for (size_t i = 0; i < s->n; i++) {
        sayf(s, "%s@%s = @%zu  slave %u  %s", indent, s->m[i].name, i + 1u,
                    (unsigned)s->m[i].conf->params.slave_addr, s->m[i].config);
    }
}

/* The simulator's own commands (quit, sleep, trace, members): *done when cmd was one;
 * returns false when the simulator should stop. */
static bool sim_cmd(sim_t *s, const char *cmd, const char *arg, int k, bool *done)
{
    *done = true;
    if (strcasecmp(cmd, "quit") == 0 || strcasecmp(cmd, "exit") == 0) {
        return false;
    }
    if (strcasecmp(cmd, "sleep") == 0) {
        char *end = NULL;
        long ms = strtol(arg, &end, 10);
        if (k < 2 || *end != '\0' || ms < 0 || ms > 3600000L) {
            say(s, "error: usage: sleep MS");
        } else {
            (void)sleep_ms(s, ms);
        }
    } else if (strcasecmp(cmd, "trace") == 0) {
        if (k == 2 && (strcasecmp(arg, "on") == 0 || strcasecmp(arg, "off") == 0)) {
            bool on = strcasecmp(arg, "on") == 0;
            if (on && !observe_trace(s)) {
                say(s, "error: trace: out of memory");
                return true;
            }
            atomic_store(&s->trace_on, on);
            if (s->bus != NULL) {
                sim_bus_trace(s->bus, strcasecmp(arg, "on") == 0);
            }
            sayf(s, "trace %s", arg);
        } else {
            say(s, "error: usage: trace on|off");
        }
    } else if (strcasecmp(cmd, "members") == 0) {
        list_members(s, "");
    } else {
        *done = false;
    }
    return true;
}

static void sim_help(sim_t *s)
{
    say(s, "  trace on|off        frame trace (simulator)");
    say(s, "  sleep MS            wait (simulator, for scripts)");
    say(s, "  quit                stop the simulator");
    if (s->bus != NULL) {
        say(s, "  members             the bus's members (@name = @index, address, config)");
        say(s, "  @M COMMAND          run COMMAND on member M (@b, @2; @* = all); without");
        say(s, "                      @M: status, diag and fault on all, the rest on the first");
        say(s, "  fault [SPEC]...     faults of a member's replies: drop=P crc=P exc06=P");
        say(s, "                      exc04=P (P in %), delay=MS|MIN-MAX, silent=N, noise=N,");
        say(s, "                      serial: parity=K framing=K break=MS gap=K:US de_cut=BITS;");
        say(s, "                      off; without SPEC: settings and counters");
        say(s, "  @master fault ...   the master's direction: the serial faults and early=US");
    }
}

/* "@name" at *rest: its index (MAX_MEMBERS: @*), -1 when there is none such (listed);
 * -2 without a prefix. *rest moves past it. */
static int member_prefix(sim_t *s, const char **rest)
{
    const char *r = *rest;
    while (*r == ' ' || *r == '\t') {
        r++;
    }
    *rest = r;
    if (*r != '@') {
        return -2;
    }
    char name[32];
    size_t k = 0;
    r++;
    while (*r != '\0' && *r != ' ' && *r != '\t' && k + 1u < sizeof name) {
        name[k++] = *r++;
    }
    name[k] = '\0';
    *rest = r;
    if (strcmp(name, "master") == 0 && s->bus != NULL) {
        return MASTER_TARGET;
    }
    int target = find_member(s, name);
    if (target < 0) {
        sayf(s, "error: no member @%s; members:", name);
        list_members(s, "  ");
    }
    return target;
}

/* `@master fault [SPEC]...`: the master's direction. */
static void master_cmd(sim_t *s, const char *rest, const char *cmd)
{
    if (strcasecmp(cmd, "fault") != 0 && strcasecmp(cmd, "faults") != 0) {
        say(s, "error: @master takes fault [SPEC]... (the master's direction of the line)");
        return;
    }
    char buf[256];
    snprintf(buf, sizeof buf, "%s", rest);
    char *save = NULL;
    (void)strtok_r(buf, " \t", &save); /* the command */
    for (char *tok = strtok_r(NULL, " \t", &save); tok != NULL; tok = strtok_r(NULL, " \t", &save)) {
        char err[200];
        if (!sim_bus_fault_set(s->bus, SIM_BUS_MASTER, tok, err, sizeof err)) {
            sayf(s, "@master error: fault %s", err);
            return;
        }
    }
    char out[512];
    sim_bus_fault_describe(s->bus, SIM_BUS_MASTER, out, sizeof out);
    sayf(s, "@master %s", out);
}

/* One console line; returns false when the simulator should stop. */
static bool handle_line(sim_t *s, const char *line)
{
    char cmd[32] = "";
    char arg[64] = "";
    const char *rest = line;
    int target = member_prefix(s, &rest);
    if (target == -1) {
        return true;
    }
    int k = sscanf(rest, " %31s %63s", cmd, arg);
    if (k >= 1 && target == -2) {
        bool done = false;
        bool go_on = sim_cmd(s, cmd, arg, k, &done);
        if (done) {
            return go_on;
        }
    }
    if (k < 1 && target != -2) {
        say(s, "error: @MEMBER needs a command (e.g. @b status)");
        return true;
    }
    if (target == MASTER_TARGET) {
        master_cmd(s, rest, cmd);
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
        sim_help(s);
    }
    if (k >= 1 && s->bus != NULL && strcasecmp(cmd, "status") == 0 &&
        sim_bus_master_faulted(s->bus)) {
        char out[512];
        sim_bus_fault_describe(s->bus, SIM_BUS_MASTER, out, sizeof out);
        sayf(s, "@master %s", out); /* the master's direction: its serial faults */
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

void wait_init(sim_t *s)
{
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
}

bool run_script(sim_t *s)
{
    wait_init(s); /* after the FB's init has finished (ready or CP_START_ERROR) */
    FILE *f = fopen(s->script, "r");
    if (f == NULL) {
        sayf(s, "modcp-sim: cannot open script %s: %s", s->script, strerror(errno));
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

void console_loop(sim_t *s, int control_fd)
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
