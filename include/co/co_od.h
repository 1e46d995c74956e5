/* SPDX-License-Identifier: Apache-2.0 */
/* The object dictionary: a const table of entries sorted by (index, sub-index), found by binary
 * search, whose values live in a per-node data block. The table is shared by every node built from
 * the same EDS; the data block belongs to one node, so several nodes can run in one process.
 *
 * Values are kept in the data block as CANopen transmits them (little-endian), so SDO and PDO
 * transfers are plain copies and the application reads and writes through co_od_value() and
 * co_od_set_value(). */
#ifndef CO_OD_H
#define CO_OD_H

#include "co_types.h"

typedef struct co_node co_node_t;
struct co_sdo_server; /* co_sdo.h: a server channel, for the streaming code below */
typedef struct co_od_entry co_od_entry_t;

/* Entry flags. Access types follow CiA 306: ro, wo, rw, rwr, rww, const. */
#define CO_OD_READ 0x0001u    /* readable by SDO */
#define CO_OD_WRITE 0x0002u   /* writable by SDO */
#define CO_OD_CONST 0x0004u   /* never changes (const access type) */
#define CO_OD_TPDO 0x0008u    /* may be mapped into a TPDO */
#define CO_OD_RPDO 0x0010u    /* may be mapped into an RPDO */
#define CO_OD_NODEID 0x0020u  /* default value is relative to the node-id ($NODEID+...) */
#define CO_OD_ZERO_OK 0x0040u /* 0 is accepted even below the low limit ("0 = disabled") */
#define CO_OD_PROCESS 0x0080u /* process data (a command, a reference): never stored (1010h) */
#define CO_OD_STREAM 0x0100u  /* a streamed DOMAIN: `hook` is the hook of a co_od_stream_t */

#define CO_OD_ACCESS_RO CO_OD_READ
#define CO_OD_ACCESS_WO CO_OD_WRITE
#define CO_OD_ACCESS_RW (CO_OD_READ | CO_OD_WRITE)
#define CO_OD_ACCESS_CONST (CO_OD_READ | CO_OD_CONST)

/* Where a write comes from, for hooks that treat them differently. Only the application writes a
 * read-only entry; every other origin gets the checks of a client's download (co_od_write). */
typedef enum co_od_origin {
    CO_OD_ORIGIN_SDO,   /* a client's SDO download */
    CO_OD_ORIGIN_PDO,   /* a received PDO */
    CO_OD_ORIGIN_APP,   /* the application or the stack itself */
    CO_OD_ORIGIN_STORE, /* a stored value applied at a reset (1010h / 1011h) */
    /* A communication card of another fieldbus on the same device, writing for its own master
     * (the drive's DeviceNet card, src/drive/devicenet): checked and hooked as an SDO download. */
    CO_OD_ORIGIN_CARD
} co_od_origin_t;

/* Returned by a write hook or a service write handler that stored (or consumed) the value itself:
 * not a valid abort code, so it can share the return value. */
#define CO_OD_HANDLED 1u

/* Value limits of a numeric entry, as the raw value widened to 64 bits: signed types are
 * sign-extended and compared as int64_t, unsigned types as uint64_t. */
typedef struct co_od_limits {
    uint64_t low;
    uint64_t high;
} co_od_limits_t;

/* Device-specific behaviour of one entry, named in the EDS hooks file and linked by name. */
typedef struct co_od_hook {
    /* Before a write is stored (after type, length and limit checks): return 0 to store it,
     * CO_OD_HANDLED if the hook stored or consumed it, or an SDO abort code to refuse it. */
    uint32_t (*write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data, size_t len,
                      co_od_origin_t origin);
    /* Before a read: may refresh the stored value. Return 0 or an SDO abort code. */
    uint32_t (*read)(co_node_t *node, const co_od_entry_t *entry);
} co_od_hook_t;

/* A DOMAIN entry whose value lives in the application and is streamed by the SDO server segment
 * by segment (CiA 301 7.4.7.1, "large amount of data"): segmented and block transfers of any size
 * up to 2^32-1 bytes pass through these functions and never through the SDO transfer buffer, so
 * the entry has no bytes in the data block (its size is 0). A value of 1..4 bytes still goes
 * expedited. Functions return 0 or an SDO abort code, which the server sends to the client. An
 * entry readable by SDO needs `size` and `read`, a writable one `begin`, `write` and `end`.
 * The entry has the flag CO_OD_STREAM and its `hook` points at the stream's `hook`, so that the
 * table keeps one hook pointer per entry (the EDS generator's hooks-file word `stream=NAME`). */
typedef struct co_od_stream {
    /* First member, so that the entry's hook pointer leads to the stream. hook.read, when set,
     * runs before every upload as for any entry; hook.write is never called: the stream takes
     * the value. */
    co_od_hook_t hook;
    /* An upload starts: the bytes of the value to upload into *size. */
    uint32_t (*size)(co_node_t *node, const co_od_entry_t *entry, uint32_t *size);
    /* Fills buf with the `len` bytes (1..7) of the value at `offset`. The offsets of one upload
     * grow, but after a lost block segment the server reads again from the last acknowledged
     * point (no further back than the start of the current sub-block). */
    uint32_t (*read)(co_node_t *node, const co_od_entry_t *entry, uint32_t offset, uint8_t *buf,
                     size_t len);
    /* A download starts, announcing `size` bytes when size_indicated. Refuse a size the
     * application cannot take: CO_SDO_ABORT_LENGTH_HIGH (0x06070012) when the object can never hold
     * it, CO_SDO_ABORT_NO_MEMORY (0x05040005) when there is no room for it now. */
    uint32_t (*begin)(co_node_t *node, const co_od_entry_t *entry, bool size_indicated,
                      uint32_t size);
    /* The next `len` bytes (1..7) of the download at `offset`: only data received in sequence,
     * each byte once, offsets contiguous from 0. An abort code ends the transfer (then `end`). */
    uint32_t (*write)(co_node_t *node, const co_od_entry_t *entry, uint32_t offset,
                      const uint8_t *data, size_t len);
    /* The download ended, called once per `begin`: ok = true when all `total` bytes arrived (in
     * the announced amount, and the CRC of a block transfer matched): return 0 to commit the value
     * or an abort code to refuse it. ok = false when it was aborted by either side, timed out or
     * replaced by a reset or a new request: discard what was written (the result is ignored). */
    uint32_t (*end)(co_node_t *node, const co_od_entry_t *entry, uint32_t total, bool ok);
} co_od_stream_t;

struct co_od_entry {
    uint16_t index;
    uint8_t subindex;
    uint8_t type;                 /* co_dtype_t */
    uint16_t flags;               /* CO_OD_* */
    uint16_t size;                /* bytes; the capacity for strings and domains */
    uint32_t offset;              /* of the value in the node's data block */
    const co_od_limits_t *limits; /* NULL: the whole range of the type */
    const co_od_hook_t *hook;     /* NULL: plain storage */
};

/* The code of streamed DOMAIN entries (src/canopen/common/od_stream.c): the dictionary's validation
 * and write, and the SDO server's transfers of a streamed entry, whose state is the server channel
 * `sdo` (co_sdo_server_t) of the transfer. */
typedef struct co_od_streaming {
    /* Whether a CO_OD_STREAM entry is a DOMAIN of size 0 with the functions of its access. */
    bool (*entry_valid)(const co_od_entry_t *entry);
    /* The value written in one piece (co_od_write of a streamed entry). */
    uint32_t (*write)(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data, size_t len);
    /* SDO server: a download of the entry starts (sdo->size_indicated, size), an upload opens
     * (the size into sdo->size); both make it sdo->stream. */
    uint32_t (*sdo_begin)(co_node_t *node, struct co_sdo_server *sdo, const co_od_entry_t *entry);
    uint32_t (*sdo_open)(co_node_t *node, struct co_sdo_server *sdo, const co_od_entry_t *entry);
    /* SDO server: bytes of sdo->stream read or written at `offset`. */
    uint32_t (*sdo_read)(co_node_t *node, struct co_sdo_server *sdo, uint32_t offset, uint8_t *buf,
                         uint32_t len);
    uint32_t (*sdo_write)(co_node_t *node, struct co_sdo_server *sdo, uint32_t offset,
                          const uint8_t *data, uint32_t len);
    /* SDO server: the download completed; the application's end decides. */
    uint32_t (*sdo_commit)(co_node_t *node, struct co_sdo_server *sdo);
    /* SDO server: the transfer of `entry` ended otherwise, a download or an upload. */
    void (*sdo_abandoned)(co_node_t *node, struct co_sdo_server *sdo, const co_od_entry_t *entry,
                          bool download);
} co_od_streaming_t;

/* The code of streamed entries, for co_od_t.streaming. */
extern const co_od_streaming_t co_od_streaming;

/* Bit of co_od_t.dummy_types for a data type index 0002h..0007h (co_dtype_t). */
#define CO_OD_DUMMY(type) (1u << (type))

/* One object dictionary: the sorted table, the image of its default values and the dummy entries
 * it supports. */
typedef struct co_od {
    const char *name;
    const co_od_entry_t *entries;
    uint16_t count;
    uint32_t data_size;      /* bytes of a node's data block */
    const uint8_t *defaults; /* data_size bytes: default values, node-id terms excluded */
    /* Data types an RPDO may map as a dummy (CiA 301 7.4.8.4), as the EDS declares them in
     * [DummyUsage] (CiA 306): CO_OD_DUMMY(n) set for data type 000nh, n = 2..7 (INTEGER8 ..
     * UNSIGNED32; other bits are ignored: BOOLEAN is not a whole byte). 0: no dummy mapping. */
    uint8_t dummy_types;
    /* ParameterName of each entry, in table order, for diagnostics; NULL when not generated. */
    const char *const *names;
    /* &co_od_streaming when the dictionary has a streamed entry (CO_OD_STREAM), else NULL, so
     * that a firmware without one does not link that code: co_od_validate refuses a streamed
     * entry in a dictionary without it (CO_OD_ERR_STREAM). */
    const co_od_streaming_t *streaming;
    /* co_sync_produce when the dictionary has 1006h (the SYNC producer's period), else NULL, so
     * that a firmware that cannot produce the SYNC does not link the producer: 1005h bit 30 is
     * then refused (0x06090030). */
    co_time_t (*sync_producer)(co_node_t *node, co_time_t now);
} co_od_t;

/* Result of co_od_validate(). */
typedef enum co_od_error {
    CO_OD_VALID = 0,
    CO_OD_ERR_EMPTY,     /* no entries */
    CO_OD_ERR_UNSORTED,  /* entry at position is not after its predecessor */
    CO_OD_ERR_DUPLICATE, /* entry at position repeats its predecessor's key */
    CO_OD_ERR_BOUNDS,    /* entry at position lies outside the data block */
    CO_OD_ERR_SIZE,      /* entry at position has a size that does not fit its type */
    CO_OD_ERR_STREAM     /* entry at position is CO_OD_STREAM but not a DOMAIN of size 0 with
                            a hook, or lacks the stream functions its access needs, or the
                            dictionary has no streaming code (co_od_t.streaming NULL) */
} co_od_error_t;

/* Checks the table once at start-up. On error *position is the offending entry. */
co_od_error_t co_od_validate(const co_od_t *od, uint16_t *position);

/* The entry's ParameterName, or NULL (no names in the dictionary, or no such entry). */
const char *co_od_name(const co_od_t *od, uint16_t index, uint8_t subindex);

/* Binary search. NULL when absent. */
const co_od_entry_t *co_od_find(const co_od_t *od, uint16_t index, uint8_t subindex);

/* Like co_od_find, with the most specific abort code: CO_SDO_ABORT_NO_OBJECT when no entry has that
 * index, CO_SDO_ABORT_NO_SUBINDEX when the index exists but not the sub-index. */
uint32_t co_od_lookup(const co_od_t *od, uint16_t index, uint8_t subindex,
                      const co_od_entry_t **entry);

/* The stream of a streamed DOMAIN (CO_OD_STREAM), NULL for any other entry (od_stream.c). */
const co_od_stream_t *co_od_stream(const co_od_entry_t *entry);

/* Byte size of a fixed-size type, 0 for strings and domains. */
size_t co_od_type_size(uint8_t type);

/* The stored bytes of an entry and their current length (strings: up to the first NUL). */
uint8_t *co_od_bytes(const co_node_t *node, const co_od_entry_t *entry);
size_t co_od_length(const co_node_t *node, const co_od_entry_t *entry);

/* SDO-side read: lookup, read access, read hook. On success *entry is ready for co_od_bytes. */
uint32_t co_od_read_check(co_node_t *node, uint16_t index, uint8_t subindex,
                          const co_od_entry_t **entry);

/* Full write path with every CiA 301 check: existence, write access, length against the type
 * (0x06070010/12/13), limits (0x06090031/32), the entry's hook, the owning service's parameter
 * rules, then storage and the application's write notification. Returns 0 or an abort code.
 * A streamed DOMAIN (co_od_stream_t) takes the value through its begin, write and end instead;
 * its end is the application's notification. */
uint32_t co_od_write(co_node_t *node, uint16_t index, uint8_t subindex, const uint8_t *data,
                     size_t len, co_od_origin_t origin);

/* co_od_write of an entry already found in the node's dictionary (a mapped object, a stored
 * value): the same checks but the lookup. */
uint32_t co_od_write_entry(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data,
                           size_t len, co_od_origin_t origin);

/* Stores bytes without any check (used by hooks and services after their own checks). */
void co_od_store(co_node_t *node, const co_od_entry_t *entry, const uint8_t *data, size_t len);

/* The numeric readers: which one depends on what the caller holds and on what an absent entry
 * must read as. None checks access rights or calls a hook (co_od_read_check does, for the SDO).
 *
 *   co_od_get(node, entry)                An entry already found (co_od_find, a PDO mapping, a
 *                                         walk over the table): its value. No search.
 *   co_od_value(node, index, sub)         By index, for the application and for a parameter
 *                                         whose absence means 0 (1005h..1007h, 100Ch, 1017h):
 *                                         an absent entry reads as 0.
 *   co_od_param(node, index, sub, absent) By index, for an optional parameter of up to 32 bits
 *                                         to which CiA 301 gives a default when the dictionary
 *                                         lacks it (100Eh: 700h + node-id, a PDO's COB-ID and
 *                                         type, 1200h): `absent` is that default.
 *
 * co_od_get and co_od_value give up to 8 bytes, sign-extended for signed types; co_od_param the
 * low 32 bits. Each reader by index is one binary search: a caller that reads one entry several
 * times finds it once and uses co_od_get. The writers without checks pair with them: co_od_set
 * (an entry), co_od_set_value (by index; false, nothing written, when absent). */
int64_t co_od_get(const co_node_t *node, const co_od_entry_t *entry);
int64_t co_od_value(const co_node_t *node, uint16_t index, uint8_t subindex);
uint32_t co_od_param(const co_node_t *node, uint16_t index, uint8_t subindex, uint32_t absent);
void co_od_set(co_node_t *node, const co_od_entry_t *entry, int64_t value);
bool co_od_set_value(co_node_t *node, uint16_t index, uint8_t subindex, int64_t value);

/* The value nearest `value` that the entry's limit check accepts: its LowLimit..HighLimit, else
 * its type's range (0 too where the entry takes it below its LowLimit, CO_OD_ZERO_OK). What an
 * application publishes or a view reports through it is always a value a client could write
 * back. For the numeric types of 1..8 bytes; a REAL, a string or a domain is returned as is. */
int64_t co_od_saturate(const co_od_entry_t *entry, int64_t value);

/* Restores defaults of the entries with index in [first, last], node-id terms added. */
void co_od_restore_defaults(co_node_t *node, uint16_t first, uint16_t last);

#endif
