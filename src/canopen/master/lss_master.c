/* SPDX-License-Identifier: Apache-2.0 */
/* CiA 305 LSS master: the requests, their answers and timeouts, and fastscan's walk through the
 * 128 bits of an LSS address, its waits, and the check of the address found. */
#include "co/co_lss_master.h"

#include <string.h>

enum step {
    STEP_IDLE = 0,
    STEP_ANSWER,         /* the first answer of `expect` ends the request */
    STEP_COUNT,          /* identify: answers of `expect` are counted until the deadline */
    STEP_FASTSCAN_RESET, /* fastscan: is any non-configured slave there */
    STEP_FASTSCAN,       /* fastscan: a bit check or a confirmation in flight */
    STEP_FASTSCAN_VERIFY /* fastscan: the slave found inquired for the part `part` */
};

int co_lss_master_init(co_lss_master_t *master, const co_lss_master_config_t *config)
{
    if (config->send == NULL || config->done == NULL)
        return CO_LSS_MASTER_ERR_CONFIG;
    memset(master, 0, sizeof(*master));
    master->send = config->send;
    master->user = config->user;
    master->done = config->done;
    master->deadline = CO_TIME_NEVER;
    return 0;
}

bool co_lss_master_busy(const co_lss_master_t *master)
{
    return master->step != STEP_IDLE;
}

static void send(co_lss_master_t *master, uint8_t cs, const uint8_t *data, size_t len)
{
    co_frame_t frame;
    co_lss_frame(&frame, CO_LSS_ID_MASTER, cs, data, len);
    master->send(master->user, &frame);
}

static void send_u32(co_lss_master_t *master, uint8_t cs, uint32_t value)
{
    uint8_t data[4];
    co_put_u32(data, value);
    send(master, cs, data, sizeof(data));
}

static int start(co_lss_master_t *master, uint8_t service, uint8_t step, uint8_t expect,
                 co_time_t timeout_us, co_time_t now)
{
    if (master->step != STEP_IDLE)
        return CO_LSS_MASTER_ERR_BUSY;
    if (timeout_us == 0)
        return CO_LSS_MASTER_ERR_ARG;
    memset(&master->result, 0, sizeof(master->result));
    master->result.service = service;
    master->step = step;
    master->expect = expect;
    master->timeout_us = timeout_us;
    master->deadline = now + timeout_us;
    return 0;
}

static void finish(co_lss_master_t *master, co_lss_master_status_t status)
{
    master->step = STEP_IDLE;
    master->deadline = CO_TIME_NEVER;
    master->result.status = status;
    master->done(master->user, &master->result);
}

int co_lss_master_switch_global(co_lss_master_t *master, co_lss_state_t state)
{
    if (master->step != STEP_IDLE)
        return CO_LSS_MASTER_ERR_BUSY;
    if (state != CO_LSS_WAITING && state != CO_LSS_CONFIGURATION)
        return CO_LSS_MASTER_ERR_ARG;
    uint8_t mode = (uint8_t)state;
    send(master, CO_LSS_CS_SWITCH_GLOBAL, &mode, 1);
    return 0;
}

int co_lss_master_activate_bit_timing(co_lss_master_t *master, uint16_t delay_ms)
{
    if (master->step != STEP_IDLE)
        return CO_LSS_MASTER_ERR_BUSY;
    uint8_t data[2];
    co_put_u16(data, delay_ms);
    send(master, CO_LSS_CS_ACTIVATE_BIT_TIMING, data, sizeof(data));
    return 0;
}

int co_lss_master_switch_selective(co_lss_master_t *master, const co_lss_address_t *address,
                                   co_time_t timeout_us, co_time_t now)
{
    int err = start(master, CO_LSS_CS_SWITCH_SELECTIVE_SERIAL, STEP_ANSWER,
                    CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE, timeout_us, now);
    if (err != 0)
        return err;
    for (unsigned part = 0; part < CO_LSS_FASTSCAN_PARTS; part++)
        send_u32(master, (uint8_t)(CO_LSS_CS_SWITCH_SELECTIVE_VENDOR + part), address->part[part]);
    return 0;
}

int co_lss_master_configure_node_id(co_lss_master_t *master, uint8_t node_id, co_time_t timeout_us,
                                    co_time_t now)
{
    if ((node_id < 1 || node_id > CO_NODE_ID_MAX) && node_id != CO_LSS_NODE_ID_UNCONFIGURED)
        return CO_LSS_MASTER_ERR_ARG;
    int err = start(master, CO_LSS_CS_CONFIGURE_NODE_ID, STEP_ANSWER, CO_LSS_CS_CONFIGURE_NODE_ID,
                    timeout_us, now);
    if (err == 0)
        send(master, CO_LSS_CS_CONFIGURE_NODE_ID, &node_id, 1);
    return err;
}

int co_lss_master_configure_bit_timing(co_lss_master_t *master, uint8_t table, uint8_t index,
                                       co_time_t timeout_us, co_time_t now)
{
    int err = start(master, CO_LSS_CS_CONFIGURE_BIT_TIMING, STEP_ANSWER,
                    CO_LSS_CS_CONFIGURE_BIT_TIMING, timeout_us, now);
    if (err == 0) {
        uint8_t data[2] = {table, index};
        send(master, CO_LSS_CS_CONFIGURE_BIT_TIMING, data, sizeof(data));
    }
    return err;
}

int co_lss_master_store(co_lss_master_t *master, co_time_t timeout_us, co_time_t now)
{
    int err = start(master, CO_LSS_CS_STORE, STEP_ANSWER, CO_LSS_CS_STORE, timeout_us, now);
    if (err == 0)
        send(master, CO_LSS_CS_STORE, NULL, 0);
    return err;
}

int co_lss_master_inquire(co_lss_master_t *master, uint8_t cs, co_time_t timeout_us, co_time_t now)
{
    if (cs < CO_LSS_CS_INQUIRE_VENDOR || cs > CO_LSS_CS_INQUIRE_NODE_ID)
        return CO_LSS_MASTER_ERR_ARG;
    int err = start(master, cs, STEP_ANSWER, cs, timeout_us, now);
    if (err == 0)
        send(master, cs, NULL, 0);
    return err;
}

int co_lss_master_identify_remote(co_lss_master_t *master, const co_lss_address_t *low,
                                  const co_lss_address_t *high, co_time_t timeout_us, co_time_t now)
{
    int err = start(master, CO_LSS_CS_IDENTIFY_VENDOR, STEP_COUNT, CO_LSS_CS_IDENTIFY_SLAVE,
                    timeout_us, now);
    if (err != 0)
        return err;
    send_u32(master, CO_LSS_CS_IDENTIFY_VENDOR, low->part[CO_LSS_VENDOR]);
    send_u32(master, CO_LSS_CS_IDENTIFY_PRODUCT, low->part[CO_LSS_PRODUCT]);
    send_u32(master, CO_LSS_CS_IDENTIFY_REVISION_LOW, low->part[CO_LSS_REVISION]);
    send_u32(master, CO_LSS_CS_IDENTIFY_REVISION_HIGH, high->part[CO_LSS_REVISION]);
    send_u32(master, CO_LSS_CS_IDENTIFY_SERIAL_LOW, low->part[CO_LSS_SERIAL]);
    send_u32(master, CO_LSS_CS_IDENTIFY_SERIAL_HIGH, high->part[CO_LSS_SERIAL]);
    return 0;
}

int co_lss_master_identify_non_configured(co_lss_master_t *master, co_time_t timeout_us,
                                          co_time_t now)
{
    int err = start(master, CO_LSS_CS_IDENTIFY_NON_CONFIGURED, STEP_COUNT,
                    CO_LSS_CS_IDENTIFY_NON_CONFIGURED_SLAVE, timeout_us, now);
    if (err == 0)
        send(master, CO_LSS_CS_IDENTIFY_NON_CONFIGURED, NULL, 0);
    return err;
}

/* The wait of a fastscan frame after the reset (docs/decisions.md, D-LSS-FASTSCAN-WAIT): twice
 * the slowest answer of this scan, the reset's included, within min_wait_us..timeout_us. */
static co_time_t fastscan_wait(const co_lss_master_t *master)
{
    co_time_t wait = 2 * master->slowest_us;
    if (wait < master->min_wait_us)
        wait = master->min_wait_us;
    return wait < master->timeout_us ? wait : master->timeout_us;
}

/* One fastscan frame, whose answers are counted until its wait ends; the reset waits the whole
 * timeout, since its answers are the first measure of the slaves' answer time. */
static void fastscan_send(co_lss_master_t *master, uint8_t bit, uint8_t next, co_time_t now)
{
    uint8_t data[7];
    co_put_u32(data, master->result.address.part[master->part]);
    data[4] = bit;
    data[5] = master->part;
    data[6] = next;
    master->bit = bit;
    master->result.answers = 0;
    master->sent_at = now;
    master->deadline =
        now + (bit == CO_LSS_FASTSCAN_RESET ? master->timeout_us : fastscan_wait(master));
    send(master, CO_LSS_CS_FASTSCAN, data, sizeof(data));
}

/* An answer to a fastscan frame: the slowest one so far stretches the wait of this frame and of
 * the next, so that the answers of other slaves queued behind it still count for this frame. */
static void fastscan_answer(co_lss_master_t *master, co_time_t now)
{
    co_time_t delay = now > master->sent_at ? now - master->sent_at : 0;
    if (delay > master->slowest_us)
        master->slowest_us = delay;
    if (master->step == STEP_FASTSCAN)
        master->deadline = master->sent_at + fastscan_wait(master);
}

static uint8_t next_part(uint8_t part)
{
    return (uint8_t)((part + 1) % CO_LSS_FASTSCAN_PARTS);
}

/* An unknown part is scanned from bit 31 with the guess 0, which the slaves whose bits so far
 * match answer. */
static void fastscan_scan_part(co_lss_master_t *master, co_time_t now)
{
    master->result.address.part[master->part] = 0;
    master->confirming = false;
    master->guessing = false;
    fastscan_send(master, CO_LSS_FASTSCAN_BIT_MAX, master->part, now);
}

/* A known or guessed part is confirmed in one frame (bit 0 checked, the next part named). */
static void fastscan_part(co_lss_master_t *master, co_time_t now)
{
    uint8_t part = master->part;
    uint8_t mask = (uint8_t)(1u << part);
    if ((master->known.known | master->known.guessed) & mask) {
        master->result.address.part[part] = master->known.address.part[part];
        master->confirming = true;
        master->guessing = !(master->known.known & mask);
        fastscan_send(master, 0, next_part(part), now);
    } else {
        fastscan_scan_part(master, now);
    }
}

/* The scan lost its slave: TIMEOUT with the answers to the reset, to be told from none found. */
static void fastscan_lost(co_lss_master_t *master)
{
    master->result.answers = master->reset_answers;
    finish(master, CO_LSS_MASTER_TIMEOUT);
}

/* Inquires the part `part` of the slave now in the configuration state (5Ah + part). */
static void fastscan_inquire(co_lss_master_t *master, co_time_t now)
{
    master->expect = (uint8_t)(CO_LSS_CS_INQUIRE_VENDOR + master->part);
    master->deadline = now + master->timeout_us;
    send(master, master->expect, NULL, 0);
}

/* The serial scanned, the slave that matched all 128 bits is in the configuration state; it is
 * asked its address, part by part, which must be the one scanned: an answer taken for a frame it
 * did not answer (a slave's answer later than the frame's wait) would otherwise give an address
 * that no slave has (docs/decisions.md, D-LSS-FASTSCAN-WAIT). */
static void fastscan_next_part(co_lss_master_t *master, co_time_t now)
{
    master->part++;
    if (master->part < CO_LSS_FASTSCAN_PARTS) {
        fastscan_part(master, now);
        return;
    }
    master->step = STEP_FASTSCAN_VERIFY;
    master->part = 0;
    fastscan_inquire(master, now);
}

static void fastscan_verify(co_lss_master_t *master, uint32_t value, co_time_t now)
{
    if (value != master->result.address.part[master->part]) {
        fastscan_lost(master);
        return;
    }
    master->part++;
    if (master->part < CO_LSS_FASTSCAN_PARTS) {
        fastscan_inquire(master, now);
        return;
    }
    master->result.answers = 1;
    finish(master, CO_LSS_MASTER_OK);
}

/* The end of one fastscan frame's timeout. The check of bit 0 carries the next part already, so
 * that a slave whose last bit is the guessed 0 moves on without a frame of its own; a 1 there
 * needs the confirmation with that bit set. */
static void fastscan_step(co_lss_master_t *master, co_time_t now)
{
    bool answered = master->result.answers > 0;
    if (master->step == STEP_FASTSCAN_RESET) {
        master->reset_answers = master->result.answers;
        if (!answered) {
            finish(master, CO_LSS_MASTER_TIMEOUT);
            return;
        }
        master->step = STEP_FASTSCAN;
        master->part = 0;
        fastscan_part(master, now);
        return;
    }
    if (master->step == STEP_FASTSCAN_VERIFY) {
        fastscan_lost(master);
        return;
    }
    uint8_t part = master->part;
    if (master->confirming) {
        if (answered) {
            fastscan_next_part(master, now);
        } else if (master->guessing) {
            /* No slave has the guessed part; all of them are still on it (CiA 305: a slave
             * moves to the next part only when its whole part matched). */
            fastscan_scan_part(master, now);
        } else {
            fastscan_lost(master);
        }
        return;
    }
    if (!answered)
        master->result.address.part[part] |= 1u << master->bit;
    if (master->bit > 0) {
        uint8_t bit = (uint8_t)(master->bit - 1);
        fastscan_send(master, bit, bit == 0 ? next_part(part) : part, now);
    } else if (answered) {
        fastscan_next_part(master, now);
    } else {
        master->confirming = true;
        fastscan_send(master, 0, next_part(part), now);
    }
}

int co_lss_master_fastscan(co_lss_master_t *master, const co_lss_fastscan_known_t *known,
                           co_time_t timeout_us, co_time_t min_wait_us, co_time_t now)
{
    if (master->step != STEP_IDLE)
        return CO_LSS_MASTER_ERR_BUSY;
    if (min_wait_us == 0 || min_wait_us > timeout_us)
        return CO_LSS_MASTER_ERR_ARG;
    int err = start(master, CO_LSS_CS_FASTSCAN, STEP_FASTSCAN_RESET, CO_LSS_CS_IDENTIFY_SLAVE,
                    timeout_us, now);
    if (err != 0)
        return err;
    master->min_wait_us = min_wait_us;
    master->slowest_us = 0;
    if (known != NULL)
        master->known = *known;
    else
        memset(&master->known, 0, sizeof(master->known));
    master->part = 0;
    fastscan_send(master, CO_LSS_FASTSCAN_RESET, 0, now);
    return 0;
}

bool co_lss_master_receive(co_lss_master_t *master, const co_frame_t *frame, co_time_t now)
{
    if (frame->id != CO_LSS_ID_SLAVE || (frame->flags & CO_FRAME_EFF))
        return false;
    if ((frame->flags & CO_FRAME_RTR) || frame->len != CO_LSS_FRAME_LEN ||
        master->step == STEP_IDLE || frame->data[0] != master->expect)
        return true;
    const uint8_t *data = frame->data;
    if (master->step == STEP_FASTSCAN_VERIFY) {
        fastscan_verify(master, co_get_u32(&data[1]), now);
        return true;
    }
    if (master->step != STEP_ANSWER) {
        if (master->result.answers < UINT16_MAX)
            master->result.answers++;
        if (master->step != STEP_COUNT)
            fastscan_answer(master, now);
        return true;
    }
    uint8_t cs = data[0];
    if (cs >= CO_LSS_CS_INQUIRE_VENDOR && cs <= CO_LSS_CS_INQUIRE_SERIAL) {
        master->result.value = co_get_u32(&data[1]);
    } else if (cs == CO_LSS_CS_INQUIRE_NODE_ID) {
        master->result.value = data[1];
    } else if (cs != CO_LSS_CS_SWITCH_SELECTIVE_RESPONSE) {
        master->result.error = data[1];
        master->result.specific = data[2];
    }
    master->result.answers = 1;
    finish(master, CO_LSS_MASTER_OK);
    return true;
}

co_time_t co_lss_master_process(co_lss_master_t *master, co_time_t now)
{
    if (master->step == STEP_IDLE || now < master->deadline)
        return master->deadline;
    if (master->step == STEP_ANSWER)
        finish(master, CO_LSS_MASTER_TIMEOUT);
    else if (master->step == STEP_COUNT)
        finish(master, master->result.answers > 0 ? CO_LSS_MASTER_OK : CO_LSS_MASTER_TIMEOUT);
    else
        fastscan_step(master, now);
    return master->deadline;
}
