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
#ifndef MODCP_SIM_SIM_H
#define MODCP_SIM_SIM_H

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
#include "capture.h"
#include "line.h"
#include "replay.h"
#include "tcp.h"
#include "vcd.h"
#include "latlog.h"
#include "trace.h"

#define RX_CHUNK 512
#define CMD_OUT_MAX 8192
/* Supervision ticks of the CP thread; nothing on a request's path waits for them. */
#define IDLE_TICK_US 5000u
#define BUSY_TICK_US 1000u
/* The CPU thread watches the clock for the last CPU_SPIN_US before an FB call that
 * blocks from the CP wait for (only then). */
#define CPU_SPIN_US 50u

#define MAX_MEMBERS SIM_BUS_MAX_MEMBERS
/* @master: the master's direction of the line (its serial faults) */
#define MASTER_TARGET (-3)

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
    const char *configs[SIM_BUS_MAX_SLAVES];
    size_t n;
    const char *pty_link;
    const char *device;
    const char *script;
    const char *control;
    const char **sets; /* --set and --fault: room for argc each (no limit) */
    size_t set_count;
    const char **faults;
    size_t fault_count;
    size_t arg_cap;
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
    /* the line model and its observers (--capture, --vcd) */
    const char *capture_path;
    const char *vcd_path;
    sim_line_t wire;
    sim_capture_t *capture;
    sim_vcd_t *vcd;
    /* --replay FILE.pcap [--speed F] */
    const char *replay_path;
    double speed;
    sim_replay_t replay;
    modcp_posix_thread_t t_replay;
    bool replay_started;
    /* --tcp [ADDR:]PORT: RTU over TCP */
    const char *tcp_spec;
    sim_tcp_t tcp;
    modcp_posix_thread_t t_tcp;
    bool tcp_started;
    /* output */
    pthread_mutex_t print_mu;
};

/* the main thread's signal (0: none) and the pipe its handler writes to */
extern volatile sig_atomic_t g_signal;
extern int g_sigpipe[2];

/* output (sim.c): one line at a time, from any thread */
void print_line(sim_t *s, const char *line);
void printf_line(sim_t *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
uint64_t since_start(const sim_t *s);
uint64_t since_start_of(const sim_t *s, uint32_t now_us);

/* CP thread (sim_cp.c) */
void cp_snapshot(member_t *m);
int this_core(void);
bool ring_pending(const modcp_ring_t *r);
void *cp_thread(void *arg);
/* CPU thread (sim_cpu.c) */
void timespec_of(uint64_t us, struct timespec *ts);
void *cpu_thread(void *arg);
/* console (sim_console.c) */
int find_member(const sim_t *s, const char *name);
/* Waits until every member's FB initialisation has finished (ready or CP_START_ERROR). */
void wait_init(sim_t *s);
bool run_script(sim_t *s);
void console_loop(sim_t *s, int control_fd);
/* command line (sim_args.c) */
int parse_args(sim_t *s, int argc, char **argv);
/* set-up (sim_setup.c) */
void open_failed(const char *device, const char *link, int orc);
void member_name(sim_t *s, size_t i);
void free_members(sim_t *s);
int load_member(sim_t *s, member_t *m);
bool same_line(const sim_t *s);
bool apply_cli_faults(sim_t *s);
/* the line model and its observers: false (message printed) when a file cannot be made */
bool open_observers(sim_t *s, const modcp_params_t *p0);
void close_observers(sim_t *s);
/* --replay: load the capture (false: message printed), start it after the start-up,
 * wait for it; the simulator stops when it has played the capture. */
bool load_replay(sim_t *s);
void start_replay(sim_t *s);
void join_replay(sim_t *s);
/* --tcp: listen (false: message printed), serve clients on the line's pty, stop. */
bool listen_tcp(sim_t *s);
void start_tcp(sim_t *s);
void join_tcp(sim_t *s);

#endif
