/* SPDX-License-Identifier: Apache-2.0 */
/* Streamed DOMAIN entries (co_od_stream_t): their validation, their write in one piece and their
 * part of the SDO server, reached only through the dictionary's co_od_t.streaming =
 * &co_od_streaming, which the EDS generator sets when the dictionary has a streamed entry. A
 * firmware whose dictionary has none links none of this (docs/footprint.md). */
#include "co/co_node.h"

const co_od_stream_t *co_od_stream(const co_od_entry_t *entry)
{
    if (!(entry->flags & CO_OD_STREAM) || entry->hook == NULL)
        return NULL;
    /* The hook is the stream's first member (C11 6.7.2.1: a pointer to a structure, suitably
     * converted, points to its first member, and back). */
    return (const co_od_stream_t *)(const void *)entry->hook;
}

/* A streamed entry is a DOMAIN without bytes in the data block, with the functions its access
 * needs. */
static bool entry_valid(const co_od_entry_t *e)
{
    const co_od_stream_t *s = co_od_stream(e);
    if (s == NULL)
        return false;
    bool readable = s->size != NULL && s->read != NULL;
    bool writable = s->begin != NULL && s->write != NULL && s->end != NULL;
    return e->type == CO_DT_DOMAIN && e->size == 0 && (readable || !(e->flags & CO_OD_READ)) &&
           (writable || !(e->flags & CO_OD_WRITE));
}

/* A streamed DOMAIN written in one piece (an expedited download): the stream's begin, write and
 * end, as the SDO server calls them segment by segment. */
static uint32_t write_whole(co_node_t *node, const co_od_entry_t *e, const uint8_t *data,
                            size_t len)
{
    if (len > UINT32_MAX)
        return CO_SDO_ABORT_LENGTH_HIGH;
    const co_od_stream_t *s = co_od_stream(e);
    uint32_t abort = s->begin(node, e, true, (uint32_t)len);
    if (abort != CO_SDO_OK)
        return abort;
    if (len > 0)
        abort = s->write(node, e, 0, data, len);
    if (abort != CO_SDO_OK) {
        s->end(node, e, 0, false);
        return abort;
    }
    return s->end(node, e, (uint32_t)len, true);
}

/* A download starts: the application may refuse the announced size. */
static uint32_t sdo_begin(co_node_t *node, co_sdo_server_t *sdo, const co_od_entry_t *e)
{
    uint32_t abort = co_od_stream(e)->begin(node, e, sdo->size_indicated, sdo->size);
    if (abort == CO_SDO_OK)
        sdo->stream = e;
    return abort;
}

/* An upload starts: its size from the application. */
static uint32_t sdo_open(co_node_t *node, co_sdo_server_t *sdo, const co_od_entry_t *e)
{
    sdo->stream = e;
    return co_od_stream(e)->size(node, e, &sdo->size);
}

static uint32_t sdo_read(co_node_t *node, co_sdo_server_t *sdo, uint32_t offset, uint8_t *buf,
                         uint32_t len)
{
    const co_od_entry_t *e = sdo->stream;
    return co_od_stream(e)->read(node, e, offset, buf, len);
}

/* The application gets no byte past the announced size (0x06070010, as when the amount differs
 * at the end) nor past 4 GiB. */
static uint32_t sdo_write(co_node_t *node, co_sdo_server_t *sdo, uint32_t offset,
                          const uint8_t *data, uint32_t len)
{
    uint64_t end = (uint64_t)offset + len;
    if (sdo->size_indicated && end > sdo->size)
        return CO_SDO_ABORT_TYPE_LENGTH;
    if (end > UINT32_MAX)
        return CO_SDO_ABORT_NO_MEMORY;
    return co_od_stream(sdo->stream)->write(node, sdo->stream, offset, data, len);
}

/* The download completed: the application's end, once (the transfer no longer counts as a stream
 * to abort). */
static uint32_t sdo_commit(co_node_t *node, co_sdo_server_t *sdo)
{
    const co_od_entry_t *e = sdo->stream;
    sdo->stream = NULL;
    return co_od_stream(e)->end(node, e, sdo->offset, true);
}

/* The transfer of a stream ended otherwise (abort by either side, timeout, new request, reset):
 * a download's application hears of it. */
static void sdo_abandoned(co_node_t *node, co_sdo_server_t *sdo, const co_od_entry_t *e,
                          bool download)
{
    if (download)
        co_od_stream(e)->end(node, e, sdo->offset, false);
}

const co_od_streaming_t co_od_streaming = {
    .entry_valid = entry_valid,
    .write = write_whole,
    .sdo_begin = sdo_begin,
    .sdo_open = sdo_open,
    .sdo_read = sdo_read,
    .sdo_write = sdo_write,
    .sdo_commit = sdo_commit,
    .sdo_abandoned = sdo_abandoned,
};
