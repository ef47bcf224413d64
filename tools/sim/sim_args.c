/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — the command line. */
#define _GNU_SOURCE
#include "sim.h"

#include "modcp/version.h"

/* ---- start-up ------------------------------------------------------------------------------ */

static int usage(void)
{
    fprintf(stderr,
            "usage: modcp-sim CONFIG.ini [CONFIG2.ini ...] [--pty-link PATH] [--device /dev/ttyX]\n"
            "                 [--trace] [--script FILE] [--cycle-ms N] [--set section.key=value]...\n"
            "                 [--control FIFO] [--bus] [--fault [@M:]KIND=VALUE]... [--seed N]\n"
            "                 [--qemu-member PTY]... [--capture FILE.pcap] [--vcd FILE.vcd]\n"
            "                 [--replay FILE.pcap [--speed F]] [--tcp [ADDR:]PORT]\n"
            "  --pty-link PATH   also make PATH a symlink to the pseudo-terminal\n"
            "  --device PATH     use a real serial device (termios from the parameters)\n"
            "  --trace           print every frame received and sent, and every event\n"
            "  --script FILE     run console commands from FILE once the FB is initialised\n"
            "  --cycle-ms N      cycle time of the user program (default: [cpu] cycle_ms)\n"
            "  --set [@M:]S.K=V  override a key of the configuration (e.g. serial.baud=115200);\n"
            "                    on a bus, of every member, or of member M (@2:, @name:)\n"
            "  --control FIFO    also read console commands from a named pipe (made if missing)\n"
            "  --bus             show even one config as a bus member (@name, every address)\n"
            "  --fault [@M:]K=V  a fault of member M's replies (default: every member); K: drop,\n"
            "                    crc, exc06, exc04 (V in %%), delay (MS or MIN-MAX), silent (N\n"
            "                    requests), noise (N bytes after each reply); serial: parity=K,\n"
            "                    framing=K (byte K), break=MS, gap=K:US, de_cut=BITS; @master:\n"
            "                    the master's direction (serial kinds, early=US); not with --device\n"
            "  --seed N          seed of the faults' random choices (default 1)\n"
            "  --qemu-member PTY a QEMU board's Modbus pty (tools/run-qemu) as a member of the\n"
            "                    line (@qemu; its console is its own); implies --bus\n"
            "  --capture FILE    write every frame on the line to FILE (pcap, Wireshark/tshark)\n"
            "  --vcd FILE        write the line at bit level to FILE (VCD, PulseView/sigrok)\n"
            "  --replay FILE     play the master's frames of a capture against the slave(s), report\n"
            "                    the replies that differ, stop (exit 3 when any differs)\n"
            "  --speed F         the replay's gaps divided by F (default 1)\n"
            "  --tcp [ADDR:]PORT RTU frames over TCP too (127.0.0.1 unless ADDR), a client at a time\n"
            "  --version         print modcp-sim's version and exit\n"
            "On a pty the slaves are members of one simulated line (bus), one pty for the master.\n"
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
        {"--capture", "a file for the Wireshark capture, e.g. line.pcap"},
        {"--vcd", "a file for the waveform, e.g. line.vcd"},
        {"--replay", "a capture of modcp-sim (--capture), e.g. line.pcap"},
        {"--speed", "a factor > 0 for the replay's gaps, e.g. 2"},
        {"--tcp", "[ADDR:]PORT for RTU over TCP, e.g. 1502 or 0.0.0.0:1502"},
    };
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++) {
        if (strcmp(a, opts[i][0]) == 0) {
            return opts[i][1];
        }
    }
    return NULL;
}

/* Appends v to list (count of cap); false (message) when full. */
static bool push(const char **list, size_t *count, size_t cap, const char *v, const char *opt)
{
    if (*count >= cap) {
        fprintf(stderr, "modcp-sim: too many %s\n", opt);
        return false;
    }
    list[(*count)++] = v;
    return true;
}

static int number_option(sim_t *s, const char *a, const char *v)
{
    char *end = NULL;
    if (strcmp(a, "--cycle-ms") == 0) {
        long x = strtol(v, &end, 10);
        if (*end != '\0' || x < 1 || x > 60000) {
            fprintf(stderr, "modcp-sim: --cycle-ms %s: must be 1..60000\n", v);
            return 1;
        }
        s->cycle_override = x;
        return 0;
    }
    unsigned long x = strtoul(v, &end, 10);
    if (*end != '\0' || x > 0xFFFFFFFFul) {
        fprintf(stderr, "modcp-sim: --seed %s: must be a number\n", v);
        return 1;
    }
    s->seed = (uint32_t)x;
    return 0;
}

/* An option with the value v: 0, the exit code, or -1 when a is not one of them. */
static int value_option(sim_t *s, const char *a, const char *v)
{
    const struct {
        const char *opt;
        const char **dst;
    } paths[] = {{"--pty-link", &s->pty_link}, {"--device", &s->device},
                 {"--capture", &s->capture_path}, {"--vcd", &s->vcd_path},
                 {"--replay", &s->replay_path}, {"--tcp", &s->tcp_spec},
                 {"--script", &s->script},
                 {"--control", &s->control}};
    const char **path = NULL;
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        if (strcmp(a, paths[i].opt) == 0) {
            path = paths[i].dst;
        }
    }
    if (path != NULL) {
        *path = v;
        return 0;
    }
    if (strcmp(a, "--speed") == 0) {
        char *end = NULL;
        double x = strtod(v, &end);
        if (*end != '\0' || !(x > 0.0 && x <= 1000.0)) {
            fprintf(stderr, "modcp-sim: --speed %s: must be a factor > 0 (up to 1000)\n", v);
            return 1;
        }
        s->speed = x;
        return 0;
    }
    if (strcmp(a, "--cycle-ms") == 0 || strcmp(a, "--seed") == 0) {
        return number_option(s, a, v);
    }
    if (strcmp(a, "--set") == 0) {
        return push(s->sets, &s->set_count, s->arg_cap, v, a) ? 0 : 1;
    }
    if (strcmp(a, "--fault") == 0) {
        return push(s->faults, &s->fault_count, s->arg_cap, v, a) ? 0 : 1;
    }
    if (strcmp(a, "--qemu-member") == 0) {
        s->bus_mode = true;
        return push(s->ext_tty, &s->n_ext, MAX_MEMBERS, v, a) ? 0 : 1;
    }
    return -1;
}

int parse_args(sim_t *s, int argc, char **argv)
{
    s->cycle_override = -1;
    s->seed = 1;
    s->speed = 1.0;
    s->arg_cap = (size_t)argc;
    s->sets = calloc(s->arg_cap, sizeof *s->sets);
    s->faults = calloc(s->arg_cap, sizeof *s->faults);
    if (s->sets == NULL || s->faults == NULL) {
        return 1;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *needs = option_value(a);
        if (needs != NULL && (i + 1 >= argc || (argv[i + 1][0] == '-' && argv[i + 1][1] == '-'))) {
            fprintf(stderr, "modcp-sim: %s needs a value (%s)\n", a, needs);
            return 1;
        }
        int rc = needs != NULL ? value_option(s, a, argv[++i]) : -1;
        if (rc >= 0) {
            if (rc != 0) {
                return rc;
            }
        } else if (strcmp(a, "--trace") == 0) {
            atomic_store(&s->trace_on, true);
        } else if (strcmp(a, "--bus") == 0) {
            s->bus_mode = true;
            s->bus_named = true;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            return usage();
        } else if (strcmp(a, "--version") == 0) {
            printf("modcp-sim %s\n", MODCP_VERSION); /* modcp/version.h */
            return -1;                                /* done: exit 0 */
        } else if (a[0] == '-') {
            fprintf(stderr, "modcp-sim: unexpected argument '%s'\n", a);
            return usage();
        } else if (s->n >= SIM_BUS_MAX_SLAVES) {
            fprintf(stderr, "modcp-sim: at most %d configs (members of one bus: one per Modbus address)\n",
                    SIM_BUS_MAX_SLAVES);
            return 1;
        } else {
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
    /* on a pty every slave, one too, is a member of the simulated line: its faults, the
     * capture and the trace work alike; a serial device is a line of its own */
    if (s->device == NULL) {
        s->bus_mode = true;
    }
    s->solo = s->n == 1u && s->n_ext == 0u && !s->bus_named;
    if (s->device != NULL && (s->n > 1u || s->n_ext > 0u || s->bus_named)) {
        fprintf(stderr, "modcp-sim: --device works with one slave; a bus runs on a pty\n");
        return 1;
    }
    if (s->device != NULL && s->fault_count > 0u) {
        fprintf(stderr, "modcp-sim: --fault: faults are made by the simulated line, which runs on "
                        "a pty, not on --device\n");
        return 1;
    }
    return 0;
}
