/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Cortex-M reset and vector table shared by the boards: copy .data, clear
 * .bss, enable the FPU's access (the C library may touch it), run the C
 * library's constructors and main(), and report a fault by its vector.
 */
#include <stdint.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
extern void __libc_init_array(void);
extern int main(void);
extern void exit(int);
/* newlib's semihosting library, when linked (rdimon.specs) */
extern void initialise_monitor_handles(void) __attribute__((weak));

/* no crti/crtn: the constructors run through __libc_init_array alone */
void _init(void) {}
void _fini(void) {}

/* Boards may override: called on any fault before the image stops. */
void bw_board_fault(uint32_t vector) __attribute__((weak));
void bw_board_fault(uint32_t vector)
{
    (void)vector;
    for (;;) {
    }
}

void Reset_Handler(void)
{
    uint32_t *src = &_sidata, *dst = &_sdata;
    while (dst < &_edata)
        *dst++ = *src++;
    for (dst = &_sbss; dst < &_ebss; dst++)
        *dst = 0;
#if defined(__ARM_FP)
    /* CPACR: full access to CP10 and CP11 */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
#endif
    if (initialise_monitor_handles)
        initialise_monitor_handles();
    __libc_init_array();
    exit(main());
}

static void fault_entry(void)
{
    uint32_t ipsr;
    __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
    bw_board_fault(ipsr & 0x1FFu);
}

void NMI_Handler(void) __attribute__((weak, alias("fault_entry")));
void HardFault_Handler(void) __attribute__((weak, alias("fault_entry")));
void MemManage_Handler(void) __attribute__((weak, alias("fault_entry")));
void BusFault_Handler(void) __attribute__((weak, alias("fault_entry")));
void UsageFault_Handler(void) __attribute__((weak, alias("fault_entry")));
void SVC_Handler(void) __attribute__((weak, alias("fault_entry")));
void PendSV_Handler(void) __attribute__((weak, alias("fault_entry")));
void SysTick_Handler(void) __attribute__((weak));
void SysTick_Handler(void) {}

__attribute__((section(".isr_vector"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(uintptr_t)&_estack,
    Reset_Handler,
    NMI_Handler,
    HardFault_Handler,
    MemManage_Handler,
    BusFault_Handler,
    UsageFault_Handler,
    0,
    0,
    0,
    0,
    SVC_Handler,
    0,
    0,
    PendSV_Handler,
    SysTick_Handler,
};
