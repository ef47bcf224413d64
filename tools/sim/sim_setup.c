/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — set-up: configurations, member names, line settings, --fault, why the line did not open. */
#define _GNU_SOURCE
#include "sim.h"

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
void open_failed(const char *device, const char *link, int orc)
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
void member_name(sim_t *s, size_t i)
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
        snprintf(m->name, sizeof m->name, "%s-%u", name, (unsigned)(i + 1u));
    } else {
        snprintf(m->name, sizeof m->name, "%s", name);
    }
}

void free_members(sim_t *s)
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

/* The --set values for member m: S.K=V for every member, @M:S.K=V for member M (name or
 * index) only, in mine[] (shown[]: as given); 0 or the exit code (message printed). */
static int member_sets(sim_t *s, const member_t *m, const char **mine, const char **shown,
                       size_t *nmine)
{
    for (size_t k = 0; k < s->set_count; k++) {
        const char *a = s->sets[k];
        if (a[0] == '@') {
            const char *colon = strchr(a, ':');
            char name[32];
            size_t len = colon != NULL ? (size_t)(colon - a - 1) : 0u;
            if (colon == NULL || len == 0u || len >= sizeof name) {
                fprintf(stderr, "modcp-sim: --set %s: expected @MEMBER:section.key=value\n", a);
                return 1;
            }
            memcpy(name, a + 1, len);
            name[len] = '\0';
            int target = find_member(s, name);
            if (target < 0 || target == MAX_MEMBERS) {
                fprintf(stderr, "modcp-sim: --set %s: no member @%s\n", a, name);
                return 1;
            }
            if ((size_t)target != m->index) {
                continue;
            }
            mine[*nmine] = colon + 1;
        } else {
            mine[*nmine] = a;
        }
        shown[(*nmine)++] = a;
    }
    return 0;
}

/* The configuration with the --set values; 0 or the exit code (message printed). */
static int load_conf(sim_t *s, member_t *m)
{
    const char **mine = calloc(s->set_count + 1u, sizeof *mine);
    const char **shown = calloc(s->set_count + 1u, sizeof *shown);
    size_t nmine = 0;
    int rc = mine == NULL || shown == NULL ? 1 : member_sets(s, m, mine, shown, &nmine);
    if (rc == 0) {
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
            rc = 2;
        }
    }
    free(mine);
    free(shown);
    return rc;
}

/* Configuration of member m: the same code and messages as modcp-conf check.
 * 0, or the exit code. */
int load_member(sim_t *s, member_t *m)
{
    m->conf = malloc(sizeof *m->conf);
    if (m->conf == NULL) {
        return 1;
    }
    memset(&m->memory, 0, sizeof m->memory);
    int rc = load_conf(s, m);
    if (rc != 0) {
        free(m->conf);
        m->conf = NULL;
        return rc;
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
bool same_line(const sim_t *s)
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
bool apply_cli_faults(sim_t *s)
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
            target = strcmp(name, "master") == 0 ? MASTER_TARGET : find_member(s, name);
            if (target == -1) {
                fprintf(stderr, "modcp-sim: --fault %s: no member @%s\n", spec, name);
                return false;
            }
            spec = colon + 1;
        }
        char err[160];
        if (target == MASTER_TARGET) {
            if (!sim_bus_fault_set(s->bus, SIM_BUS_MASTER, spec, err, sizeof err)) {
                fprintf(stderr, "modcp-sim: --fault %s: %s\n", s->faults[k], err);
                return false;
            }
            continue;
        }
        for (size_t i = 0; i < s->n; i++) {
            if (target != MAX_MEMBERS && (size_t)target != i) {
                continue;
            }
            if (!sim_bus_fault_set(s->bus, i, spec, err, sizeof err)) {
                fprintf(stderr, "modcp-sim: --fault %s: %s\n", s->faults[k], err);
                return false;
            }
        }
    }
    return true;
}
