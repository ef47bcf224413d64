/* SPDX-License-Identifier: Apache-2.0 */
/* modcp-sim — RTU over TCP (--tcp [ADDR:]PORT), a source of the line (tcp.c). */
#ifndef MODCP_SIM_TCP_H
#define MODCP_SIM_TCP_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
    int fd;          /* the listening socket, -1: none */
    char where[80];  /* "127.0.0.1:1502" */
    uint32_t clients;
} sim_tcp_t;

/* spec: "PORT" (127.0.0.1) or "ADDR:PORT" (IPv4); listens. false + err. */
bool sim_tcp_listen(sim_tcp_t *t, const char *spec, char *err, size_t cap);
/* Serves clients one after the other on the line's pty at line_path until *stop. */
void sim_tcp_run(sim_tcp_t *t, const char *line_path, const atomic_bool *stop);
void sim_tcp_close(sim_tcp_t *t);

#endif
