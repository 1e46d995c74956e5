/* SPDX-License-Identifier: Apache-2.0 */
/* GNU libmicrohttpd, loaded by the web surface when it opens (--http) instead of linked: a
 * linked library, and the GnuTLS, nettle, gmp and p11-kit it brings, would be mapped by every
 * daemon, 2.5 MB of resident memory for nothing without --http (issue 27, docs/benchmarks.md).
 * The types and constants are still those of <microhttpd.h>; the functions http.c calls are
 * this table's, resolved by name in the library the build found, loaded by its soname. */
#ifndef ATV312D_MHD_LOAD_H
#define ATV312D_MHD_LOAD_H

#include <microhttpd.h>
#include <stddef.h>

/* The library's functions that the web surface calls, each of the type its header declares. */
typedef struct atv312d_mhd {
    void *handle; /* dlopen's; NULL: not loaded */
    __typeof__(MHD_start_daemon) *start_daemon;
    __typeof__(MHD_stop_daemon) *stop_daemon;
    __typeof__(MHD_run) *run;
    __typeof__(MHD_get_timeout) *get_timeout;
    __typeof__(MHD_get_daemon_info) *get_daemon_info;
    __typeof__(MHD_get_connection_info) *get_connection_info;
    __typeof__(MHD_lookup_connection_value) *lookup_connection_value;
    __typeof__(MHD_create_response_from_buffer) *create_response_from_buffer;
    __typeof__(MHD_create_response_from_callback) *create_response_from_callback;
    __typeof__(MHD_add_response_header) *add_response_header;
    __typeof__(MHD_queue_response) *queue_response;
    __typeof__(MHD_destroy_response) *destroy_response;
    __typeof__(MHD_suspend_connection) *suspend_connection;
    __typeof__(MHD_resume_connection) *resume_connection;
} atv312d_mhd_t;

/* Loads the library and resolves every function of the table. 0, or EX_UNAVAILABLE with a
 * one-line message in err: the library, the dynamic loader's reason and what to do about it;
 * the table is then empty. */
int atv312d_mhd_load(atv312d_mhd_t *mhd, char *err, size_t err_len);

/* Unloads the library, once its daemon is stopped (no callback into the daemon left), and empties
 * the table. Safe when not loaded. */
void atv312d_mhd_unload(atv312d_mhd_t *mhd);

#endif
