/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — build-time feature switches (CMake options of the same names, passed to
 * every user of the core library as compile definitions; default on). A switched-off
 * feature is not compiled into the core, and a PARAMS record that asks for it is
 * refused with (0E)2EH naming the field (params.c), so the CP stays "not ready".
 *   MODCP_WITH_EXTENDED       FC08 sub-functions beyond 0000, FC11/12/17/22/23/43,
 *                             the scanner, comm-loss supervision, the comm event log
 *                             (fset = extended, scan_count, commloss_ms)
 *   MODCP_WITH_ASCII          Modbus ASCII framing (framing = ascii); without it the
 *                             frame buffer is MODCP_ADU_MAX (264) bytes instead of 513
 *   MODCP_WITH_RS232_SIGNALS  RS232 automatic secondary signals (rs232_auto = on)
 * and MODCP_SHARED_PARAMS_BUFFER (below).
 * docs/porting.md lists their sizes. */
#ifndef MODCP_FEATURES_H
#define MODCP_FEATURES_H

#ifndef MODCP_WITH_EXTENDED
#define MODCP_WITH_EXTENDED 1
#endif
#ifndef MODCP_WITH_ASCII
#define MODCP_WITH_ASCII 1
#endif
#ifndef MODCP_WITH_RS232_SIGNALS
#define MODCP_WITH_RS232_SIGNALS 1
#endif
/* RAM, not a feature (default off): the CP reassembles an incoming PARAMS record in its
 * frame buffer instead of a separate 400-byte buffer. When the first PARAMS block
 * arrives the job module reports MODCP_JOBP_PARAMS_START; the CP drops the request in
 * progress, switches the link off (waiting for a reply on the line to finish first)
 * and only then lets the block be stored (modcp_job_params_grant). The CP is "not
 * ready" from the first block on instead of from the last. */
#ifndef MODCP_SHARED_PARAMS_BUFFER
#define MODCP_SHARED_PARAMS_BUFFER 0
#endif

#endif
