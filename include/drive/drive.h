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

/* What a model adds to the generic drive: its dictionary and its differences, as data. */
typedef struct drive_profile {
    const co_od_t *od;
    uint32_t node_options; /* the core's CO_NODE_* options of the model's profile (co_node.h) */
    /* The 1001h bits of the drive's faults and CAN errors (CiA 301 table 48; 1001h bit 0 is
     * always set with them). */
    uint8_t fault_error_register;
    /* Control word bits 11-15 are manufacturer-specific in CiA 402: the model's meaning of each. */
    uint16_t control_reverse;   /* reverses the reference */
    uint16_t control_ramp_stop; /* stops on the deceleration ramp, run command kept */
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
} drive_profile_t;

/* CAN conditions the runtime reports at once (overrun, error passive, bus off). */
#define DRIVE_BUS_EVENTS_MAX 4

/* The dictionary entries the drive reads and writes whenever it settles, found once by
 * drive_init (NULL where the model has none: it reads as 0 and writes to it do nothing), so that
 * its work never searches the dictionary. */
typedef struct drive_entries {
    const co_od_entry_t *error_code, *control_word, *status_word, *target_velocity;
    const co_od_entry_t *velocity_demand, *velocity_actual;
    const co_od_entry_t *acceleration, *deceleration, *low_speed, *high_speed;
    const co_od_entry_t *nominal_frequency, *nominal_speed, *nominal_current;
    const co_od_entry_t *motor_current, *motor_torque, *control_word_copy, *status_word_copy;
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
    /* The EMCY code of the latched fault, 0 when none: 603Fh shows it where the model has it. */
    uint16_t fault;
    /* Bus conditions still present: a reset node forgets their EMCYs, not the conditions. */
    uint16_t bus_events[DRIVE_BUS_EVENTS_MAX];
    uint8_t bus_event_count;
} drive_t;

typedef struct drive_config {
    const drive_profile_t *profile;
    uint8_t *od_data; /* profile->od->data_size bytes owned by the caller */
    uint8_t node_id;  /* 1..127 */
    co_send_fn send;
    void *send_user;
    const co_storage_t *storage; /* may be NULL: 1010h/1011h then abort */
} drive_config_t;

/* 0 or the co_node_init error. Sends nothing; call drive_start next. */
int drive_init(drive_t *drive, const drive_config_t *config);
/* Boot-up: Pre-operational, the power state machine in Switch on disabled. */
void drive_start(drive_t *drive, co_time_t now);
void drive_receive(drive_t *drive, const co_frame_t *frame, co_time_t now);
/* Runs the motor model and co_node_process; returns the next deadline (CO_TIME_NEVER when the
 * motor is steady and the core has nothing due). */
co_time_t drive_process(drive_t *drive, co_time_t now);
/* CAN errors seen by the runtime (0x8110 overrun, 0x8120 passive, 0x8140 bus-off): raises
 * (active) or clears the EMCY, and raises it again after a reset node while it lasts. They do not
 * fault the drive. */
void drive_bus_event(drive_t *drive, uint16_t emcy_code, bool active);
/* For logs: "Switch on disabled", "Operation enabled", ... */
const char *drive_state_name(const drive_t *drive);

/* Dictionary hooks for a model's hooks file, on the entries its profile names:
 * drive_configuration_parameter: motor data, refused with 0x08000022 while the motor turns or has
 *   a non-zero target; a change returns the drive to Switch on disabled;
 * drive_speed_limit: low_speed and high_speed, low <= high (else 0x06090036);
 * drive_velocity_limits: 6046h:01/02 (rpm), views of low_speed/high_speed (0.1 Hz);
 * drive_ramp_rate: 6048h/6049h (delta speed / delta time), views of acceleration/deceleration.
 * A view is written through its parameter's own checks and read from it. */
extern const co_od_hook_t drive_configuration_parameter;
extern const co_od_hook_t drive_speed_limit;
extern const co_od_hook_t drive_velocity_limits;
extern const co_od_hook_t drive_ramp_rate;

#endif
