/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — between the files of this HAL only. */
#ifndef MODCP_STM32F4_INTERNAL_H
#define MODCP_STM32F4_INTERNAL_H

#include <stdint.h>

/* SysTick one-shot: call fire(ctx, now_us) at the SysTick's priority `us` microseconds
 * from now, replacing an armed one; us == 0 disarms. */
void stm32_systick_oneshot(uint32_t us, void (*fire)(void *ctx, uint32_t now_us), void *ctx);

#endif
