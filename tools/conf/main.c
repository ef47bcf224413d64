/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-conf — INI configuration -> binary parameter record / C source.
 *
 *   modcp-conf check FILE              exit 0, or 2 with one line per problem
 *   modcp-conf build FILE -o OUT.bin   the record of modcp_params_encode()
 *   modcp-conf c FILE -o OUT.c         C source for firmware images (modcp/cfg_gen.h)
 *   ... --set section.key=value        override / add a key (repeatable)
 *   modcp-conf fields                  self-check: every parameter field has an INI key
 *   modcp-conf doc-table               the parameter tables of docs/parameters.md
 *   modcp-conf event-table             the event tables of docs/diagnostics.md
 *
 * Problems go to stderr, one per line:
 *   FILE:LINE: section.key = value: rule (event (0E)23H)
 * Warnings (the CP corrects the value, e.g. f_mul -> 1) are listed but do not fail.
 * Exit codes: 0 ok, 1 usage or I/O error, 2 configuration problems. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp_conf.h"

static int usage(void)
{
    fprintf(stderr, "usage: modcp-conf check FILE [--set section.key=value]...\n"
                    "       modcp-conf build FILE -o OUT.bin [--set section.key=value]...\n"
                    "       modcp-conf c FILE -o OUT.c [--set section.key=value]...\n"
                    "       modcp-conf fields\n"
                    "       modcp-conf doc-table\n"
                    "       modcp-conf event-table\n");
    return 1;
}

static void print_problems(const modcp_conf_t *c)
{
    size_t n = c->problem_count < MODCP_CONF_MAX_PROBLEMS ? c->problem_count : MODCP_CONF_MAX_PROBLEMS;
    for (size_t i = 0; i < n; i++) {
        fprintf(stderr, "%s\n", c->problems[i].text);
    }
    if (c->problem_count > n) {
        fprintf(stderr, "%s: ... and %zu more problems\n", c->name, c->problem_count - n);
    }
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "fields") == 0) {
        /* schema self-check: every parameter field has an INI key */
        uint8_t f[MODCP_PF_COUNT];
        size_t n = modcp_conf_uncovered(f, sizeof f);
        for (size_t i = 0; i < n && i < sizeof f; i++) {
            printf("parameter field %u (modcp_param_field_t) has no INI key\n", (unsigned)f[i]);
        }
        if (n == 0u) {
            printf("every parameter field has an INI key\n");
        }
        return n == 0u ? 0 : 2;
    }
    if (argc == 2 && strcmp(argv[1], "doc-table") == 0) {
        return modcp_conf_write_doc_table(stdout) ? 0 : 1;
    }
    if (argc == 2 && strcmp(argv[1], "event-table") == 0) {
        return modcp_conf_write_event_table(stdout) ? 0 : 1;
    }
    if (argc < 3) {
        return usage();
    }
    const char *cmd = argv[1];
    const char *file = argv[2];
    const char *out = NULL;
    const char *sets[32];
    size_t nsets = 0;
    for (int i = 3; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            out = argv[++i];
        } else if (strcmp(argv[i], "--set") == 0 && i + 1 < argc && nsets < 32u) {
            sets[nsets++] = argv[++i];
        } else {
            return usage();
        }
    }
    bool is_check = strcmp(cmd, "check") == 0;
    bool is_build = strcmp(cmd, "build") == 0;
    bool is_c = strcmp(cmd, "c") == 0;
    if (!is_check && !is_build && !is_c) {
        return usage();
    }
    if ((is_build || is_c) && out == NULL) {
        return usage();
    }
    modcp_conf_t *c = malloc(sizeof *c);
    if (c == NULL) {
        fprintf(stderr, "modcp-conf: out of memory\n");
        return 1;
    }
    size_t fatal = modcp_conf_load_ex(c, file, sets, nsets);
    print_problems(c);
    if (fatal > 0u) {
        free(c);
        return 2;
    }
    uint8_t rec[MODCP_PARAMS_RECORD_MAX];
    size_t rlen = modcp_conf_record(c, rec, sizeof rec);
    if (rlen == 0u) {
        fprintf(stderr, "%s: cannot encode the parameter record\n", file);
        free(c);
        return 1;
    }
    int rc = 0;
    if (is_check) {
        char settings[48];
        modcp_conf_line_settings(&c->params, settings, sizeof settings);
        printf("%s: ok: slave %u, %s, record %zu bytes\n", file, (unsigned)c->params.slave_addr,
               settings, rlen);
    } else {
        FILE *f = fopen(out, is_build ? "wb" : "w");
        if (f == NULL) {
            perror(out);
            free(c);
            return 1;
        }
        bool ok = is_build ? fwrite(rec, 1, rlen, f) == rlen : modcp_conf_write_c(c, f);
        if (fclose(f) != 0 || !ok) {
            fprintf(stderr, "%s: write error\n", out);
            remove(out);
            rc = 1;
        }
    }
    free(c);
    return rc;
}
