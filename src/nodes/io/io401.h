/* SPDX-License-Identifier: Apache-2.0 */
/* A plain CiA 401 I/O node (nodes/plain_node.h; eds/IO401.eds): eight digital inputs (6000h:01),
 * eight digital outputs (6200h:01) and two 16-bit analogue inputs (6401h:01..02), with the
 * CiA 401 default PDOs: RPDO1 sets the outputs, TPDO1 sends the inputs and TPDO2 the analogue
 * inputs, each when its data changes. The application (atv312d's control commands) is the
 * world at the terminals: it sets the inputs and reads the outputs. docs/io.md. */
#ifndef NODES_IO401_H
#define NODES_IO401_H

#include "nodes/plain_node.h"

#define IO401_DIGITAL_INPUTS 8u
#define IO401_DIGITAL_OUTPUTS 8u
#define IO401_ANALOG_INPUTS 2u

/* CiA 401's objects. */
#define IO401_IDX_READ_INPUT_8 0x6000u
#define IO401_IDX_WRITE_OUTPUT_8 0x6200u
#define IO401_IDX_READ_ANALOG_16 0x6401u

extern const plain_model_t io401_model;

/* Digital input `input` (1..8) on or off: false when there is no such input. */
bool io401_set_input(plain_node_t *io, uint8_t input, bool on);
/* Analogue input `input` (1..2) at `value` (the raw INTEGER16 of 6401h): false when no such
 * input. */
bool io401_set_analog(plain_node_t *io, uint8_t input, int16_t value);

uint8_t io401_inputs(const plain_node_t *io);  /* 6000h:01, input 1 in bit 0 */
uint8_t io401_outputs(const plain_node_t *io); /* 6200h:01, output 1 in bit 0 */
int16_t io401_analog(const plain_node_t *io, uint8_t input);

#endif
