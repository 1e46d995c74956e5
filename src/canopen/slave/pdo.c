/* SPDX-License-Identifier: Apache-2.0 */
/* PDO engine (CiA 301 section 7.2.2; parameters 7.5.2.35-7.5.2.38). RPDO n+1 is configured by
 * 1400h+n / 1600h+n, TPDO n+1 by 1800h+n / 1A00h+n, for every such record in the dictionary.
 * PDOs run only in Operational: node.c routes frames here only then, and co_pdo_process() and
 * co_pdo_sync() do nothing in the other states. */
#include "co/co_node.h"

#include <string.h>

/* Communication parameter sub-indices (CiA 301 tables 71 and 73). */
#define PDO_SUB_COB_ID 1u
#define PDO_SUB_TYPE 2u
#define PDO_SUB_INHIBIT 3u
#define PDO_SUB_EVENT_TIMER 5u
#define PDO_SUB_SYNC_START 6u

#define PDO_MAX_BITS 64u             /* a classic CAN frame */
#define PDO_INHIBIT_UNIT_US 100u     /* inhibit time in 100 us units (CiA 301 table 72) */
#define PDO_INHIBIT_MS_UNIT_US 1000u /* a device's TPDO that counts it in ms (tpdo_inhibit_ms) */
#define PDO_INHIBIT_MS_TPDOS 32u     /* TPDOs the bit set co_pdo_t.inhibit_ms covers */
#define PDO_EVENT_UNIT_US 1000u      /* event timer in ms */

/* Register bits of the PDO and SYNC emergencies: a communication error is also a generic one. */
#define PDO_EMCY_REGISTER (CO_ERR_REG_GENERIC | CO_ERR_REG_COMMUNICATION)

typedef enum pdo_dir { PDO_RX, PDO_TX } pdo_dir_t;

static uint32_t pdo_cob_id(const co_node_t *node, uint16_t comm_index)
{
    return co_od_param(node, comm_index, PDO_SUB_COB_ID, CO_PDO_COBID_INVALID);
}

static bool pdo_cob_id_valid(uint32_t cob_id)
{
    return !(cob_id & CO_PDO_COBID_INVALID);
}

static bool tpdo_type_is_event(uint8_t type)
{
    return type >= CO_PDO_TYPE_EVENT_MANUFACTURER;
}

static bool tpdo_type_is_rtr(uint8_t type)
{
    return type == CO_PDO_TYPE_RTR_SYNC || type == CO_PDO_TYPE_RTR_EVENT;
}

static bool pdo_type_is_sync(uint8_t type)
{
    return type <= CO_PDO_TYPE_SYNC_MAX;
}

/* ---- Mapping ---------------------------------------------------------------------------- */

/* A data type index 0002h..0007h, sub-index 0, that this dictionary declares as a dummy. */
static bool map_entry_is_dummy(const co_od_t *od, uint16_t index, uint8_t subindex)
{
    return index >= CO_DT_INTEGER8 && index <= CO_DT_UNSIGNED32 && subindex == 0 &&
           (od->dummy_types & CO_OD_DUMMY(index)) != 0;
}

/* One mapping entry: index << 16 | sub-index << 8 | bit length. The object must exist and be
 * mappable in this direction (0x06040041), and be mapped whole (0x06040043). RPDOs may map a
 * data type index 0002h..0007h as a dummy that swallows bytes (CiA 301 7.4.8.4), if the
 * dictionary supports it ([DummyUsage] of CiA 306, co_od_t.dummy_types); otherwise it is an
 * absent object (0x06040041). */
static uint32_t map_entry_decode(const co_node_t *node, uint32_t value, pdo_dir_t dir,
                                 const co_od_entry_t **entry, uint8_t *size)
{
    uint16_t index = (uint16_t)(value >> 16);
    uint8_t subindex = (uint8_t)(value >> 8);
    uint32_t bits = value & 0xFFu;
    *entry = NULL;
    if (dir == PDO_RX && map_entry_is_dummy(node->od, index, subindex)) {
        if (bits != co_od_type_size((uint8_t)index) * 8u)
            return CO_SDO_ABORT_PARAM_INCOMPATIBLE;
        *size = (uint8_t)(bits / 8u);
        return CO_SDO_OK;
    }
    const co_od_entry_t *e = co_od_find(node->od, index, subindex);
    if (e == NULL || !(e->flags & (dir == PDO_RX ? CO_OD_RPDO : CO_OD_TPDO)))
        return CO_SDO_ABORT_NOT_MAPPABLE;
    if (bits != (uint32_t)e->size * 8u)
        return CO_SDO_ABORT_PARAM_INCOMPATIBLE;
    *entry = e;
    *size = (uint8_t)e->size;
    return CO_SDO_OK;
}

/* Decodes entries 1..count of a mapping parameter; the total must fit one frame (0x06040042). */
static uint32_t map_load(const co_node_t *node, uint16_t map_index, uint8_t count, pdo_dir_t dir,
                         co_pdo_map_t *map)
{
    memset(map, 0, sizeof(*map));
    if (count > CO_CONFIG_PDO_MAP_MAX)
        return CO_SDO_ABORT_PDO_LENGTH;
    uint32_t bits = 0;
    for (uint8_t i = 0; i < count; i++) {
        const co_od_entry_t *slot = co_od_find(node->od, map_index, (uint8_t)(i + 1));
        if (slot == NULL)
            return CO_SDO_ABORT_PDO_LENGTH;
        uint32_t abort = map_entry_decode(node, (uint32_t)co_od_get(node, slot), dir,
                                          &map->entry[i], &map->size[i]);
        if (abort != CO_SDO_OK)
            return abort;
        bits += map->size[i] * 8u;
    }
    if (bits > PDO_MAX_BITS)
        return CO_SDO_ABORT_PDO_LENGTH;
    map->count = count;
    map->length = (uint8_t)(bits / 8u);
    return CO_SDO_OK;
}

static bool pdo_map_load(const co_node_t *node, uint16_t map_index, pdo_dir_t dir,
                         co_pdo_map_t *map)
{
    uint8_t count = (uint8_t)co_od_param(node, map_index, 0, 0);
    return map_load(node, map_index, count, dir, map) == CO_SDO_OK;
}

/* The mapped objects' current bytes. A read hook may refresh a value first; if it refuses, the
 * stored value is sent. */
static void map_read(co_node_t *node, const co_pdo_map_t *map, uint8_t *data)
{
    uint8_t pos = 0;
    for (uint8_t i = 0; i < map->count; i++) {
        const co_od_entry_t *e = map->entry[i];
        if (e->hook != NULL && e->hook->read != NULL)
            (void)e->hook->read(node, e);
        memcpy(data + pos, co_od_bytes(node, e), map->size[i]);
        pos = (uint8_t)(pos + map->size[i]);
    }
}

/* ---- RPDO errors ------------------------------------------------------------------------ */

static bool rpdo_error_held(const co_node_t *node, uint16_t code)
{
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++) {
        const co_rpdo_t *r = &node->pdo.rpdo[n];
        if (r->length_error == code || (r->timed_out && code == CO_EMCY_RPDO_TIMEOUT))
            return true;
    }
    return false;
}

/* An error code is shared by all RPDOs: it clears when no RPDO holds it any more. */
static void rpdo_error_release(co_node_t *node, uint16_t code)
{
    if (!rpdo_error_held(node, code))
        co_emcy_clear(node, code);
}

/* Ends an RPDO's errors: its flags, and each EMCY that no other RPDO holds. The two go together:
 * a flag left without its EMCY makes the RPDO take the next fault for one already reported. */
static void rpdo_errors_end(co_node_t *node, co_rpdo_t *r)
{
    uint16_t length_error = r->length_error;
    bool timed_out = r->timed_out;
    r->length_error = 0;
    r->timed_out = false;
    if (length_error != 0)
        rpdo_error_release(node, length_error);
    if (timed_out)
        rpdo_error_release(node, CO_EMCY_RPDO_TIMEOUT);
}

/* ---- Configuration ---------------------------------------------------------------------- */

/* Loads an RPDO's or a TPDO's mapping and reads sub-indexes 1..6 of its communication parameter
 * (an RPDO uses fewer), an absent one as the PDO's default: an invalid COB-ID, event-driven, no
 * times, no SYNC start value. The PDO is valid when both its COB-ID and its mapping are. */
static bool pdo_load(const co_node_t *node, uint16_t comm, pdo_dir_t dir,
                     uint32_t param[PDO_SUB_SYNC_START + 1], co_pdo_map_t *map)
{
    param[PDO_SUB_COB_ID] = pdo_cob_id(node, comm);
    param[PDO_SUB_TYPE] = co_od_param(node, comm, PDO_SUB_TYPE, CO_PDO_TYPE_EVENT_PROFILE);
    for (uint8_t sub = PDO_SUB_INHIBIT; sub <= PDO_SUB_SYNC_START; sub++)
        param[sub] = co_od_param(node, comm, sub, 0);
    bool map_ok = pdo_map_load(node, (uint16_t)(comm + CO_PDO_INDEX_SPAN), dir, map);
    return pdo_cob_id_valid(param[PDO_SUB_COB_ID]) && map_ok;
}

/* An RPDO takes its parameters and restarts: nothing buffered, no deadline before a frame. */
static void rpdo_reload(co_node_t *node, uint16_t n)
{
    co_rpdo_t *r = &node->pdo.rpdo[n];
    uint32_t param[PDO_SUB_SYNC_START + 1];
    r->valid = pdo_load(node, (uint16_t)(CO_PDO_RPDO_COMM + n), PDO_RX, param, &r->map);
    r->can_id = (uint16_t)(param[PDO_SUB_COB_ID] & CO_PDO_COBID_CAN_ID);
    r->type = (uint8_t)param[PDO_SUB_TYPE];
    r->event_us = param[PDO_SUB_EVENT_TIMER] * PDO_EVENT_UNIT_US;
    r->buffered = false;
    r->deadline = CO_TIME_NEVER;
}

/* Forgets the transmission state: the next transmission is immediate (event-driven) or waits
 * for the next SYNC (synchronous). */
static void tpdo_restart(co_tpdo_t *t)
{
    t->sent = false;
    t->pending = false;
    t->requested = false;
    t->sync_due = false;
    t->sampled = false;
    t->started = false;
    t->sync_count = 0;
    t->inhibit_end = 0;
    t->event_due = CO_TIME_NEVER;
}

/* The unit of TPDO n+1's inhibit time: CiA 301's 100 us, or 1 ms where the node's device prints
 * that unit for this TPDO's row (co_node_config_t.tpdo_inhibit_ms). */
static uint32_t tpdo_inhibit_unit_us(const co_node_t *node, uint16_t n)
{
    bool in_ms = n < PDO_INHIBIT_MS_TPDOS && (node->pdo.inhibit_ms >> n) & 1u;
    return in_ms ? PDO_INHIBIT_MS_UNIT_US : PDO_INHIBIT_UNIT_US;
}

/* What a parameter write changes in a running TPDO. */
typedef enum tpdo_change {
    TPDO_RESTART,         /* COB-ID, type, mapping...: the transmission state starts afresh */
    TPDO_NEW_EVENT_TIMER, /* sub 5: only the event timer restarts */
    TPDO_NEW_INHIBIT      /* sub 3 of a valid TPDO: the running inhibit window stays as it is */
} tpdo_change_t;

/* A TPDO takes its parameters and keeps of its transmission state what `change` leaves. */
static void tpdo_load(co_node_t *node, uint16_t n, tpdo_change_t change)
{
    co_tpdo_t *t = &node->pdo.tpdo[n];
    uint32_t param[PDO_SUB_SYNC_START + 1];
    t->valid = pdo_load(node, (uint16_t)(CO_PDO_TPDO_COMM + n), PDO_TX, param, &t->map);
    uint32_t cob_id = param[PDO_SUB_COB_ID];
    t->rtr_allowed = !(cob_id & CO_PDO_COBID_NO_RTR);
    t->can_id = (uint16_t)(cob_id & CO_PDO_COBID_CAN_ID);
    t->type = (uint8_t)param[PDO_SUB_TYPE];
    t->inhibit_us = param[PDO_SUB_INHIBIT] * tpdo_inhibit_unit_us(node, n);
    t->event_us = param[PDO_SUB_EVENT_TIMER] * PDO_EVENT_UNIT_US;
    t->sync_start = (uint8_t)param[PDO_SUB_SYNC_START];
    if (change == TPDO_RESTART)
        tpdo_restart(t);
    else if (change == TPDO_NEW_EVENT_TIMER)
        t->event_due = t->event_us != 0 && t->sent ? node->now + t->event_us : CO_TIME_NEVER;
}

void co_pdo_restart(co_node_t *node)
{
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++)
        rpdo_reload(node, n);
    for (uint16_t n = 0; n < CO_CONFIG_TPDO_MAX; n++)
        tpdo_load(node, n, TPDO_RESTART);
}

/* The errors were detected by the communication that the reset restarts from its restored
 * parameters: none of them is detected any more (docs/error-control.md, "Errors and resets"). The
 * node is in Initialising, so clearing their EMCYs sends no error reset: the boot-up says it. */
void co_pdo_reset(co_node_t *node)
{
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++)
        rpdo_errors_end(node, &node->pdo.rpdo[n]);
    co_pdo_restart(node);
}

/* ---- TPDO transmission ------------------------------------------------------------------ */

static void tpdo_send(co_node_t *node, co_tpdo_t *t, const uint8_t *data)
{
    co_frame_t frame = {.id = t->can_id, .len = t->map.length};
    memcpy(frame.data, data, t->map.length);
    co_node_send(node, &frame);
    memcpy(t->last, data, t->map.length);
    t->sent = true;
    t->pending = false;
    t->inhibit_end = node->now + t->inhibit_us;
    /* The event timer restarts at every transmission. */
    t->event_due = t->event_us != 0 ? node->now + t->event_us : CO_TIME_NEVER;
}

static bool tpdo_changed(const co_tpdo_t *t, const uint8_t *data)
{
    return !t->sent || memcmp(data, t->last, t->map.length) != 0;
}

/* Event-driven TPDO (254/255): a change of the mapped data or the event timer makes a
 * transmission pending; it goes out once the inhibit time since the last one has elapsed. */
static co_time_t tpdo_process_event(co_node_t *node, co_tpdo_t *t, co_time_t now)
{
    uint8_t data[8];
    map_read(node, &t->map, data);
    t->pending = t->pending || tpdo_changed(t, data) || now >= t->event_due;
    if (t->pending && now >= t->inhibit_end)
        tpdo_send(node, t, data);
    return t->pending ? t->inhibit_end : t->event_due;
}

/* CiA 301 7.5.2.7: synchronous PDOs go and come within the synchronous window (1007h, us; 0:
 * no window) after the last SYNC. */
static bool in_sync_window(const co_node_t *node, co_time_t now)
{
    uint32_t window = co_sync_window_us(node);
    return window == 0 || now - node->pdo.sync_at <= window;
}

/* Synchronous TPDO sampled at the last SYNC: sent unless the window has already elapsed. */
static void tpdo_process_sync(co_node_t *node, co_tpdo_t *t, co_time_t now)
{
    t->sync_due = false;
    if (in_sync_window(node, now))
        tpdo_send(node, t, t->sample);
}

/* Cyclic synchronous TPDO (1..240): every n-th SYNC. With a SYNC start value and a SYNC counter
 * (1019h > 0) the first transmission is at the SYNC whose counter equals the start value. */
static bool tpdo_cyclic_due(const co_node_t *node, co_tpdo_t *t, uint8_t counter)
{
    bool use_start = t->sync_start != 0 && co_sync_overflow(node) != 0;
    if (!t->started) {
        if (use_start && counter != t->sync_start)
            return false;
        t->started = true;
        if (use_start) {
            t->sync_count = 0;
            return true;
        }
    }
    if (++t->sync_count < t->type)
        return false;
    t->sync_count = 0;
    return true;
}

static void tpdo_sync(co_node_t *node, co_tpdo_t *t, uint8_t counter)
{
    uint8_t data[8];
    if (t->type == CO_PDO_TYPE_SYNC_ACYCLIC) {
        map_read(node, &t->map, data);
        if (tpdo_changed(t, data) || t->requested) {
            memcpy(t->sample, data, t->map.length);
            t->sync_due = true;
        }
        t->requested = false;
    } else if (pdo_type_is_sync(t->type)) {
        if (tpdo_cyclic_due(node, t, counter)) {
            map_read(node, &t->map, t->sample);
            t->sync_due = true;
        }
    } else if (t->type == CO_PDO_TYPE_RTR_SYNC) {
        map_read(node, &t->map, t->sample);
        t->sampled = true;
    }
}

/* A remote request (COB-ID bit 30 clear): 252 answers with the data sampled at the last SYNC,
 * 253 with the current data, an event-driven TPDO is sent as soon as its inhibit time allows. */
static void tpdo_remote_request(co_node_t *node, co_tpdo_t *t)
{
    uint8_t data[8];
    if (!t->rtr_allowed)
        return;
    if (t->type == CO_PDO_TYPE_RTR_SYNC && t->sampled) {
        tpdo_send(node, t, t->sample);
    } else if (t->type == CO_PDO_TYPE_RTR_EVENT) {
        map_read(node, &t->map, data);
        tpdo_send(node, t, data);
    } else if (tpdo_type_is_event(t->type)) {
        t->pending = true;
    }
}

void co_tpdo_request(co_node_t *node, uint16_t pdo_number)
{
    if (pdo_number == 0 || pdo_number > CO_CONFIG_TPDO_MAX)
        return;
    co_tpdo_t *t = &node->pdo.tpdo[pdo_number - 1];
    if (!t->valid)
        return;
    if (t->type == CO_PDO_TYPE_SYNC_ACYCLIC)
        t->requested = true;
    else if (tpdo_type_is_event(t->type))
        t->pending = true;
}

/* ---- RPDO reception --------------------------------------------------------------------- */

static void rpdo_emcy(co_node_t *node, uint16_t n, uint16_t code, uint8_t received)
{
    uint8_t msef[5] = {(uint8_t)(n + 1), (uint8_t)((n + 1) >> 8), received,
                       node->pdo.rpdo[n].map.length, 0};
    co_emcy_raise(node, code, PDO_EMCY_REGISTER, msef);
}

/* CiA 301 table 21: 0x8210 for a frame shorter than the mapping, 0x8220 for a longer one; on a
 * node of 8-byte frames (CO_NODE_PAD_DLC8) DLC 8 is the padded length of every mapping. */
static void rpdo_check_length(co_node_t *node, uint16_t n, uint8_t len)
{
    co_rpdo_t *r = &node->pdo.rpdo[n];
    bool padded = (node->options & CO_NODE_PAD_DLC8) && len == CO_FRAME_DLC_MAX;
    uint16_t code = len < r->map.length              ? CO_EMCY_PDO_LENGTH
                    : len > r->map.length && !padded ? CO_EMCY_PDO_LENGTH_EXCEEDED
                                                     : 0;
    /* Each condition whole, on purpose: an early return when nothing changed, or a shared
     * "changed" flag, made GCC copy the calls below into a path for each code (44 bytes on a
     * Cortex-M4, docs/footprint.md). */
    uint16_t previous = r->length_error;
    r->length_error = code;
    if (previous != 0 && previous != code)
        rpdo_error_release(node, previous);
    if (code != 0 && previous != code)
        rpdo_emcy(node, n, code, len);
}

/* Writes the mapped objects with the full write path (limits, hooks, od_written); a value that
 * the dictionary refuses is not applied and the other objects still are. */
static void rpdo_apply(co_node_t *node, uint16_t n, const uint8_t *data)
{
    /* A copy: a mapped object's write may reconfigure this very PDO. */
    co_pdo_map_t map = node->pdo.rpdo[n].map;
    uint8_t pos = 0;
    for (uint8_t i = 0; i < map.count; i++) {
        const co_od_entry_t *e = map.entry[i];
        if (e != NULL)
            (void)co_od_write_entry(node, e, data + pos, map.size[i], CO_OD_ORIGIN_PDO);
        pos = (uint8_t)(pos + map.size[i]);
    }
    if (node->hooks != NULL && node->hooks->rpdo != NULL)
        node->hooks->rpdo(node, (uint16_t)(n + 1));
}

static void rpdo_receive(co_node_t *node, uint16_t n, const co_frame_t *frame)
{
    co_rpdo_t *r = &node->pdo.rpdo[n];
    rpdo_check_length(node, n, frame->len);
    /* A short frame is not applied; a long one is, up to the mapped length. */
    if (r->length_error == CO_EMCY_PDO_LENGTH)
        return;
    if (r->event_us != 0)
        r->deadline = node->now + r->event_us;
    if (r->timed_out) {
        r->timed_out = false;
        rpdo_error_release(node, CO_EMCY_RPDO_TIMEOUT);
    }
    if (pdo_type_is_sync(r->type)) {
        /* Received after the window closed: discarded (CiA 301 7.5.2.7). */
        if (!in_sync_window(node, node->now))
            return;
        memcpy(r->buffer, frame->data, r->map.length);
        r->buffered = true;
    } else {
        rpdo_apply(node, n, frame->data);
    }
}

bool co_pdo_receive(co_node_t *node, const co_frame_t *frame)
{
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++) {
        co_rpdo_t *r = &node->pdo.rpdo[n];
        if (r->valid && r->can_id == frame->id) {
            if (!(frame->flags & CO_FRAME_RTR))
                rpdo_receive(node, n, frame);
            return true;
        }
    }
    for (uint16_t n = 0; n < CO_CONFIG_TPDO_MAX; n++) {
        co_tpdo_t *t = &node->pdo.tpdo[n];
        if (t->valid && t->can_id == frame->id) {
            if (frame->flags & CO_FRAME_RTR)
                tpdo_remote_request(node, t);
            return true;
        }
    }
    return false;
}

/* ---- SYNC and timers -------------------------------------------------------------------- */

void co_pdo_sync(co_node_t *node, uint8_t counter)
{
    if (node->nmt_state != CO_NMT_OPERATIONAL)
        return;
    node->pdo.sync_at = node->now;
    /* Outputs received before this SYNC take effect now, then inputs are sampled. */
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++) {
        co_rpdo_t *r = &node->pdo.rpdo[n];
        if (r->valid && r->buffered) {
            r->buffered = false;
            rpdo_apply(node, n, r->buffer);
        }
    }
    for (uint16_t n = 0; n < CO_CONFIG_TPDO_MAX; n++) {
        co_tpdo_t *t = &node->pdo.tpdo[n];
        if (t->valid)
            tpdo_sync(node, t, counter);
    }
}

/* RPDO deadline monitoring (event timer, CiA 301 7.5.2.35): EMCY 0x8250 once per silence, and a
 * communication error (1029h:01) after the EMCY, which a Stopped node could no longer send. */
static co_time_t rpdo_process_deadline(co_node_t *node, uint16_t n, co_time_t now)
{
    co_rpdo_t *r = &node->pdo.rpdo[n];
    if (now >= r->deadline) {
        r->deadline = CO_TIME_NEVER;
        r->timed_out = true;
        rpdo_emcy(node, n, CO_EMCY_RPDO_TIMEOUT, 0);
        co_node_communication_error(node);
    }
    return r->deadline;
}

co_time_t co_pdo_process(co_node_t *node, co_time_t now)
{
    co_time_t next = CO_TIME_NEVER;
    if (node->nmt_state != CO_NMT_OPERATIONAL)
        return next;
    for (uint16_t n = 0; n < CO_CONFIG_TPDO_MAX; n++) {
        co_tpdo_t *t = &node->pdo.tpdo[n];
        if (!t->valid)
            continue;
        if (t->sync_due)
            tpdo_process_sync(node, t, now);
        if (tpdo_type_is_event(t->type))
            next = co_time_min(next, tpdo_process_event(node, t, now));
    }
    for (uint16_t n = 0; n < CO_CONFIG_RPDO_MAX; n++) {
        if (node->pdo.rpdo[n].valid)
            next = co_time_min(next, rpdo_process_deadline(node, n, now));
    }
    return next;
}

/* ---- Parameter writes (CiA 301 7.5.2.35-7.5.2.38) ----------------------------------------- */

/* CiA 301 table 72: 11-bit CAN-IDs only (bit 29 and bits 28..11 clear), no restricted CAN-ID for
 * a valid PDO (7.3.5, co_can_id_restricted), and the CAN-ID of a valid PDO may only change together
 * with invalidating it. A TPDO that answers RTRs (252/253) cannot forbid them (bit 30). */
static uint32_t pdo_write_cob_id(const co_node_t *node, uint16_t comm, uint32_t cob_id,
                                 uint32_t value, pdo_dir_t dir)
{
    if (!pdo_cob_id_valid(value))
        return value & ~CO_COB_ID_ALLOWED ? CO_SDO_ABORT_VALUE_RANGE : CO_SDO_OK;
    uint32_t abort = co_cob_id_check(cob_id, value, CO_PDO_COBID_INVALID, CO_PDO_COBID_INVALID);
    if (abort != CO_SDO_OK)
        return abort;
    uint8_t type = (uint8_t)co_od_param(node, comm, PDO_SUB_TYPE, CO_PDO_TYPE_EVENT_PROFILE);
    if (dir == PDO_TX && (value & CO_PDO_COBID_NO_RTR) && tpdo_type_is_rtr(type))
        return CO_SDO_ABORT_VALUE_RANGE;
    return CO_SDO_OK;
}

/* CiA 301 tables 71/73: 241..251 reserved; 252/253 are TPDO-only and need RTRs allowed. */
static uint32_t pdo_write_type(uint32_t cob_id, uint8_t type, pdo_dir_t dir)
{
    if (type > CO_PDO_TYPE_SYNC_MAX && type < CO_PDO_TYPE_RTR_SYNC)
        return CO_SDO_ABORT_VALUE_RANGE;
    if (tpdo_type_is_rtr(type) && (dir == PDO_RX || (cob_id & CO_PDO_COBID_NO_RTR)))
        return CO_SDO_ABORT_VALUE_RANGE;
    return CO_SDO_OK;
}

static uint32_t entry_value(const co_od_entry_t *entry, const uint8_t *data)
{
    if (entry->size == 1)
        return data[0];
    if (entry->size == 2)
        return co_get_u16(data);
    return co_get_u32(data);
}

/* CiA 301 table 72: the inhibit time may only change while the PDO is invalid; a node with
 * CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE takes it on a valid asynchronous TPDO (254/255) too. */
static uint32_t tpdo_write_valid_inhibit(const co_node_t *node, uint16_t comm)
{
    uint8_t type = (uint8_t)co_od_param(node, comm, PDO_SUB_TYPE, CO_PDO_TYPE_EVENT_PROFILE);
    bool writable =
        (node->options & CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE) && tpdo_type_is_event(type);
    return writable ? CO_SDO_OK : CO_SDO_ABORT_VALUE_RANGE;
}

static uint32_t pdo_write_comm(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                               pdo_dir_t dir)
{
    uint32_t value = entry_value(entry, data);
    uint32_t cob_id = pdo_cob_id(node, entry->index);
    bool valid = pdo_cob_id_valid(cob_id);
    switch (entry->subindex) {
    case PDO_SUB_COB_ID:
        return pdo_write_cob_id(node, entry->index, cob_id, value, dir);
    case PDO_SUB_TYPE:
        return pdo_write_type(cob_id, (uint8_t)value, dir);
    case PDO_SUB_INHIBIT:
        return dir == PDO_TX && valid ? tpdo_write_valid_inhibit(node, entry->index) : CO_SDO_OK;
    case PDO_SUB_SYNC_START:
        /* CiA 301 7.5.2.37: 0..240, only while the PDO is invalid. */
        if (dir == PDO_TX && valid)
            return CO_SDO_ABORT_VALUE_RANGE;
        return value > CO_PDO_TYPE_SYNC_MAX ? CO_SDO_ABORT_VALUE_RANGE : CO_SDO_OK;
    default:
        return CO_SDO_OK;
    }
}

/* CiA 301 7.5.2.36/38 mapping procedure: the PDO must be invalid (COB-ID bit 31) for any change,
 * and the entries may only change while sub 0 is 0 (0x06010000 otherwise, as the CCT expects);
 * writing sub 0 = n checks entries 1..n together. */
static uint32_t pdo_write_map(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                              uint16_t comm, pdo_dir_t dir)
{
    uint32_t value = entry_value(entry, data);
    if (pdo_cob_id_valid(pdo_cob_id(node, comm)))
        return CO_SDO_ABORT_UNSUPPORTED_ACCESS;
    if (entry->subindex == 0) {
        co_pdo_map_t map;
        return map_load(node, entry->index, (uint8_t)value, dir, &map);
    }
    if (co_od_param(node, entry->index, 0, 0) != 0)
        return CO_SDO_ABORT_UNSUPPORTED_ACCESS;
    if (value == 0)
        return CO_SDO_OK;
    const co_od_entry_t *mapped;
    uint8_t size;
    return map_entry_decode(node, value, dir, &mapped, &size);
}

/* Stores an accepted parameter and reconfigures its PDO: a changed COB-ID, type or mapping
 * restarts the PDO; a new event timer only restarts the timer. An RPDO made invalid receives
 * nothing, so no frame could end its errors: they end now (docs/error-control.md). */
static void rpdo_written(co_node_t *node, uint16_t n)
{
    co_rpdo_t *r = &node->pdo.rpdo[n];
    rpdo_reload(node, n);
    if (!r->valid)
        rpdo_errors_end(node, r);
}

/* A new event timer (sub-index 5 of the communication parameter) only restarts the timer; a new
 * inhibit time of a valid TPDO (CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE) leaves the window of the last
 * transmission running and governs from the next one. */
static void tpdo_written(co_node_t *node, uint16_t n, const co_od_entry_t *entry)
{
    bool comm = entry->index < CO_PDO_TPDO_MAP;
    tpdo_change_t change = TPDO_RESTART;
    if (comm && entry->subindex == PDO_SUB_EVENT_TIMER)
        change = TPDO_NEW_EVENT_TIMER;
    else if (comm && entry->subindex == PDO_SUB_INHIBIT && node->pdo.tpdo[n].valid)
        change = TPDO_NEW_INHIBIT;
    tpdo_load(node, n, change);
}

/* PDO n of the parameter just stored, an RPDO or a TPDO by the parameter's index. */
static void pdo_written(co_node_t *node, const co_od_entry_t *entry, uint16_t n)
{
    if (entry->index < CO_PDO_TPDO_COMM)
        rpdo_written(node, n);
    else
        tpdo_written(node, n, entry);
}

uint32_t co_pdo_od_write(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                         size_t len)
{
    unsigned range = (entry->index - CO_PDO_RPDO_COMM) / CO_PDO_INDEX_SPAN; /* 0..3 */
    pdo_dir_t dir = range >= 2 ? PDO_TX : PDO_RX;
    bool mapping = (range & 1u) != 0;
    uint16_t n = (uint16_t)(entry->index % CO_PDO_INDEX_SPAN);
    if (n >= (dir == PDO_TX ? CO_CONFIG_TPDO_MAX : CO_CONFIG_RPDO_MAX))
        return CO_SDO_OK;
    uint16_t comm = (uint16_t)(entry->index - (mapping ? CO_PDO_INDEX_SPAN : 0));
    uint32_t abort = mapping ? pdo_write_map(node, entry, data, comm, dir)
                             : pdo_write_comm(node, entry, data, dir);
    if (abort != CO_SDO_OK)
        return abort;
    co_od_store(node, entry, data, len);
    pdo_written(node, entry, n);
    return CO_OD_HANDLED;
}
