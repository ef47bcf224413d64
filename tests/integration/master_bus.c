/* SPDX-License-Identifier: Apache-2.0 */
/* master_bus — a libmodbus master on a line with several modcp slaves (modcp-sim with
 * several configs, each a copy of configs/default.ini with its own address).
 *
 *   master_bus --device PATH --slaves 1,2,3|1-247 [--baud 9600] [--parity E|O|N]
 *              [--ops 10000] [--seed N] [--timeout-ms 1000] [--same-start]
 *              [--broadcast] [--collide ADDR:N] [--bench SECONDS] [--expect-errors]
 *              [--gap-us US] [--max-regs 125] [--max-coils 400]
 *
 * Before every request the master keeps t3.5 of silence (--gap-us, default 3.5
 * characters, 1750 us above 19200 baud): on a multi-drop line the other slaves heard
 * the previous reply, and only that gap ends it for them — a request sent sooner is
 * glued to the reply and ignored by every slave but the one that sent it.
 *
 *   (default)      mixed requests to the slaves in turn at random: FC03, FC06, FC16 on
 *                  DB800..802 (registers 0..1535), FC01, FC05, FC15 on M (coils 0..2047);
 *                  every read is checked against a shadow of that slave's memory (each
 *                  snapshot first), every write's echo checked. Zero mismatches and zero
 *                  errors pass. A slave answering another's request, or a slave taking
 *                  another's reply for a request, shows up as a mismatch here.
 *   --broadcast    FC16 to address 0 (registers 1000..1009, a fresh pattern), no reply
 *                  expected; then the registers read back from every slave.
 *   --collide A:N  N reads of register 0 from address A, which two members share: no
 *                  valid reply may arrive; counts CRC errors, timeouts and other errors.
 *                  Passes when no reply was valid and at least one CRC error was seen.
 *   --bench S      FC03 reads of 10 registers from the slaves in turn for S seconds;
 *                  prints transactions per second (not a check).
 *   --same-start   (with the default mode) the slaves are copies of one configuration and
 *                  start with the same memory: only the first is snapshot, the others'
 *                  shadows are copies of it (a whole line of 247 slaves would take minutes
 *                  of snapshots). The final read-back of every slave stays.
 *   --recover-ms MS  after an error wait MS and drop what the line delivered meanwhile (a
 *                  reply that came after the timeout is not taken for the next one's).
 *   --expect-errors  (with the default mode) a fault-injecting bus: count errors by kind,
 *                  print them, pass whatever they are (the caller checks the counts).
 * The last line is "N passed, M failed"; exit 0 only when nothing failed. */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <modbus.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "master_util.h"

#define MAX_SLAVES 247 /* every Modbus address */
#define NREGS 1536
#define NCOILS 2048

typedef struct {
    int addr;
    uint16_t regs[NREGS];
    uint8_t coils[NCOILS];
} slave_t;

static modbus_t *ctx;
static slave_t sl[MAX_SLAVES];
static unsigned gap_us; /* t3.5 of silence after a reply before the next request */
static int max_regs = 125, max_coils = 400; /* sizes of the mixed requests */

/* A master on a multi-drop line keeps t3.5 of silence after a reply before its next
 * request: the other slaves heard that reply, and only the gap ends it for them. */
static void gap(void)
{
    if (gap_us > 0u) {
        usleep(gap_us);
    }
}
static int nsl;
static long e_crc, e_timeout, e_exc, e_other;
static unsigned recover_ms; /* --recover-ms: after an error, silence then flush */

static void count_error(void)
{
    {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        /* on stderr, to find the request in the simulator's trace */
        fprintf(stderr, "master_bus: error at %lld.%06ld s (CLOCK_MONOTONIC), slave %d: %s\n",
                (long long)ts.tv_sec, ts.tv_nsec / 1000, modbus_get_slave(ctx),
                modbus_strerror(errno));
    }
    if (errno == EMBBADCRC) {
        e_crc++;
    } else if (errno == ETIMEDOUT) {
        e_timeout++;
    } else if (errno > MODBUS_ENOBASE && errno < EMBXGPATH + 1) {
        e_exc++;
    } else {
        e_other++;
    }
    if (recover_ms > 0u) {
        /* a reply that came late (a stalled host) must not be read as the next one's */
        usleep(recover_ms * 1000u);
        (void)modbus_flush(ctx);
    }
}

static bool rd_regs(int a, int addr, int n, uint16_t *out)
{
    modbus_set_slave(ctx, a);
    for (int off = 0; off < n;) {
        int k = n - off > 125 ? 125 : n - off;
        int to_db_end = 512 - (addr + off) % 512; /* one read stays in one DB */
        k = k > to_db_end ? to_db_end : k;
        gap();
        if (modbus_read_registers(ctx, addr + off, k, out + off) != k) {
            count_error();
            return false;
        }
        off += k;
    }
    return true;
}

static bool rd_bits(int a, int addr, int n, uint8_t *out)
{
    modbus_set_slave(ctx, a);
    for (int off = 0; off < n;) {
        int k = n - off > 2000 ? 2000 : n - off;
        gap();
        if (modbus_read_bits(ctx, addr + off, k, out + off) != k) {
            count_error();
            return false;
        }
        off += k;
    }
    return true;
}

static unsigned rnd(unsigned n)
{
    return (unsigned)rand() % n;
}

static bool same_start;

static void snapshot(void)
{
    for (int i = 0; i < nsl; i++) {
        if (same_start && i > 0) {
            memcpy(sl[i].regs, sl[0].regs, sizeof sl[i].regs);
            memcpy(sl[i].coils, sl[0].coils, sizeof sl[i].coils);
            continue;
        }
        ok(rd_regs(sl[i].addr, 0, NREGS, sl[i].regs), "slave %d: snapshot registers 0..%d",
           sl[i].addr, NREGS - 1);
        ok(rd_bits(sl[i].addr, 0, NCOILS, sl[i].coils), "slave %d: snapshot coils 0..%d",
           sl[i].addr, NCOILS - 1);
    }
}

static void print_per(const long *per)
{
    if (nsl <= 16) {
        for (int i = 0; i < nsl; i++) {
            printf("%s%d: %ld", i > 0 ? ", " : "", sl[i].addr, per[i]);
        }
        return;
    }
    long lo = per[0], hi = per[0];
    for (int i = 1; i < nsl; i++) {
        lo = per[i] < lo ? per[i] : lo;
        hi = per[i] > hi ? per[i] : hi;
    }
    printf("%ld..%ld each", lo, hi);
}

static int mixed(long ops, bool expect_errors)
{
    snapshot();
    long mismatches = 0, errors = 0, per[MAX_SLAVES] = {0};
    double t0 = now_s();
    for (long op = 0; op < ops; op++) {
        slave_t *s = &sl[rnd((unsigned)nsl)];
        per[s - sl]++;
        modbus_set_slave(ctx, s->addr);
        gap();
        unsigned kind = rnd(6);
        if (kind == 0 || kind == 1 || kind == 2) { /* registers */
            int n = kind == 0 ? 1 + (int)rnd((unsigned)max_regs)
                              : (kind == 1 ? 1 : 1 + (int)rnd((unsigned)(max_regs < 100 ? max_regs : 100)));
            int addr = (int)rnd(512u - (unsigned)n + 1u) + 512 * (int)rnd(3);
            uint16_t v[125], got[125];
            if (kind == 0) {
                if (modbus_read_registers(ctx, addr, n, got) != n) {
                    count_error();
                    errors++;
                } else if (memcmp(got, s->regs + addr, (size_t)n * 2u) != 0) {
                    mismatches++;
                    if (!expect_errors) {
                        printf("op %ld: slave %d FC03 %d+%d differs from its memory\n", op,
                               s->addr, addr, n);
                    }
                }
                continue;
            }
            for (int i = 0; i < n; i++) {
                v[i] = (uint16_t)rand();
            }
            int r = kind == 1 ? modbus_write_register(ctx, addr, v[0])
                              : modbus_write_registers(ctx, addr, n, v);
            if (r != (kind == 1 ? 1 : n)) {
                count_error();
                errors++;
                /* the write may or may not have landed: read the truth back */
                (void)rd_regs(s->addr, addr, n, s->regs + addr);
                continue;
            }
            memcpy(s->regs + addr, v, (size_t)n * 2u);
        } else { /* coils */
            int n = kind == 4 ? 1 : 1 + (int)rnd((unsigned)max_coils);
            int addr = (int)rnd((unsigned)(NCOILS - n + 1));
            uint8_t v[400], got[400];
            if (kind == 3) {
                if (modbus_read_bits(ctx, addr, n, got) != n) {
                    count_error();
                    errors++;
                } else if (memcmp(got, s->coils + addr, (size_t)n) != 0) {
                    mismatches++;
                    if (!expect_errors) {
                        printf("op %ld: slave %d FC01 %d+%d differs from its memory\n", op,
                               s->addr, addr, n);
                    }
                }
                continue;
            }
            for (int i = 0; i < n; i++) {
                v[i] = (uint8_t)(rand() & 1);
            }
            int r = kind == 4 ? modbus_write_bit(ctx, addr, v[0]) : modbus_write_bits(ctx, addr, n, v);
            if (r != (kind == 4 ? 1 : n)) {
                count_error();
                errors++;
                (void)rd_bits(s->addr, addr, n, s->coils + addr);
                continue;
            }
            memcpy(s->coils + addr, v, (size_t)n);
        }
    }
    double dt = now_s() - t0;
    printf("mixed: %ld requests to %d slaves (", ops, nsl);
    print_per(per);
    printf(") in %.1f s, %.0f/s; %ld mismatches, %ld errors (CRC %ld, timeout %ld, exception %ld, "
           "other %ld)\n",
           dt, dt > 0 ? (double)ops / dt : 0.0, mismatches, errors, e_crc, e_timeout, e_exc, e_other);
    if (!expect_errors) {
        ok(mismatches == 0 && errors == 0, "mixed: %ld requests, %ld mismatches, %ld errors", ops,
           mismatches, errors);
        /* every slave's final memory is its own shadow: no write landed on another */
        for (int i = 0; i < nsl; i++) {
            static uint16_t r[NREGS];
            static uint8_t c[NCOILS];
            ok(rd_regs(sl[i].addr, 0, NREGS, r) && memcmp(r, sl[i].regs, sizeof r) == 0,
               "slave %d: registers 0..%d are its own writes only", sl[i].addr, NREGS - 1);
            ok(rd_bits(sl[i].addr, 0, NCOILS, c) && memcmp(c, sl[i].coils, sizeof c) == 0,
               "slave %d: coils 0..%d are its own writes only", sl[i].addr, NCOILS - 1);
        }
    } else {
        ok(mismatches == 0, "with faults: %ld mismatches among the valid replies", mismatches);
    }
    return 0;
}

static void broadcast(void)
{
    uint16_t v[10];
    unsigned base = (unsigned)rand();
    for (int i = 0; i < 10; i++) {
        v[i] = (uint16_t)(base + 0x1111u * (unsigned)i);
    }
    uint8_t raw[7 + 20] = {0x00, 0x10, 0x03, 0xE8, 0x00, 0x0A, 20};
    for (int i = 0; i < 10; i++) {
        raw[7 + 2 * i] = (uint8_t)(v[i] >> 8);
        raw[8 + 2 * i] = (uint8_t)v[i];
    }
    gap();
    int r = modbus_send_raw_request(ctx, raw, sizeof raw);
    ok(r > 0, "broadcast FC16 registers 1000..1009 sent (%d bytes)", r);
    uint8_t junk[64];
    int extra = read_want(modbus_get_socket(ctx), junk, sizeof junk, 300);
    ok(extra == 0, "broadcast: no reply on the line (%d bytes)", extra);
    for (int i = 0; i < nsl; i++) {
        uint16_t got[10];
        bool rd = rd_regs(sl[i].addr, 1000, 10, got);
        ok(rd && memcmp(got, v, sizeof v) == 0, "broadcast landed in slave %d (%04X %04X ...)",
           sl[i].addr, rd ? got[0] : 0, rd ? got[1] : 0);
    }
}

static void collide(int a, int n)
{
    long valid = 0;
    e_crc = e_timeout = e_exc = e_other = 0;
    modbus_set_slave(ctx, a);
    for (int i = 0; i < n; i++) {
        uint16_t v;
        if (modbus_read_registers(ctx, 0, 1, &v) == 1) {
            valid++;
            printf("collide: read %d gave a valid reply %04X\n", i, v);
        } else {
            count_error();
        }
        modbus_flush(ctx);
        usleep(50000);
    }
    printf("collide: %d reads of slave %d: %ld valid, %ld CRC errors, %ld timeouts, %ld exceptions, "
           "%ld other errors\n", n, a, valid, e_crc, e_timeout, e_exc, e_other);
    ok(valid == 0, "collide: no valid reply from two slaves at address %d (%ld)", a, valid);
    ok(e_crc >= 1, "collide: CRC errors at the master (%ld)", e_crc);
}

static void bench(double secs)
{
    long n = 0, errs = 0;
    double t0 = now_s();
    uint16_t v[10];
    while (now_s() - t0 < secs) {
        modbus_set_slave(ctx, sl[n % nsl].addr);
        gap();
        if (modbus_read_registers(ctx, 0x50, 10, v) != 10) {
            errs++;
        }
        n++;
    }
    double dt = now_s() - t0;
    printf("bench: %d slave%s, %ld transactions in %.2f s: %.1f transactions/s, %ld errors\n", nsl,
           nsl == 1 ? "" : "s", n, dt, (double)n / dt, errs);
    ok(errs == 0, "bench: no errors");
}

int main(int argc, char **argv)
{
    const char *device = NULL;
    int baud = 9600, timeout_ms = 1000;
    char parity = 'E';
    long ops = 10000;
    unsigned seed = 3411;
    bool bc = false, expect_errors = false;
    int c_addr = 0, c_n = 0;
    double bench_s = 0.0;
    static struct option lo[] = {
        {"device", required_argument, 0, 'd'}, {"baud", required_argument, 0, 'b'},
        {"parity", required_argument, 0, 'p'}, {"slaves", required_argument, 0, 'S'},
        {"ops", required_argument, 0, 'n'},    {"seed", required_argument, 0, 's'},
        {"timeout-ms", required_argument, 0, 't'}, {"broadcast", no_argument, 0, 'B'},
        {"collide", required_argument, 0, 'C'}, {"bench", required_argument, 0, 'X'},
        {"expect-errors", no_argument, 0, 'E'}, {"gap-us", required_argument, 0, 'G'},
        {"max-regs", required_argument, 0, 'R'}, {"max-coils", required_argument, 0, 'K'},
        {"same-start", no_argument, 0, 'Y'}, {"recover-ms", required_argument, 0, 'V'},
        {0, 0, 0, 0}};
    int ch;
    while ((ch = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (ch) {
        case 'd': device = optarg; break;
        case 'b': baud = atoi(optarg); break;
        case 'p': parity = optarg[0]; break;
        case 'n': ops = atol(optarg); break;
        case 's': seed = (unsigned)strtoul(optarg, NULL, 10); break;
        case 't': timeout_ms = atoi(optarg); break;
        case 'B': bc = true; break;
        case 'E': expect_errors = true; break;
        case 'Y': same_start = true; break;
        case 'V': recover_ms = (unsigned)strtoul(optarg, NULL, 10); break;
        case 'R': max_regs = atoi(optarg) < 1 || atoi(optarg) > 125 ? 125 : atoi(optarg); break;
        case 'K': max_coils = atoi(optarg) < 1 || atoi(optarg) > 400 ? 400 : atoi(optarg); break;
        case 'G': gap_us = (unsigned)strtoul(optarg, NULL, 10); break;
        case 'X': bench_s = atof(optarg); break;
        case 'C':
            if (sscanf(optarg, "%d:%d", &c_addr, &c_n) != 2) {
                fprintf(stderr, "master_bus: --collide ADDR:N\n");
                return 2;
            }
            break;
        case 'S': {
            char *save = NULL, buf[2048];
            snprintf(buf, sizeof buf, "%s", optarg);
            for (char *t = strtok_r(buf, ",", &save); t != NULL;
                 t = strtok_r(NULL, ",", &save)) {
                int first = 0, last = 0; /* A or A-B */
                if (sscanf(t, "%d-%d", &first, &last) != 2) {
                    last = first = atoi(t);
                }
                for (int a = first; a <= last && nsl < MAX_SLAVES; a++) {
                    sl[nsl++].addr = a;
                }
            }
            break;
        }
        default:
            fprintf(stderr, "usage: master_bus --device PATH --slaves 1,2,3|1-247 [--baud B] [--parity E]\n"
                            "       [--same-start] [--recover-ms MS] [--ops N] [--seed N] [--timeout-ms MS] [--broadcast]\n"
                            "       [--collide ADDR:N] [--bench SECONDS] [--expect-errors]\n"
                            "       [--gap-us US] [--max-regs N] [--max-coils N]\n");
            return 2;
        }
    }
    if (device == NULL || (nsl == 0 && c_n == 0)) {
        fprintf(stderr, "master_bus: --device and --slaves are needed\n");
        return 2;
    }
    srand(seed);
    /* t3.5: 3.5 characters of 11 bits; 1750 us above 19200 baud (Modbus serial line) */
    if (gap_us == 0u) {
        gap_us = baud > 19200 ? 1750u : (unsigned)(3.5 * 11.0 * 1e6 / baud) + 1u;
    }
    ctx = modbus_new_rtu(device, baud, parity, 8, 1);
    if (ctx == NULL || modbus_connect(ctx) != 0) {
        /* a pty has no parity: libmodbus's tcsetattr may refuse it */
        if (ctx != NULL) {
            modbus_free(ctx);
        }
        ctx = modbus_new_rtu(device, baud, 'N', 8, 1);
        if (ctx == NULL || modbus_connect(ctx) != 0) {
            printf("master_bus: cannot open %s\n0 passed, 1 failed\n", device);
            return 1;
        }
    }
    modbus_set_response_timeout(ctx, (uint32_t)(timeout_ms / 1000),
                                (uint32_t)(timeout_ms % 1000) * 1000u);
    printf("master_bus: libmodbus %s, %s %d, %d slaves, seed %u\n", LIBMODBUS_VERSION_STRING,
           device, baud, nsl, seed);
    if (c_n > 0) {
        collide(c_addr, c_n);
    } else if (bench_s > 0.0) {
        bench(bench_s);
    } else {
        if (bc) {
            broadcast();
        }
        if (ops > 0) {
            mixed(ops, expect_errors);
        }
    }
    modbus_close(ctx);
    modbus_free(ctx);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
