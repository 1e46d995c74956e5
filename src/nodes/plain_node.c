/* SPDX-License-Identifier: Apache-2.0 */
/* A plain node (plain_node.h): the core's node with the model's error-control reaction, LEDs and
 * serial number. */
#include "nodes/plain_node.h"

#include "co/co_cia301.h"

/* CiA 301 7.5.2.32: without 1029h a communication error takes an Operational node to
 * Pre-operational; the PLC300 goes there from any state (plain_model_t.loss_from_any_state). A
 * node with the core's error behaviour has already changed state as its 1029h:01 says. */
static void react_to_loss(plain_node_t *plain)
{
    co_node_t *node = &plain->node;
    if (node->error_behaviour != NULL)
        return;
    if (node->nmt_state == CO_NMT_OPERATIONAL ||
        (plain->model->loss_from_any_state && node->nmt_state == CO_NMT_STOPPED))
        co_nmt_enter(node, CO_NMT_PRE_OPERATIONAL);
}

static void on_heartbeat(co_node_t *node, uint8_t producer, bool lost)
{
    plain_node_t *plain = plain_node_of(node);
    if (!lost) {
        if (plain->loss == PLAIN_LOSS_HEARTBEAT && plain->lost_producer == producer)
            plain->loss = PLAIN_LOSS_NONE;
        return;
    }
    plain->loss = PLAIN_LOSS_HEARTBEAT;
    plain->lost_producer = producer;
    react_to_loss(plain);
}

static void on_guarding(co_node_t *node, bool lost)
{
    plain_node_t *plain = plain_node_of(node);
    if (!lost) {
        if (plain->loss == PLAIN_LOSS_GUARDING)
            plain->loss = PLAIN_LOSS_NONE;
        return;
    }
    plain->loss = PLAIN_LOSS_GUARDING;
    react_to_loss(plain);
}

/* A reset restarts the error control services without a call (co_node.h): the event is over. */
static void on_reset(co_node_t *node, co_nmt_reset_t scope)
{
    (void)scope;
    plain_node_of(node)->loss = PLAIN_LOSS_NONE;
}

/* Every reset ends here, having brought 1018h back to its EDS default: the node's own serial
 * number goes back in. */
static void on_nmt_state(co_node_t *node, co_nmt_state_t state)
{
    (void)state;
    plain_node_t *plain = plain_node_of(node);
    co_od_set_value(node, CO_IDX_IDENTITY, CO_IDENTITY_SERIAL, plain->serial_number);
}

static void on_time_stamp(co_node_t *node, const co_time_of_day_t *time)
{
    plain_node_t *plain = plain_node_of(node);
    plain->time = *time;
    plain->time_received = true;
}

static const co_app_hooks_t plain_hooks = {
    .nmt_state = on_nmt_state,
    .reset = on_reset,
    .heartbeat = on_heartbeat,
    .guarding = on_guarding,
    .time_stamp = on_time_stamp,
};

int plain_node_init(plain_node_t *plain, const plain_node_config_t *config)
{
    plain->model = config->model;
    plain->serial_number = config->serial_number;
    plain->loss = PLAIN_LOSS_NONE;
    plain->time_received = false;
    if (config->model->lss)
        co_lss_slave_init(&plain->lss, config->lss_hooks, config->lss_bit_timing);
    uint8_t sdo_servers = config->model->sdo_servers;
    if (sdo_servers > 0 &&
        co_sdo_servers_init(&plain->sdo_servers, plain->sdo_channels, sdo_servers, NULL) != 0)
        return CO_NODE_ERR_CONFIG;
    co_node_config_t node_config = {
        .node_id = config->node_id,
        .od = config->model->od,
        .od_data = config->od_data,
        .send = config->send,
        .user = config->send_user,
        .hooks = &plain_hooks,
        .storage = config->storage,
        .options = config->node_options,
        .options_code = config->node_options_code,
        .time_stamp = config->model->time_stamp ? &co_time_stamp : NULL,
        .lss = config->model->lss ? &plain->lss : NULL,
        .error_behaviour = config->model->error_behaviour ? &co_error_behaviour : NULL,
        .nmt_startup = config->model->nmt_startup ? &co_nmt_startup : NULL,
        .sdo_servers = sdo_servers > 0 ? &plain->sdo_servers : NULL,
    };
    int rc = co_node_init(&plain->node, &node_config);
    if (rc == 0)
        co_od_set_value(&plain->node, CO_IDX_IDENTITY, CO_IDENTITY_SERIAL, plain->serial_number);
    return rc;
}

/* A node without node-id loads its dictionary at the start and stays in Initialising, so no NMT
 * state change puts the serial number back: the start does, since LSS reads it (1018h:04). */
void plain_node_start(plain_node_t *plain, co_time_t now)
{
    co_node_start(&plain->node, now);
    co_od_set_value(&plain->node, CO_IDX_IDENTITY, CO_IDENTITY_SERIAL, plain->serial_number);
}

void plain_node_receive(plain_node_t *plain, const co_frame_t *frame, co_time_t now)
{
    co_node_receive(&plain->node, frame, now);
}

co_time_t plain_node_process(plain_node_t *plain, co_time_t now)
{
    return co_node_process(&plain->node, now);
}

void plain_node_bus_event(plain_node_t *plain, uint16_t emcy_code, bool active)
{
    if (emcy_code == CO_EMCY_CAN_PASSIVE)
        plain->bus_passive = active;
    else if (emcy_code == CO_EMCY_BUS_OFF)
        plain->bus_off = active;
    /* The recovery from bus off is a communication error (CiA 301 7.5.2.32) where 1029h rules. */
    if (emcy_code == CO_EMCY_BUS_OFF && !active)
        co_node_communication_error(&plain->node);
}

void plain_node_bus_warning(plain_node_t *plain, bool active)
{
    plain->bus_warning = active;
}

/* The node's conditions as CiA 303-3 names them; no LSS here yet. */
static co_indicator_state_t indicator_state(const plain_node_t *plain)
{
    return (co_indicator_state_t){
        .nmt_state = plain->node.nmt_state,
        .bus_off = plain->bus_off,
        .sync_error = plain->node.sync.timeout_error,
        .error_control = plain->loss != PLAIN_LOSS_NONE,
        .warning = plain->bus_warning || plain->bus_passive,
    };
}

co_led_t plain_node_err_led(const plain_node_t *plain)
{
    co_indicator_state_t state = indicator_state(plain);
    return co_indicator_err(&state);
}

co_led_t plain_node_run_led(const plain_node_t *plain)
{
    co_indicator_state_t state = indicator_state(plain);
    if (plain->model->err_over_run && co_indicator_err(&state) != CO_LED_OFF)
        return CO_LED_OFF;
    return co_indicator_run(&state);
}
