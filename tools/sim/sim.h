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
#include "trace_obs.h"

#define RX_CHUNK 512
#define CMD_OUT_MAX 8192
/* Supervision ticks of the CP side; nothing on a request's path waits for them. A CP
 * with nothing to do (no job, no request, no timer, no reply on the line: "quiet") is
 * not woken by its own tick: the scheduler visits every quiet CP on one shared tick of
 * QUIET_TICK_US, and its thread sleeps until it has work (QUIET_MAX_US at most). */
#define IDLE_TICK_US 5000u
#define QUIET_TICK_US 10000u
#define BUSY_TICK_US 1000u
#define QUIET_MAX_US 1000000u
/* The CPU thread watches the clock for the last CPU_SPIN_US before an FB call that
 * blocks from the CP wait for (only then). */
#define CPU_SPIN_US 50u

#define MAX_MEMBERS SIM_BUS_MAX_MEMBERS
/* @master: the master's direction of the line (its serial faults) */
#define MASTER_TARGET (-3)

typedef struct sim sim_t;

typedef struct {
    uint8_t last_state;
    bool ready_printed, counted;
} cpu_report_t;

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
    modcp_posix_thread_t t_cp;
    /* the CP side runs under cp_mu: its own thread with work, or the scheduler's shared
     * tick while the thread sleeps quiet (cp_quiet) */
    pthread_mutex_t cp_mu;
    atomic_bool cp_quiet;
    uint32_t cp_put_seen; /* CP side: to_cpu.head when it last interrupted */
    uint64_t cpu_next; /* scheduler: when this member's next FB call is due (us) */
    cpu_report_t rep;  /* scheduler: the FB state last reported */
    atomic_uint cpu_due; /* scheduler: cpu_next's low 32 bits (for the CP side) */
    atomic_int cpu_core; /* scheduler: the processor it last ran on (-1: unknown) */
    atomic_bool cpu_calls; /* scheduler: the FB is called (not paused) */
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
    bool bus_named; /* --bus */
    bool solo;      /* one slave, shown as one (not a bus of one: --bus) */
    uint32_t seed;
    atomic_bool stop;
    atomic_bool trace_on;
    uint64_t t0_us64;
    uint64_t cpu_t0_us64; /* all members' CPU cycles in phase from here */
    /* the scheduler (sim_sched.c): every member's CPU side and the quiet CPs' tick, one
     * thread; woken by sched_irq: a console command (cmds), the stop, or a CP side's
     * "backplane interrupt" (the CP put blocks for the CPU side) */
    modcp_posix_thread_t t_sched;
    modcp_posix_event_t sched_irq;
    atomic_bool cmds;
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
    sim_trace_obs_t *trace_obs; /* --trace, `trace on`: the text trace, from the first on */
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
/* console output: while the trace runs, through the line (in time order with it) */
void say(sim_t *s, const char *text);
void sayf(sim_t *s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
uint64_t since_start(const sim_t *s);
uint64_t since_start_of(const sim_t *s, uint32_t now_us);

/* CP thread (sim_cp.c) */
void cp_snapshot(member_t *m);
int this_core(void);
bool ring_pending(const modcp_ring_t *r);
void *cp_thread(void *arg);
/* The CP side after it ran: the backplane interrupt, the trace, the snapshot (sim_cp.c) */
void cp_after(member_t *m, uint32_t now, uint64_t t, bool tr);
/* The CP has nothing to do but supervision (sim_cp.c) */
bool cp_is_quiet(const member_t *m);
/* The scheduler's shared tick: poll a quiet CP (its thread asleep) at now - CP_VISIT_LAG_US. */
#define CP_VISIT_LAG_US 2000u
void cp_visit(member_t *m, uint32_t now);
/* One member's CPU side (sim_cpu.c), run by the scheduler */
void timespec_of(uint64_t us, struct timespec *ts);
void cpu_start(member_t *m, uint64_t t0);
void cpu_command(member_t *m);
bool cpu_blocks_wait(const member_t *m);
void cpu_cycle(member_t *m); /* the FB call due at m->cpu_next; the next one planned */
/* The scheduler (sim_sched.c): one thread for every member's CPU side and the quiet
 * CPs' supervision tick. */
void *sched_thread(void *arg);
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
/* The text trace reads the line from now on (--trace, `trace on`); false: no memory. */
bool observe_trace(sim_t *s);
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
