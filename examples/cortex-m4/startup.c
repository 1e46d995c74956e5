/* Startup of a Cortex-M4 (ARMv7-M): the vector table the hardware reads at reset, and the reset
 * handler that sets up C (.data copied from flash, .bss zeroed) before main(). */
#include <stdint.h>
#include <string.h>

/* Symbols of cortex-m4.ld. */
extern uint32_t __stack_top[];
extern uint8_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];

int main(void);
void SysTick_Handler(void);
void CAN_RX_IRQHandler(void);

void Reset_Handler(void)
{
    memcpy(__data_start, __data_load, (size_t)(__data_end - __data_start));
    memset(__bss_start, 0, (size_t)(__bss_end - __bss_start));
    main();
    for (;;)
        ;
}

/* Faults and interrupts without a handler stop here, where a debugger finds them. */
static void unexpected(void)
{
    for (;;)
        ;
}

/* ARMv7-M: 16 system entries (the initial stack pointer first), then the MCU's interrupts; the
 * CAN receive interrupt's number is the vendor's (20 here, as on many STM32F4 parts). */
#define SYSTEM_VECTORS 16
#define CAN_RX_IRQ 20
typedef void (*vector_t)(void);
__attribute__((section(".isr_vector"),
               used)) static const vector_t vectors[SYSTEM_VECTORS + CAN_RX_IRQ + 1] = {
    [0] = (vector_t)(uintptr_t)__stack_top,
    [1] = Reset_Handler,
    [2] = unexpected,  /* NMI */
    [3] = unexpected,  /* HardFault */
    [4] = unexpected,  /* MemManage */
    [5] = unexpected,  /* BusFault */
    [6] = unexpected,  /* UsageFault */
    [11] = unexpected, /* SVCall */
    [14] = unexpected, /* PendSV */
    [15] = SysTick_Handler,
    [SYSTEM_VECTORS + CAN_RX_IRQ] = CAN_RX_IRQHandler,
};
