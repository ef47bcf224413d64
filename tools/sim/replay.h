/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — replay of a capture (--replay FILE.pcap [--speed F]): a source of the
 * line that plays the master's frames of a capture with their recorded gaps against
 * the configured slave(s) and reports, frame by frame, where the replies differ from
 * the recorded ones (replay.c). */
#ifndef MODCP_SIM_REPLAY_H
#define MODCP_SIM_REPLAY_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define SIM_REPLAY_MAX_FRAMES 20000u
#define SIM_REPLAY_FRAME_MAX 1024u

typedef struct {
    uint64_t t_us;  /* its time stamp (us since the epoch) */
    bool master;    /* sent by the master (else by a slave) */
    uint16_t len;
    uint8_t b[SIM_REPLAY_FRAME_MAX];
} sim_replay_frame_t;

typedef struct {
    sim_replay_frame_t *f; /* the capture's frames, in file order */
    size_t n;
    size_t requests;  /* master frames played */
    size_t differ;    /* requests whose replies differ */
} sim_replay_t;

/* Reads the frames of a modcp-sim capture (link type 252: the Modbus RTU and ASCII
 * frames, not the LINE / NOISE / COLLISION records). false + err. */
bool sim_replay_load(sim_replay_t *r, const char *path, char *err, size_t cap);
void sim_replay_free(sim_replay_t *r);

/* Plays r's master frames on the pty at path (the master's end of the line) with their
 * gaps divided by speed; t3.5_us: the line's end of frame. Each difference is one call
 * of print(user, line); returns false when the pty cannot be opened. *stop ends it. */
bool sim_replay_run(sim_replay_t *r, const char *path, double speed, uint32_t t35_us,
                    const atomic_bool *stop, void (*print)(void *user, const char *line),
                    void *user);

#endif
