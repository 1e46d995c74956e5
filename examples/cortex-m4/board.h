/* What the porter writes for a board: the CAN controller, a microsecond clock and flash pages.
 * Here they are stubs for a generic Cortex-M4 (the example links, it does not drive a real
 * controller): replace their bodies with your MCU vendor's registers or HAL. */
#ifndef BOARD_H
#define BOARD_H

#include "co/co_types.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* CAN: frames out (false when every transmit mailbox is busy) and a receive queue that the
 * controller's interrupt fills and the main loop empties. */
bool can_transmit(const co_frame_t *frame);
bool can_receive(co_frame_t *frame);

/* Starts the cycle counter behind clock_us() and the 1 ms SysTick. */
void board_init(void);

/* Microseconds since reset, 64 bits: never wraps, never goes back. */
co_time_t clock_us(void);
/* Sleeps until the next interrupt (a frame, or the 1 ms SysTick). */
void board_idle(void);

/* Flash: pages of FLASH_PAGE_SIZE bytes at the end of the flash, read through the memory map,
 * erased to 0xFF a page at a time and programmed byte-wise. */
#define FLASH_PAGE_SIZE 2048u
#define FLASH_STORAGE_PAGES 6u
const uint8_t *flash_page(unsigned page);
int flash_erase(unsigned page);
int flash_program(unsigned page, uint32_t offset, const uint8_t *data, size_t len);

#endif
