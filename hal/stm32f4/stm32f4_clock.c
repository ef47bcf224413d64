/* SPDX-License-Identifier: Apache-2.0 */
/* modcp HAL (STM32F4) — clock tree, peripheral clocks, GPIO and the TIM5 time base. */
#include <stdbool.h>
#include <stdint.h>

#include "modcp/hal_stm32f4.h"
#include "stm32f4_regs.h"

#define HSI_HZ 16000000u
#define PLL_M 8u   /* 16 MHz / 8 = 2 MHz VCO input */
#define PLL_N 168u /* VCO 336 MHz */
#define PLL_P 2u   /* SYSCLK 168 MHz */
#define PLL_Q 7u   /* 48 MHz for USB / SDIO */
#define SYSCLK_HZ 168000000u
#define PLL_LOCK_SPINS 100000u

/* QEMU 7.2's netduinoplus2: core clock 168 MHz, timer model clock 1 GHz. */
#define QEMU_HCLK_HZ 168000000u
#define QEMU_TIM_HZ 1000000000u

bool modcp_stm32_is_qemu(void)
{
    /* HSION and HSIRDY are set from reset on every STM32F4; QEMU 7.2 has no RCC model
     * and reads 0 there. */
    return RCC_CR == 0u;
}

void modcp_stm32_clock_init(modcp_stm32_clocks_t *out)
{
    if (modcp_stm32_is_qemu()) {
        out->qemu = true;
        out->hclk_hz = QEMU_HCLK_HZ;
        out->pclk1_hz = QEMU_HCLK_HZ / 4u; /* BRR is not modelled */
        out->pclk2_hz = QEMU_HCLK_HZ / 2u;
        out->tim_apb1_hz = QEMU_TIM_HZ;
        return;
    }
    out->qemu = false;
    /* flash wait states before raising the clock: 5 WS at 168 MHz, 2.7 .. 3.6 V */
    FLASH_ACR = FLASH_ACR_LATENCY_5WS | FLASH_ACR_PRFTEN | FLASH_ACR_ICEN | FLASH_ACR_DCEN;
    RCC_CFGR = RCC_CFGR_PPRE1_DIV4 | RCC_CFGR_PPRE2_DIV2; /* SW = HSI, AHB /1 */
    RCC_PLLCFGR = PLL_M | (PLL_N << 6) | (((PLL_P / 2u) - 1u) << 16) | (PLL_Q << 24); /* src HSI */
    RCC_CR |= RCC_CR_PLLON;
    uint32_t spins = 0u;
    while ((RCC_CR & RCC_CR_PLLRDY) == 0u && spins < PLL_LOCK_SPINS) {
        spins++;
    }
    if ((RCC_CR & RCC_CR_PLLRDY) == 0u) {
        /* no lock: stay on HSI with the bus prescalers set above */
        out->hclk_hz = HSI_HZ;
        out->pclk1_hz = HSI_HZ / 4u;
        out->pclk2_hz = HSI_HZ / 2u;
        out->tim_apb1_hz = HSI_HZ / 2u; /* APB1 prescaler != 1: timers run at 2 x PCLK1 */
        return;
    }
    RCC_CFGR = (RCC_CFGR & ~0x3u) | RCC_CFGR_SW_PLL;
    while ((RCC_CFGR & RCC_CFGR_SWS_MASK) != RCC_CFGR_SWS_PLL) {
    }
    out->hclk_hz = SYSCLK_HZ;
    out->pclk1_hz = SYSCLK_HZ / 4u;
    out->pclk2_hz = SYSCLK_HZ / 2u;
    out->tim_apb1_hz = SYSCLK_HZ / 2u;
}

void modcp_stm32_rcc_enable(uint32_t ahb1, uint32_t apb1, uint32_t apb2)
{
    RCC_AHB1ENR |= ahb1;
    RCC_APB1ENR |= apb1;
    RCC_APB2ENR |= apb2;
    (void)RCC_APB2ENR; /* read back: the clock is on before the first access */
}

/* ---- GPIO ---- */

static void set2(uintptr_t reg_addr, uint8_t pin, uint32_t v)
{
    volatile uint32_t *r = (volatile uint32_t *)reg_addr;
    uint32_t shift = 2u * (uint32_t)pin;
    *r = (*r & ~(3u << shift)) | ((v & 3u) << shift);
}

void modcp_stm32_pin_output(const modcp_stm32_pin_t *p)
{
    if (p->port == 0u) {
        return;
    }
    modcp_stm32_pin_set(p, false);
    GPIO_OTYPER(p->port) &= ~(1u << p->pin);
    set2(p->port + 0x08u, p->pin, 1u); /* OSPEEDR: medium */
    set2(p->port + 0x0Cu, p->pin, 0u); /* PUPDR: none */
    set2(p->port + 0x00u, p->pin, 1u); /* MODER: output */
}

void modcp_stm32_pin_af(uintptr_t port, uint8_t pin, uint8_t af, bool pull_up)
{
    uint32_t n = pin / 8u;
    uint32_t shift = 4u * (uint32_t)(pin % 8u);
    GPIO_AFR(port, n) = (GPIO_AFR(port, n) & ~(0xFu << shift)) | ((uint32_t)(af & 0xFu) << shift);
    set2(port + 0x08u, pin, 2u);                  /* OSPEEDR: fast */
    set2(port + 0x0Cu, pin, pull_up ? 1u : 0u);   /* PUPDR */
    set2(port + 0x00u, pin, 2u);                  /* MODER: alternate function */
}

void modcp_stm32_pin_set(const modcp_stm32_pin_t *p, bool on)
{
    if (p->port == 0u) {
        return;
    }
    bool level = on != p->active_low;
    GPIO_BSRR(p->port) = level ? (1u << p->pin) : (1u << (p->pin + 16u));
}

/* ---- TIM5: microseconds ---- */

static uintptr_t us_tim;
static modcp_timebase_t ms_tb; /* milliseconds from the microseconds (modcp/hal_timebase.h) */

void modcp_stm32_clock_us_init(uintptr_t tim, uint32_t tim_clk_hz)
{
    us_tim = tim;
    TIM_CR1(tim) = 0u;
    TIM_DIER(tim) = 0u;
    TIM_PSC(tim) = tim_clk_hz / 1000000u - 1u;
    TIM_ARR(tim) = 0xFFFFFFFFu;
    TIM_EGR(tim) = TIM_EGR_UG; /* load the prescaler, counter to 0 */
    TIM_SR(tim) = 0u;
    TIM_CR1(tim) = TIM_CR1_CEN;
    modcp_timebase_init(&ms_tb, 1000000u, 32u, false, TIM_CNT(tim));
}

uint32_t modcp_stm32_clock_us(void)
{
    return TIM_CNT(us_tim);
}

uint32_t modcp_stm32_clock_ms(void)
{
    uint32_t pm = stm32_irq_save();
    modcp_timebase_feed(&ms_tb, TIM_CNT(us_tim)); /* at least every 71 minutes (the tick does) */
    uint32_t ms = ms_tb.ms;
    stm32_irq_restore(pm);
    return ms;
}
