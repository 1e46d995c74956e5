/* An emulated Schneider Altivar 312 drive on the portable CANopen core: the ATV312 object
 * dictionary (generated from eds/ATV312.eds), the CiA 402 / Drivecom power state machine driven
 * by the control word, and a motor model whose speed ramps to the reference. Portable like the
 * core: no malloc, no OS calls, no globals; time is passed in by the caller. */
#ifndef ATV312_H
#define ATV312_H

#include "atv312_od.h" /* generated */
#include "co/co_node.h"

/* CiA 402 power states (ATV312 DeviceNet manual, "ETA status word"). "Not ready to switch on"
 * and "Malfunction reaction active" are transient and never visible here: initialisation is
 * instantaneous and the fault reaction is a freewheel stop. */
typedef enum atv312_state {
    ATV312_SWITCH_ON_DISABLED,
    ATV312_READY_TO_SWITCH_ON,
    ATV312_SWITCHED_ON,
    ATV312_OPERATION_ENABLED,
    ATV312_QUICK_STOP_ACTIVE,
    ATV312_FAULT
} atv312_state_t;

/* The power state machine: its state and the last control word, for the fault reset edge. */
typedef struct atv312_cia402 {
    atv312_state_t state;
    uint16_t control; /* last control word written (6040h / CMD) */
} atv312_cia402_t;

/* Ramp parameters as the motor model uses them, refreshed from the dictionary. */
typedef struct atv312_ramp {
    uint16_t acc;         /* 0.1 s from 0 to nominal speed */
    uint16_t dec;         /* 0.1 s from nominal speed to 0 */
    uint16_t fast_dec;    /* fast stop / quick stop ramp, 0.1 s */
    uint16_t nominal_rpm; /* NSP */
} atv312_ramp_t;

/* The motor: speed in milli-rpm so that ramps of any slope add up exactly over time. */
typedef struct atv312_motor {
    int64_t speed;      /* milli-rpm, signed (negative = reverse) */
    int32_t target;     /* rpm the ramp is heading to */
    bool fast;          /* decelerate on the fast ramp */
    int8_t phase;       /* +1 accelerating, -1 decelerating, 0 steady, over the last interval */
    uint64_t remainder; /* of the last ramp division, carried to the next interval */
    co_time_t updated;  /* time the speed refers to */
    atv312_ramp_t ramp; /* parameters used since `updated` */
} atv312_motor_t;

/* CAN conditions the runtime reports at once (overrun, error passive, bus off). */
#define ATV312_BUS_EVENTS_MAX 4

typedef struct atv312 {
    co_node_t node;
    uint8_t od_data[ATV312_OD_DATA_SIZE];
    atv312_cia402_t cia402;
    atv312_motor_t motor;
    bool limited; /* the reference is outside LSP..HSP (status word bit 11) */
    /* Bus conditions still present: a reset node forgets their EMCYs, not the conditions. */
    uint16_t bus_events[ATV312_BUS_EVENTS_MAX];
    uint8_t bus_event_count;
} atv312_t;

/* 0 or the co_node_init error. Sends nothing; call atv312_start next. */
int atv312_init(atv312_t *drive, uint8_t node_id, co_send_fn send, void *send_user,
                const co_storage_t *storage);
/* Boot-up: Pre-operational, drive in Switch on disabled. */
void atv312_start(atv312_t *drive, co_time_t now);
void atv312_receive(atv312_t *drive, const co_frame_t *frame, co_time_t now);
/* Runs the motor model and co_node_process; returns the next deadline (CO_TIME_NEVER when the
 * motor is steady and the core has nothing due). */
co_time_t atv312_process(atv312_t *drive, co_time_t now);
/* CAN errors seen by the runtime (0x8110 overrun, 0x8120 passive, 0x8140 bus-off): raises
 * (active) or clears the EMCY, and raises it again after a reset node while it lasts. They do not
 * fault the drive. */
void atv312_bus_event(atv312_t *drive, uint16_t emcy_code, bool active);
/* For logs: "Switch on disabled", "Operation enabled", ... */
const char *atv312_state_name(const atv312_t *drive);

#endif
