/* SPDX-License-Identifier: Apache-2.0 */
/* The event loop's timer (co_linux/events.h): armed to the earliest deadline, with as few
 * timerfd_settime calls as the deadlines allow. A deadline that only moves later, as an I/O
 * connection's watchdog does at every poll, leaves the timer where it is until it fires; an
 * earlier deadline, a passed one and no deadline at all are armed at once. */
#include "check_main.h"
#include "co_linux/events.h"

#include <check.h>
#include <sys/timerfd.h>

static co_linux_events_t ev;

static void on_timer(void *ctx, uint32_t events)
{
    (void)ctx;
    (void)events;
}

static void setup(void)
{
    co_linux_events_init(&ev);
    ck_assert_ptr_null(co_linux_events_open(&ev, on_timer, NULL));
}

static void teardown(void)
{
    co_linux_events_close(&ev);
}

static co_time_t clock_now_us(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (co_time_t)now.tv_sec * 1000000u + (co_time_t)now.tv_nsec / 1000u;
}

/* The kernel's timer expires at `expected` (microseconds), or is disarmed (0). timerfd_gettime
 * answers the time left when it ran, somewhere between two clock reads around it: the expiry
 * lies between the first read plus the time left and the second plus it (1 us more for the
 * nanoseconds cut), however long a loaded machine (or valgrind) takes between the calls. */
#define assert_kernel_expiry(expected) assert_kernel_expiry_at(expected, __LINE__)
static void assert_kernel_expiry_at(co_time_t expected, int line)
{
    struct itimerspec its;
    co_time_t before = clock_now_us();
    ck_assert_int_eq(timerfd_gettime(ev.timer_fd, &its), 0);
    co_time_t after = clock_now_us();
    if (its.it_value.tv_sec == 0 && its.it_value.tv_nsec == 0) {
        ck_assert_msg(expected == 0, "line %d: the timer is disarmed", line);
        return;
    }
    co_time_t left =
        (co_time_t)its.it_value.tv_sec * 1000000u + (co_time_t)its.it_value.tv_nsec / 1000u;
    ck_assert_msg(expected != 0 && before + left <= expected && expected <= after + left + 1u,
                  "line %d: the timer expires between %llu and %llu us, not at %llu", line,
                  (unsigned long long)(before + left), (unsigned long long)(after + left + 1u),
                  (unsigned long long)expected);
}

static co_time_t clock_now_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return ((co_time_t)now.tv_sec * 1000u + (co_time_t)now.tv_nsec / 1000000u) * 1000u;
}

START_TEST(later_deadline_leaves_the_timer_until_it_fires)
{
    co_time_t now = clock_now_ms();
    co_time_t first = now + 100000u;
    co_linux_events_arm(&ev, first, now);
    ck_assert_uint_eq(ev.timer_armed, first);
    /* a poll pushes the watchdog 25 ms later: no timerfd_settime */
    co_linux_events_arm(&ev, first + 25000u, now + 25000u);
    ck_assert_uint_eq(ev.timer_armed, first);
    assert_kernel_expiry(first);
    /* the timer fired at `first`: the deadline now in force is armed */
    co_linux_events_arm(&ev, first + 75000u, first);
    ck_assert_uint_eq(ev.timer_armed, first + 75000u);
}
END_TEST

START_TEST(earlier_deadline_is_armed_at_once)
{
    co_time_t now = clock_now_ms();
    co_linux_events_arm(&ev, now + 100000u, now);
    co_linux_events_arm(&ev, now + 40000u, now);
    ck_assert_uint_eq(ev.timer_armed, now + 40000u);
    assert_kernel_expiry(now + 40000u);
}
END_TEST

START_TEST(no_deadline_disarms_at_once)
{
    co_time_t now = clock_now_ms();
    co_linux_events_arm(&ev, now + 100000u, now);
    co_linux_events_arm(&ev, CO_TIME_NEVER, now);
    ck_assert_uint_eq(ev.timer_armed, CO_TIME_NEVER);
    assert_kernel_expiry(0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("events");
    TCase *tc = tcase_create("timer");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, later_deadline_leaves_the_timer_until_it_fires);
    tcase_add_test(tc, earlier_deadline_is_armed_at_once);
    tcase_add_test(tc, no_deadline_disarms_at_once);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
