/* SPDX-License-Identifier: Apache-2.0 */
/* modcp — the function-code table (fc_table_internal.h): one row per function code,
 * read by the PDU engine (pdu.c) and by modem mode's framing (rtu_modem.c). */
#include "fc_table_internal.h"

#if MODCP_WITH_EXTENDED
#define EXT_RUN(h) (h)
#else
#define EXT_RUN(h) H_RW /* in no function set of this build (F_EXT only) */
#endif
#define BOTH (F_CP341 | F_EXT)

const modcp_fc_row_t modcp_fc_table[MODCP_FC_ROWS] = {
    /* fc                     {min, function sets and flags,                           quantity limits | form,           handler} */
    [0x01u] =                 {5u,  BOTH | F_ADDR,                                      MODCP_QLIM_READ_BITS | FC_EXACT,  H_RW},
    [0x02u] =                 {5u,  BOTH | F_ADDR,                                      MODCP_QLIM_READ_BITS | FC_EXACT,  H_RW},
    [0x03u] =                 {5u,  BOTH | F_ADDR | F_R32 | F_SCAN,                     MODCP_QLIM_READ_REGS | FC_EXACT,  H_RW},
    [0x04u] =                 {5u,  BOTH | F_ADDR,                                      MODCP_QLIM_READ_REGS | FC_EXACT,  H_RW},
    [0x05u] =                 {5u,  BOTH | F_ADDR | F_BCAST | F_WRITE,                  MODCP_QLIM_NONE | FC_EXACT,       H_RW},
    [0x06u] =                 {3u,  BOTH | F_ADDR | F_R32 | F_SCAN | F_BCAST | F_WRITE, MODCP_QLIM_NONE | FC_PLUS2,       H_RW},
    [0x08u] =                 {3u,  F_CP341,                                            MODCP_QLIM_NONE | FC_PLUS2 | FC_OPEN, H_DIAG0},
    [0x0Bu] =                 {1u,  F_EXT | F_NOCOUNT,                                  MODCP_QLIM_NONE | FC_EXACT,       EXT_RUN(H_FC11)},
    [0x0Cu] =                 {1u,  F_EXT | F_NOCOUNT,                                  MODCP_QLIM_NONE | FC_EXACT,       EXT_RUN(H_FC12)},
    [0x0Fu] =                 {6u,  BOTH | F_ADDR | F_BCAST | F_WRITE,                  MODCP_QLIM_WRITE_BITS | FC_COUNT, H_RW},
    [0x10u] =                 {6u,  BOTH | F_ADDR | F_R32 | F_SCAN | F_BCAST | F_WRITE, MODCP_QLIM_WRITE_REGS | FC_COUNT, H_RW},
    [0x11u] =                 {1u,  F_EXT,                                              MODCP_QLIM_NONE | FC_EXACT,       EXT_RUN(H_FC17)},
    [0x16u] =                 {7u,  F_EXT | F_WRITE,                                    MODCP_QLIM_NONE | FC_EXACT,       EXT_RUN(H_FC22)},
    [0x17u] =                 {10u, F_EXT | F_WRITE,                                    MODCP_QLIM_NONE | FC_COUNT,       EXT_RUN(H_FC23)},
    [MODCP_FC_ROW_FC43] =     {2u,  F_EXT,                                              MODCP_QLIM_NONE | FC_PLUS2 | FC_OPEN, EXT_RUN(H_FC43)}, /* 2BH */
#if MODCP_WITH_EXTENDED
    [MODCP_FC_ROW_FC08_EXT] = {3u,  F_EXT,                                              MODCP_QLIM_NONE,                  H_FC08},
#endif
};
