/* SPDX-License-Identifier: Apache-2.0 */
/* The page's files (apps/atv312d/web/), built into the daemon: web_assets.c is generated at build
 * time by web_assets.cmake, one array per file, so that the page needs neither a build step nor
 * files beside the binary. */
#ifndef ATV312D_WEB_ASSETS_H
#define ATV312D_WEB_ASSETS_H

#include <stddef.h>

typedef struct atv312d_web_asset {
    const char *path;         /* "/index.html": its name under web/ */
    const char *content_type; /* by its extension */
    const unsigned char *data;
    size_t size;
    const char *etag; /* "\"<first 16 hex digits of its SHA-1>\"" */
} atv312d_web_asset_t;

extern const atv312d_web_asset_t atv312d_web_assets[];
extern const size_t atv312d_web_asset_count;

#endif
