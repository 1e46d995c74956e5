/* SPDX-License-Identifier: Apache-2.0 */
/* A drive on DeviceNet: the drive (drive.h) behind a DeviceNet slave (dn/dn_node.h), as the
 * Altivar 312's DeviceNet card puts it (Altivar 312 DeviceNet manual): the card talks to the drive
 * through the drive's own dictionary (6040h, 6041h, 6042h, 6044h and the parameters by their
 * addresses), so the model's dictionary stays the drive's one parameter store and the drive layer
 * works unchanged. The adapter registers the drive's CIP classes with the slave: Motor data 0x28,
 * Control supervisor 0x29, AC/DC drive 0x2A, the application objects (0x70.. on the ATV312) that
 * reach every parameter by its address, and the assemblies 20, 21, 70, 71 (the ODVA AC drive
 * profile, translated to the drive's Drivecom/CiA 402 control word) and 100, 101 (6040h/6042h
 * and 6041h/6044h as they are). An I/O connection timeout, and any end of the connection that
 * carries the drive's commands while it runs on them, is the drive's communication-loss fault (CnF
 * on an Altivar). The drive's CANopen node sends nothing on the bus: its frames are the
 * card's internal link, dropped. Portable like the core: no malloc, no OS calls, no globals.
 * docs/devicenet.md, "The drive on DeviceNet". */
#ifndef DRIVE_DRIVE_DEVICENET_H
#define DRIVE_DRIVE_DEVICENET_H

#include "dn/dn_node.h"
#include "drive/drive.h"

/* What a model adds for DeviceNet, as data: its Identity, its motor data and the address formula
 * of its application objects. A parameter of address ADL is reached as class
 * class_first + (ADL - address_first) / addresses_per_class, instance 1, attribute
 * (ADL - address_first) % addresses_per_class + 1, and lives in the dictionary at index
 * index_first + (ADL - address_first) / addresses_per_index, sub-index
 * (ADL - address_first) % addresses_per_index + 1. */
/* How many faults a profile may name as needing commissioning (the Altivars' CFF and CFI). */
#define DRIVE_DN_COMMISSIONING_FAULTS 2u

typedef struct drive_dn_profile {
    /* The drive behind the card: the model's profile as the card's manual names its faults (the
     * ATV312's communication loss is CnF here, COF on CANopen). */
    const drive_profile_t *drive;
    uint16_t vendor_id;
    uint16_t device_type;
    uint16_t product_code;
    uint8_t major_revision;
    uint8_t minor_revision;
    const char *product_name;
    uint8_t motor_type;          /* Motor data attribute 3 (7: squirrel cage induction motor) */
    drive_param_t rated_voltage; /* Motor data attribute 7, V: a parameter of the dictionary */
    /* The drive's faults of a missing or incorrect configuration: while one is latched the card's
     * MS LED flashes green (the manual's "Needs commissioning"). */
    const char *commissioning_faults[DRIVE_DN_COMMISSIONING_FAULTS];
    uint8_t class_first;
    uint8_t class_last;
    uint16_t address_first;
    uint16_t addresses_per_class;
    uint16_t index_first;
    uint16_t addresses_per_index;
} drive_dn_profile_t;

/* The assemblies of the manual, 4 bytes each, little-endian. */
#define DRIVE_DN_BASIC_OUTPUT 20u        /* Run fwd, fault reset, speed reference */
#define DRIVE_DN_EXTENDED_OUTPUT 21u     /* + Run rev, NetCtrl, NetRef (the default) */
#define DRIVE_DN_BASIC_INPUT 70u         /* Faulted, Running1, speed actual */
#define DRIVE_DN_EXTENDED_INPUT 71u      /* + the other status bits, the state (the default) */
#define DRIVE_DN_TRANSPARENT_OUTPUT 100u /* 6040h, 6042h */
#define DRIVE_DN_TRANSPARENT_INPUT 101u  /* 6041h, 6044h */
#define DRIVE_DN_ASSEMBLY_SIZE 4u

/* Control supervisor State (0x29 attribute 6). */
typedef enum drive_dn_state {
    DRIVE_DN_STARTUP = 1,
    DRIVE_DN_NOT_READY = 2,
    DRIVE_DN_READY = 3,
    DRIVE_DN_ENABLED = 4,
    DRIVE_DN_STOPPING = 5,
    DRIVE_DN_FAULT_STOP = 6,
    DRIVE_DN_FAULTED = 7
} drive_dn_state_t;

/* The ODVA profile's command as the scanner last gave it (assemblies 20/21, 0x29, 0x2A). */
typedef struct drive_dn_command {
    bool run1;               /* Run fwd */
    bool run2;               /* Run rev */
    bool fault_reset;        /* FaultRst */
    bool net_ctrl;           /* NetCtrl */
    bool net_ref;            /* NetRef */
    int16_t speed_reference; /* SpeedRef, rpm */
} drive_dn_command_t;

typedef struct drive_dn_config {
    drive_t *drive; /* initialised with drive_init, not started */
    const drive_dn_profile_t *profile;
    uint8_t mac_id;    /* 0..63 */
    uint8_t baud_rate; /* 0 125 kbit/s, 1 250 kbit/s, 2 500 kbit/s */
    uint32_t serial_number;
    dn_stored_t stored; /* as loaded; zeros: the defaults 21 / 71 */
    co_send_fn send;    /* the DeviceNet frames */
    void *user;
    /* Keeps the assembly selection and Quick Connect across restarts; false when it could not.
     * NULL: not stored, the Sets are refused. */
    bool (*store)(void *user, const dn_stored_t *stored);
} drive_dn_config_t;

typedef struct drive_dn {
    drive_t *drive;
    const drive_dn_profile_t *profile;
    dn_node_t node;
    dn_config_t config;
    dn_app_t app;
    dn_object_t objects[4];
    void *user;
    co_send_fn send;
    bool (*store)(void *user, const dn_stored_t *stored);
    drive_dn_command_t command;
    /* The explicit connection (1, or 10-14 the UCMM opened) whose requests last changed the
     * command (drive_dn_command), 0 once it ended: the one whose end is the drive's
     * communication loss when no I/O carries the commands. */
    uint8_t command_connection;
    /* The profile's commissioning_faults as indices of the drive's fault table (-1: none),
     * resolved once at drive_dn_init: the Identity status is reported after every frame. */
    int commissioning_fault[DRIVE_DN_COMMISSIONING_FAULTS];
    bool reverse;          /* the last run was Run2: 6042h is the negated speed reference */
    int16_t pending_reset; /* an Identity Reset type to carry out, or -1 */
    co_time_t now;
    dn_stats_t stats; /* the card's traffic since drive_dn_init, through its resets */
} drive_dn_t;

/* The send callback of the drive's CANopen node on DeviceNet: its frames are the card's internal
 * link to the drive, not on the bus. */
void drive_dn_drop_frame(void *user, const co_frame_t *frame);

/* drive_dn_init's refusals, besides dn_node_init's. */
#define DRIVE_DN_INIT_BAD_CONFIG -10

/* Builds the DeviceNet node on the drive (not started). 0, DRIVE_DN_INIT_BAD_CONFIG or a
 * dn_node_init error. The adapter keeps `config->drive` and the profile. */
int drive_dn_init(drive_dn_t *dn, const drive_dn_config_t *config);
/* Starts the drive (its CANopen node's frames go nowhere) and the duplicate MAC ID check. */
void drive_dn_start(drive_dn_t *dn, co_time_t now);
void drive_dn_receive(drive_dn_t *dn, const co_frame_t *frame, co_time_t now);
/* The drive and the DeviceNet node; the earlier of their deadlines. */
co_time_t drive_dn_process(drive_dn_t *dn, co_time_t now);
/* The interface came back after being down: the node goes on the bus again (a new duplicate MAC
 * ID check), its connections gone; a drive running on their commands takes its communication-loss
 * reaction, any other keeps its state. */
void drive_dn_restart(drive_dn_t *dn, co_time_t now);
/* The CAN controller went bus off: the connections end as at a restart. */
void drive_dn_bus_off(drive_dn_t *dn, co_time_t now);

/* What the scanner sees. */
drive_dn_state_t drive_dn_state(const drive_dn_t *dn);
const char *drive_dn_state_name(drive_dn_state_t state);
const char *drive_dn_led_name(dn_led_t led);

/* The CIP status (dn_status_t) of a dictionary access's SDO abort code: how the application
 * objects and the drive's attributes answer a refusal of the drive. */
uint16_t drive_dn_cip_status(uint32_t abort_code);

#endif
