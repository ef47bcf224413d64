/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the line model's set-up: its settings, its members, the observers the
 * command line asks for (--capture FILE.pcap, --vcd FILE.vcd) and the sources beside the
 * master's pty (--replay FILE.pcap, --tcp [ADDR:]PORT). */
#define _GNU_SOURCE
#include "sim.h"

static void obs_print(void *user, const char *line)
{
    print_line(user, line);
}

bool observe_trace(sim_t *s)
{
    if (s->trace_obs != NULL) {
        return true;
    }
    s->trace_obs = sim_trace_obs_new(&s->wire, &s->trace_on, s->solo, obs_print, s);
    return s->trace_obs != NULL && sim_line_observe(&s->wire, sim_trace_obs_observer(s->trace_obs));
}

bool open_observers(sim_t *s, const modcp_params_t *p0)
{
    bool ascii = p0->framing == MODCP_FRAMING_ASCII;
    sim_line_cfg_t cfg = {p0->data_bits, (uint8_t)p0->parity, p0->stop_bits, ascii, p0->baud,
                          modcp_params_char_us(p0),
                          ascii ? p0->ascii_timeout_ms * 1000u : modcp_params_t35_us(p0)};
    sim_line_init(&s->wire, &cfg, s->t0_us64);
    for (size_t i = 0; i < s->n; i++) {
        sim_line_member(&s->wire, i, s->m[i].name, s->m[i].conf->params.slave_addr);
    }
    for (size_t i = 0; i < s->n_ext; i++) {
        sim_line_member(&s->wire, s->n + i, s->ext_name[i], 0);
    }
    char err[160];
    if (s->capture_path != NULL) {
        s->capture = sim_capture_open(&s->wire, s->capture_path, err, sizeof err);
        if (s->capture == NULL) {
            fprintf(stderr, "modcp-sim: --capture %s: %s\n", s->capture_path, err);
            return false;
        }
        (void)sim_line_observe(&s->wire, sim_capture_observer(s->capture));
    }
    if (s->vcd_path != NULL) {
        s->vcd = sim_vcd_open(&s->wire, s->vcd_path, err, sizeof err);
        if (s->vcd == NULL) {
            fprintf(stderr, "modcp-sim: --vcd %s: %s\n", s->vcd_path, err);
            return false;
        }
        (void)sim_line_observe(&s->wire, sim_vcd_observer(s->vcd));
    }
    if (atomic_load(&s->trace_on) && !observe_trace(s)) {
        fprintf(stderr, "modcp-sim: --trace: out of memory\n");
        return false;
    }
    return true;
}

void close_observers(sim_t *s)
{
    sim_line_close(&s->wire);
    sim_trace_obs_free(s->trace_obs);
    s->trace_obs = NULL;
    if (s->capture != NULL) {
        uint32_t n = sim_capture_close(s->capture);
        s->capture = NULL;
        printf_line(s, "modcp-sim: capture %s: %u records", s->capture_path, (unsigned)n);
    }
    if (s->vcd != NULL) {
        sim_vcd_close(s->vcd);
        s->vcd = NULL;
        printf_line(s, "modcp-sim: waveform %s written", s->vcd_path);
    }
}

bool load_replay(sim_t *s)
{
    char err[200];
    if (s->replay_path == NULL) {
        return true;
    }
    if (!sim_replay_load(&s->replay, s->replay_path, err, sizeof err)) {
        fprintf(stderr, "modcp-sim: --replay %s: %s\n", s->replay_path, err);
        return false;
    }
    return true;
}

static void replay_print(void *user, const char *line)
{
    print_line(user, line);
}

static void *replay_thread(void *arg)
{
    sim_t *s = arg;
    wait_init(s);
    const modcp_params_t *p0 = &s->m[0].conf->params;
    uint32_t t35 = p0->framing == MODCP_FRAMING_ASCII ? 20000u : modcp_params_t35_us(p0);
    const char *path = s->bus_mode ? s->line_port.path : s->m[0].port.path;
    if (!sim_replay_run(&s->replay, path, s->speed, t35, &s->stop, replay_print, s)) {
        printf_line(s, "modcp-sim: --replay: cannot open %s", path);
    } else {
        printf_line(s, "modcp-sim: replay %s: %zu requests, %zu differ", s->replay_path,
                    s->replay.requests, s->replay.differ);
    }
    if (g_sigpipe[1] >= 0) { /* the console loop ends: the simulator stops */
        char c = 'r';
        ssize_t w = write(g_sigpipe[1], &c, 1);
        (void)w;
    }
    return NULL;
}

void start_replay(sim_t *s)
{
    if (s->replay_path != NULL) {
        s->replay_started = modcp_posix_thread_start(&s->t_replay, replay_thread, s) == 0;
    }
}

void join_replay(sim_t *s)
{
    if (s->replay_started) {
        modcp_posix_thread_join(&s->t_replay);
        s->replay_started = false;
    }
    sim_replay_free(&s->replay);
}

bool listen_tcp(sim_t *s)
{
    char err[200];
    s->tcp.fd = -1;
    if (s->tcp_spec == NULL) {
        return true;
    }
    if (!sim_tcp_listen(&s->tcp, s->tcp_spec, err, sizeof err)) {
        fprintf(stderr, "modcp-sim: --tcp %s: %s\n", s->tcp_spec, err);
        return false;
    }
    return true;
}

static void *tcp_thread(void *arg)
{
    sim_t *s = arg;
    sim_tcp_run(&s->tcp, s->bus_mode ? s->line_port.path : s->m[0].port.path, &s->stop);
    return NULL;
}

void start_tcp(sim_t *s)
{
    if (s->tcp.fd >= 0 && s->tcp_spec != NULL) {
        s->tcp_started = modcp_posix_thread_start(&s->t_tcp, tcp_thread, s) == 0;
        printf_line(s, "modcp-sim: RTU over TCP on %s", s->tcp.where);
    }
}

void join_tcp(sim_t *s)
{
    if (s->tcp_started) {
        modcp_posix_thread_join(&s->t_tcp);
        s->tcp_started = false;
    }
    if (s->tcp_spec != NULL) {
        sim_tcp_close(&s->tcp);
    }
}
