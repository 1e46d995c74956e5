/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 58 CANopen card manual's EMCY code table, on its own so that a master or a trace
 * decoder can read the drive's emergencies without the drive (cotrace --emcy-table atv58). */
#ifndef ATV58_EMCY_H
#define ATV58_EMCY_H

#include "co/co_emcy_consumer.h"

/* For co_emcy_code_text_in: mnemonic and meaning of each code the card sends (atv58_emcy.c). */
extern const co_emcy_code_table_t atv58_emcy_table;

#endif
