/* SPDX-License-Identifier: Apache-2.0 */
/* Startup of a Cortex-M4 (ARMv7-M): the system part of the vector table the hardware reads at
 * reset, and the reset handler that sets up C (.data copied from flash, .bss zeroed) before
 * main(). The MCU's interrupts follow in the board's file (section .isr_vector.irq, which
 * sections.ld places right after this table). */
#include <stdint.h>
#include <string.h>

/* Symbols of sections.ld. */
extern uint32_t __stack_top[];
extern uint8_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];

int main(void);
void SysTick_Handler(void);

void Reset_Handler(void)
{
    memcpy(__data_start, __data_load, (size_t)(__data_end - __data_start));
    memset(__bss_start, 0, (size_t)(__bss_end - __bss_start));
    main();
    for (;;)
        ;
}

/* Faults and interrupts without a handler stop here, where a debugger finds them. */
void unexpected_interrupt(void)
{
    for (;;)
        ;
}

/* ARMv7-M: 16 system entries, the initial stack pointer first. */
#define SYSTEM_VECTORS 16
typedef void (*vector_t)(void);
__attribute__((section(".isr_vector"), used)) static const vector_t vectors[SYSTEM_VECTORS] = {
    [0] = (vector_t)(uintptr_t)__stack_top,
    [1] = Reset_Handler,
    [2] = unexpected_interrupt,  /* NMI */
    [3] = unexpected_interrupt,  /* HardFault */
    [4] = unexpected_interrupt,  /* MemManage */
    [5] = unexpected_interrupt,  /* BusFault */
    [6] = unexpected_interrupt,  /* UsageFault */
    [11] = unexpected_interrupt, /* SVCall */
    [14] = unexpected_interrupt, /* PendSV */
    [15] = SysTick_Handler,
};
