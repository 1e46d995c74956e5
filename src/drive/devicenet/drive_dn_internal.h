/* SPDX-License-Identifier: Apache-2.0 */
/* Internal interface of the drive on DeviceNet (drive_devicenet.h): the ODVA translation
 * (odva.c) and the drive's CIP classes (cip_objects.c), which the adapter (adapter.c) puts
 * together. */
#ifndef DRIVE_DN_INTERNAL_H
#define DRIVE_DN_INTERNAL_H

#include "drive/drive_devicenet.h"

/* Drivecom control word bits 0..3 of the commands the card generates (Altivar 312 DeviceNet
 * manual, "Run/Stop event triggers"), and the switching bits of NetCtrl and NetRef (C212, C213). */
#define DN_DRIVECOM_SHUTDOWN 0x0006u
#define DN_DRIVECOM_SWITCH_ON 0x0007u /* also Disable operation */
#define DN_DRIVECOM_ENABLE_OPERATION 0x000Fu
#define DN_DRIVECOM_COMMAND_BITS 0x000Fu
#define DN_DRIVECOM_FAULT_RESET 0x0080u
#define DN_DRIVECOM_NET_CTRL_BIT 0x1000u /* C212 */
#define DN_DRIVECOM_NET_REF_BIT 0x2000u  /* C213 */

/* odva.c. The drive's words through the entries it found at init. */
uint16_t drive_dn_status_word(const drive_t *drive);
uint16_t drive_dn_control_word(const drive_t *drive);
int16_t drive_dn_speed_actual(const drive_t *drive);
/* A new ODVA command: the Run/Stop events, the fault reset edge, the switching bits and the
 * reference, written to 6040h and 6042h as the card does. */
void drive_dn_command(drive_dn_t *dn, const drive_dn_command_t *next);
/* The explicit connection of the request being carried out, if any, as the one the commands now
 * come on (drive_dn_t.command_connection): every path that changes the command calls it. */
void drive_dn_note_command_connection(drive_dn_t *dn);
/* Status bits of the Control supervisor and the AC/DC drive. */
bool drive_dn_running1(drive_dn_state_t state);
bool drive_dn_ready(drive_dn_state_t state);
bool drive_dn_faulted(const drive_t *drive);
bool drive_dn_warning(const drive_t *drive);
bool drive_dn_at_reference(const drive_t *drive);
bool drive_dn_control_from_net(const drive_t *drive);
bool drive_dn_reference_from_net(const drive_t *drive);

/* cip_objects.c: the table of the drive's classes, sorted by class. */
#define DRIVE_DN_OBJECT_COUNT 4u
void drive_dn_objects(drive_dn_t *dn, dn_object_t objects[DRIVE_DN_OBJECT_COUNT]);

#endif
