/* SPDX-License-Identifier: Apache-2.0 */
/* The drive layer's floors: its internal interface, for its own files and never a model's. The
 * CiA 402 indexes every model has, then a section per file from the ground floor up (profile.c,
 * local_control.c, channels.c, output.c, faults.c). A file calls only the sections above its own
 * (and cia402.c, motor.c, which need none of this); drive.c, the composition root, calls any, and
 * so may parameters.c and panel.c beside it (the dictionary hooks models share, the front panel),
 * which no file of the layer calls. */
#ifndef DRIVE_FLOORS_H
#define DRIVE_FLOORS_H

#include "drive/drive.h"

/* CiA 402 objects of the velocity mode ("vl") every model has at these addresses. */
#define CIA402_IDX_ERROR_CODE 0x603Fu
#define CIA402_IDX_CONTROLWORD 0x6040u
#define CIA402_IDX_STATUSWORD 0x6041u
#define CIA402_IDX_TARGET_VELOCITY 0x6042u
#define CIA402_IDX_VELOCITY_DEMAND 0x6043u
#define CIA402_IDX_VELOCITY_ACTUAL 0x6044u
#define CIA402_IDX_VELOCITY_ACCELERATION 0x6048u

/* The profile's parameters and their units (profile.c). The drive of a node, for the core's
 * hooks. */
drive_t *drive_of(co_node_t *node);
/* A parameter of the profile, unsigned, found by its index. */
uint32_t drive_param_value(const drive_t *drive, drive_param_t param);
/* Two codes or names alike but for case ("ohf" and OHF). */
bool drive_same_code(const char *a, const char *b);
/* Whether `entry` is the parameter `param` of the model's dictionary. */
bool drive_is_param(const co_od_entry_t *entry, drive_param_t param);
/* Once at init: the entries the drive reads and writes whenever it settles (drive_entries_t). */
void drive_entries_find(drive_t *drive);
/* An entry found at init (NULL: reads as 0, a write does nothing). A value set is held within
 * the entry's limits. */
int64_t drive_entry_value(const drive_t *drive, const co_od_entry_t *entry);
void drive_entry_set(drive_t *drive, const co_od_entry_t *entry, int64_t value);
/* Parameter `param` of the profile through its entry found at init, with no search. */
uint32_t drive_entry_param(const drive_t *drive, const co_od_entry_t *entry, drive_param_t param);
/* Conversions between 0.1 Hz and rpm through the motor's nominal frequency and speed. */
uint32_t drive_frequency_to_rpm(const drive_t *drive, uint32_t decihertz);
uint32_t drive_rpm_to_frequency(const drive_t *drive, uint32_t rpm);
/* The same with a sign (the direction of rotation). */
int32_t drive_signed_rpm_to_frequency(const drive_t *drive, int32_t rpm);
int32_t drive_signed_frequency_to_rpm(const drive_t *drive, int32_t decihertz);

/* At the drive (local_control.c). Local control: forced, or a command channel other than the
 * network (drive.h). Each event below brings the motor to `now` and changes the state; the caller
 * settles the drive. */
void drive_local_force(drive_t *drive, bool local, co_time_t now);
void drive_local_stop_key(drive_t *drive, co_time_t now);
/* false (nothing happens) unless local control holds and the drive is not in Fault. */
bool drive_local_run_key(drive_t *drive, co_time_t now);
void drive_local_load(drive_t *drive, uint8_t percent, co_time_t now);
/* false (nothing happens) when the model has no such input. */
bool drive_local_input(drive_t *drive, uint8_t input, bool on, co_time_t now);
/* false (nothing happens) when the model has no such analogue input or the value is out of its
 * range. */
bool drive_local_analog(drive_t *drive, uint8_t index, int32_t value, co_time_t now);
/* The terminals' run inputs after a change of the logic inputs (`before`: as they were), while
 * the terminals command: a run or a stop. */
void drive_local_terminals(drive_t *drive, uint8_t before);
/* The command channel changed: a freewheel stop to Switch on disabled. */
void drive_local_channel_changed(drive_t *drive);
/* The motor follows the reference under forced local control. */
bool drive_local_runs(const drive_t *drive);
/* The motor stands: a local stop ends in Switch on disabled. */
void drive_local_motor_stopped(drive_t *drive);
/* Status word bits of the command channel: remote (bit 9) and the STOP key's. */
uint16_t drive_local_status(const drive_t *drive);
/* A network command was applied: it may be the run command that clears the STOP key's bit. */
void drive_local_command_applied(drive_t *drive);

/* Channels (channels.c): the network gives the reference, the network commands. Kept in the
 * drive, recomputed by drive_channels_update when a channel parameter is written, at a reset, at
 * the start and when an input changes, so that the periodic work reads no parameter; true when
 * the command channel changed. */
bool drive_channels_update(drive_t *drive);
bool drive_channel_parameter(const drive_t *drive, const co_od_entry_t *entry);
bool drive_reference_from_network(const drive_t *drive);
/* The analogue input the reference comes from, or NULL (the network's, or a channel without
 * one: a zero reference). */
const drive_analog_input_t *drive_reference_analog(const drive_t *drive);
/* Switching sources (drive.h, DRIVE_SOURCE_*): a control word bit of 11..15; a bit or a logic
 * input of the model. */
bool drive_source_is_bit(uint32_t code);
bool drive_source_valid(const drive_t *drive, uint32_t code);
/* The access level allows separate channels and control word bits as switching sources. */
bool drive_access_full(const drive_t *drive);
/* A channel_mode value with separate command channels: the separate and the I/O modes. */
bool drive_mode_separate(const drive_profile_t *profile, uint32_t mode);

/* The output (output.c). Steers the motor to the target and ramp of the state, the control word
 * and the channels. */
void drive_output_steer(drive_t *drive);
/* The drive's output is on: it drives the motor (current and torque), and a fault reaction can
 * stop it on a ramp. */
bool drive_output_on(const drive_t *drive);
/* Publishes the status word, speeds, current and torque. */
void drive_output_publish(drive_t *drive);

/* Faults (faults.c). The profile has a usable fault table. */
bool drive_faults_valid(const drive_profile_t *profile);
/* Raises fault `index` (the drive faults, EMCY, 603Fh) unless it is active already: true when it
 * was raised now, and the drive must settle on its reaction. */
bool drive_fault_raise(drive_t *drive, uint8_t index);
/* The cause of fault `index` appears at `now` and raises it: drive_fault_raise's answer. */
bool drive_fault_cause_appears(drive_t *drive, uint8_t index, co_time_t now);
/* The cause of fault `index` ends at `now`: true when that ended an automatic fault. */
bool drive_fault_cause_ends(drive_t *drive, uint8_t index, co_time_t now);
/* Every active fault may be reset by a fault reset command now. */
bool drive_faults_resettable(const drive_t *drive);
/* A fault reset was accepted: every active fault ends (its EMCY cleared), 603Fh = 0. */
void drive_faults_acknowledge(drive_t *drive);
/* An active fault or a bus condition still present reports EMCY `code`. The EMCY producer keeps
 * one active error per code (CiA 301), however many causes share it: the code is cleared only
 * when none does. */
bool drive_emcy_code_in_use(const drive_t *drive, uint16_t code);
/* 603Fh: the latched fault's EMCY code while a fault is active, else the code of a CAN bus
 * condition still present, else 0 (the Altivar manuals: "The Emergency Error Code is the same as
 * the variable Fault code (603F)"; D-ERROR-CODE-EMCY). */
void drive_error_code_publish(drive_t *drive);
/* Reset node: the drive forgets its faults (the EMCY producer forgets their errors), not the
 * causes still present. */
void drive_faults_restart(drive_t *drive);

#endif
