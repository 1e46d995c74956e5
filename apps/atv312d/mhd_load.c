/* SPDX-License-Identifier: Apache-2.0 */
/* Loading GNU libmicrohttpd and resolving the web surface's functions (mhd_load.h). The soname
 * and the Debian package that holds it come from the build (apps/atv312d/CMakeLists.txt):
 * ATV312D_MHD_SONAME, ATV312D_MHD_PACKAGE. */
#include "atv312d/mhd_load.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>
#include <sysexits.h>

/* dlsym gives an object pointer; POSIX requires it to convert to the function pointer it stands
 * for, ISO C has no such conversion: the address is copied into the table's member instead. */
_Static_assert(sizeof(void *) == sizeof(void (*)(void)),
               "a function pointer must be the size of dlsym's void *");

/* Each function of the table: its symbol and its member's place in the table. */
#define FUNCTION(name) "MHD_" #name, offsetof(atv312d_mhd_t, name)

static const struct function {
    const char *symbol;
    size_t offset;
} functions[] = {
    {FUNCTION(start_daemon)},
    {FUNCTION(stop_daemon)},
    {FUNCTION(run)},
    {FUNCTION(get_timeout)},
    {FUNCTION(get_daemon_info)},
    {FUNCTION(get_connection_info)},
    {FUNCTION(lookup_connection_value)},
    {FUNCTION(create_response_from_buffer)},
    {FUNCTION(create_response_from_callback)},
    {FUNCTION(add_response_header)},
    {FUNCTION(queue_response)},
    {FUNCTION(destroy_response)},
    {FUNCTION(suspend_connection)},
    {FUNCTION(resume_connection)},
};

static int cannot_load(const char *reason, char *err, size_t err_len)
{
    snprintf(err, err_len,
             "%s (GNU libmicrohttpd, the web server) cannot be loaded: %s; install %s or run "
             "without --http",
             ATV312D_MHD_SONAME, reason, ATV312D_MHD_PACKAGE);
    return EX_UNAVAILABLE;
}

int atv312d_mhd_load(atv312d_mhd_t *mhd, char *err, size_t err_len)
{
    *mhd = (atv312d_mhd_t){0};
    /* RTLD_NOW: a library whose own dependencies cannot be resolved fails here, at start, rather
     * than at its first call. */
    void *handle = dlopen(ATV312D_MHD_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        return cannot_load(dlerror(), err, err_len);
    for (size_t i = 0; i < sizeof functions / sizeof functions[0]; i++) {
        void *address = dlsym(handle, functions[i].symbol);
        if (!address) {
            int rc = cannot_load(dlerror(), err, err_len);
            dlclose(handle);
            *mhd = (atv312d_mhd_t){0};
            return rc;
        }
        memcpy((char *)mhd + functions[i].offset, &address, sizeof address);
    }
    mhd->handle = handle;
    return 0;
}

void atv312d_mhd_unload(atv312d_mhd_t *mhd)
{
    if (mhd->handle)
        dlclose(mhd->handle);
    *mhd = (atv312d_mhd_t){0};
}
