/* SPDX-License-Identifier: Apache-2.0 */
/* modcp boards — reset handler, default handlers and the C library's minimal system
 * calls. The vector table itself is board-specific (boards/<board>/board.c) because the
 * interrupt numbers differ; it references Reset_Handler and the handlers here.
 * Memory layout symbols come from boards/common/sections.ld. */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "board/cortexm.h"
#include "board/startup.h"

extern uint32_t _sidata[], _sdata[], _edata[], _sbss[], _ebss[];
extern uint8_t _heap_start[], _heap_end[];

int main(void);

void Reset_Handler(void)
{
    /* Interrupts stay masked (PRIMASK) until the application has set up everything an
     * interrupt handler may touch; app.c enables them. */
    cm_disable_irqs();
#if defined(__ARM_FP)
    /* Cortex-M4F: full access to CP10/CP11 before any floating-point instruction. */
    SCB_CPACR |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    const uint32_t *src = _sidata;
    for (uint32_t *dst = _sdata; dst < _edata;) {
        *dst++ = *src++;
    }
    for (uint32_t *dst = _sbss; dst < _ebss;) {
        *dst++ = 0u;
    }
#if !defined(__ARM_ARCH_6M__) && !defined(__ARM_ARCH_8M_BASE__)
    /* (ARMv6-M: CCR is read-only, SHCSR / CFSR do not exist, every fault is HardFault) */
    SCB_CCR |= CCR_DIV_0_TRP;
    SCB_SHCSR |= SHCSR_FAULTS_ENA;
#endif
    (void)main();
    for (;;) {
        cm_wfi();
    }
}

/* Faults and unexpected interrupts stop here; the fault status stays readable in a
 * debugger (SCB_CFSR, the stacked PC). */
volatile uint32_t startup_fault_cfsr;
volatile uint32_t startup_fault_ipsr;

void Default_Handler(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    startup_fault_ipsr = ipsr;
#if !defined(__ARM_ARCH_6M__) && !defined(__ARM_ARCH_8M_BASE__)
    startup_fault_cfsr = SCB_CFSR;
#endif
    cm_disable_irqs();
    for (;;) {
    }
}

/* The C library's dtoa / strtod (used by the console's float formatting) allocate a few
 * hundred bytes of big-number scratch; they get a small fixed arena reserved by the
 * linker script. Nothing else allocates. */
void *_sbrk(ptrdiff_t incr);
void *_sbrk(ptrdiff_t incr)
{
    static uint8_t *brk = _heap_start;
    if (incr < 0 || (size_t)incr > (size_t)(_heap_end - brk)) {
        errno = ENOMEM;
        return (void *)-1;
    }
    uint8_t *prev = brk;
    brk += incr;
    return prev;
}

/* The rest of the system-call layer newlib-nano links against (its printf family shares
 * the stdio machinery, assert() ends in abort()). No file I/O exists: every descriptor
 * is closed; abort() and exit() stop like an unexpected fault. */
struct stat;
void _exit(int status) __attribute__((noreturn));
int _kill(int pid, int sig);
int _getpid(void);
int _write(int fd, const void *buf, size_t n);
int _read(int fd, void *buf, size_t n);
int _close(int fd);
int _fstat(int fd, struct stat *st);
int _isatty(int fd);
off_t _lseek(int fd, off_t off, int whence);

void _exit(int status)
{
    (void)status;
    Default_Handler();
    for (;;) {
    }
}

int _kill(int pid, int sig)
{
    (void)pid;
    (void)sig;
    errno = EINVAL;
    return -1;
}

int _getpid(void)
{
    return 1;
}

int _write(int fd, const void *buf, size_t n)
{
    (void)fd;
    (void)buf;
    (void)n;
    errno = EBADF;
    return -1;
}

int _read(int fd, void *buf, size_t n)
{
    (void)fd;
    (void)buf;
    (void)n;
    errno = EBADF;
    return -1;
}

int _close(int fd)
{
    (void)fd;
    errno = EBADF;
    return -1;
}

int _fstat(int fd, struct stat *st)
{
    (void)fd;
    (void)st;
    errno = EBADF;
    return -1;
}

int _isatty(int fd)
{
    (void)fd;
    errno = EBADF;
    return 0;
}

off_t _lseek(int fd, off_t off, int whence)
{
    (void)fd;
    (void)off;
    (void)whence;
    errno = EBADF;
    return -1;
}
