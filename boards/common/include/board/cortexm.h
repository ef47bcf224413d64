/* SPDX-License-Identifier: Apache-2.0 */
/* modcp boards — the few ARMv7-M core registers the boards use (SCB, NVIC, SysTick)
 * and the interrupt priority plan. Defined here from the ARMv7-M Architecture
 * Reference Manual; no CMSIS. */
#ifndef MODCP_BOARD_CORTEXM_H
#define MODCP_BOARD_CORTEXM_H

#include <stdbool.h>
#include <stdint.h>

#define CM_REG(addr) (*(volatile uint32_t *)(uintptr_t)(addr))
#define CM_REG8(addr) (*(volatile uint8_t *)(uintptr_t)(addr))

/* System control block */
#define SCB_ICSR CM_REG(0xE000ED04u)
#define SCB_VTOR CM_REG(0xE000ED08u)
#define SCB_AIRCR CM_REG(0xE000ED0Cu)
#define SCB_SCR CM_REG(0xE000ED10u)
#define SCB_CCR CM_REG(0xE000ED14u)
#define SCB_SHPR(n) CM_REG8(0xE000ED18u + (uint32_t)(n)) /* n = exception number - 4 */
#define SCB_SHCSR CM_REG(0xE000ED24u)
#define SCB_CFSR CM_REG(0xE000ED28u)
#define SCB_CPACR CM_REG(0xE000ED88u)
#define ICSR_PENDSVSET (1u << 28)
#define ICSR_PENDSTCLR (1u << 25)
#define CCR_DIV_0_TRP (1u << 4)
#define SHCSR_FAULTS_ENA (7u << 16) /* MemManage, BusFault, UsageFault handlers */

/* NVIC */
#define NVIC_ISER(n) CM_REG(0xE000E100u + 4u * (uint32_t)(n))
#define NVIC_ICER(n) CM_REG(0xE000E180u + 4u * (uint32_t)(n))
#define NVIC_ISPR(n) CM_REG(0xE000E200u + 4u * (uint32_t)(n))
#define NVIC_ICPR(n) CM_REG(0xE000E280u + 4u * (uint32_t)(n))
#define NVIC_IPR(irq) CM_REG8(0xE000E400u + (uint32_t)(irq))

/* SysTick */
#define SYST_CSR CM_REG(0xE000E010u)
#define SYST_RVR CM_REG(0xE000E014u)
#define SYST_CVR CM_REG(0xE000E018u)
#define SYST_CALIB CM_REG(0xE000E01Cu)
#define SYST_CSR_ENABLE 0x1u
#define SYST_CSR_TICKINT 0x2u
#define SYST_CSR_CLKSOURCE 0x4u /* processor clock */

/* Exception numbers of the system handlers whose priority is set (SHPR index = n - 4). */
enum { CM_EXC_SVCALL = 11, CM_EXC_PENDSV = 14, CM_EXC_SYSTICK = 15 };

/* Interrupt priority plan (upper bits; every Cortex-M implements at least 3).
 *  - CP level: the Modbus UART, the end-of-frame and transmit-complete timers, the
 *    tick and the CP task (PendSV). All modcp_cp_* calls of the CP happen at this one
 *    level, so they never preempt each other.
 *  - console level, below: the monitor console UART.
 *  - thread mode: the cyclic user program (FB) and the console commands.
 * The main loop masks the CP level with BASEPRI while it copies CP state. */
#define PRIO_CP 0x40u
#define PRIO_CONSOLE 0x80u

static inline void cm_irq_enable(unsigned irq, uint8_t prio)
{
    NVIC_IPR(irq) = prio;
    NVIC_ICPR(irq / 32u) = 1u << (irq % 32u);
    NVIC_ISER(irq / 32u) = 1u << (irq % 32u);
}

static inline void cm_irq_disable(unsigned irq)
{
    NVIC_ICER(irq / 32u) = 1u << (irq % 32u);
}

static inline void cm_irq_clear_pending(unsigned irq)
{
    NVIC_ICPR(irq / 32u) = 1u << (irq % 32u);
}

static inline void cm_enable_irqs(void)
{
    __asm__ volatile("cpsie i" ::: "memory");
}

static inline void cm_disable_irqs(void)
{
    __asm__ volatile("cpsid i" ::: "memory");
}

/* PRIMASK save / restore around a few instructions. */
static inline uint32_t cm_irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void cm_irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

/* BASEPRI: mask every interrupt at prio or lower urgency (numerically >= prio).
 * ARMv6-M (Cortex-M0/M0+) and ARMv8-M baseline have no BASEPRI: there any prio != 0
 * masks every interrupt (PRIMASK) and 0 unmasks them, which is what the callers (thread
 * mode with interrupts enabled, a short copy in between) need. */
static inline void cm_set_basepri(uint32_t prio)
{
#if defined(__ARM_ARCH_6M__) || defined(__ARM_ARCH_8M_BASE__)
    if (prio != 0u) {
        __asm__ volatile("cpsid i" ::: "memory");
    } else {
        __asm__ volatile("cpsie i" ::: "memory");
    }
#else
    __asm__ volatile("msr basepri, %0\n\tisb" ::"r"(prio) : "memory");
#endif
}

static inline void cm_wfi(void)
{
    __asm__ volatile("dsb\n\twfi" ::: "memory");
}

static inline void cm_dsb(void)
{
    __asm__ volatile("dsb" ::: "memory");
}

#endif
