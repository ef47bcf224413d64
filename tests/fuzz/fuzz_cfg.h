/* SPDX-License-Identifier: Apache-2.0 */
/* The line fuzz targets' parameter set and controller memory (and how the user program
 * drives CP_START), built field by field from
 * the first FUZZ_CFG_BYTES bytes of an input (fuzz_cfg.c has the layout). Every byte 0
 * keeps the base set: the manual's example (fuzz_line.c), so an input that starts with
 * FUZZ_CFG_BYTES zero bytes runs the example as before. What the core's validation
 * (modcp_params_validate) refuses falls back, field by field, to the base set. */
#ifndef FUZZ_CFG_H
#define FUZZ_CFG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "modcp/params.h"

#define FUZZ_CFG_BYTES 48u

/* Controller memory and CP_START, which the input chooses besides the parameters. */
typedef struct {
    uint16_t db_size[5];   /* per DB of the world (0: the DB does not exist) */
    uint16_t m_size;       /* bytes of M */
    uint16_t work_db;      /* the FB's work DB (0: none) */
    uint8_t restart_every; /* every n-th FB cycle of the input drops CP_START (0: never) */
} fuzz_mem_t;

typedef struct {
    unsigned rounds;    /* validation rounds until the set was accepted */
    unsigned fallbacks; /* fields set back to the base set */
    unsigned whole;     /* 1: the whole set fell back to the base set */
} fuzz_cfg_stats_t;

/* The base set: the manual's example (fuzz_cfg.c), RTU or ASCII (7 data bits). */
void fuzz_cfg_base(modcp_params_t *p, bool ascii);

/* Build p (and mem) from h[0 .. FUZZ_CFG_BYTES) over base; base must be valid (and
 * framed as the target's framing; byte 47 bit 0 switches to the other one). */
void fuzz_cfg_build(const uint8_t *h, const modcp_params_t *base, modcp_params_t *p,
                    fuzz_mem_t *mem, fuzz_cfg_stats_t *stats);

#endif
