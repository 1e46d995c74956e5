/* A small reader of EDS and DCF files (CiA 306 INI format) for cotrace: object names, data types
 * and values (DCF ParameterValue, else DefaultValue, with $NODEID resolved), enough to name SDO
 * objects and to decode PDOs by their mapping (1600h-17FFh, 1A00h-1BFFh) and COB-IDs
 * (1400h-15FFh, 1800h-19FFh). No python: the installed decoder reads the file itself. */
#ifndef COTRACE_EDS_H
#define COTRACE_EDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Marks the entry of an object's own section ([1008]): the name of the object, and its value
 * when it is a plain variable (sub-index 0). */
#define COTRACE_EDS_OBJECT 0xFFFFu

typedef struct cotrace_eds_entry {
    uint16_t index;
    uint16_t sub; /* 0..255, or COTRACE_EDS_OBJECT */
    uint16_t data_type;
    bool has_value;
    uint64_t value; /* numeric value, $NODEID resolved */
    char *name;
} cotrace_eds_entry_t;

typedef struct cotrace_eds {
    cotrace_eds_entry_t *entries;
    size_t count, capacity;
} cotrace_eds_t;

typedef enum cotrace_eds_result {
    COTRACE_EDS_OK = 0,
    COTRACE_EDS_CANNOT_READ, /* the file cannot be opened */
    COTRACE_EDS_MALFORMED    /* not an EDS or DCF, or out of memory */
} cotrace_eds_result_t;

/* Reads `path` for a node (its node-id resolves $NODEID). On failure err gets a one-line message
 * (file, line, what is wrong) and eds is empty. */
cotrace_eds_result_t cotrace_eds_load(cotrace_eds_t *eds, const char *path, uint8_t node_id,
                                      char *err, size_t err_len);
void cotrace_eds_free(cotrace_eds_t *eds);

/* The entry of index:sub (a plain variable's object section for sub 0), or NULL. */
const cotrace_eds_entry_t *cotrace_eds_find(const cotrace_eds_t *eds, uint16_t index, uint8_t sub);
/* The name of index:sub, or of its object when the sub-index has none; NULL when unknown. */
const char *cotrace_eds_name(const cotrace_eds_t *eds, uint16_t index, uint8_t sub);

#endif
