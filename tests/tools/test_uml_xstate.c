/* SPDX-License-Identifier: Apache-2.0 */
/* tools/uml-xstate.c, the ptrace() wrapper vcan-run preloads into User-Mode Linux, on this host's
 * real XSAVE area: a write shorter than the area, which the host kernel refuses (the failure of UML
 * on hosts with AMX, where UML's 2,696 bytes are short), goes through the wrapper, sets what it
 * carries and keeps the rest of the target's state; a whole write is passed on unchanged.
 *
 * A short write here is the legacy region and the XSAVE header (576 bytes), shorter than the area
 * of any CPU with AVX, so the case of the AMX hosts is met on every x86-64 host. The module is
 * loaded with dlopen() rather than LD_PRELOAD so that the test runs in sanitizer builds too. */
#define _GNU_SOURCE
#include "check_main.h"

#include <check.h>
#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ptrace.h>
#include <sys/syscall.h>
#include <sys/uio.h>
#include <sys/wait.h>
#include <unistd.h>

/* The standard XSAVE layout (Intel SDM vol. 1, 13.4): XMM0 in the legacy region, the header's
 * XSTATE_BV, the upper halves of the YMM registers as component 2. */
enum {
    XMM0_OFFSET = 160,
    XSTATE_BV_OFFSET = 512,
    SHORT_WRITE = 576,
    YMM_HI_OFFSET = 576,
    XFEATURE_YMM = 1u << 2,
};

typedef long ptrace_fn(enum __ptrace_request request, ...);

static const char *module_path;
static void *module;
static ptrace_fn *wrapped_ptrace;
static pid_t child;
static unsigned char area[64 * 1024] __attribute__((aligned(64)));
static size_t area_size;

/* The kernel's own answer, without the wrapper. */
static long raw_ptrace(long request, pid_t pid, void *addr, void *data)
{
    return syscall(SYS_ptrace, request, pid, addr, data);
}

static size_t read_area(unsigned char *into, size_t size)
{
    struct iovec iov = {.iov_base = into, .iov_len = size};
    ck_assert_int_eq(raw_ptrace(PTRACE_GETREGSET, child, (void *)NT_X86_XSTATE, &iov), 0);
    return iov.iov_len;
}

static void start_traced_child(void)
{
    /* Loaded anew for each test, so that each starts with the module's first write. */
    module = dlopen(module_path, RTLD_NOW | RTLD_LOCAL);
    ck_assert_msg(module != NULL, "dlopen %s: %s", module_path, dlerror());
    void *symbol = dlsym(module, "ptrace");
    ck_assert(symbol != NULL);
    memcpy(&wrapped_ptrace, &symbol,
           sizeof wrapped_ptrace); /* POSIX dlsym(): a function's address */

    child = fork();
    ck_assert_int_ge(child, 0);
    if (child == 0) {
        raw_ptrace(PTRACE_TRACEME, 0, NULL, NULL);
        raise(SIGSTOP);
        _exit(0);
    }
    int status;
    ck_assert_int_eq(waitpid(child, &status, 0), child);
    ck_assert(WIFSTOPPED(status));
    area_size = read_area(area, sizeof area);
    ck_assert_uint_gt(area_size, SHORT_WRITE);
    ck_assert_uint_lt(area_size, sizeof area);
}

static void stop_traced_child(void)
{
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
    dlclose(module);
}

START_TEST(short_write_is_refused_by_the_host_kernel)
{
    struct iovec iov = {.iov_base = area, .iov_len = SHORT_WRITE};
    errno = 0;
    ck_assert_int_eq(raw_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &iov), -1);
    ck_assert_int_eq(errno, EFAULT);
}
END_TEST

START_TEST(short_write_sets_its_bytes_and_keeps_the_rest)
{
    /* The rest first: a YMM upper half with a pattern, written whole. */
    static unsigned char before[sizeof area] __attribute__((aligned(64)));
    memcpy(before, area, area_size);
    uint64_t xstate_bv;
    memcpy(&xstate_bv, before + XSTATE_BV_OFFSET, sizeof xstate_bv);
    xstate_bv |= XFEATURE_YMM;
    memcpy(before + XSTATE_BV_OFFSET, &xstate_bv, sizeof xstate_bv);
    memset(before + YMM_HI_OFFSET, 0xA5, 16);
    struct iovec whole = {.iov_base = before, .iov_len = area_size};
    ck_assert_int_eq(raw_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &whole), 0);

    /* Then XMM0 through a short write, as UML writes. */
    static unsigned char part[SHORT_WRITE] __attribute__((aligned(64)));
    memcpy(part, before, SHORT_WRITE);
    memset(part + XMM0_OFFSET, 0x3C, 16);
    struct iovec iov = {.iov_base = part, .iov_len = SHORT_WRITE};
    ck_assert_int_eq(wrapped_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &iov), 0);

    static unsigned char after[sizeof area] __attribute__((aligned(64)));
    ck_assert_uint_eq(read_area(after, sizeof after), area_size);
    ck_assert_mem_eq(after + XMM0_OFFSET, part + XMM0_OFFSET, 16);
    ck_assert_mem_eq(after + YMM_HI_OFFSET, before + YMM_HI_OFFSET, 16);
}
END_TEST

START_TEST(whole_write_is_passed_on)
{
    memset(area + XMM0_OFFSET, 0x5A, 16);
    struct iovec iov = {.iov_base = area, .iov_len = area_size};
    ck_assert_int_eq(wrapped_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &iov), 0);
    static unsigned char after[sizeof area] __attribute__((aligned(64)));
    read_area(after, sizeof after);
    ck_assert_mem_eq(after + XMM0_OFFSET, area + XMM0_OFFSET, 16);
}
END_TEST

START_TEST(first_completed_write_is_noted_once)
{
    int note[2];
    ck_assert_int_eq(pipe(note), 0);
    char fd_text[16];
    snprintf(fd_text, sizeof fd_text, "%d", note[1]);
    setenv("UML_XSTATE_NOTE_FD", fd_text, 1);

    struct iovec iov = {.iov_base = area, .iov_len = SHORT_WRITE};
    ck_assert_int_eq(wrapped_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &iov), 0);
    ck_assert_int_eq(wrapped_ptrace(PTRACE_SETREGSET, child, (void *)NT_X86_XSTATE, &iov), 0);
    close(note[1]);
    unsetenv("UML_XSTATE_NOTE_FD");

    char text[512] = {0};
    ssize_t len = read(note[0], text, sizeof text - 1);
    close(note[0]);
    char expected[128];
    snprintf(expected, sizeof expected,
             "XSAVE area is %zu bytes and User-Mode Linux writes back %d:", area_size, SHORT_WRITE);
    ck_assert_msg(len > 0 && strstr(text, expected) != NULL, "note: '%s'", text);
    ck_assert_ptr_eq(strchr(text, '\n'), text + len - 1); /* one line: noted once */
}
END_TEST

static Suite *uml_xstate_suite(void)
{
    Suite *s = suite_create("uml_xstate");
    TCase *tc = tcase_create("ptrace");
    tcase_add_checked_fixture(tc, start_traced_child, stop_traced_child);
    tcase_add_test(tc, short_write_is_refused_by_the_host_kernel);
    tcase_add_test(tc, short_write_sets_its_bytes_and_keeps_the_rest);
    tcase_add_test(tc, whole_write_is_passed_on);
    tcase_add_test(tc, first_completed_write_is_noted_once);
    suite_add_tcase(s, tc);
    return s;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s PATH/uml-xstate.so\n", argv[0]);
        return 2;
    }
    module_path = argv[1];
    return check_run_suite(uml_xstate_suite());
}
