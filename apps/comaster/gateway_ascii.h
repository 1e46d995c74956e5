/* SPDX-License-Identifier: Apache-2.0 */
/* The text of CiA 309-3, the ASCII gateway of comaster gateway: a command line parsed into a
 * request, the defaults a connection sets (set node, set sdo_timeout ...), and the reply lines,
 * formatted as CANopenNode's canopend writes them (docs/comaster.md, D-GATEWAY-REPLIES). Pure
 * functions, no bus: tests/comaster tests them. */
#ifndef COMASTER_GATEWAY_ASCII_H
#define COMASTER_GATEWAY_ASCII_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* The internal error codes of CiA 309-3 comaster answers with. */
#define GW_ERROR_NOT_SUPPORTED 100u    /* request not supported */
#define GW_ERROR_SYNTAX 101u           /* syntax error */
#define GW_ERROR_INTERNAL_STATE 102u   /* request not processed due to internal state */
#define GW_ERROR_TIMEOUT 103u          /* time-out */
#define GW_ERROR_NO_DEFAULT_NODE 105u  /* no default node set */
#define GW_ERROR_UNSUPPORTED_NET 106u  /* unsupported net */
#define GW_ERROR_UNSUPPORTED_NODE 107u /* unsupported node */
#define GW_ERROR_LSS_MANUFACTURER 501u /* LSS implementation- or manufacturer-specific error */
#define GW_ERROR_LSS_NODE_ID 502u      /* LSS node-ID not supported */
#define GW_ERROR_LSS_BIT_RATE 503u     /* LSS bit-rate not supported */
#define GW_ERROR_LSS_STORE 504u        /* LSS parameter storing failed */

/* The one network of comaster gateway: its interface. */
#define GW_NET 1u
/* The SDO timeout before set sdo_timeout, canopend's. */
#define GW_DEFAULT_SDO_TIMEOUT_MS 500u
/* Longest command line with its terminating NUL; the largest value written or read. */
#define GW_LINE_MAX 1024u
#define GW_VALUE_MAX 4096u

/* A CiA 309-3 data type: how an SDO's bytes are written and printed. */
typedef struct gw_type {
    const char *name; /* b, i8 ... u64, x8 ... x64, r32, r64, vs, hex */
    uint8_t size;     /* bytes; 0 for vs and hex */
    char kind;     /* 'u' unsigned, 'i' signed, 'x' hexadecimal, 'r' real, 's' string, 'h' bytes */
    uint16_t code; /* the CiA 301 data type a written value is parsed as (co_dtype_t) */
} gw_type_t;

/* What a connection keeps between its lines (set network, node, sdo_timeout, sdo_block). */
typedef struct gw_session {
    int16_t node; /* the default node, -1 before set node */
    uint16_t sdo_timeout_ms;
    bool sdo_block;
} gw_session_t;

void gw_session_init(gw_session_t *session);

typedef enum gw_action {
    GW_REPLY, /* reply is ready (OK, an error, an empty line, help) */
    GW_READ,  /* an SDO upload of index:sub from node, printed as type */
    GW_WRITE, /* an SDO download of data (len bytes) */
    GW_NMT,   /* an NMT command (nmt_command) to node (0: all) */
    GW_LSS    /* an LSS service (lss) with its args */
} gw_action_t;

/* The LSS services of CiA 309-3 that comaster gateway runs on the core's LSS master. */
typedef enum gw_lss {
    GW_LSS_SWITCH_GLOBAL,    /* args[0]: 0 waiting, 1 configuration */
    GW_LSS_SWITCH_SELECTIVE, /* args: vendor-ID, product code, revision, serial */
    GW_LSS_SET_NODE,         /* args[0]: 1..127 or 255 */
    GW_LSS_CONF_BITRATE,     /* args[0]: table 0, args[1]: index 0..9 (not 5) */
    GW_LSS_ACTIVATE_BITRATE, /* args[0]: switch delay in ms */
    GW_LSS_STORE,
    GW_LSS_INQUIRE,     /* args[0]: LSSSUB 0..3 (vendor-ID, product code, revision, serial) */
    GW_LSS_INQUIRE_ALL, /* the four parts of the address */
    GW_LSS_GET_NODE,
    GW_LSS_FASTSCAN /* args[0]: the timeout in ms */
} gw_lss_t;

/* The timeout of _lss_fastscan without one, canopend's. */
#define GW_DEFAULT_FASTSCAN_MS 100u

typedef struct gw_request {
    gw_action_t action;
    uint32_t sequence;
    uint8_t node;
    uint16_t index;
    uint8_t sub;
    const gw_type_t *type;
    uint8_t nmt_command;
    gw_lss_t lss;
    uint32_t args[4];
    uint8_t data[GW_VALUE_MAX];
    size_t len;
    char reply[GW_LINE_MAX + 64]; /* for GW_REPLY; help is longer: see help */
    const char *help;             /* GW_REPLY of help: this text after reply */
} gw_request_t;

/* Parses one line (without its end of line) of a connection into req; the set commands change
 * the session. *last_sequence is the sequence of the line before, which an error reply of a line
 * without one repeats (as canopend does), and is updated. */
void gw_parse(gw_session_t *session, uint32_t *last_sequence, const char *line, gw_request_t *req);

/* The reply lines, each ending in CR LF. gw_reply_words: count numbers in 0x and `digits`
 * hexadecimal digits, blank-separated (LSS addresses and node-ids). */
size_t gw_reply_words(char *out, size_t cap, uint32_t sequence, const uint32_t *words,
                      unsigned count, unsigned digits);
size_t gw_reply_ok(char *out, size_t cap, uint32_t sequence);
size_t gw_reply_error(char *out, size_t cap, uint32_t sequence, unsigned code);
size_t gw_reply_abort(char *out, size_t cap, uint32_t sequence, uint32_t abort_code);
/* An upload's bytes as type; false when their size does not fit it. */
bool gw_reply_value(char *out, size_t cap, uint32_t sequence, const gw_type_t *type,
                    const uint8_t *data, size_t len);

#endif
