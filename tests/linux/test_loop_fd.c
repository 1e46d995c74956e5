/* SPDX-License-Identifier: Apache-2.0 */
/* The runtime loop on a socket the caller gives (co_linux_loop_open_fd): an ATV312 drive answers
 * over an AF_UNIX SOCK_SEQPACKET socketpair frame for frame, datagrams that are not a CAN frame
 * are ignored, the peer's hang-up ends the loop (also when the peer is gone before the replies
 * leave), and descriptors that cannot carry frames are refused and left to the caller. */
#include "check_main.h"
#include "co_linux/loop.h"
#include "drive/drive.h"
#include "drive/models/models.h"
#include "drive/panel.h"

#include <check.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <stdlib.h>
#include <string.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#define NODE_ID 4
#define SDO_RX (CO_CAN_ID_SDO_RX + NODE_ID)
#define SDO_TX (CO_CAN_ID_SDO_TX + NODE_ID)
#define BOOTUP (CO_CAN_ID_ERROR_CONTROL + NODE_ID)
/* Longest a test may take: a loop that spins on a hung-up peer never returns. */
#define TEST_ALARM_S 10

typedef struct {
    drive_t drive;
    uint8_t *od_data;
    co_linux_device_t device;
} test_drive_t;

static co_linux_loop_t loop;
static test_drive_t slot;
static int bus[2];           /* bus[0] for the loop, bus[1] the test's end */
static int first_frame = -1; /* an eventfd written when the drive got its first frame, or -1 */

static void send_frame(void *user, const co_frame_t *frame)
{
    test_drive_t *d = user;
    co_linux_device_send(&d->device, frame);
}

static void start(void *ctx, co_time_t now)
{
    drive_start(&((test_drive_t *)ctx)->drive, now);
}

static void restart(void *ctx, co_time_t now)
{
    (void)ctx;
    (void)now;
    ck_abort_msg("a given socket never goes down and comes back");
}

static void receive(void *ctx, const co_frame_t *frame, co_time_t now)
{
    drive_receive(&((test_drive_t *)ctx)->drive, frame, now);
    if (first_frame >= 0 && loop.stats.rx == 1)
        ck_assert_int_eq(eventfd_write(first_frame, 1), 0);
}

static co_time_t process(void *ctx, co_time_t now)
{
    return drive_process(&((test_drive_t *)ctx)->drive, now);
}

static void bus_warning(void *ctx, bool active)
{
    drive_bus_warning(&((test_drive_t *)ctx)->drive, active);
}

static const co_node_t *node_of(void *ctx)
{
    return &((test_drive_t *)ctx)->drive.node;
}

static const co_linux_device_ops_t ops = {.start = start,
                                          .restart = restart,
                                          .receive = receive,
                                          .process = process,
                                          .bus_warning = bus_warning,
                                          .node = node_of};

static void setup(void)
{
    alarm(TEST_ALARM_S);
    ck_assert_int_eq(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, bus), 0);
    co_linux_loop_config_t config = {.iface = "pair"};
    ck_assert_int_eq(co_linux_loop_open_fd(&loop, &config, bus[0]), CO_LINUX_OPEN_OK);
    const drive_model_t *model = drive_model_find("atv312");
    ck_assert_ptr_nonnull(model);
    slot.od_data = calloc(1, model->profile->od->data_size);
    ck_assert_ptr_nonnull(slot.od_data);
    drive_config_t dc = {.profile = model->profile,
                         .od_data = slot.od_data,
                         .node_id = NODE_ID,
                         .send = send_frame,
                         .send_user = &slot};
    ck_assert_int_eq(drive_init(&slot.drive, &dc), 0);
    co_linux_loop_add(&loop, &slot.device, &ops, &slot);
}

static void teardown(void)
{
    co_linux_loop_close(&loop);
    if (bus[1] >= 0)
        close(bus[1]);
    free(slot.od_data);
    alarm(0);
}

static void write_datagram(const void *data, size_t len)
{
    ck_assert_int_eq(write(bus[1], data, len), (ssize_t)len);
}

static void write_upload_request(uint16_t index)
{
    struct can_frame request = {.can_id = SDO_RX, .can_dlc = 8};
    request.data[0] = 0x40; /* ccs 2: initiate upload */
    request.data[1] = (uint8_t)index;
    request.data[2] = (uint8_t)(index >> 8);
    write_datagram(&request, sizeof request);
}

static void expect_frame(canid_t id, uint8_t dlc, const uint8_t *data)
{
    struct can_frame frame;
    ck_assert_int_eq(read(bus[1], &frame, sizeof frame), (ssize_t)sizeof frame);
    ck_assert_uint_eq(frame.can_id, id);
    ck_assert_uint_eq(frame.can_dlc, dlc);
    ck_assert_mem_eq(frame.data, data, dlc);
}

static void expect_end_of_bus(void)
{
    char byte;
    ck_assert_int_eq(read(bus[1], &byte, sizeof byte), 0);
}

static const uint8_t bootup[] = {0x00};
/* 1000h of the ATV312: device type 0x00010192, expedited, 4 bytes (scs 2, e = 1, s = 1). */
static const uint8_t device_type[] = {0x43, 0x00, 0x10, 0x00, 0x92, 0x01, 0x01, 0x00};

START_TEST(drive_answers_over_socketpair)
{
    write_upload_request(0x1000);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_eq(loop.stats.rx, 1);
    ck_assert_uint_eq(loop.stats.tx, 2);
    /* Not a CAN_RAW socket: no CAN_RAW_FILTER was tried, the routes alone sort the frames. */
    ck_assert_uint_eq(loop.stats.filters, 0);
    co_linux_loop_close(&loop);
    expect_frame(BOOTUP, 1, bootup);
    expect_frame(SDO_TX, 8, device_type);
    expect_end_of_bus();
}
END_TEST

START_TEST(datagrams_not_a_frame_are_ignored)
{
    const uint8_t short_datagram[3] = {0x04, 0x06, 0x00};
    uint8_t fd_frame[CANFD_MTU] = {0x04, 0x06, 0x00, 0x00, 8, 0, 0, 0, 0x40, 0x00, 0x10};
    write_datagram(short_datagram, sizeof short_datagram);
    write_datagram(fd_frame, sizeof fd_frame);
    write_upload_request(0x1000);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_eq(loop.stats.rx, 1);
    co_linux_loop_close(&loop);
    expect_frame(BOOTUP, 1, bootup);
    expect_frame(SDO_TX, 8, device_type);
    expect_end_of_bus();
}
END_TEST

/* More frames than one wake-up reads (4 batches of 32) are waiting when the peer hangs up: each
 * is answered before the loop ends. */
START_TEST(hang_up_after_a_burst_loses_no_frame)
{
    enum { BURST = 150 };
    for (int i = 0; i < BURST; i++)
        write_upload_request(0x1000);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_eq(loop.stats.rx, BURST);
    co_linux_loop_close(&loop);
    expect_frame(BOOTUP, 1, bootup);
    for (int i = 0; i < BURST; i++)
        expect_frame(SDO_TX, 8, device_type);
    expect_end_of_bus();
}
END_TEST

/* An error frame as a controller driver reports a change of state (linux/can/error.h). */
static void write_error_frame(canid_t error_class, uint8_t controller)
{
    struct can_frame frame = {.can_id = CAN_ERR_FLAG | error_class, .can_dlc = CAN_ERR_DLC};
    frame.data[1] = controller;
    write_datagram(&frame, sizeof frame);
}

static bool condition(co_linux_condition_kind_t which)
{
    return loop.bus.conditions.items[which].wanted;
}

/* The kernel's can_change_state names the state entered: from error passive back to the warning
 * level the frame has the warning bits alone, which end error passive and keep the warning. Bus
 * off counts once per entry; the restart ends every state. */
START_TEST(error_frames_track_the_controller_state)
{
    write_error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_PASSIVE);
    write_error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_TX_WARNING);
    write_error_frame(CAN_ERR_BUSOFF, 0);
    write_error_frame(CAN_ERR_BUSOFF, 0);
    write_error_frame(CAN_ERR_RESTARTED, 0);
    write_error_frame(CAN_ERR_BUSOFF, 0);
    write_error_frame(CAN_ERR_RESTARTED, 0);
    write_error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_WARNING);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_eq(loop.stats.error_frames, 8);
    ck_assert_uint_eq(loop.bus.conditions.bus_offs, 2);
    ck_assert(condition(CO_LINUX_COND_WARNING));
    ck_assert(!condition(CO_LINUX_COND_PASSIVE));
    ck_assert(!condition(CO_LINUX_COND_BUS_OFF));
    ck_assert_int_eq(drive_panel_err_led(&slot.drive), DRIVE_LED_SINGLE_FLASH);
}
END_TEST

/* Error passive is above the warning limit; error active ends both. */
START_TEST(error_active_ends_warning_and_passive)
{
    write_error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_RX_PASSIVE);
    write_error_frame(CAN_ERR_CRTL, CAN_ERR_CRTL_ACTIVE);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert(!condition(CO_LINUX_COND_WARNING));
    ck_assert(!condition(CO_LINUX_COND_PASSIVE));
    ck_assert_uint_eq(loop.bus.conditions.bus_offs, 0);
    ck_assert_int_eq(drive_panel_err_led(&slot.drive), DRIVE_LED_OFF);
}
END_TEST

static void write_burst(void *ctx, int fd);

/* Requests of the burst after the lone frame: more than the reads one by one take. */
#define BURST_REQUESTS (CO_LINUX_RX_PROBE_EVERY + 10)

/* A wake-up that found one frame makes the loop read one frame per wake-up; a burst that follows
 * is read so for CO_LINUX_RX_PROBE_EVERY - 1 wake-ups, then in a batch, which also finds the end.
 * The reads one by one ignore datagrams that are not a frame, as the batches do. */
START_TEST(burst_after_a_lone_frame_is_read_in_a_batch_again)
{
    first_frame = eventfd(0, EFD_NONBLOCK);
    ck_assert_int_ge(first_frame, 0);
    ck_assert_int_eq(co_linux_loop_watch(&loop, first_frame, write_burst, NULL), 0);
    write_upload_request(0x1000);
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    /* The lone frame, the eventfd, CO_LINUX_RX_PROBE_EVERY - 1 reads of one datagram each, one
     * batch to the end. */
    ck_assert_uint_eq(loop.stats.wakeups, 2 + CO_LINUX_RX_PROBE_EVERY);
    ck_assert_uint_eq(loop.stats.rx, 1 + BURST_REQUESTS);
    co_linux_loop_close(&loop);
    close(first_frame);
    first_frame = -1;
    expect_frame(BOOTUP, 1, bootup);
    for (int i = 0; i < 1 + BURST_REQUESTS; i++)
        expect_frame(SDO_TX, 8, device_type);
    expect_end_of_bus();
}
END_TEST

/* After the first frame: a datagram too short, one too long (a CAN FD frame), BURST_REQUESTS
 * requests, the end. */
static void write_burst(void *ctx, int fd)
{
    (void)ctx;
    eventfd_t count;
    ck_assert_int_eq(eventfd_read(fd, &count), 0);
    co_linux_loop_unwatch(&loop, fd);
    const uint8_t short_datagram[3] = {0x04, 0x06, 0x00};
    uint8_t fd_frame[CANFD_MTU] = {0x04, 0x06, 0x00, 0x00, 8, 0, 0, 0, 0x40, 0x00, 0x10};
    write_datagram(short_datagram, sizeof short_datagram);
    write_datagram(fd_frame, sizeof fd_frame);
    for (int i = 0; i < BURST_REQUESTS; i++)
        write_upload_request(0x1000);
    ck_assert_int_eq(shutdown(bus[1], SHUT_WR), 0);
}

START_TEST(peer_gone_ends_the_loop)
{
    write_upload_request(0x1000);
    close(bus[1]);
    bus[1] = -1;
    /* The boot-up and the reply find no reader (EPIPE): counted as dropped. */
    ck_assert_int_eq(co_linux_loop_run(&loop), 0);
    ck_assert_uint_eq(loop.stats.rx, 1);
    ck_assert_uint_eq(loop.stats.tx, 0);
    ck_assert_uint_eq(loop.stats.tx_dropped, 2);
}
END_TEST

static void expect_refused(int fd, int expected_errno)
{
    co_linux_loop_t refused;
    co_linux_loop_config_t config = {.iface = "refused"};
    ck_assert_int_eq(co_linux_loop_open_fd(&refused, &config, fd), CO_LINUX_OPEN_OS_ERROR);
    ck_assert_int_eq(refused.open_errno, expected_errno);
    ck_assert_int_ne(fcntl(fd, F_GETFD), -1); /* still the caller's */
    close(fd);
}

START_TEST(descriptors_without_frame_boundaries_are_refused)
{
    int pipe_fds[2], stream[2];
    ck_assert_int_eq(pipe(pipe_fds), 0);
    ck_assert_int_eq(socketpair(AF_UNIX, SOCK_STREAM, 0, stream), 0);
    expect_refused(pipe_fds[0], ENOTSOCK);
    close(pipe_fds[1]);
    expect_refused(stream[0], EPROTOTYPE);
    close(stream[1]);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("loop_fd");
    TCase *tc = tcase_create("socketpair");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, drive_answers_over_socketpair);
    tcase_add_test(tc, datagrams_not_a_frame_are_ignored);
    tcase_add_test(tc, hang_up_after_a_burst_loses_no_frame);
    tcase_add_test(tc, burst_after_a_lone_frame_is_read_in_a_batch_again);
    tcase_add_test(tc, peer_gone_ends_the_loop);
    tcase_add_test(tc, error_frames_track_the_controller_state);
    tcase_add_test(tc, error_active_ends_warning_and_passive);
    tcase_add_test(tc, descriptors_without_frame_boundaries_are_refused);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
