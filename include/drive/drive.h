/* SPDX-License-Identifier: Apache-2.0 */
/* A device-side CiA 402 velocity drive on the portable CANopen core: a node whose control word
 * 6040h drives the power state machine (cia402.h), whose reference 6042h and ramps drive a motor
 * model (motor.h), and which publishes the status word 6041h, the speeds 6043h/6044h, current and
 * torque. Communication loss (heartbeat consumer or life guarding) is the drive's network fault.
 *
 * A model (an Altivar 312, say) is its object dictionary (generated from its EDS), the hooks its
 * hooks file names (the drive_* hooks below, and its own) and a drive_profile_t: where its
 * parameters are, what its manufacturer-specific control word bits do. The drive knows no model.
 * Portable like the core: no malloc, no OS calls, no globals; time is passed in by the caller. */
#ifndef DRIVE_DRIVE_H
#define DRIVE_DRIVE_H

#include "co/co_node.h"
#include "drive/cia402.h"
#include "drive/faults.h"
#include "drive/motor.h"

/* Where a parameter lives in a model's dictionary; {0, 0, fixed} where the model has none (it then
 * reads as `fixed`, a setting the network cannot change, and writes to it are ignored). */
typedef struct drive_param {
    uint16_t index;
    uint8_t subindex;
    uint32_t fixed;
} drive_param_t;

/* The parameter at index:subindex of the model's dictionary. */
#define DRIVE_PARAM(index, subindex)                                                               \
    {                                                                                              \
        (index), (subindex), 0                                                                     \
    }
/* A setting the model's dictionary lacks: it reads as `value`. */
#define DRIVE_FIXED(value)                                                                         \
    {                                                                                              \
        0, 0, (value)                                                                              \
    }

/* Switching sources: what a switch parameter (a channel pair's `select`, the profile's
 * ramp_switch) may hold besides its fixed values, in one code space for every model. A logic
 * input at the drive (drive_set_input), a bit of the network's control word whichever channel
 * commands (the Altivars' C211..C215), or a bit of the active command channel's word (Cd11..Cd15:
 * the network's while the network commands, 0 otherwise). Only the manufacturer-specific bits
 * 11..15 may be assigned; an assigned bit loses its profile meaning (reverse, stops). A source is
 * active at 1: it selects channel 2, the second ramp. */
#define DRIVE_SOURCE_INPUT(n) (100u + (n))
#define DRIVE_SOURCE_NETWORK_BIT(bit) (200u + (bit))
#define DRIVE_SOURCE_COMMAND_BIT(bit) (300u + (bit))
#define DRIVE_SOURCE_BIT_FIRST 11u
#define DRIVE_SOURCE_BIT_LAST 15u
/* Logic inputs a profile may give its model (LI1..LI8). */
#define DRIVE_INPUTS_MAX 8u

/* Analogue inputs at the drive, as reference channels: a reference channel parameter holding an
 * input's `channel` code takes its reference from it, the low speed at the bottom of its range, the
 * high speed at the top, linearly between. Values are set by drive_set_analog in the input's unit.
 */
typedef enum drive_analog_kind {
    DRIVE_ANALOG_VOLTAGE,       /* 0..10 V, in mV */
    DRIVE_ANALOG_BIPOLAR,       /* -10..+10 V, in mV: the sign is the direction of rotation */
    DRIVE_ANALOG_CURRENT,       /* 0..20 mA, in uA, from the `low` to the `high` current */
    DRIVE_ANALOG_POTENTIOMETER, /* 0..100 %, in 0.1 % */
} drive_analog_kind_t;
#define DRIVE_ANALOG_VOLTAGE_MAX_MV 10000
#define DRIVE_ANALOG_CURRENT_MAX_UA 20000
#define DRIVE_ANALOG_POTENTIOMETER_MAX 1000
/* Analogue inputs a profile may give its model. */
#define DRIVE_ANALOG_MAX 4u

typedef struct drive_analog_input {
    const char *name;         /* as the model's manuals name it: "AI2" */
    uint16_t channel;         /* the reference channel code that assigns it */
    drive_analog_kind_t kind; /* its range and unit */
    /* A current input: the currents (0.1 mA) of the low and of the high speed (the Altivars' CrL3
     * and CrH3); below the first the low speed, above the second the high speed, and the low
     * speed throughout while the second is not above the first. Unused by other kinds. */
    drive_param_t low;
    drive_param_t high;
} drive_analog_input_t;

/* A pair of channels (command or reference) and the switch between them: each channel parameter
 * holds a channel code of the model; `network` is the code of the network this node is on.
 * Channel 2 is active while `select` equals `select_second` or holds an active switching source,
 * channel 1 otherwise; `select` values up to `select_second` are fixed choices. */
typedef struct drive_channels {
    drive_param_t first;
    drive_param_t second;
    drive_param_t select;
    uint16_t select_second;
    uint16_t network;
} drive_channels_t;

/* What a model adds to the generic drive: its dictionary and its differences, as data. */
typedef struct drive_profile {
    const co_od_t *od;
    uint32_t node_options; /* the core's CO_NODE_* options of the model's profile (co_node.h) */
    /* &co_node_options when node_options is not 0: the options' code (co_node.h). */
    const co_node_options_code_t *node_options_code;
    /* The TPDOs whose inhibit time counts in 1 ms, as its manual prints each TPDO's row
     * (co_node_config_t.tpdo_inhibit_ms); 0: CiA 301's 100 us for every TPDO. */
    uint32_t tpdo_inhibit_ms;
    /* Control word bits 11-15 are manufacturer-specific in CiA 402: the model's meaning of each. */
    uint16_t control_reverse;   /* reverses the reference */
    uint16_t control_ramp_stop; /* stops as stop_type says, run command kept */
    uint16_t control_fast_stop; /* any of these bits stops on the fast ramp, still enabled */
    uint16_t status_reverse;    /* status word bit set while the motor turns in reverse */
    /* The fast ramp (fast stop, quick stop) is the deceleration time divided by this (0 or 1:
     * the deceleration ramp itself), at least 0.1 s. */
    uint8_t fast_ramp_divider;
    /* Parameters the drive reads, in the units of the Altivar family. */
    drive_param_t acceleration;      /* 0.1 s from 0 to nominal speed */
    drive_param_t deceleration;      /* 0.1 s from nominal speed to 0 */
    drive_param_t low_speed;         /* 0.1 Hz: the speed of a zero reference */
    drive_param_t high_speed;        /* 0.1 Hz: the highest speed */
    drive_param_t nominal_frequency; /* 0.1 Hz, with nominal_speed converts Hz to rpm */
    drive_param_t nominal_speed;     /* rpm */
    drive_param_t nominal_current;   /* 0.1 A */
    /* Values the drive publishes besides the CiA 402 objects. */
    drive_param_t motor_current; /* 0.1 A */
    drive_param_t motor_torque;  /* % of nominal torque, signed */
    /* Manufacturer copies of the CiA 402 words: one word at two addresses, kept equal. */
    drive_param_t control_word_copy;
    drive_param_t status_word_copy;
    /* What the drive does on a communication loss (the Altivars' COL: a DRIVE_COMMUNICATION_LOSS_*
     * value, the fault and its stop, or ignore; {0, 0}: always the fault with the reaction of its
     * table entry), and where it latches the network fault code (CnF:
     * DRIVE_NETWORK_FAULT_TIME_OUT after a loss, until a reset node; {0, 0}: nowhere). */
    drive_param_t communication_loss_mode;
    drive_param_t network_fault_code;
    /* What the ramp stop bit does: a DRIVE_STOP_* value ({0, 0}: the deceleration ramp). */
    drive_param_t stop_type;
    /* Where the commands and the reference come from (the Altivars' CHCF, Cd1/Cd2/CCS and
     * Fr1/Fr2/rFC). While channel_mode equals channel_mode_separate the command has its own
     * channels, otherwise it follows the reference's. A command channel other than the network
     * is local control (the network's control word is recorded, not obeyed; status word bit 9
     * clear); a reference channel that is one of the analogue inputs takes its reference from
     * it, any other (a keypad, another network) gives a zero reference (the low speed). All
     * zero: the network commands and gives the reference. */
    drive_param_t channel_mode;
    uint16_t channel_mode_separate;
    /* The I/O mode's value of channel_mode (0: the model has none): separate channels, and the
     * network's control word read as terminals: bit 0 is the run command (1 Operation enabled
     * with no state chart procedure, 0 a stop on the deceleration ramp to Switched on), bit 7
     * the fault reset, bits 11-15 keep their meaning. */
    uint16_t channel_mode_io;
    drive_channels_t command_channels;
    drive_channels_t reference_channels;
    /* Frequencies (0.1 Hz, signed): the output frequency the drive publishes (the motor's speed
     * through nominal_frequency / nominal_speed), and a frequency reference that is a view of
     * 6042h (a write to either sets both). */
    drive_param_t output_frequency;
    drive_param_t frequency_reference;
    /* Auto-tuning (the Altivars' tUn): a DRIVE_AUTO_TUNE_* value, with the drive_auto_tune hook. */
    drive_param_t auto_tune;
    /* The second ramp pair (the Altivars' AC2/dE2, 0.1 s as acceleration/deceleration), used
     * instead of the first while the switching source in ramp_switch (rPS; 0: none) is active. */
    drive_param_t ramp_switch;
    drive_param_t acceleration_2;
    drive_param_t deceleration_2;
    /* Logic inputs LI1..LIn at the drive (0..DRIVE_INPUTS_MAX), switching sources. */
    uint8_t logic_inputs;
    /* Analogue inputs at the drive (0..DRIVE_ANALOG_MAX of them), reference channels. */
    const drive_analog_input_t *analog_inputs;
    uint8_t analog_input_count;
    /* The terminals' run inputs, 2-wire control: while the command comes from the terminals (the
     * active command channel holds `terminals`; not separate, while the reference is an analogue
     * input), logic input run_forward (run_reverse) switched on runs the drive forward (in
     * reverse), and off stops it on the deceleration ramp. 0: the model has none. */
    uint16_t terminals;
    uint8_t run_forward;
    uint8_t run_reverse;
    /* The access level (the Altivars' LAC): below access_level_full the separate channel mode and
     * control word bits as switching sources are refused, and the channels are managed by
     * priority: the network commands and gives the reference (forced local control first).
     * {0, 0} with access_level_full 0: always the full level. */
    drive_param_t access_level;
    uint16_t access_level_full;
    /* Status word bit set after the keypad's STOP key (the Altivars' ETA bit 14). */
    uint16_t status_stop_key;
    /* The STOP key also resets the faults in Fault when a fault reset would (the ATV31's
     * STOP/RESET key: every active fault reset by command, its cause gone). */
    bool stop_key_resets_faults;
    /* The internal control word (the Altivars' CMI): while its bit internal_control_no_check is 1
     * the parameters' cross checks (low_speed <= high_speed) are suspended for a configuration
     * transfer; when it goes back to 0 they are made, and a configuration they find inconsistent
     * is the fault of code inconsistent_fault (CFI) until a write makes it consistent. {0, 0}:
     * none. */
    drive_param_t internal_control;
    uint16_t internal_control_no_check;
    const char *inconsistent_fault;
    /* The node-id as the drive's own parameter (the Altivars' AdCO): 0 while CANopen is off
     * (drive_config_t.node_id 0); {0, 0}: the model has none. */
    drive_param_t can_address;
    /* The faults of the model's manuals (faults.h); required. */
    const drive_fault_table_t *faults;
    /* The LEDs of the model's card as its manual names them (panel.h), indicator_count of them;
     * NULL: the CiA 303-3 RUN and ERR pair of the drive layer. */
    const struct drive_indicator *indicators;
    uint8_t indicator_count;
} drive_profile_t;

/* Values of the profile's communication_loss_mode. */
#define DRIVE_COMMUNICATION_LOSS_IGNORE 0    /* the drive goes on; only the fault code is latched */
#define DRIVE_COMMUNICATION_LOSS_FAULT 1     /* the communication-loss fault: freewheel, Fault */
#define DRIVE_COMMUNICATION_LOSS_RAMP_STOP 2 /* the fault, stopping on the deceleration ramp */
#define DRIVE_COMMUNICATION_LOSS_FAST_STOP 3 /* the fault, stopping on the fast ramp */
/* Values of the profile's stop_type. */
#define DRIVE_STOP_RAMP 0         /* the deceleration ramp */
#define DRIVE_STOP_FAST 1         /* the fast ramp */
#define DRIVE_STOP_FREEWHEEL 2    /* the output is cut, the motor coasts */
#define DRIVE_STOP_DC_INJECTION 3 /* modelled as the fast ramp */
/* Values of the profile's auto_tune: writing YES in Operation enabled with the motor standing
 * runs a simulated tune of DRIVE_AUTO_TUNE_TIME_US, after which it reads DONE; NO cancels. */
#define DRIVE_AUTO_TUNE_NO 0
#define DRIVE_AUTO_TUNE_YES 1
#define DRIVE_AUTO_TUNE_DONE 2
#define DRIVE_AUTO_TUNE_TIME_US 500000u
/* The network fault code of a communication loss ("time out on the reception of the periodic
 * variables addressed to the drive", ATV312 DeviceNet manual). */
#define DRIVE_NETWORK_FAULT_TIME_OUT 1

/* CAN conditions the runtime reports at once (overrun, error passive, bus off). */
#define DRIVE_BUS_EVENTS_MAX 4

/* What the last communication loss was (drive_comm_loss_t.source). */
typedef enum drive_comm_loss_source {
    DRIVE_COMM_LOSS_NONE,      /* none since the power-up, the last reset node or fault reset */
    DRIVE_COMM_LOSS_GUARDING,  /* life guarding: the master's guarding requests stopped */
    DRIVE_COMM_LOSS_HEARTBEAT, /* a heartbeat consumer: the producer `node` fell silent */
    DRIVE_COMM_LOSS_NETWORK    /* drive_communication_loss: a fieldbus front-end's timeout */
} drive_comm_loss_source_t;

typedef struct drive_comm_loss {
    drive_comm_loss_source_t source;
    uint8_t node; /* the heartbeat producer's node-id; 0 otherwise */
} drive_comm_loss_t;

/* The dictionary entries the drive reads and writes whenever it settles, found once by
 * drive_init (NULL where the model has none: it reads as 0 and writes to it do nothing), so that
 * its work never searches the dictionary. */
typedef struct drive_entries {
    const co_od_entry_t *error_code, *control_word, *status_word, *target_velocity;
    const co_od_entry_t *velocity_demand, *velocity_actual;
    const co_od_entry_t *acceleration, *deceleration, *low_speed, *high_speed;
    const co_od_entry_t *nominal_frequency, *nominal_speed, *nominal_current;
    const co_od_entry_t *motor_current, *motor_torque, *control_word_copy, *status_word_copy;
    const co_od_entry_t *output_frequency, *frequency_reference, *stop_type;
    const co_od_entry_t *acceleration_2, *deceleration_2;
    /* Each analogue input's low and high parameters (a current input's). */
    const co_od_entry_t *analog_low[DRIVE_ANALOG_MAX], *analog_high[DRIVE_ANALOG_MAX];
} drive_entries_t;

typedef struct drive {
    co_node_t node;
    const drive_profile_t *profile;
    drive_entries_t entries;
    /* Something the published values depend on may have changed without a written entry (a
     * reset restored the defaults): the next drive_process settles the drive. */
    bool dirty;
    cia402_state_machine_t cia402;
    drive_motor_t motor;
    bool limited; /* the reference is outside the speed limits (status word bit 11) */
    /* Bus conditions still present: a reset node forgets their EMCYs, not the conditions. */
    uint16_t bus_events[DRIVE_BUS_EVENTS_MAX];
    uint8_t bus_event_count;
    bool can_warning; /* the CAN controller is at its error warning level (no EMCY) */
    /* The cause of the communication loss the drive last reacted to, until the communication-loss
     * fault is reset or a reset node (with a COL that ignores the loss: until a reset node, as
     * the network fault code). */
    drive_comm_loss_t comm_loss;
    /* Faults, one bit per entry of the profile's table: raised and not yet reset, and those
     * whose cause is present (injected and not removed). */
    uint32_t faults_active;
    uint32_t fault_causes;
    uint8_t fault_latched; /* the entry in 603Fh and on the display while faults_active */
    drive_fault_reaction_t fault_reaction; /* the stop that runs in Fault reaction active */
    /* At the drive (local_control.c): forced local control, the keypad's keys, the load. */
    /* The profile's channels as last computed (channels.c): the network commands, and gives the
     * reference. */
    bool command_from_network;
    /* drive_config_t.node_id was 0: the node stays in Initialising, silent. */
    bool can_off;
    bool reference_from_network;
    bool second_ramp;                 /* the ramp switch's source is active: AC2/dE2 */
    bool io_mode;                     /* channel_mode is the I/O mode */
    uint16_t assigned_bits;           /* control word bits assigned to switching sources */
    uint8_t inputs;                   /* logic inputs on: bit n - 1 for LIn */
    int32_t analog[DRIVE_ANALOG_MAX]; /* the analogue inputs' values, in their units */
    int8_t reference_analog;          /* the analogue input the reference comes from; -1: none */
    bool local;     /* forced local: the network's control word is ignored, bit 9 = 0 */
    bool local_run; /* the RUN key's or the terminals' run command, under local control */
    bool command_from_terminals; /* the terminals command: their run inputs count */
    bool terminal_reverse;       /* the terminals' run command is the reverse one */
    bool stop_key;               /* the STOP key was pressed, until the next run command */
    uint8_t load;                /* extra load torque, % of nominal torque */
    co_time_t auto_tune_end; /* when the running auto-tune completes; CO_TIME_NEVER: none runs */
    /* When the node last received an SDO request or one of its RPDOs (a card's reception LED,
     * drive_last_service_request); CO_TIME_NEVER: none since the power-up. */
    co_time_t service_received_at;
} drive_t;

/* drive_init's error for a profile without a valid fault table, with too many analogue inputs. */
#define DRIVE_INIT_BAD_FAULTS 0x200
#define DRIVE_INIT_BAD_ANALOG 0x201

typedef struct drive_config {
    const drive_profile_t *profile;
    uint8_t *od_data; /* profile->od->data_size bytes owned by the caller */
    /* 1..127, or 0: CANopen off (the Altivars' AdCO = 0, "disables the CANopen communications"):
     * the drive runs (terminals, keypad, the motor) but its node is never started, so it sends
     * nothing and takes no frame; the profile's can_address reads 0. */
    uint8_t node_id;
    co_send_fn send;
    void *send_user;
    const co_storage_t *storage; /* may be NULL: 1010h/1011h then abort */
    /* CO_NODE_* options the application adds to the profile's (co_node.h), such as
     * CO_NODE_HEARTBEAT_GRID for a runtime of many drives; 0 for none. */
    uint32_t node_options;
    /* &co_node_options when node_options is not 0; NULL takes the profile's. */
    const co_node_options_code_t *node_options_code;
} drive_config_t;

/* 0, the co_node_init error, DRIVE_INIT_BAD_FAULTS or DRIVE_INIT_BAD_ANALOG. Sets every field of
 * *drive (the caller's memory need not be zeroed): the channels are those of the dictionary's
 * defaults. Sends nothing; call drive_start next. */
int drive_init(drive_t *drive, const drive_config_t *config);
/* Boot-up: Pre-operational, the power state machine in Switch on disabled. */
void drive_start(drive_t *drive, co_time_t now);
void drive_receive(drive_t *drive, const co_frame_t *frame, co_time_t now);
/* When the drive last received an SDO request or one of its valid RPDOs; CO_TIME_NEVER: none
 * since the power-up (or the last reset node). */
co_time_t drive_last_service_request(const drive_t *drive);
/* Runs the motor model and co_node_process; returns the next deadline (CO_TIME_NEVER when the
 * motor is steady and the core has nothing due). */
co_time_t drive_process(drive_t *drive, co_time_t now);
/* CAN errors seen by the runtime (0x8110 overrun, 0x8120 passive, 0x8140 bus-off): raises
 * (active) or clears the EMCY, and raises it again after a reset node while it lasts. They do not
 * fault the drive. */
void drive_bus_event(drive_t *drive, uint16_t emcy_code, bool active);
/* The CAN controller reached (active) or left its error warning level: no EMCY (CiA 301 has
 * none), the ERR LED's single flash (CiA 303-3). Outlives a reset node, as the bus conditions. */
void drive_bus_warning(drive_t *drive, bool active);
/* The network the drive is on stopped sending what it must (a fieldbus front-end's timeout, as
 * the heartbeat consumer's or life guarding's on CANopen): the communication-loss fault at `now`,
 * with the reaction and network fault code of the model's parameters. */
void drive_communication_loss(drive_t *drive, co_time_t now);
/* Faults (faults.h). The index of the model's fault whose code is `code`, compared without
 * case ("ohf" finds OHF), or -1. */
int drive_fault_find(const drive_t *drive, const char *code);
/* The cause of fault `index` appears at `now`: the drive faults unless that fault is active
 * already. Other faults may be active too: each sends its EMCY; the first stays in 603Fh. */
void drive_fault_inject(drive_t *drive, uint8_t index, co_time_t now);
/* The cause of fault `index` is gone at `now`: a fault of the automatic class resets itself (the
 * drive leaves Fault when no other fault is active); the others may now be reset. */
void drive_fault_remove_cause(drive_t *drive, uint8_t index, co_time_t now);
bool drive_fault_cause_present(const drive_t *drive, uint8_t index);
/* The fault in 603Fh while the drive is in Fault, else NULL. */
const drive_fault_def_t *drive_fault_latched(const drive_t *drive);
/* At the drive, for people testing a master (atv312d's control surface); `now` is the time of
 * the event. Forced local control on or off (status word bit 9 = 0 while on) changes the command
 * channel: a freewheel stop to Switch on disabled (a fault stays latched); under it the network's
 * control word is kept but ignored and the keypad runs the drive. */
void drive_set_local(drive_t *drive, bool local, co_time_t now);
/* Local control: forced local control, or a command channel other than the network (the
 * profile's channels): status word bit 9 clear, the network's control word not obeyed. */
bool drive_local_control(const drive_t *drive);
/* The keypad's STOP key: the profile's status_stop_key bit is set until the next run command (the
 * RUN key, or a network command leaving Switch on disabled). Under network control a freewheel
 * stop to Switch on disabled (the Altivars' "STOP key priority"); under local control a stop on
 * the deceleration ramp, then Switch on disabled. With the profile's stop_key_resets_faults, in
 * Fault it is also a fault reset: Switch on disabled when the network's reset edge would be. */
void drive_stop_key(drive_t *drive, co_time_t now);
/* The keypad's RUN key: under local control (forced, or a command channel other than the network)
 * and not in Fault, Operation enabled and the motor
 * runs to the reference 6042h; false (nothing happens) otherwise. */
bool drive_run_key(drive_t *drive, co_time_t now);
/* An extra load on the motor, % of nominal torque (0..150): torque and current follow while
 * the motor turns. */
void drive_set_load(drive_t *drive, uint8_t percent, co_time_t now);
/* Logic input `input` (1 for LI1) on or off at `now`: a switching source on it acts at once, and
 * while the terminals command, a run input (the profile's run_forward, run_reverse) switched on
 * alone runs the drive (not in Fault), switched off stops it on the deceleration ramp to Switch on
 * disabled; both on stop it. A run needs the input's change to on: one on already when the
 * terminals take the command starts nothing. false (nothing happens) when the model has no such
 * input. Inputs outlive a reset node. */
bool drive_set_input(drive_t *drive, uint8_t input, bool on, co_time_t now);
bool drive_input(const drive_t *drive, uint8_t input);
/* The index of the model's analogue input named `name` ("ai2" finds AI2), or -1. */
int drive_analog_find(const drive_t *drive, const char *name);
/* Analogue input `index` at `value` in its unit (mV, uA or 0.1 %, drive_analog_kind_t) from
 * `now`: a reference channel assigned to it follows at once. false (nothing happens) when the
 * model has no such input or the value is outside the input's range. Inputs outlive a reset
 * node. */
bool drive_set_analog(drive_t *drive, uint8_t index, int32_t value, co_time_t now);
int32_t drive_analog(const drive_t *drive, uint8_t index);
/* For logs: "Switch on disabled", "Operation enabled", ... */
const char *drive_state_name(const drive_t *drive);

/* Dictionary hooks for a model's hooks file, on the entries its profile names:
 * drive_configuration_parameter: motor data, refused with 0x08000022 while the motor turns or has
 *   a non-zero target; a change returns the drive to Switch on disabled;
 * drive_speed_limit: low_speed and high_speed, low <= high (else 0x06090036) unless the internal
 *   control word suspends the check; a consistent write ends the inconsistent_fault's cause;
 * drive_internal_control: internal_control; its check bit back to 0 checks the configuration;
 * drive_velocity_limits: 6046h:01/02 (rpm), views of low_speed/high_speed (0.1 Hz);
 * drive_ramp_rate: 6048h/6049h (delta speed / delta time), views of acceleration/deceleration;
 * drive_auto_tune: auto_tune; YES only in Operation enabled with the motor standing (else
 *   0x08000022), DONE only from the drive (else 0x06090030).
 * drive_command_setting: access_level, channel_mode, the channel pairs' selects, ramp_switch; a
 *   configuration parameter whose value the access level must allow (separate and I/O modes and
 *   control word bits only at the full level, nor a lower level while they are set: 0x06040043); a
 *   switch holds a fixed value or a switching source of the model (else 0x06090030).
 * A view is written through its parameter's own checks and read from it, within its own limits
 * (a ramp whose reduced fraction does not fit: the nearest fraction that does); what it reads,
 * written back, keeps its parameter, and a ramp's terms written one after the other compose
 * (docs/decisions.md, D-VIEW-LIMITS). */
extern const co_od_hook_t drive_configuration_parameter;
extern const co_od_hook_t drive_speed_limit;
extern const co_od_hook_t drive_internal_control;
extern const co_od_hook_t drive_velocity_limits;
extern const co_od_hook_t drive_ramp_rate;
extern const co_od_hook_t drive_auto_tune;
extern const co_od_hook_t drive_command_setting;

#endif
