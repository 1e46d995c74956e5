/* SPDX-License-Identifier: Apache-2.0 */
/* The board of the firmware that runs: Arm's MPS2 with the AN386 image (a Cortex-M4 at 25 MHz) as
 * QEMU emulates it (qemu-system-arm -M mps2-an386; tools/slcan-node starts it). It has no CAN
 * controller, so its frames travel over UART0 in the serial-line CAN protocol (src/slcan), which
 * Linux's slcan driver turns into a SocketCAN interface on the host.
 *
 * - Clock: SysTick counts the CPU clock down from 2^24, its interrupt counts the wraps (every
 *   671 ms); clock_us() is both together divided by 25.
 * - Deadline: the core's next deadline arms TIMER0, a one-shot, whose interrupt wakes the loop.
 * - Receive: the UART's receive interrupt reads the bytes, decodes lines and queues the frames;
 *   it answers the host's commands (O, C, Sn) itself.
 * - Transmit: can_transmit encodes the frame into a ring that the UART's transmit interrupt
 *   drains.
 * - LEDs: the FPGA's user LEDs 0 and 1 (FPGAIO).
 * - Flash: the storage pages are in the board's code SSRAM (mps2-an386.ld), which QEMU keeps across
 *   a reset of the board; erase and program follow NOR flash's rules.
 * Registers: the ARMv7-M Architecture Reference Manual (SysTick, NVIC, SCB) and the Cortex-M
 * System Design Kit's APB UART and timer, at the addresses of the AN386 memory map. */
#include "board.h"
#include "slcan/slcan.h"

#include <string.h>

#define CPU_HZ 25000000u
#define CPU_MHZ (CPU_HZ / 1000000u)

#define REG(addr) (*(volatile uint32_t *)(addr))

/* SysTick, NVIC, SCB. */
#define SYST_CSR REG(0xE000E010u)
#define SYST_RVR REG(0xE000E014u)
#define SYST_CVR REG(0xE000E018u)
#define SYST_CSR_ENABLE_TICKINT_CLKSOURCE 7u /* counting, interrupt, the processor's clock */
#define SYSTICK_BITS 24u
#define SYSTICK_MAX ((1u << SYSTICK_BITS) - 1u)
#define NVIC_ISER0 REG(0xE000E100u)
#define SCB_ICSR REG(0xE000ED04u)
#define SCB_ICSR_PENDSTSET (1u << 26)

/* CMSDK APB UART0 and its interrupts (receive 0, transmit 1). */
#define UART0_BASE 0x40004000u
#define UART_DATA REG(UART0_BASE + 0x00u)
#define UART_STATE REG(UART0_BASE + 0x04u)
#define UART_CTRL REG(UART0_BASE + 0x08u)
#define UART_INTCLEAR REG(UART0_BASE + 0x0Cu)
#define UART_BAUDDIV REG(UART0_BASE + 0x10u)
#define UART_STATE_TXFULL 0x1u
#define UART_STATE_RXFULL 0x2u
#define UART_CTRL_TX_RX_AND_THEIR_INTERRUPTS 0xFu
#define UART_INT_TX 0x1u
#define UART_INT_RX 0x2u
#define UART_BAUD 115200u
#define UART0_RX_IRQ 0
#define UART0_TX_IRQ 1

/* CMSDK APB TIMER0 and its interrupt (8). */
#define TIMER0_BASE 0x40000000u
#define TIMER_CTRL REG(TIMER0_BASE + 0x00u)
#define TIMER_VALUE REG(TIMER0_BASE + 0x04u)
#define TIMER_RELOAD REG(TIMER0_BASE + 0x08u)
#define TIMER_INTCLEAR REG(TIMER0_BASE + 0x0Cu)
#define TIMER_CTRL_ENABLE_AND_INTERRUPT 0x9u
#define TIMER0_IRQ 8

static inline uint32_t irq_save(void)
{
    uint32_t primask;
    __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void irq_restore(uint32_t primask)
{
    __asm volatile("msr primask, %0" ::"r"(primask) : "memory");
}

/* --- Clock --- */
static volatile uint32_t systick_wraps;
static uint64_t cycles_last; /* the latest time read, for the check below */

void SysTick_Handler(void)
{
    systick_wraps++;
}

co_time_t clock_us(void)
{
    uint32_t primask = irq_save();
    uint32_t wraps = systick_wraps;
    uint32_t count = SYST_CVR;
    /* A wrap whose interrupt has not run yet (masked here): count it, and read the counter again,
     * which has then certainly wrapped. */
    if (SCB_ICSR & SCB_ICSR_PENDSTSET) {
        wraps++;
        count = SYST_CVR;
    }
    uint64_t cycles = ((uint64_t)wraps << SYSTICK_BITS) + (SYSTICK_MAX - count);
    /* QEMU sets the pending bit from its timer thread, a moment after the counter shows the
     * wrap: a time 671 ms behind the last one is that wrap, not yet pending. (On silicon the
     * reload and the pending bit are one clock edge, and this never happens.) */
    if (cycles < cycles_last)
        cycles += 1u << SYSTICK_BITS;
    cycles_last = cycles;
    irq_restore(primask);
    return cycles / CPU_MHZ;
}

/* --- Deadline timer: one shot, stopped by its own interrupt. --- */
void TIMER0_Handler(void)
{
    TIMER_CTRL = 0;
    TIMER_INTCLEAR = 1;
}

static void timer_arm(co_time_t delay_us)
{
    /* At most 171 s (the 32-bit counter): the loop wakes, finds nothing due and sleeps again.
     * Capped before the multiplication, which a far deadline would overflow. */
    uint32_t ticks = delay_us >= UINT32_MAX / CPU_MHZ ? UINT32_MAX : (uint32_t)(delay_us * CPU_MHZ);
    if (ticks == 0)
        ticks = 1;
    TIMER_CTRL = 0;
    TIMER_INTCLEAR = 1;
    TIMER_RELOAD = ticks;
    TIMER_VALUE = ticks;
    TIMER_CTRL = TIMER_CTRL_ENABLE_AND_INTERRUPT;
}

/* --- CAN over the UART --- */
#define RX_QUEUE 16u /* frames, a power of two */
#define TX_RING 512u /* bytes, a power of two: 18 frames of 8 data bytes */
static co_frame_t rx_queue[RX_QUEUE];
static volatile uint32_t rx_head, rx_tail, rx_overruns;
static slcan_reader_t reader;
static uint8_t tx_ring[TX_RING];
static volatile uint32_t tx_head, tx_tail;

/* Writes bytes while the UART takes them; with interrupts masked or in an interrupt handler. */
static void tx_drain(void)
{
    while (tx_tail != tx_head && !(UART_STATE & UART_STATE_TXFULL)) {
        UART_DATA = tx_ring[tx_tail % TX_RING];
        tx_tail++;
    }
}

/* Queues len bytes whole, or none; with interrupts masked or in an interrupt handler. */
static bool tx_put(const char *bytes, size_t len)
{
    if (TX_RING - (tx_head - tx_tail) < len)
        return false;
    for (size_t i = 0; i < len; i++)
        tx_ring[(tx_head + i) % TX_RING] = (uint8_t)bytes[i];
    tx_head += (uint32_t)len;
    tx_drain();
    return true;
}

/* The transmitter took a byte: it has room for the next ones. */
void UART0_TX_Handler(void)
{
    UART_INTCLEAR = UART_INT_TX;
    tx_drain();
}

/* A byte came: a complete line is a frame to queue or a command to answer. The link is always
 * open: O and C are answered but change nothing, so that the board, reset on its own, is back on
 * the bus without the host opening the channel again (slcand opens it once). */
void UART0_RX_Handler(void)
{
    UART_INTCLEAR = UART_INT_RX;
    while (UART_STATE & UART_STATE_RXFULL) {
        slcan_message_t m = slcan_read(&reader, (uint8_t)UART_DATA);
        if (m.kind == SLCAN_FRAME) {
            if (rx_head - rx_tail < RX_QUEUE) {
                rx_queue[rx_head % RX_QUEUE] = m.frame;
                rx_head++;
            } else {
                rx_overruns++;
            }
        }
        char answer = slcan_answer(m.kind);
        if (answer != 0)
            (void)tx_put(&answer, 1); /* a full ring loses the answer, which the host ignores */
    }
}

bool can_receive(co_frame_t *frame)
{
    if (rx_tail == rx_head)
        return false;
    *frame = rx_queue[rx_tail % RX_QUEUE];
    rx_tail++;
    return true;
}

uint32_t can_receive_overruns(void)
{
    uint32_t primask = irq_save();
    uint32_t n = rx_overruns;
    rx_overruns = 0;
    irq_restore(primask);
    return n;
}

bool can_transmit(const co_frame_t *frame)
{
    char line[SLCAN_LINE_MAX];
    size_t len = slcan_encode(frame, line);
    if (len == 0)
        return false;
    uint32_t primask = irq_save();
    bool queued = tx_put(line, len);
    irq_restore(primask);
    return queued;
}

/* Interrupts are masked from the test to the sleep, so that a frame queued in between is not left
 * waiting for the next interrupt: wfi wakes on a pending interrupt, which runs once unmasked. */
void board_wait(co_time_t deadline)
{
    uint32_t primask = irq_save();
    co_time_t now = clock_us();
    if (rx_tail == rx_head && now < deadline) {
        if (deadline != CO_TIME_NEVER)
            timer_arm(deadline - now);
        __asm volatile("wfi");
    }
    irq_restore(primask);
}

/* The FPGA's user LEDs (AN386's FPGAIO LED0 register): LED 0 the RUN LED, LED 1 the ERR LED. */
#define FPGAIO_LED0 REG(0x40028000u)
#define LED_RUN 0x1u
#define LED_ERR 0x2u

void board_leds(bool run, bool err)
{
    FPGAIO_LED0 = (run ? LED_RUN : 0u) | (err ? LED_ERR : 0u);
}

void board_init(void)
{
    SYST_RVR = SYSTICK_MAX;
    SYST_CVR = 0;
    SYST_CSR = SYST_CSR_ENABLE_TICKINT_CLKSOURCE;
    slcan_reader_init(&reader);
    UART_BAUDDIV = CPU_HZ / UART_BAUD;
    UART_CTRL = UART_CTRL_TX_RX_AND_THEIR_INTERRUPTS;
    NVIC_ISER0 = 1u << UART0_RX_IRQ | 1u << UART0_TX_IRQ | 1u << TIMER0_IRQ;
}

/* The MCU's interrupts after the system vectors of startup.c (AN386: UART0 receive 0, transmit 1,
 * TIMER0 8). */
typedef void (*vector_t)(void);
__attribute__((section(".isr_vector.irq"),
               used)) static const vector_t irq_vectors[TIMER0_IRQ + 1] = {
    [UART0_RX_IRQ] = UART0_RX_Handler,
    [UART0_TX_IRQ] = UART0_TX_Handler,
    [TIMER0_IRQ] = TIMER0_Handler,
};

/* --- Flash, emulated in the storage pages: erase sets a page's bytes to 0xFF, programming only
 * clears bits, as NOR flash does; QEMU starts the pages at 0, which flash_storage.c reads as no
 * valid image. A real board calls its flash controller here (board_stub.c). --- */
extern uint8_t __storage_start[];

const uint8_t *flash_page(unsigned page)
{
    return &__storage_start[page * FLASH_PAGE_SIZE];
}

int flash_erase(unsigned page)
{
    if (page >= FLASH_STORAGE_PAGES)
        return -1;
    memset(&__storage_start[page * FLASH_PAGE_SIZE], 0xFF, FLASH_PAGE_SIZE);
    return 0;
}

int flash_program(unsigned page, uint32_t offset, const uint8_t *data, size_t len)
{
    if (page >= FLASH_STORAGE_PAGES || offset > FLASH_PAGE_SIZE || len > FLASH_PAGE_SIZE - offset)
        return -1;
    uint8_t *cell = &__storage_start[page * FLASH_PAGE_SIZE + offset];
    for (size_t i = 0; i < len; i++)
        cell[i] &= data[i];
    return 0;
}
