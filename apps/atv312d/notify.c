/* SPDX-License-Identifier: Apache-2.0 */
/* The service manager's notification socket (notify.h). */
#include "atv312d/notify.h"

#include <errno.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* Fills addr from $NOTIFY_SOCKET's value; its length, or 0 (errno EINVAL) for a name that is
 * empty, too long, or neither a path nor an abstract name. */
static socklen_t notify_address(const char *name, struct sockaddr_un *addr)
{
    size_t len = strlen(name);
    memset(addr, 0, sizeof *addr);
    addr->sun_family = AF_UNIX;
    if ((name[0] != '/' && name[0] != '@') || len < 2 || len >= sizeof addr->sun_path) {
        errno = EINVAL;
        return 0;
    }
    memcpy(addr->sun_path, name, len);
    if (name[0] == '@')
        addr->sun_path[0] = '\0'; /* abstract: no terminating NUL counts */
    else
        len++;
    return (socklen_t)(offsetof(struct sockaddr_un, sun_path) + len);
}

bool atv312d_notify(const char *state)
{
    const char *name = getenv("NOTIFY_SOCKET");
    if (name == NULL)
        return true;
    struct sockaddr_un addr;
    socklen_t addr_len = notify_address(name, &addr);
    if (addr_len == 0)
        return false;
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return false;
    size_t len = strlen(state);
    bool sent =
        sendto(fd, state, len, MSG_NOSIGNAL, (struct sockaddr *)&addr, addr_len) == (ssize_t)len;
    int err = errno;
    close(fd);
    errno = err;
    return sent;
}
