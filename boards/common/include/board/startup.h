/* SPDX-License-Identifier: Apache-2.0 */
/* modcp boards — symbols of the common startup code (boards/common/startup.c). */
#ifndef MODCP_BOARD_STARTUP_H
#define MODCP_BOARD_STARTUP_H

#include <stdint.h>

typedef void (*cm_handler_t)(void);

/* A vector table with n_irq external interrupts: the initial stack pointer, the 15
 * system exception handlers (Reset ... SysTick), then the interrupt handlers. */
#define CM_VECTORS_T(n_irq)                                                             \
    struct {                                                                            \
        uint32_t *sp;                                                                   \
        cm_handler_t handler[15 + (n_irq)];                                             \
    }

extern uint32_t _estack[];

void Reset_Handler(void);
void Default_Handler(void);

#endif
