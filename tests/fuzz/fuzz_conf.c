/* SPDX-License-Identifier: Apache-2.0 */
/* Fuzz target: the configuration file text (tools/conf: INI -> parameter record +
 * controller memory), through the reader's public functions only (modcp_conf.h):
 * load, record, memory, generated C source, line settings.
 * Input: the file's text (a NUL ends it).
 * Invariants: every problem text is NUL-terminated and non-empty; the counts agree;
 * a file without fatal problems gives a record that the CP decodes and applies (the
 * reader refuses what the CP would refuse), and a controller memory that can be
 * allocated; the generated C source can be written. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modcp/params.h"
#include "modcp_conf.h"
#include "params_internal.h"

static void die(const char *what)
{
    fprintf(stderr, "fuzz invariant violated: %s\n", what);
    abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static modcp_conf_t conf; /* large: not on the stack */
    static FILE *sink;
    if (sink == NULL) {
        sink = fopen("/dev/null", "w");
        if (sink == NULL) {
            die("cannot open /dev/null");
        }
    }
    char *text = malloc(size + 1u);
    if (text == NULL) {
        abort();
    }
    memcpy(text, data, size);
    text[size] = '\0';
    size_t fatal = modcp_conf_load_string(&conf, "fuzz.ini", text);
    free(text);

    if (fatal != conf.fatal_count || conf.fatal_count > conf.problem_count) {
        die("problem counts disagree");
    }
    size_t stored = conf.problem_count < MODCP_CONF_MAX_PROBLEMS ? conf.problem_count
                                                                 : MODCP_CONF_MAX_PROBLEMS;
    for (size_t k = 0; k < stored; k++) {
        const char *t = conf.problems[k].text;
        if (memchr(t, 0, sizeof conf.problems[k].text) == NULL || t[0] == '\0') {
            die("problem text empty or not terminated");
        }
    }
    char settings[64];
    modcp_conf_line_settings(&conf.params, settings, sizeof settings);
    if (memchr(settings, 0, sizeof settings) == NULL) {
        die("line settings not terminated");
    }
    if (fatal != 0) {
        return 0;
    }
    uint8_t record[MODCP_PARAMS_RECORD_MAX];
    size_t len = modcp_conf_record(&conf, record, sizeof record);
    modcp_params_t p, eff;
    if (len == 0 || modcp_params_decode(record, len, &p) != MODCP_EV_NONE) {
        die("accepted file, record does not decode");
    }
    if (modcp_params_apply(&p, &eff, NULL) != MODCP_EV_NONE) {
        die("accepted file, the CP refuses its record");
    }
    modcp_conf_memory_t mem;
    if (!modcp_conf_memory_alloc(&conf, &mem)) {
        die("accepted file, no controller memory");
    }
    modcp_conf_memory_free(&mem);
    if (!modcp_conf_write_c(&conf, sink)) {
        die("generated C source not written");
    }
    return 0;
}
