/* SPDX-License-Identifier: Apache-2.0 */
/* The [RTU-2003] §9 parameter set, once for every test harness (the unit tests' world,
 * the fuzz targets' and the differential run's base set): slave 5; coils M 0-2047 @
 * MB1000, Q 2048-2559 @ QB256, T 4096-4607 @ T100, C 4608-5119 @ C200; inputs M 0-4095
 * @ MB2000, I 4096-5119 @ IB128; holding base DB 800, input base DB 900; write limits
 * DB 800-899, MB 1000-1255, QB 256-319 (admit the examples). Public API only. */
#ifndef MODCP_TEST_EXAMPLE_PARAMS_H
#define MODCP_TEST_EXAMPLE_PARAMS_H

#include "modcp/params.h"

static inline void example_params(modcp_params_t *p)
{
    modcp_params_defaults(p);
    p->slave_addr = 5;
    p->coils[0] = (modcp_bitwin_t){MODCP_AREA_M, 0, 2047, 1000, 0};
    p->coils[1] = (modcp_bitwin_t){MODCP_AREA_Q, 2048, 2559, 256, 0};
    p->coils[2] = (modcp_bitwin_t){MODCP_AREA_T, 4096, 4607, 100, 0};
    p->coils[3] = (modcp_bitwin_t){MODCP_AREA_C, 4608, 5119, 200, 0};
    p->inputs[0] = (modcp_bitwin_t){MODCP_AREA_M, 0, 4095, 2000, 0};
    p->inputs[1] = (modcp_bitwin_t){MODCP_AREA_I, 4096, 5119, 128, 0};
    p->hr_base_db = 800;
    p->ir_base_db = 900;
    p->lim_db = (modcp_limit_t){800, 899};
    p->lim_m = (modcp_limit_t){1000, 1255};
    p->lim_q = (modcp_limit_t){256, 319};
}

#endif
