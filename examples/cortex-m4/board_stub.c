/* SPDX-License-Identifier: Apache-2.0 */
/* Board stubs: the CAN controller, the clock and the flash controller of a generic Cortex-M4
 * (STM32F4-like, cortex-m4.ld). They link; they drive no real controller. */
#include "board.h"

#include <string.h>

#define CPU_HZ 168000000u
#define CPU_MHZ (CPU_HZ / 1000000u)

/* Cortex-M4 core registers (ARMv7-M Architecture Reference Manual): the DWT cycle counter and
 * SysTick. */
#define DEMCR (*(volatile uint32_t *)0xE000EDFCu)
#define DEMCR_TRCENA (1u << 24)
#define DWT_CTRL (*(volatile uint32_t *)0xE0001000u)
#define DWT_CTRL_CYCCNTENA 1u
#define DWT_CYCCNT (*(volatile uint32_t *)0xE0001004u)
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CSR_ENABLE_TICKINT_CLKSOURCE 7u

/* --- Clock: the 32-bit cycle counter wraps every 25 s at 168 MHz, so it is extended to 64 bits
 * in software; the 1 ms SysTick interrupt reads it often enough never to miss a wrap. --- */
static uint32_t cycles_last;
static uint64_t cycles_total;

static uint64_t cycles(void)
{
    uint32_t primask;
    __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask));
    uint32_t now = DWT_CYCCNT;
    cycles_total += now - cycles_last; /* modulo 2^32: right across a wrap */
    cycles_last = now;
    uint64_t total = cycles_total;
    __asm volatile("msr primask, %0" ::"r"(primask));
    return total;
}

co_time_t clock_us(void)
{
    return cycles() / CPU_MHZ;
}

void board_init(void)
{
    DEMCR |= DEMCR_TRCENA;
    DWT_CYCCNT = 0;
    DWT_CTRL |= DWT_CTRL_CYCCNTENA;
    SYST_RVR = CPU_HZ / 1000u - 1u;
    SYST_CSR = SYST_CSR_ENABLE_TICKINT_CLKSOURCE;
}

void SysTick_Handler(void)
{
    (void)cycles();
}

/* --- CAN: a receive ring the interrupt fills (one producer, one consumer: no lock), and a
 * transmit stub. --- */
#define RX_QUEUE 16u /* a power of two */
static co_frame_t rx_queue[RX_QUEUE];
static volatile uint32_t rx_head, rx_tail, rx_overruns;

/* The controller's receive interrupt: read the mailbox into a frame and queue it. */
void CAN_RX_IRQHandler(void)
{
    co_frame_t frame = {0}; /* stub: id, len, flags and data from the receive mailbox */
    if (rx_head - rx_tail < RX_QUEUE) {
        rx_queue[rx_head % RX_QUEUE] = frame;
        rx_head++;
    } else {
        rx_overruns++;
    }
}

uint32_t can_receive_overruns(void)
{
    uint32_t primask;
    __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask));
    uint32_t n = rx_overruns;
    rx_overruns = 0;
    __asm volatile("msr primask, %0" ::"r"(primask));
    return n;
}

bool can_receive(co_frame_t *frame)
{
    if (rx_tail == rx_head)
        return false;
    *frame = rx_queue[rx_tail % RX_QUEUE];
    rx_tail++;
    return true;
}

/* The SysTick wakes the loop every millisecond: the deadline is met within 1 ms without a timer
 * of its own (board_mps2_an386.c arms one). Interrupts are masked from the test to the sleep, so
 * that a frame queued in between wakes the wfi instead of waiting for the next tick. */
void board_wait(co_time_t deadline)
{
    __asm volatile("cpsid i" ::: "memory");
    if (rx_tail == rx_head && clock_us() < deadline)
        __asm volatile("wfi");
    __asm volatile("cpsie i" ::: "memory");
}

/* The MCU's interrupts after the system vectors of startup.c: the CAN receive interrupt's number
 * is the vendor's (20 here, as on many STM32F4 parts). */
#define CAN_RX_IRQ 20
typedef void (*vector_t)(void);
__attribute__((section(".isr_vector.irq"),
               used)) static const vector_t irq_vectors[CAN_RX_IRQ + 1] = {
    [CAN_RX_IRQ] = CAN_RX_IRQHandler,
};

bool can_transmit(const co_frame_t *frame)
{
    (void)frame; /* stub: find a free transmit mailbox, write id, DLC and data, request */
    return true;
}

void board_leds(bool run, bool err)
{
    (void)run; /* stub: set or clear the two LEDs' GPIO output bits */
    (void)err;
}

/* --- Flash: the pages are the linker script's STORAGE region. --- */
extern uint8_t __storage_start[];

const uint8_t *flash_page(unsigned page)
{
    return &__storage_start[page * FLASH_PAGE_SIZE];
}

int flash_erase(unsigned page)
{
    if (page >= FLASH_STORAGE_PAGES)
        return -1;
    return 0; /* stub: unlock the flash controller, erase the page, wait, lock */
}

int flash_program(unsigned page, uint32_t offset, const uint8_t *data, size_t len)
{
    if (page >= FLASH_STORAGE_PAGES || offset > FLASH_PAGE_SIZE || len > FLASH_PAGE_SIZE - offset)
        return -1;
    (void)data; /* stub: unlock, program the bytes (in the controller's write unit), lock */
    return 0;
}
