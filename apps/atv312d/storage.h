/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's --store file at start: its directory checked (a store that can never be saved is
 * told at once, not at the first 1010h write), the file read (co_linux/file_store.h) and what it
 * held logged, image by image, so that after a crash the log says which parameters came back.
 * The drives bind to it (drives.h). docs/atv312d.md, "Storage file". */
#ifndef ATV312D_STORAGE_H
#define ATV312D_STORAGE_H

#include "co_linux/file_store.h"

/* Opens the store at path: loaded, missing (defaults until a save) or ignored (defaults, with a
 * warning). 0, or an exit status after logging why (the store then closed). */
int atv312d_storage_open(const char *path, co_file_store_t *store);

#endif
