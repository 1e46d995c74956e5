/* SPDX-License-Identifier: Apache-2.0 */
/* A ptrace() wrapper that makes this host look, to User-Mode Linux, like one whose XSAVE area is
 * larger than UML's buffer (a CPU with AMX): it shortens each PTRACE_SETREGSET(NT_X86_XSTATE) to
 * the legacy region, the XSAVE header and the AVX registers' upper halves (832 bytes, what the
 * guest's programs use on an x86-64 host without AVX-512), which the host kernel refuses as it
 * refuses UML's 2,696 bytes there. Preloaded before tools/uml-xstate.c, which must make up for it
 * (tests/tools/vcan_run_check.py). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <elf.h>
#include <stdarg.h>
#include <stdint.h>
#include <string.h>
#include <sys/ptrace.h>
#include <sys/types.h>
#include <sys/uio.h>

enum { SHORT_WRITE = 832 };

typedef long ptrace_fn(enum __ptrace_request request, ...);

long ptrace(enum __ptrace_request request, ...)
{
    va_list args;
    va_start(args, request);
    pid_t pid = va_arg(args, pid_t);
    void *addr = va_arg(args, void *);
    void *data = va_arg(args, void *);
    va_end(args);

    ptrace_fn *next;
    void *symbol = dlsym(RTLD_NEXT, "ptrace");
    memcpy(&next, &symbol, sizeof next); /* POSIX dlsym(): a function's address */
    if (request == PTRACE_SETREGSET && (uintptr_t)addr == NT_X86_XSTATE && data != NULL) {
        struct iovec shortened = *(struct iovec *)data;
        if (shortened.iov_len > SHORT_WRITE)
            shortened.iov_len = SHORT_WRITE;
        return next(request, pid, addr, &shortened);
    }
    return next(request, pid, addr, data);
}
