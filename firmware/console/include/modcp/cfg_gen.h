/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — a configuration compiled into a firmware image.
 *
 * `modcp-conf c CONFIG.ini -o cfg.c` generates a C source that defines these symbols
 * from one INI file: the binary parameter record (what the FB hands to the CP), the
 * controller memory of the [cpu] section as static arrays with the [memory] initial
 * values applied (DB table sorted by number), the FB's work DB and the user program's
 * cycle time. A board links the generated file and calls
 *     modcp_fb_init(&fb, &bp, &modcp_cfg_mem, modcp_cfg_record, modcp_cfg_record_len,
 *                   modcp_cfg_work_db, modcp_cfg_start_time_ms);
 * The memory is mutable (it is the controller memory); everything else is const. */
#ifndef MODCP_CFG_GEN_H
#define MODCP_CFG_GEN_H

#include <stdint.h>

#include "modcp/plcmem.h"

extern const uint8_t modcp_cfg_record[];     /* modcp_params_encode() output */
extern const uint16_t modcp_cfg_record_len;  /* its length in bytes */
extern modcp_plcmem_t modcp_cfg_mem;          /* controller memory, initialised */
extern const uint16_t modcp_cfg_work_db;      /* [cpu] work_db (0 = none) */
extern const uint32_t modcp_cfg_cycle_ms;     /* [cpu] cycle_ms */
extern const uint32_t modcp_cfg_start_time_ms; /* [cpu] start_time_ms (FB START_TIME) */
extern const uint8_t modcp_cfg_slave_addr;    /* [protocol] slave_address, for banners */
extern const uint32_t modcp_cfg_baud;         /* [serial] baud, for the board's UART */
extern const char modcp_cfg_name[];           /* file name of the INI it came from */

#endif
