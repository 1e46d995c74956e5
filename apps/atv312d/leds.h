/* SPDX-License-Identifier: Apache-2.0 */
/* How loud a DeviceNet card's LED change is in the daemon's log (docs/atv312d.md, "Messages"):
 * the levels follow what CANopen logs, not how often a LED changes. */
#ifndef ATV312D_LEDS_H
#define ATV312D_LEDS_H

#include "co_linux/log.h"
#include "dn/dn_node.h"

/* warn for a change to red or flashing red (a network fault: duplicate MAC ID, bus off, an I/O
 * connection timed out, as CANopen's communication loss and bus off are warnings); debug between
 * green and flashing green (a scanner's connections allocated and released, with every one of
 * its transactions, as CANopen logs no SDO transfer); info for the rest (going online, off,
 * back from a fault). */
co_log_level_t atv312d_led_change_level(dn_led_t from, dn_led_t to);

#endif
