/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — the registers this HAL uses, from RM0090 (STM32F405/407
 * reference manual) and the ARMv7-M ARM for SysTick. Private to hal/stm32f4. */
#ifndef MODCP_STM32F4_REGS_H
#define MODCP_STM32F4_REGS_H

#include <stdint.h>

#define STM_REG(base, off) (*(volatile uint32_t *)((base) + (uintptr_t)(off)))

/* RCC */
#define RCC_BASE 0x40023800u
#define RCC_CR STM_REG(RCC_BASE, 0x00u)
#define RCC_PLLCFGR STM_REG(RCC_BASE, 0x04u)
#define RCC_CFGR STM_REG(RCC_BASE, 0x08u)
#define RCC_AHB1ENR STM_REG(RCC_BASE, 0x30u)
#define RCC_APB1ENR STM_REG(RCC_BASE, 0x40u)
#define RCC_APB2ENR STM_REG(RCC_BASE, 0x44u)
#define RCC_CR_HSION (1u << 0)
#define RCC_CR_HSIRDY (1u << 1)
#define RCC_CR_PLLON (1u << 24)
#define RCC_CR_PLLRDY (1u << 25)
#define RCC_CFGR_SW_PLL 0x2u
#define RCC_CFGR_SWS_MASK (0x3u << 2)
#define RCC_CFGR_SWS_PLL (0x2u << 2)
#define RCC_CFGR_PPRE1_DIV4 (0x5u << 10)
#define RCC_CFGR_PPRE2_DIV2 (0x4u << 13)

/* FLASH interface */
#define FLASH_ACR STM_REG(0x40023C00u, 0x00u)
#define FLASH_ACR_LATENCY_5WS 5u
#define FLASH_ACR_PRFTEN (1u << 8)
#define FLASH_ACR_ICEN (1u << 9)
#define FLASH_ACR_DCEN (1u << 10)

/* GPIO */
#define GPIO_MODER(b) STM_REG(b, 0x00u)
#define GPIO_OTYPER(b) STM_REG(b, 0x04u)
#define GPIO_OSPEEDR(b) STM_REG(b, 0x08u)
#define GPIO_PUPDR(b) STM_REG(b, 0x0Cu)
#define GPIO_IDR(b) STM_REG(b, 0x10u)
#define GPIO_ODR(b) STM_REG(b, 0x14u)
#define GPIO_BSRR(b) STM_REG(b, 0x18u)
#define GPIO_AFR(b, n) STM_REG(b, 0x20u + 4u * (uint32_t)(n))

/* USART */
#define USART_SR(b) STM_REG(b, 0x00u)
#define USART_DR(b) STM_REG(b, 0x04u)
#define USART_BRR(b) STM_REG(b, 0x08u)
#define USART_CR1(b) STM_REG(b, 0x0Cu)
#define USART_CR2(b) STM_REG(b, 0x10u)
#define USART_CR3(b) STM_REG(b, 0x14u)
#define USART_SR_PE (1u << 0)
#define USART_SR_FE (1u << 1)
#define USART_SR_NF (1u << 2)
#define USART_SR_ORE (1u << 3)
#define USART_SR_RXNE (1u << 5)
#define USART_SR_TC (1u << 6)
#define USART_SR_TXE (1u << 7)
#define USART_CR1_RE (1u << 2)
#define USART_CR1_TE (1u << 3)
#define USART_CR1_RXNEIE (1u << 5)
#define USART_CR1_TCIE (1u << 6)
#define USART_CR1_TXEIE (1u << 7)
#define USART_CR1_PS (1u << 9)
#define USART_CR1_PCE (1u << 10)
#define USART_CR1_M (1u << 12)
#define USART_CR1_UE (1u << 13)
#define USART_CR2_STOP_2 (0x2u << 12)

/* General-purpose timers TIM2..TIM5 */
#define TIM_CR1(b) STM_REG(b, 0x00u)
#define TIM_DIER(b) STM_REG(b, 0x0Cu)
#define TIM_SR(b) STM_REG(b, 0x10u)
#define TIM_EGR(b) STM_REG(b, 0x14u)
#define TIM_CNT(b) STM_REG(b, 0x24u)
#define TIM_PSC(b) STM_REG(b, 0x28u)
#define TIM_ARR(b) STM_REG(b, 0x2Cu)
#define TIM_CR1_CEN (1u << 0)
#define TIM_CR1_URS (1u << 2)
#define TIM_CR1_OPM (1u << 3)
#define TIM_DIER_UIE (1u << 0)
#define TIM_SR_UIF (1u << 0)
#define TIM_EGR_UG (1u << 0)

/* SysTick and the SCB bit that clears a pending SysTick */
#define SYST_CSR STM_REG(0xE000E010u, 0x0u)
#define SYST_RVR STM_REG(0xE000E014u, 0x0u)
#define SYST_CVR STM_REG(0xE000E018u, 0x0u)
#define SYST_CSR_ENABLE 0x1u
#define SYST_CSR_TICKINT 0x2u
#define SYST_CSR_CLKSOURCE 0x4u
#define SYST_MAX 0x00FFFFFFu
#define SCB_ICSR STM_REG(0xE000ED04u, 0x0u)
#define NVIC_ISPR(n) STM_REG(0xE000E200u, 4u * (uint32_t)(n))
#define SCB_ICSR_PENDSTCLR (1u << 25)

/* Make interrupt irq pending (it runs when its priority allows). */
static inline void stm32_irq_pend(uint8_t irq)
{
    NVIC_ISPR(irq / 32u) = 1u << (irq % 32u);
}

static inline uint32_t stm32_irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void stm32_irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

#endif
