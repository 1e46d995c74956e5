/* SPDX-License-Identifier: Apache-2.0 */
/*
 * uml-xstate: lets User-Mode Linux restore its processes' FPU state on hosts whose XSAVE area is
 * larger than the one UML knows (tools/vcan-run preloads it into the UML kernel; docs/decisions.md,
 * D-TEST-UML-XSTATE).
 *
 * UML saves each guest process's FPU and vector registers with PTRACE_GETREGSET(NT_X86_XSTATE)
 * into a buffer of a fixed size (2,696 bytes in Debian's 6.1 and 6.12 kernels) and writes them back
 * with PTRACE_SETREGSET. The host kernel accepts a write only when it covers its whole XSAVE area,
 * which is larger on CPUs with AMX (11,008 bytes): the write fails with EFAULT and UML panics at
 * boot. This wrapper of ptrace() completes such a short write with the rest of the target's own
 * area, read just before: the bytes past UML's buffer are state (AMX tiles) that no guest process
 * can use, since asking the host kernel for it is a system call UML intercepts. Every other call
 * goes to the C library unchanged.
 *
 * The first time it completes a write, it says so on the file descriptor named by the environment
 * variable UML_XSTATE_NOTE_FD, if set.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ptrace.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

typedef long ptrace_fn(enum __ptrace_request request, ...);

/* Room for the whole area of any x86 CPU so far (11,008 bytes with AMX). The buffer is static, not
 * on the stack, because UML calls ptrace() on its own small kernel stacks; UML makes these calls
 * from one host thread only. */
enum { XSTATE_AREA_MAX = 64 * 1024 };
static _Alignas(64) unsigned char whole_area[XSTATE_AREA_MAX];
static size_t area_size; /* the host's, once known: the same for every process */
static bool note_written;

static ptrace_fn *libc_ptrace(void)
{
    static ptrace_fn *next;
    if (next == NULL) {
        void *symbol = dlsym(RTLD_NEXT, "ptrace");
        memcpy(&next, &symbol, sizeof next); /* POSIX dlsym(): a function's address */
    }
    return next;
}

static void note_completed_write(size_t area_size, size_t written)
{
    const char *fd_text = getenv("UML_XSTATE_NOTE_FD");
    note_written = true;
    if (fd_text == NULL || *fd_text == '\0') {
        return;
    }
    char text[400];
    int len = snprintf(text, sizeof text,
                       "vcan-run: this host's XSAVE area is %zu bytes and User-Mode Linux writes "
                       "back %zu: each of its FPU state writes is completed with the process's own "
                       "last %zu bytes, state no guest process can use (uml-xstate)\n",
                       area_size, written, area_size - written);
    if (len > 0 && write(atoi(fd_text), text, (size_t)len) < 0) {
        /* The note is a courtesy: UML runs on without it. */
    }
}

/* PTRACE_SETREGSET(NT_X86_XSTATE) of *iov, completed to the target's whole area when shorter. */
static long set_xstate(pid_t pid, struct iovec *iov)
{
    ptrace_fn *next = libc_ptrace();
    if (area_size != 0 && iov->iov_len >= area_size) {
        return next(PTRACE_SETREGSET, pid, (void *)NT_X86_XSTATE, iov);
    }
    struct iovec whole = {.iov_base = whole_area, .iov_len = sizeof whole_area};
    if (next(PTRACE_GETREGSET, pid, (void *)NT_X86_XSTATE, &whole) < 0 ||
        whole.iov_len <= iov->iov_len || whole.iov_len == sizeof whole_area) {
        /* Nothing to complete, or an area larger than we can hold: as without the wrapper. */
        return next(PTRACE_SETREGSET, pid, (void *)NT_X86_XSTATE, iov);
    }
    area_size = whole.iov_len;
    memcpy(whole_area, iov->iov_base, iov->iov_len);
    long result = next(PTRACE_SETREGSET, pid, (void *)NT_X86_XSTATE, &whole);
    if (result == 0 && !note_written) {
        note_completed_write(whole.iov_len, iov->iov_len);
    }
    return result;
}

long ptrace(enum __ptrace_request request, ...)
{
    va_list args;
    va_start(args, request);
    pid_t pid = va_arg(args, pid_t);
    void *addr = va_arg(args, void *);
    void *data = va_arg(args, void *);
    va_end(args);

    ptrace_fn *next = libc_ptrace();
    if (next == NULL) {
        errno = ENOSYS;
        return -1;
    }
    if (request == PTRACE_SETREGSET && (uintptr_t)addr == NT_X86_XSTATE && data != NULL) {
        return set_xstate(pid, data);
    }
    return next(request, pid, addr, data);
}
