/* SPDX-License-Identifier: Apache-2.0 */
/* The PLC300 slave (plc300.h): its model, the network markers' shared memory, the PLC program's
 * access to them. */
#include "nodes/plc300/plc300.h"

#include "plc300_od.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>

const plain_model_t plc300_model = {
    .name = "plc300",
    .description = "WEG PLC300 controller as a CANopen slave, network markers (eds/PLC300.eds)",
    .od = &plc300_od,
    .node_id_max = CO_NODE_ID_MAX,
    /* Different for every PLC300 (6.1.4): 0x30000000 plus the node-id. */
    .serial_base = 0x30000000u,
    .loss_from_any_state = true,
    .err_over_run = true,
    .lss = false,
    .error_behaviour = false, /* no 1029h or 1F80h in the manual's object list */
    .nmt_startup = false,
};

/* The views of an area start at multiples of 400h (3000h, 3400h, 3800h; 4000h, ...). */
#define VIEW_MASK 0x03FFu
#define VIEW_DWORD_BYTES 4u

static const uint16_t input_views[] = {PLC300_INPUT_BYTES, PLC300_INPUT_WORDS, PLC300_INPUT_DWORDS};
static const uint16_t output_views[] = {PLC300_OUTPUT_BYTES, PLC300_OUTPUT_WORDS,
                                        PLC300_OUTPUT_DWORDS};

static bool is_output(uint16_t index)
{
    return index >= PLC300_OUTPUT_BYTES;
}

/* The write of `len` bytes at `offset` of an area reaches every other object over those bytes:
 * each view's objects that start up to 3 bytes before it (a double word) and before its end. */
static void share_write(co_node_t *node, const co_od_entry_t *written, const uint8_t *data,
                        size_t len)
{
    const uint16_t *views = is_output(written->index) ? output_views : input_views;
    uint16_t offset = (uint16_t)(written->index & VIEW_MASK);
    uint16_t from =
        offset >= VIEW_DWORD_BYTES - 1 ? (uint16_t)(offset - (VIEW_DWORD_BYTES - 1)) : 0;
    for (size_t v = 0; v < 3; v++) {
        for (uint16_t start = from; start < offset + len; start++) {
            const co_od_entry_t *e = co_od_find(node->od, (uint16_t)(views[v] + start), 0);
            if (!e || e == written || start + e->size <= offset)
                continue;
            uint8_t *bytes = co_od_bytes(node, e);
            for (uint16_t b = start; b < start + e->size; b++) {
                if (b >= offset && b < offset + len)
                    bytes[b - start] = data[b - offset];
            }
        }
    }
}

/* Every marker object (plc300.hooks): the value is stored as written, and the other objects of
 * its area over the same bytes take it (Table 5.4's note: one memory per area). */
static uint32_t marker_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                             size_t len, co_od_origin_t origin)
{
    (void)origin;
    share_write(node, entry, data, len);
    return 0;
}

const co_od_hook_t plc300_marker = {.write = marker_write};

bool plc300_marker_parse(const char *text, plc300_marker_t *marker)
{
    if (*text == '%')
        text++;
    char area = (char)toupper((unsigned char)text[0]);
    char width = area ? (char)toupper((unsigned char)text[1]) : '\0';
    if ((area != 'I' && area != 'Q') || !isdigit((unsigned char)text[2]))
        return false;
    uint8_t size = width == 'B' ? 1 : width == 'W' ? 2 : width == 'D' ? 4 : 0;
    char *end;
    unsigned long number = strtoul(text + 2, &end, 10);
    if (size == 0 || *end != '\0' || number < PLC300_MARKER_FIRST ||
        number - PLC300_MARKER_FIRST + size > PLC300_AREA_BYTES ||
        (number - PLC300_MARKER_FIRST) % size != 0)
        return false;
    const uint16_t *views = area == 'Q' ? output_views : input_views;
    marker->output = area == 'Q';
    marker->size = size;
    marker->offset = (uint16_t)(number - PLC300_MARKER_FIRST);
    marker->index = (uint16_t)(views[size == 1 ? 0 : size == 2 ? 1 : 2] + marker->offset);
    return true;
}

void plc300_marker_name(const plc300_marker_t *marker, char *buf, size_t len)
{
    snprintf(buf, len, "%%%c%c%u", marker->output ? 'Q' : 'I',
             marker->size == 1   ? 'B'
             : marker->size == 2 ? 'W'
                                 : 'D',
             PLC300_MARKER_FIRST + marker->offset);
}

uint8_t plc300_area_byte(const plain_node_t *plc, bool output, uint16_t offset)
{
    const co_node_t *node = &plc->node;
    uint16_t index = (uint16_t)((output ? PLC300_OUTPUT_BYTES : PLC300_INPUT_BYTES) + offset);
    return co_od_bytes(node, co_od_find(node->od, index, 0))[0];
}

uint32_t plc300_marker_get(const plain_node_t *plc, const plc300_marker_t *marker)
{
    uint32_t value = 0;
    for (uint8_t b = 0; b < marker->size; b++)
        value |= (uint32_t)plc300_area_byte(plc, marker->output, (uint16_t)(marker->offset + b))
                 << (8 * b);
    return value;
}

/* The marker's object may be wider than the marker (3000h, two bytes: docs/decisions.md,
 * D-PLC300-3000H): its other bytes are written back as they are. */
uint32_t plc300_marker_set(plain_node_t *plc, const plc300_marker_t *marker, uint32_t value)
{
    co_node_t *node = &plc->node;
    const co_od_entry_t *entry = co_od_find(node->od, marker->index, 0);
    uint8_t bytes[4];
    for (uint8_t b = 0; b < entry->size && b < sizeof bytes; b++)
        bytes[b] = b < marker->size ? (uint8_t)(value >> (8 * b)) : co_od_bytes(node, entry)[b];
    return co_od_write_entry(node, entry, bytes, entry->size, CO_OD_ORIGIN_APP);
}
