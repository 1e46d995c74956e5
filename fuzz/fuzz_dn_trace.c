/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of cotrace's DeviceNet decoder (src/trace/devicenet_decoder.c) on what
 * `cotrace --devicenet` reads: the input is a header byte (the assemblies of `--assemblies`, or
 * the defaults, and a small output size) and then a candump -L log, its lines read by
 * co_candump_parse as cotrace reads them (a line that does not parse is skipped). Each frame is
 * decoded by three decoders side by side: A into cotrace's 1,024 bytes, B with the frame's bytes
 * past its length set to garbage, C into the header's small buffer. Invariants (docs/fuzzing.md):
 * the text is NUL-terminated within its buffer (allocated at its exact size for
 * AddressSanitizer) and printable; it starts with the message group, message ID and MAC ID the
 * identifier has; B gives A's text and state (deterministic, and only the frame's bytes count), C
 * the start of A's text and A's state; a frame changes only its own node's state; a reassembled
 * message is never longer than the fragments received since its first one; the connections
 * allocated change only at the slave's response, by the choice the last request showed, or at
 * its restart (its duplicate MAC ID check request), as do the assemblies in use; and the line
 * cotrace prints for the frame reads back as the same frame, interface and time. */
#include "co_linux/candump.h"
#include "dn/dn_link.h"
#include "rig.h"
#include "trace/devicenet_decoder.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MEANING_MAX 1024u /* cotrace's (apps/cotrace/main.c) */
#define SMALL_CAP_STEP 5u
#define GARBAGE 0xA5u

enum { TO_SLAVE, FROM_SLAVE };

/* What the harness knows of a node from the frames and the texts, per slave MAC ID. */
typedef struct seen {
    size_t fragment_bytes[2]; /* since the last first fragment, master to slave and back */
    uint8_t choice;           /* of the last request, when its text showed one ("choice 0x..") */
} seen_t;

typedef struct harness {
    cotrace_dn_decoder_t a, b, c, before;
    seen_t seen[DN_MAC_ID_MAX + 1];
    char *text_a, *text_b, *text_c; /* heap buffers of exactly their size */
    size_t small_cap;
} harness_t;

static harness_t h;

static void check_text(const char *text, size_t cap)
{
    size_t len = strnlen(text, cap);
    rig_check(len < cap, "a text not NUL-terminated within its buffer");
    for (size_t i = 0; i < len; i++)
        rig_check(isprint((unsigned char)text[i]), "a text with a character that is not printable");
}

/* Group 2's messages of the master to a slave, whose identifier carries the slave's MAC ID. */
static bool master_to_slave(unsigned message)
{
    return message == 2 || message == 4 || message == 5 || message == 6;
}

/* The start of every text, from the identifier alone (DeviceNet's message groups). */
static void expected_start(const struct can_frame *f, char *out, size_t cap)
{
    canid_t id = f->can_id & CAN_SFF_MASK;
    if (f->can_id & CAN_ERR_FLAG)
        snprintf(out, cap, "CAN error frame");
    else if (f->can_id & CAN_EFF_FLAG)
        snprintf(out, cap, "29-bit identifier: not DeviceNet");
    else if (f->can_id & CAN_RTR_FLAG)
        snprintf(out, cap, "remote frame 0x%03X: DeviceNet has none", (unsigned)id);
    else if (id < 0x400)
        snprintf(out, cap, "G1 msg %u from %u: ", (unsigned)id >> 6, (unsigned)id & 0x3F);
    else if (id < 0x600)
        snprintf(out, cap, "G2 msg %u %s %u: ", (unsigned)id & 7,
                 master_to_slave(id & 7) ? "to" : "from", (unsigned)(id >> 3) & 0x3F);
    else if (id < 0x7C0)
        snprintf(out, cap, "G3 msg %u from %u: ", (unsigned)(id >> 6) & 7, (unsigned)id & 0x3F);
    else if (id < 0x7F0)
        snprintf(out, cap, "G4 msg %u: ", (unsigned)id - 0x7C0);
    else
        snprintf(out, cap, "identifier 0x%03X: invalid in DeviceNet", (unsigned)id);
}

static bool is_group2(const struct can_frame *f)
{
    canid_t id = f->can_id;
    return !(id & (CAN_ERR_FLAG | CAN_EFF_FLAG | CAN_RTR_FLAG)) && id >= 0x400 && id < 0x600;
}

/* The choice a request's text shows, or 0. */
static uint8_t shown_choice(const char *text)
{
    const char *at = strstr(text, "choice 0x");
    unsigned choice = 0;
    if (at)
        sscanf(at, "choice 0x%2x", &choice);
    return (uint8_t)choice;
}

/* Whether the text of a frame on the master's identifiers is a whole request (not a fragment on
 * its way, nor malformed, nor a response on the request's identifier, which answers nothing). */
static bool whole_request(const char *text)
{
    return !strstr(text, ": malformed") && !strstr(text, " on a request identifier") &&
           (!strstr(text, ": fragment ") || strstr(text, ", message of "));
}

/* The fragment model: bytes of fragments (not acknowledgements) since the last first one. */
static void count_fragment(seen_t *s, const struct can_frame *f, int direction)
{
    if (f->len < 2 || !(f->data[0] & DN_HDR_FRAG))
        return;
    uint8_t type = f->data[1] & DN_FRAG_TYPE;
    if (type == DN_FRAG_ACK)
        return;
    if (type == DN_FRAG_FIRST)
        s->fragment_bytes[direction] = 0;
    s->fragment_bytes[direction] += f->len - 2u;
}

/* A message being reassembled, or said reassembled, holds no more than the fragments received in
 * its direction since its first one. */
static void check_reassembly(const cotrace_dn_node_t *now, const seen_t *s, const char *text,
                             int direction)
{
    const dn_fragments_t *rx[2] = {&now->request, &now->response};
    for (int d = TO_SLAVE; d <= FROM_SLAVE; d++) {
        rig_check(rx[d]->len <= DN_MESSAGE_MAX, "a reassembled message longer than its buffer");
        rig_check(rx[d]->len <= s->fragment_bytes[d],
                  "a reassembled message longer than the fragments since its first");
    }
    unsigned long message_len;
    const char *at = strstr(text, ", message of ");
    if (at && sscanf(at, ", message of %lu bytes", &message_len) == 1)
        rig_check(message_len <= s->fragment_bytes[direction],
                  "a message said longer than the fragments since its first");
}

/* The connections and assemblies change only as the trace showed: at the slave's response, by
 * the last request's choice, or at a restart. */
static void check_tracking(const cotrace_dn_node_t *was, const cotrace_dn_node_t *now,
                           const seen_t *s, bool restart, bool response)
{
    if (restart) {
        rig_check(now->allocation == 0, "connections still allocated after a restart");
        rig_check(now->consumed == was->stored_consumed && now->produced == was->stored_produced,
                  "a restart that does not use the assemblies selected");
    } else {
        rig_check(now->consumed == was->consumed && now->produced == was->produced,
                  "assemblies in use changed without a restart");
        uint8_t changed = now->allocation ^ was->allocation;
        rig_check(!changed || response,
                  "connections allocated or released without the slave's response");
        rig_check((changed & (uint8_t)~s->choice) == 0,
                  "connections allocated or released that the last request did not choose");
    }
    rig_check(response || (now->stored_consumed == was->stored_consumed &&
                           now->stored_produced == was->stored_produced),
              "an assembly selection stored without the slave's response");
}

/* A group 2 frame against its node's state, and what the harness learns from it. */
static void check_node(const struct can_frame *f, const char *text)
{
    uint8_t mac = (uint8_t)(f->can_id >> 3) & DN_MAC_ID_MAX;
    uint8_t message = f->can_id & 7u;
    seen_t *s = &h.seen[mac];
    bool restart = message == DN_G2_DUPLICATE_MAC_CHECK && f->len == DN_DUP_MAC_LEN &&
                   !(f->data[0] & DN_DUP_MAC_RESPONSE);
    bool response = message == DN_G2_SLAVE_EXPLICIT_RESPONSE;
    bool request = message == DN_G2_MASTER_EXPLICIT_REQUEST || message == DN_G2_UNCONNECTED_REQUEST;
    if (restart)
        *s = (seen_t){.choice = 0};
    if (request || response)
        count_fragment(s, f, response ? FROM_SLAVE : TO_SLAVE);
    check_reassembly(&h.a.node[mac], s, text, response ? FROM_SLAVE : TO_SLAVE);
    check_tracking(&h.before.node[mac], &h.a.node[mac], s, restart, response);
    if (request && whole_request(text))
        s->choice = shown_choice(text);
}

/* The node a frame may change: a group 2 frame its own; a group 3 message on a connection the
 * UCMM opened the server's, which a request names in its header and a response sends; -1 for
 * none. */
static int node_of(const struct can_frame *f)
{
    if (is_group2(f))
        return (int)((f->can_id >> 3) & DN_MAC_ID_MAX);
    if (f->can_id & (CAN_ERR_FLAG | CAN_EFF_FLAG | CAN_RTR_FLAG))
        return -1;
    dn_can_id_t id = dn_can_id_decode(f->can_id);
    if (id.group != 3 || id.message_id == DN_G3_UNCONNECTED_REQUEST ||
        id.message_id == DN_G3_UNCONNECTED_RESPONSE || f->len < 2 || f->data[0] & DN_HDR_FRAG)
        return -1;
    return f->data[1] & DN_SERVICE_RESPONSE ? id.mac_id : f->data[0] & DN_HDR_MAC;
}

/* A frame changes no node but the one it may (node_of). */
static void check_other_nodes(const struct can_frame *f)
{
    int own = node_of(f);
    for (int i = 0; i <= (int)DN_MAC_ID_MAX; i++) {
        if (i != own)
            rig_check(memcmp(&h.a.node[i], &h.before.node[i], sizeof h.a.node[i]) == 0,
                      "a frame changed another node's state");
    }
}

static void decode_frame(const struct can_frame *f)
{
    h.before = h.a;
    cotrace_dn_decode(&h.a, f, h.text_a, MEANING_MAX);
    struct can_frame garbage = *f;
    memset(&garbage.data[f->len], GARBAGE, sizeof garbage.data - f->len);
    cotrace_dn_decode(&h.b, &garbage, h.text_b, MEANING_MAX);
    cotrace_dn_decode(&h.c, f, h.text_c, h.small_cap);

    check_text(h.text_a, MEANING_MAX);
    check_text(h.text_c, h.small_cap);
    char start[64];
    expected_start(f, start, sizeof start);
    rig_check(strncmp(h.text_a, start, strlen(start)) == 0,
              "a text that does not start with what the identifier says");
    rig_check(strcmp(h.text_a, h.text_b) == 0 && memcmp(&h.a, &h.b, sizeof h.a) == 0,
              "the bytes past a frame's length changed its text or the state");
    size_t shown = strlen(h.text_c);
    rig_check(shown == strnlen(h.text_a, h.small_cap - 1u) &&
                  memcmp(h.text_a, h.text_c, shown) == 0,
              "a text in a small buffer is not the start of the whole text");
    rig_check(memcmp(&h.a, &h.c, sizeof h.a) == 0, "the size of the text changed the state");
    check_other_nodes(f);
    if (is_group2(f))
        check_node(f, h.text_a);
}

/* The line cotrace prints for the frame (co_candump_format, into its CO_CANDUMP_LINE_MAX) reads
 * back as the frame, on the same interface, at the same time to the microsecond. */
static void check_printed_line(const struct timespec *wall, const char *iface,
                               const struct can_frame *f)
{
    char line[CO_CANDUMP_LINE_MAX];
    size_t n = co_candump_format(line, sizeof line, wall, iface, f);
    rig_check(n > 0, "a frame read from a line that cotrace cannot print");
    struct timespec wall_back;
    char iface_back[IFNAMSIZ];
    struct can_frame back;
    rig_check(co_candump_parse(line, &wall_back, iface_back, &back), "a printed line unreadable");
    rig_check(back.can_id == f->can_id && back.len == f->len &&
                  memcmp(back.data, f->data, f->len) == 0,
              "a printed line reads back as another frame");
    rig_check(strcmp(iface, iface_back) == 0, "a printed line reads back on another interface");
    rig_check(wall_back.tv_sec == wall->tv_sec && wall_back.tv_nsec == wall->tv_nsec / 1000 * 1000,
              "a printed line reads back at another time");
}

static void decode_line(const char *line)
{
    struct timespec wall;
    char iface[IFNAMSIZ];
    struct can_frame f;
    if (!co_candump_parse(line, &wall, iface, &f))
        return;
    check_printed_line(&wall, iface, &f);
    decode_frame(&f);
}

/* The header byte: bits 0-1 the consumed assembly (the default, 20, 21, 100), bits 2-3 the
 * produced one (the default, 70, 71, 101), bits 4-7 the small buffer's size (1..76). */
static void start(uint8_t header)
{
    static const uint16_t consumed[] = {0, 20, 21, 100}, produced[] = {0, 70, 71, 101};
    cotrace_dn_decoder_init(&h.a, consumed[header & 3u], produced[header >> 2 & 3u]);
    h.b = h.a;
    h.c = h.a;
    memset(h.seen, 0, sizeof h.seen);
    h.small_cap = 1u + SMALL_CAP_STEP * (header >> 4);
    h.text_a = malloc(MEANING_MAX);
    h.text_b = malloc(MEANING_MAX);
    h.text_c = malloc(h.small_cap);
    rig_check(h.text_a && h.text_b && h.text_c, "out of memory");
}

static void finish(void)
{
    free(h.text_a);
    free(h.text_b);
    free(h.text_c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    start(data[0]);
    char *line = malloc(size);
    rig_check(line != NULL, "out of memory");
    for (size_t at = 1; at < size;) {
        const uint8_t *end = memchr(&data[at], '\n', size - at);
        size_t len = end ? (size_t)(end - &data[at]) : size - at;
        memcpy(line, &data[at], len);
        line[len] = '\0';
        decode_line(line);
        at += len + 1u;
    }
    free(line);
    finish();
    return 0;
}
