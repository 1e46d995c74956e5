/* SPDX-License-Identifier: Apache-2.0 */
/* The EDS of a node for the commands that name objects: the file of --eds, or the one of
 * --eds-dir, the installed directory or the source tree whose identity (1018h:01, 1018h:02,
 * 1008h) the node reports over SDO. */
#include "comaster/comaster.h"

#include <stdio.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

/* The EDS directory of the source tree, for a comaster run from the build tree. */
#ifndef COMASTER_SOURCE_EDS_DIR
#define COMASTER_SOURCE_EDS_DIR "eds"
#endif

static int load_eds_file(const comaster_options_t *opts, const char *path, uint8_t node, eds_t *eds)
{
    char err[512];
    eds_result_t loaded = eds_load(eds, path, node, err, sizeof err);
    if (loaded == EDS_CANNOT_READ)
        return comaster_fail(opts, EX_NOINPUT, "%s", err);
    if (loaded != EDS_OK)
        return comaster_fail(opts, EX_DATAERR, "%s", err);
    return 0;
}

/* Reads an identity object; a node without it (an abort) leaves *value as it is. Returns 0 or
 * the status of a transfer that could not run (timeout, signal). */
static int read_identity(comaster_bus_t *bus, const comaster_options_t *opts, uint8_t node,
                         uint16_t index, uint8_t sub, uint8_t *buf, uint32_t cap, uint32_t *size)
{
    co_sdo_client_result_t result;
    int rc = comaster_sdo_upload(bus, node, index, sub, buf, cap, CO_SDO_CLIENT_AUTO,
                                 opts->timeout_ms, &result);
    if (rc != 0)
        return rc;
    if (result.status == CO_SDO_CLIENT_CLIENT_ABORT && result.abort_code == CO_SDO_ABORT_TIMEOUT)
        return comaster_sdo_status(opts, node, &result);
    *size = result.status == CO_SDO_CLIENT_OK ? result.size : 0;
    return 0;
}

/* The installed EDS directory: share/canopen-atv312/eds beside the bin/ of this program, so
 * that it is found under any installation prefix. False when /proc/self/exe cannot be read. */
static bool installed_eds_dir(char *dir, size_t len)
{
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return false;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash)
        return false;
    *slash = '\0';
    int written = snprintf(dir, len, "%s/../%s", exe, COMASTER_DEFAULT_EDS_DIR);
    return written > 0 && (size_t)written < len;
}

int comaster_load_eds(comaster_bus_t *bus, const comaster_options_t *opts, uint8_t node, eds_t *eds)
{
    memset(eds, 0, sizeof *eds);
    if (opts->eds_path)
        return load_eds_file(opts, opts->eds_path, node, eds);
    uint8_t vendor[4] = {0}, product[4] = {0};
    char name[64] = {0};
    uint32_t size = 0;
    int rc = read_identity(bus, opts, node, CO_IDX_IDENTITY, CO_IDENTITY_VENDOR, vendor,
                           sizeof vendor, &size);
    if (rc != 0)
        return rc;
    if (size != 4)
        return -1;
    rc = read_identity(bus, opts, node, CO_IDX_IDENTITY, CO_IDENTITY_PRODUCT, product,
                       sizeof product, &size);
    if (rc == 0)
        rc = read_identity(bus, opts, node, CO_IDX_DEVICE_NAME, 0, (uint8_t *)name, sizeof name - 1,
                           &size);
    if (rc != 0)
        return rc;
    name[size < sizeof name ? size : sizeof name - 1] = '\0';
    eds_identity_t identity = {co_get_u32(vendor), co_get_u32(product), name[0] ? name : NULL};
    char installed[4200];
    const char *dirs[] = {opts->eds_dir,
                          installed_eds_dir(installed, sizeof installed) ? installed : NULL,
                          COMASTER_SOURCE_EDS_DIR};
    char path[4096];
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        if (dirs[i] && eds_find_for_identity(dirs[i], &identity, path, sizeof path))
            return load_eds_file(opts, path, node, eds);
        if (opts->eds_dir)
            break; /* an --eds-dir given is the only place to look in */
    }
    return -1;
}
