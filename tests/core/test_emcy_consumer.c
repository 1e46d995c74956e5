/* SPDX-License-Identifier: Apache-2.0 */
/* The EMCY consumer: exact decoding of 080h + node-id frames, malformed frames reported and never
 * read past, watched nodes only, and the meaning of error codes, most specific first. */
#include "check_main.h"
#include "co/co_emcy.h"
#include "co/co_emcy_consumer.h"

#include <string.h>

static co_frame_t frame(uint32_t id, uint8_t len, const uint8_t *data)
{
    co_frame_t f = {.id = id, .len = len};
    memcpy(f.data, data, len);
    return f;
}

static const uint8_t heartbeat_emcy[8] = {0x30, 0x81, 0x11, 0xA1, 0xB2, 0xC3, 0xD4, 0xE5};

START_TEST(decodes_every_field)
{
    co_frame_t f = frame(0x084, 8, heartbeat_emcy);
    co_emcy_message_t msg;
    ck_assert_int_eq(co_emcy_decode(&f, &msg), CO_EMCY_DECODE_OK);
    ck_assert_uint_eq(msg.node_id, 4);
    ck_assert_uint_eq(msg.code, 0x8130);
    ck_assert_uint_eq(msg.reg, 0x11);
    const uint8_t msef[5] = {0xA1, 0xB2, 0xC3, 0xD4, 0xE5};
    ck_assert_mem_eq(msg.msef, msef, 5);

    f = frame(0x0FF, 8, heartbeat_emcy);
    ck_assert_int_eq(co_emcy_decode(&f, &msg), CO_EMCY_DECODE_OK);
    ck_assert_uint_eq(msg.node_id, 127);
}
END_TEST

/* The bytes beyond len hold a valid-looking EMCY: the decoder must not use them. */
START_TEST(short_frame_is_malformed)
{
    for (uint8_t len = 0; len < 8; len++) {
        co_frame_t f = frame(0x084, 8, heartbeat_emcy);
        f.len = len;
        co_emcy_message_t msg = {.code = 0x1234, .reg = 0x56};
        ck_assert_int_eq(co_emcy_decode(&f, &msg), CO_EMCY_DECODE_SHORT);
        ck_assert_uint_eq(msg.node_id, 4);
        ck_assert_uint_eq(msg.code, 0x1234);
        ck_assert_uint_eq(msg.reg, 0x56);
    }
    ck_assert_str_eq(co_emcy_decode_text(CO_EMCY_DECODE_SHORT), "EMCY frame shorter than 8 bytes");
}
END_TEST

START_TEST(other_frames_are_not_emcy)
{
    co_emcy_message_t msg;
    co_frame_t sync = frame(0x080, 0, heartbeat_emcy);
    ck_assert_int_eq(co_emcy_decode(&sync, &msg), CO_EMCY_DECODE_NOT_EMCY);
    co_frame_t time_stamp = frame(0x100, 6, heartbeat_emcy);
    ck_assert_int_eq(co_emcy_decode(&time_stamp, &msg), CO_EMCY_DECODE_NOT_EMCY);
    co_frame_t remote = frame(0x084, 8, heartbeat_emcy);
    remote.flags = CO_FRAME_RTR;
    ck_assert_int_eq(co_emcy_decode(&remote, &msg), CO_EMCY_DECODE_NOT_EMCY);
    co_frame_t extended = frame(0x084, 8, heartbeat_emcy);
    extended.flags = CO_FRAME_EFF;
    ck_assert_int_eq(co_emcy_decode(&extended, &msg), CO_EMCY_DECODE_NOT_EMCY);
    ck_assert_str_eq(co_emcy_decode_text(CO_EMCY_DECODE_NOT_EMCY), "not an EMCY frame");
}
END_TEST

typedef struct seen {
    int calls;
    co_emcy_decode_t result;
    co_emcy_message_t msg;
    co_time_t now;
} seen_t;

static void on_emcy(void *user, co_emcy_decode_t result, const co_emcy_message_t *msg,
                    co_time_t now)
{
    seen_t *seen = user;
    seen->calls++;
    seen->result = result;
    seen->msg = *msg;
    seen->now = now;
}

START_TEST(consumer_reports_watched_nodes_only)
{
    seen_t a = {0}, b = {0};
    co_emcy_consumer_t ca, cb;
    co_emcy_consumer_init(&ca, on_emcy, &a);
    co_emcy_consumer_init(&cb, on_emcy, &b);
    ck_assert(co_emcy_consumer_watch(&ca, 4, true));
    ck_assert(co_emcy_consumer_watch(&cb, 5, true));
    ck_assert(!co_emcy_consumer_watch(&ca, 0, true));
    ck_assert(!co_emcy_consumer_watch(&ca, 128, true));

    co_frame_t f4 = frame(0x084, 8, heartbeat_emcy);
    ck_assert(co_emcy_consumer_receive(&ca, &f4, 1000));
    ck_assert(!co_emcy_consumer_receive(&cb, &f4, 1000));
    ck_assert_int_eq(a.calls, 1);
    ck_assert_int_eq(b.calls, 0);
    ck_assert_int_eq(a.result, CO_EMCY_DECODE_OK);
    ck_assert_uint_eq(a.msg.code, 0x8130);
    ck_assert_uint_eq(a.now, 1000);

    co_frame_t short5 = frame(0x085, 3, heartbeat_emcy);
    ck_assert(co_emcy_consumer_receive(&cb, &short5, 2000));
    ck_assert_int_eq(b.calls, 1);
    ck_assert_int_eq(b.result, CO_EMCY_DECODE_SHORT);
    ck_assert_uint_eq(b.msg.node_id, 5);

    ck_assert(co_emcy_consumer_watch(&ca, 4, false));
    ck_assert(!co_emcy_consumer_receive(&ca, &f4, 3000));
    co_frame_t sync = frame(0x080, 0, heartbeat_emcy);
    ck_assert(co_emcy_consumer_watch(&ca, 127, true));
    ck_assert(!co_emcy_consumer_receive(&ca, &sync, 3000));
    ck_assert_int_eq(a.calls, 1);
}
END_TEST

START_TEST(cia301_texts)
{
    ck_assert_str_eq(co_emcy_code_text(0x0000), "error reset or no error");
    ck_assert_str_eq(co_emcy_code_text(0x1000), "generic error");
    ck_assert_str_eq(co_emcy_code_text(0x5000), "device hardware");
    ck_assert_str_eq(co_emcy_code_text(0x6100), "internal software");
    ck_assert_str_eq(co_emcy_code_text(0x7000), "additional modules");
    ck_assert_str_eq(co_emcy_code_text(0x9000), "external error");
    ck_assert_str_eq(co_emcy_code_text(0xF0AB), "additional functions");
    ck_assert_str_eq(co_emcy_code_text(0xFF42), "device specific");
    ck_assert_str_eq(co_emcy_code_text(0x8150), "CAN-ID collision");
    ck_assert_str_eq(co_emcy_code_text(0xE000), "unknown error code");
}
END_TEST

/* Every code the project's core, runtime and drives send means something specific. */
START_TEST(codes_the_project_sends)
{
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_CAN_OVERRUN), "CAN overrun (objects lost)");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_CAN_PASSIVE), "CAN in error passive mode");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_HEARTBEAT), "life guard error or heartbeat error");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_BUS_OFF), "recovered from bus off");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_PDO_LENGTH),
                     "PDO not processed due to length error");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_PDO_LENGTH_EXCEEDED), "PDO length exceeded");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_SYNC_LENGTH), "unexpected SYNC data length");
    ck_assert_str_eq(co_emcy_code_text(CO_EMCY_RPDO_TIMEOUT), "RPDO timeout");
}
END_TEST

/* An exact code beats its subclass, a subclass its class, whichever table they are in. */
START_TEST(most_specific_match_first)
{
    ck_assert_str_eq(co_emcy_code_text(0x8131), "communication");
    ck_assert_str_eq(co_emcy_code_text(0x8F00), "monitoring");
    ck_assert_str_eq(co_emcy_code_text(0x2310), "continuous over current");
    ck_assert_str_eq(co_emcy_code_text(0x2311), "current, device output side");
    ck_assert_str_eq(co_emcy_code_text(0x2F00), "current");
    ck_assert_str_eq(co_emcy_code_text(0x3210), "DC link over-voltage");
    ck_assert_str_eq(co_emcy_code_text(0x4310), "excess temperature of the drive");
    ck_assert_str_eq(co_emcy_code_text(0x4301), "drive temperature");
    ck_assert_str_eq(co_emcy_code_text(0x4001), "temperature");
    ck_assert_str_eq(co_emcy_code_text(0x7121), "motor blocked");
    ck_assert_str_eq(co_emcy_code_text(0x8611), "following error");
    ck_assert_str_eq(co_emcy_code_text(0xF001), "deceleration");
}
END_TEST

/* A vendor's table (here the test's own) is consulted first: its match wins over a standard one
 * that is no more specific, a code it does not list or lists less precisely keeps its standard
 * meaning. The models' own tables are tested with the models (tests/drive/models/atv58). */
START_TEST(vendor_table_first)
{
    static const co_emcy_meaning_t meanings[] = {
        {0x0000, CO_EMCY_MASK_SUBCLASS, "vendor: no fault"},
        {0x2310, CO_EMCY_MASK_EXACT, "vendor: overcurrent"},
        {0x8130, CO_EMCY_MASK_EXACT, "vendor: life guard time out"},
        {0x3200, CO_EMCY_MASK_SUBCLASS, "vendor: DC link"},
    };
    static const co_emcy_code_table_t vendor = {meanings, sizeof meanings / sizeof meanings[0]};
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x2310), "vendor: overcurrent");
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x8130), "vendor: life guard time out");
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x0000), "vendor: no fault");
    /* Codes the vendor does not list, or lists less precisely, keep their standard meaning. */
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x8110), "CAN overrun (objects lost)");
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x3220), "DC link under-voltage");
    /* A tie in specificity: the vendor's wins. */
    ck_assert_str_eq(co_emcy_code_text_in(&vendor, 0x3201), "vendor: DC link");
    ck_assert_str_eq(co_emcy_code_text_in(NULL, 0x2310), "continuous over current");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("emcy_consumer");
    TCase *tc = tcase_create("emcy_consumer");
    tcase_add_test(tc, decodes_every_field);
    tcase_add_test(tc, short_frame_is_malformed);
    tcase_add_test(tc, other_frames_are_not_emcy);
    tcase_add_test(tc, consumer_reports_watched_nodes_only);
    tcase_add_test(tc, cia301_texts);
    tcase_add_test(tc, codes_the_project_sends);
    tcase_add_test(tc, most_specific_match_first);
    tcase_add_test(tc, vendor_table_first);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
