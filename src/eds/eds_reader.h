/* SPDX-License-Identifier: Apache-2.0 */
/* A small reader of EDS and DCF files (CiA 306 INI format) shared by the installed tools (cotrace,
 * comaster): object names, data types and values (DCF ParameterValue, else DefaultValue, with
 * $NODEID resolved), enough to name SDO objects, to find an object by its name and to decode PDOs
 * by their mapping (1600h-17FFh, 1A00h-1BFFh) and COB-IDs (1400h-15FFh, 1800h-19FFh); the
 * device's identity ([DeviceInfo]) to find the EDS of a node. No python: the installed tools read
 * the file themselves; the INI syntax is ini_reader.h's. */
#ifndef EDS_READER_H
#define EDS_READER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Marks the entry of an object's own section ([1008]): the name of the object, and its value
 * when it is a plain variable (sub-index 0). */
#define EDS_OBJECT 0xFFFFu

typedef struct eds_entry {
    uint16_t index;
    uint16_t sub; /* 0..255, or EDS_OBJECT */
    uint16_t data_type;
    bool has_value;
    uint64_t value; /* numeric value, $NODEID resolved; a negative one in two's complement */
    bool negative;  /* the value was written with a '-' sign (only a lone number may have one) */
    unsigned value_line; /* the line of the value's key, for messages */
    char *name;
    char *text; /* the value as written (a VISIBLE_STRING's default), or NULL */
    /* A DCF's own keys: the value is a ParameterValue (the configuration of the device, which a
     * network master downloads), and the Denotation (the application's name of the object). */
    bool configured;
    /* The DefaultValue as a number, also when a ParameterValue wins over it: what the device
     * holds after its reset (a master invalidates a PDO on the COB-ID it holds). */
    bool has_default;
    uint64_t default_value;
    char *denotation;
    bool writable; /* AccessType rw, wo, rww or rwr */
} eds_entry_t;

typedef struct eds {
    eds_entry_t *entries;
    size_t count, capacity;
    /* [DeviceInfo]: the identity 1018h:01/02 of the device the file describes (0 when absent). */
    uint32_t vendor_number;
    uint32_t product_number;
} eds_t;

typedef enum eds_result {
    EDS_OK = 0,
    EDS_CANNOT_READ, /* the file cannot be opened */
    EDS_MALFORMED    /* not an EDS or DCF, or out of memory */
} eds_result_t;

/* Reads `path` for a node (its node-id resolves $NODEID). On failure err gets a one-line message
 * (file, line, what is wrong) and eds is empty. An object's section is named by four hex digits
 * ([1018]), a sub-index's by those, "sub" and one or two ([1018sub1]), in any case; a name that
 * starts as a number in another notation ([0x12], [12], [1018sub]) is such a failure, one that
 * goes on with a word ([FileInfo], [1F22Value]) a section of another kind, whose keys are
 * ignored. */
eds_result_t eds_load(eds_t *eds, const char *path, uint8_t node_id, char *err, size_t err_len);
void eds_free(eds_t *eds);

/* The entry of index:sub (a plain variable's object section for sub 0), or NULL. */
const eds_entry_t *eds_find(const eds_t *eds, uint16_t index, uint8_t sub);
/* The name of index:sub, or of its object when the sub-index has none; NULL when unknown. */
const char *eds_name(const eds_t *eds, uint16_t index, uint8_t sub);

/* Sets the value of index:sub as a DCF's ParameterValue would (a device's actual PDO mapping read
 * over SDO), adding the entry when the file has none. False when out of memory. */
bool eds_set_value(eds_t *eds, uint16_t index, uint8_t sub, uint64_t value);

/* The outcome of eds_find_by_name. */
typedef enum eds_lookup {
    EDS_LOOKUP_FOUND = 0,
    EDS_LOOKUP_NONE,     /* no object has that name */
    EDS_LOOKUP_AMBIGUOUS /* several objects match a part of a name: *found is the first */
} eds_lookup_t;

/* Finds a variable (not a record's own section) by its ParameterName, case-insensitive: the whole
 * name ("ACC acceleration time (0.1 s)") or a DCF's Denotation ("speed"), else its first word, the
 * code of a manufacturer parameter ("ACC"), else whole words of one name ("acceleration time";
 * "NOPE" is no word of "COL CANopen fault management"). */
eds_lookup_t eds_find_by_name(const eds_t *eds, const char *name, const eds_entry_t **found);

/* The manufacturer parameters (2000h-5FFFh) whose code, the first word of the name, is closest to
 * name by edit distance, at most half its letters changed: up to max entries in *codes, one per
 * code, nearest first. For a name that eds_find_by_name does not know ("ACX": ACC, AC2). */
size_t eds_closest_codes(const eds_t *eds, const char *name, const eds_entry_t **codes, size_t max);

/* A device as it tells who it is: 1018h:01, 1018h:02 and 1008h. */
typedef struct eds_identity {
    uint32_t vendor;
    uint32_t product;
    const char *device_name; /* 1008h, or NULL when the device has none */
} eds_identity_t;

/* Looks in `dir` for the *.eds file whose [DeviceInfo] VendorNumber and ProductNumber are the
 * device's; among several (a vendor's drives that all say product 0), the one whose 1008h
 * default is the device's name. On success `path` (path_len bytes) names it. False when none
 * matches or the directory cannot be read. */
bool eds_find_for_identity(const char *dir, const eds_identity_t *identity, char *path,
                           size_t path_len);

#endif
