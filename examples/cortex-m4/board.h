/* SPDX-License-Identifier: Apache-2.0 */
/* What the porter writes for a board: the CAN transport, a microsecond clock, the wait for the
 * next event, two LEDs and flash pages. Two boards implement it: board_stub.c, stubs for a generic
 * STM32F4-like Cortex-M4 (the example links, it drives no real controller: replace their bodies
 * with your MCU vendor's registers or HAL), and board_mps2_an386.c, Arm's MPS2 board as QEMU
 * emulates it, whose frames travel over its UART in the serial-line CAN protocol (slcan), so that
 * the firmware runs and answers on the host's SocketCAN (docs/porting.md). */
#ifndef BOARD_H
#define BOARD_H

#include "co/co_types.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* CAN: frames out (false when the transmitter has no room: the frame is lost) and a receive
 * queue that the receive interrupt fills and the main loop empties. */
bool can_transmit(const co_frame_t *frame);
bool can_receive(co_frame_t *frame);
/* Frames lost since the last call because the receive queue was full. */
uint32_t can_receive_overruns(void);

/* Starts the clock behind clock_us(), the timer of board_wait() and the CAN transport. */
void board_init(void);

/* Microseconds since reset, 64 bits: never wraps, never goes back. */
co_time_t clock_us(void);

/* Sleeps until a frame is queued or clock_us() reaches deadline (CO_TIME_NEVER: until a frame),
 * whichever comes first; returns at once if either is already so. */
void board_wait(co_time_t deadline);

/* The RUN (green) and ERR (red) LEDs, lit or dark; main.c blinks them as CiA 303-3 says. */
void board_leds(bool run, bool err);

/* Flash: pages of FLASH_PAGE_SIZE bytes at the end of the flash, read through the memory map,
 * erased to 0xFF a page at a time and programmed byte-wise (a bit goes from 1 to 0 only). */
#define FLASH_PAGE_SIZE 2048u
#define FLASH_STORAGE_PAGES 8u
const uint8_t *flash_page(unsigned page);
int flash_erase(unsigned page);
int flash_program(unsigned page, uint32_t offset, const uint8_t *data, size_t len);

#endif
