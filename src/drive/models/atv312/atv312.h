/* SPDX-License-Identifier: Apache-2.0 */
/* The Schneider Altivar 312 model of the CiA 402 velocity drive (drive/drive.h): its object
 * dictionary atv312_od (generated from eds/ATV312.eds with the hooks of
 * src/drive/models/atv312/atv312.hooks; a node's data block is ATV312_OD_DATA_SIZE bytes) and its
 * profile, where its parameters are and what its control word bits 11-14 do. The behaviour is the
 * drive layer's: give atv312_profile to drive_init. Portable like the core: no malloc, no OS
 * calls, no globals. */
#ifndef ATV312_H
#define ATV312_H

#include "atv312_od.h" /* generated */
#include "co/co_emcy.h"
#include "drive/drive.h"

/* The faults of the Altivar 312 and of the Altivar 31, their EMCY codes and reset classes
 * (src/drive/models/atv312/atv312_faults.c, docs/atv312.md): the same but for the name of the
 * communication-loss fault, COF on CANopen (both CANopen manuals), CnF behind the ATV312's
 * DeviceNet card (its DeviceNet manual). */
extern const drive_fault_table_t atv312_family_faults;
extern const drive_fault_table_t atv312_devicenet_faults;

/* Codes of the channel parameters (the project's, docs/atv312.md): CHCF 1 not separate, 2
 * separate, 3 I/O; rFC 1 Fr1, 2 Fr2; CCS 1 Cd1, 2 Cd2; Fr1/Fr2 1 AI1, 2 AI2, 3 AI3, 4 keypad, 5
 * Modbus, 6 CANopen; Cd1/Cd2 1 terminals, 2 keypad, 3 Modbus, 4 CANopen. */
#define ATV312_CHCF_SEPARATE 2
#define ATV312_CHCF_IO 3
#define ATV312_RFC_FR2 2
#define ATV312_CCS_CD2 2
#define ATV312_FR_CANOPEN 6
#define ATV312_CD_CANOPEN 4
#define ATV312_CD_TERMINALS 1

/* AdCO, the CANopen address of the [COMMUNICATION] (COM-) menu, 0 to 127, 0 CANopen off, and
 * bdCO, its speed (kbit/s, 125 by default): read-only on the bus, the node-id and the bitrate the
 * drive runs with ("any change will only be applied after a power cycle"), at ADL 6051 and 6052,
 * the project's addresses (docs/decisions.md, D-ADCO-BDCO). */
#define ATV312_ADCO DRIVE_PARAM(0x201E, 0x34)

/* The access level (LAC): 1 L1, 2 L2, 3 L3, the project's codes; L3 allows separate channels and
 * control word bits as switching sources. */
#define ATV312_LAC_L3 3
/* Logic inputs LI1-LI3: the terminals of the CANopen daisy chain card VW3A31208, which replaces
 * the base terminal card (ATV312 CANopen manual, "Control terminals characteristics"). */
#define ATV312_LOGIC_INPUTS 3

/* The reference channel codes of the analogue inputs (Fr1/Fr2: 1 AI1, 2 AI2, 3 AI3; the ATV31's
 * potentiometer 7) and the AI3 scaling parameters CrL3 and CrH3, 0.1 mA (ADL 4602, 4603: the
 * project's addresses, docs/atv312.md). */
#define ATV312_FR_AI1 1
#define ATV312_FR_AI2 2
#define ATV312_FR_AI3 3
#define ATV312_FR_AIP 7
#define ATV312_AI3_LOW DRIVE_PARAM(0x2010, 3)
#define ATV312_AI3_HIGH DRIVE_PARAM(0x2010, 4)

/* The family's node options: an expedited write longer than its object taken when the extra bytes
 * are 0 (D-ATV312-LONG-EXPEDITED); 1001h in every EMCY, the core's RPDO and SYNC length errors
 * and the CAN bus conditions too, the manuals' byte 2, "=0 (no error) =1 (error)", the generic bit
 * alone (D-ERROR-REGISTER); and an asynchronous TPDO's inhibit time written while the TPDO runs,
 * the manuals' "In asynchronous mode "Inhibit time" and "Event timer" can be modified"
 * (docs/decisions.md, D-ASYNC-INHIBIT-WRITE). */
#define ATV312_NODE_OPTIONS                                                                        \
    (CO_NODE_SDO_LONG_EXPEDITED | CO_NODE_ERROR_REGISTER_GENERIC |                                 \
     CO_NODE_ASYNC_TPDO_INHIBIT_WRITABLE)

/* The unit of each TPDO's inhibit time as the ATV312 manual's object table prints its row: TPDO1
 * (1800h:03) "unit = 1 ms", TPDO6 (1805h:03) "unit = 0,1 ms", CiA 301's (docs/decisions.md,
 * D-INHIBIT-TIME): the bit of TPDO1 alone (co_node_config_t.tpdo_inhibit_ms). */
#define ATV312_TPDO_INHIBIT_MS (1u << 0)

/* The profile of an Altivar 31/312 on the dictionary `dictionary`, with `inputs` logic inputs (LI1
 * forward and LI2 reverse in 2-wire control while the terminals command, the factory assignment
 * the project takes, docs/decisions.md D-TERMINAL-RUN), the
 * analogue inputs of the array `analog` (drive_analog_input_t, as reference channels), the
 * faults of `fault_table` and a STOP key that resets faults when `stop_key_resets` (the ATV31's
 * STOP/RESET key; the ATV312 CANopen manual gives its key no reset). The
 * family's default assignment of control word bits 11-14 (DeviceNet manual, "CMD control word":
 * "CMD = 16#080F: reverse operation" ...): bit 11 reverses, bit 12 stops on the ramp (Stt), bits 13
 * (DC injection stop, modelled as the fast stop) and 14 stop on the fast ramp, DEC / 4 (dCF's
 * default); status word bit 15 is the direction of rotation, bit 14 "stop via the STOP key". Its
 * parameters, at 0x2000 + (ADL - 3000) / 100, sub-index ADL mod 100 + 1 (docs/decisions.md,
 * D-MANUFACTURER-ADDRESS): ACC 9001, DEC 9002, HSP 3104, LSP 3105, FRS 9602, NCR 9603, NSP 9604,
 * LCR 3203, OTR 3208, CMD 8501, ETA 3201, COL 6401, CnF 6402, RFR 3202, LFR 8502, CHCF 8401,
 * rFC 8411, Fr1 8413, Fr2 8414, CCS 8421, Cd1 8423, Cd2 8424, Stt 11203, tUn 9608, LAC 8400,
 * rPS 9010, AC2 9012, dE2 9013. SDO writes longer than their object are taken when the extra bytes
 * are 0 (CO_NODE_SDO_LONG_EXPEDITED): the manuals' own PL7 guarding example writes 100Ch and 100Dh
 * with "Data length = 4 bytes" (docs/decisions.md, D-ATV312-LONG-EXPEDITED). A macro, not a
 * function, so that each model's profile stays a constant initialiser (in flash on a
 * microcontroller); the ATV31 (atv31/atv31.h) is the same drive under another name. */
#define ATV312_FAMILY_PROFILE(dictionary, inputs, analog, fault_table, stop_key_resets,            \
                              inhibit_ms)                                                          \
    {                                                                                              \
        .od = (dictionary), .node_options = ATV312_NODE_OPTIONS, .tpdo_inhibit_ms = (inhibit_ms),  \
        .node_options_code = &co_node_options, .control_reverse = 0x0800,                          \
        .control_ramp_stop = 0x1000, .control_fast_stop = 0x2000 | 0x4000,                         \
        .status_reverse = 0x8000, .status_stop_key = 0x4000, .fast_ramp_divider = 4,               \
        .acceleration = DRIVE_PARAM(0x203C, 2), .deceleration = DRIVE_PARAM(0x203C, 3),            \
        .high_speed = DRIVE_PARAM(0x2001, 5), .low_speed = DRIVE_PARAM(0x2001, 6),                 \
        .nominal_frequency = DRIVE_PARAM(0x2042, 3), .nominal_current = DRIVE_PARAM(0x2042, 4),    \
        .nominal_speed = DRIVE_PARAM(0x2042, 5), .motor_current = DRIVE_PARAM(0x2002, 4),          \
        .motor_torque = DRIVE_PARAM(0x2002, 9), .control_word_copy = DRIVE_PARAM(0x2037, 2),       \
        .status_word_copy = DRIVE_PARAM(0x2002, 2),                                                \
        .communication_loss_mode = DRIVE_PARAM(0x2022, 2),                                         \
        .network_fault_code = DRIVE_PARAM(0x2022, 3), .faults = (fault_table),                     \
        .stop_type = DRIVE_PARAM(0x2052, 4), .channel_mode = DRIVE_PARAM(0x2036, 2),               \
        .channel_mode_separate = ATV312_CHCF_SEPARATE, .channel_mode_io = ATV312_CHCF_IO,          \
        .command_channels = {DRIVE_PARAM(0x2036, 24), DRIVE_PARAM(0x2036, 25),                     \
                             DRIVE_PARAM(0x2036, 22), ATV312_CCS_CD2, ATV312_CD_CANOPEN},          \
        .reference_channels = {DRIVE_PARAM(0x2036, 14), DRIVE_PARAM(0x2036, 15),                   \
                               DRIVE_PARAM(0x2036, 12), ATV312_RFC_FR2, ATV312_FR_CANOPEN},        \
        .output_frequency = DRIVE_PARAM(0x2002, 3), .frequency_reference = DRIVE_PARAM(0x2037, 3), \
        .auto_tune = DRIVE_PARAM(0x2042, 9), .ramp_switch = DRIVE_PARAM(0x203C, 11),               \
        .acceleration_2 = DRIVE_PARAM(0x203C, 13), .deceleration_2 = DRIVE_PARAM(0x203C, 14),      \
        .logic_inputs = (inputs), .analog_inputs = (analog), .terminals = ATV312_CD_TERMINALS,     \
        .run_forward = 1, .run_reverse = 2,                                                        \
        .analog_input_count = sizeof(analog) / sizeof((analog)[0]),                                \
        .access_level = DRIVE_PARAM(0x2036, 1), .access_level_full = ATV312_LAC_L3,                \
        .stop_key_resets_faults = (stop_key_resets), .internal_control = DRIVE_PARAM(0x2037, 5),   \
        .internal_control_no_check = 0x8000, .inconsistent_fault = "CFI",                          \
        .can_address = ATV312_ADCO,                                                                \
    }

extern const drive_profile_t atv312_profile;
/* The same drive behind its DeviceNet card (atv312_devicenet.h): the faults of its DeviceNet
 * manual. */
extern const drive_profile_t atv312_devicenet_drive_profile;

#endif
