/* SPDX-License-Identifier: Apache-2.0 */
/* The texts of the CIP vocabulary of include/dn/dn_cip.h, for the programs that show DeviceNet
 * traffic (cotrace's DeviceNet decoder, a scanner's command line); a separate small library so
 * that the portable slave library does not carry them. */
#ifndef COTRACE_CIP_TEXT_H
#define COTRACE_CIP_TEXT_H

#include <stdint.h>

/* "Get_Attribute_Single", ... by service code (without the response bit); NULL when unknown. */
const char *cip_service_name(uint8_t service);
/* "object does not exist", ... by general status code; "reserved" for unassigned codes. */
const char *cip_general_status_text(uint8_t status);
/* "Identity", "Connection", ... by class code; NULL when the DeviceNet vocabulary has none. */
const char *cip_class_name(uint8_t class_id);

#endif
