/* SPDX-License-Identifier: Apache-2.0 */
/* The CiA 401 I/O node (io401.h): its model and its terminals. */
#include "nodes/io/io401.h"

#include "io401_od.h"

const plain_model_t io401_model = {
    .name = "io",
    .description =
        "CiA 401 I/O node: 8 digital inputs, 8 outputs, 2 analogue inputs (eds/IO401.eds)",
    .od = &io401_od,
    .node_id_max = CO_NODE_ID_MAX,
    /* docs/decisions.md, D-IO401-IDENTITY: 0x40100000 plus the node-id. */
    .serial_base = 0x40100000u,
    .loss_from_any_state = false,
    .err_over_run = false,
    /* 1012h = 80000100h: consumes TIME on 100h (docs/io.md). */
    .time_stamp = true,
    .lss = true,
    /* 1029h:01 = 0 and 1F80h = 4 by default: CiA 301's behaviour without them (docs/io.md). */
    .error_behaviour = true,
    .nmt_startup = true,
    /* 1201h, a second SDO server for a second client (docs/io.md). */
    .sdo_servers = 1,
};

bool io401_set_input(plain_node_t *io, uint8_t input, bool on)
{
    if (input < 1 || input > IO401_DIGITAL_INPUTS)
        return false;
    uint8_t bit = (uint8_t)(1u << (input - 1));
    uint8_t inputs = io401_inputs(io);
    inputs = on ? (uint8_t)(inputs | bit) : (uint8_t)(inputs & ~bit);
    return co_od_set_value(&io->node, IO401_IDX_READ_INPUT_8, 1, inputs);
}

bool io401_set_analog(plain_node_t *io, uint8_t input, int16_t value)
{
    if (input < 1 || input > IO401_ANALOG_INPUTS)
        return false;
    return co_od_set_value(&io->node, IO401_IDX_READ_ANALOG_16, input, value);
}

uint8_t io401_inputs(const plain_node_t *io)
{
    return (uint8_t)co_od_value(&io->node, IO401_IDX_READ_INPUT_8, 1);
}

uint8_t io401_outputs(const plain_node_t *io)
{
    return (uint8_t)co_od_value(&io->node, IO401_IDX_WRITE_OUTPUT_8, 1);
}

int16_t io401_analog(const plain_node_t *io, uint8_t input)
{
    return (int16_t)co_od_value(&io->node, IO401_IDX_READ_ANALOG_16, input);
}
