/* SPDX-License-Identifier: Apache-2.0 */
/* Replay of a fuzz target's corpus without libFuzzer (gcc builds, ctest label fuzz):
 *   fuzz_<target>_replay FILE|DIR...
 * runs LLVMFuzzerTestOneInput once on every file (directories: their regular files, in
 * name order), so that each input that once reached new coverage is checked again on
 * every build. A violated invariant aborts, as under libFuzzer. Fails when it ran no
 * input at all. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define REPLAY_MAX_INPUT (1u << 20)

static unsigned long inputs;
static unsigned long long bytes;

static int run_file(const char *path)
{
    static uint8_t buf[REPLAY_MAX_INPUT];
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        perror(path);
        return -1;
    }
    size_t n = fread(buf, 1, sizeof buf, f);
    int err = ferror(f);
    fclose(f);
    if (err) {
        fprintf(stderr, "%s: read error\n", path);
        return -1;
    }
    /* a copy of exactly n bytes, so that ASan (MODCP_SANITIZE) sees reads past the end */
    uint8_t *in = malloc(n ? n : 1u);
    if (in == NULL) {
        return -1;
    }
    memcpy(in, buf, n);
    LLVMFuzzerTestOneInput(in, n);
    free(in);
    inputs++;
    bytes += n;
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        perror(dir);
        return -1;
    }
    char **names = NULL;
    size_t count = 0, cap = 0;
    int rc = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (e->d_name[0] == '.') {
            continue;
        }
        if (count == cap) {
            cap = cap ? 2u * cap : 64u;
            char **nn = realloc(names, cap * sizeof *names);
            if (nn == NULL) {
                rc = -1;
                break;
            }
            names = nn;
        }
        size_t len = strlen(dir) + strlen(e->d_name) + 2u;
        names[count] = malloc(len);
        if (names[count] == NULL) {
            rc = -1;
            break;
        }
        snprintf(names[count], len, "%s/%s", dir, e->d_name);
        count++;
    }
    closedir(d);
    if (count > 0) {
        qsort(names, count, sizeof *names, by_name);
    }
    for (size_t k = 0; k < count; k++) {
        struct stat st;
        if (rc == 0 && stat(names[k], &st) == 0 && S_ISREG(st.st_mode) && run_file(names[k]) != 0) {
            rc = -1;
        }
        free(names[k]);
    }
    free(names);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s FILE|DIR...\n", argv[0]);
        return 2;
    }
    for (int k = 1; k < argc; k++) {
        struct stat st;
        if (stat(argv[k], &st) != 0) {
            perror(argv[k]);
            return 1;
        }
        if ((S_ISDIR(st.st_mode) ? run_dir(argv[k]) : run_file(argv[k])) != 0) {
            return 1;
        }
    }
    printf("%s: %lu inputs (%llu bytes) replayed, invariants held\n", argv[0], inputs, bytes);
    return inputs > 0 ? 0 : 1;
}
