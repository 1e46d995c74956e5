/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV58 with its VW3-A58308 card on the bus: every example frame of the card's manual
 * (T58-01..15, docs/manuals.md), frame for frame, on the real generated
 * dictionary; its dictionary (what it has, and "object does not exist" for the rest); its SDO
 * error layout; node guarding, the life guarding fault and its EMCY; NMT Disconnect. */
#include "atv58/atv58.h"
#include "check_main.h"
#include "drive_bench.h"

/* The last frame the drive sent with this COB-ID, all frames consumed. */
static const co_frame_t *last_frame(bench_t *b, uint32_t id)
{
    const co_frame_t *last = NULL;
    for (; b->next < b->count; b->next++)
        if (b->frame[b->next].id == id)
            last = &b->frame[b->next];
    ck_assert_ptr_nonnull(last);
    return last;
}

/* Every frame the drive sent since the last check has DLC 8. */
static void assert_all_dlc8(const bench_t *b, size_t from)
{
    for (size_t i = from; i < b->count; i++)
        ck_assert_msg(b->frame[i].len == 8, "frame %zu (COB-ID %03X) has DLC %u", i,
                      (unsigned)b->frame[i].id, (unsigned)b->frame[i].len);
}

/* The card's dictionary, values as built (docs/atv58.md): 1001h and 100Ah are 4 bytes, 1008h
 * fits one expedited upload, guard time 500 ms and life time factor 2 (the manual's table). */
START_TEST(dictionary_as_built)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    static const bench_exchange_t reads[] = {
        {"1000h", "604#4000100000000000", 0, {"584#4300100092010100"}},
        {"1001h U32", "604#4001100000000000", 0, {"584#4301100000000000"}},
        {"1008h", "604#4008100000000000", 0, {"584#4308100041543538"}}, /* "AT58" */
        {"1009h", "604#4009100000000000", 0, {"584#4309100000000000"}},
        {"100Ah U32", "604#400A100000000000", 0, {"584#430A100001010000"}},
        {"100Ch", "604#400C100000000000", 0, {"584#4B0C1000F4010000"}},
        {"100Dh", "604#400D100000000000", 0, {"584#4F0D100002000000"}},
        {"1014h", "604#4014100000000000", 0, {"584#4314100084000000"}},
        {"1200h:01", "604#4000120100000000", 0, {"584#4300120104060000"}},
        {"1200h:02", "604#4000120200000000", 0, {"584#4300120284050000"}},
        {"1400h:00", "604#4000140000000000", 0, {"584#4F00140002000000"}},
        {"1400h:01", "604#4000140100000000", 0, {"584#4300140104020000"}},
        {"1400h:02", "604#4000140200000000", 0, {"584#4F001402FF000000"}},
        {"1600h:01", "604#4000160100000000", 0, {"584#4300160110004060"}},
        {"1600h:02", "604#4000160200000000", 0, {"584#4300160210004260"}},
        {"1800h:01", "604#4000180100000000", 0, {"584#4300180184010000"}},
        {"1800h:02", "604#4000180200000000", 0, {"584#4F001802FF000000"}},
        {"1A00h:01", "604#40001A0100000000", 0, {"584#43001A0110004160"}},
        {"1A00h:02", "604#40001A0200000000", 0, {"584#43001A0210004460"}},
        {"6041h", "604#4041600000000000", 0, {"584#4B41600040060000"}},
        {"ACC", "604#40E55F0300000000", 0, {"584#4BE55F031E000000"}},
    };
    BENCH_PLAY(&b, reads);
    /* What the card lacks does not exist: identity, SYNC, heartbeat, error history, store and
     * restore, PDO timers, the other CiA 402 objects, the ATV312's manufacturer parameters. */
    static const uint16_t absent[] = {0x1002, 0x1003, 0x1005, 0x100B, 0x100E, 0x1010, 0x1011,
                                      0x1015, 0x1016, 0x1017, 0x1018, 0x1019, 0x1405, 0x1805,
                                      0x603F, 0x6046, 0x6048, 0x203C, 0x2042};
    for (size_t i = 0; i < sizeof absent / sizeof absent[0]; i++) {
        uint32_t value;
        ck_assert_uint_eq(bench_sdo_read(&b, absent[i], 0, &value), CO_SDO_ABORT_NO_OBJECT);
    }
    uint32_t value;
    ck_assert_uint_eq(bench_sdo_read(&b, 0x1800, 3, &value), 0x06090000);
    ck_assert_uint_eq(bench_sdo_read(&b, 0x1800, 5, &value), 0x06090000);
}
END_TEST

/* T58-01..11 in one session: started by NMT (8 bytes), the drive runs forward at 1500 rpm by the
 * control PDO (T58-02) and reports Operation enabled at 1500 rpm (T58-03); ACC written and read
 * back (T58-06/07 before T58-04/05: ACC is 3 s until written), the guard time written with 0x23
 * (T58-08/09) and the life time factor (T58-10/11). Every frame has DLC 8. */
START_TEST(manual_vectors_frame_for_frame)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    size_t first = b.count;
    static const bench_exchange_t power_up[] = {
        {"start", "000#0104000000000000", 0, {"184#4006000000000000"}},
        {"shutdown", "204#0600DC0500000000", 0, {"184#2106000000000000"}},
        {"switch on", "204#0700DC0500000000", 0, {"184#2306000000000000"}},
    };
    BENCH_PLAY(&b, power_up);
    bench_rx(&b, "204#0F00DC0500000000"); /* T58-02 */
    bench_advance(&b, 4000000);
    assert_all_dlc8(&b, first);
    const co_frame_t *at_speed = last_frame(&b, 0x184); /* T58-03 */
    ck_assert_uint_eq(at_speed->len, 8);
    ck_assert_mem_eq(at_speed->data, "\x27\x06\xDC\x05\x00\x00\x00\x00", 8);
    static const bench_exchange_t sdo[] = {
        {"T58-06/07", "604#2BE55F03E8030000", 0, {"584#60E55F0300000000"}},
        {"T58-04/05", "604#40E55F0300000000", 0, {"584#4BE55F03E8030000"}},
        {"T58-08/09", "604#230C1000F4010000", 0, {"584#600C100000000000"}},
        {"T58-10/11", "604#2F0D100004000000", 0, {"584#600D100000000000"}},
        {"T58-01", "000#8004000000000000", 0, {NULL}},
        {"T58-12/13", "704#R8", 0, {"704#7F00000000000000"}},
        {"T58-12/13", "704#R8", 0, {"704#FF00000000000000"}},
    };
    BENCH_PLAY(&b, sdo);
    ck_assert_uint_eq(bench_read(&b, 0x100C, 0), 500);
    ck_assert_uint_eq(bench_read(&b, 0x100D, 0), 4);
    ck_assert_uint_eq(bench_read(&b, 0x5FE5, 3), 1000);
}
END_TEST

/* T58-14: the error response, 0x80, index, sub-index, 0, 0, error code, error class: the
 * manual's four, and the nearest of them for the other refusals. */
START_TEST(sdo_error_layout)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    static const bench_exchange_t errors[] = {
        {"2/6 index", "604#4000300000000000", 0, {"584#8000300000000206"}},
        {"2/6 1018h", "604#4018100100000000", 0, {"584#8018100100000206"}},
        {"9/6 sub-index", "604#40E55F0100000000", 0, {"584#80E55F0100000906"}},
        {"1/6 read only", "604#2B41600000000000", 0, {"584#8041600000000106"}},
        {"1/6 fixed COB-ID", "604#2300180184010080", 0, {"584#8000180100000106"}},
        {"1/6 out of range", "604#2BE55F0300000000", 0, {"584#80E55F0300000106"}},
        {"1/6 too long", "604#230C1000F4010100", 0, {"584#800C100000000106"}},
        {"3/5 segmented", "604#21E55F0302000000", 0, {"584#80E55F0300000305"}},
        {"3/5 block up", "604#A4E55F0310000000", 0, {"584#80E55F0300000305"}},
        {"3/5 unknown", "604#E0E55F0300000000", 0, {"584#80E55F0300000305"}},
        {"client abort", "604#80E55F0300000000", 0, {NULL}},
    };
    BENCH_PLAY(&b, errors);
}
END_TEST

/* T58-12/13/15: guarded by T58-08/10's 500 ms x 4, the drive that hears no poll for 2 s faults
 * (CnF), sends EMCY 0x8130 (its table's "Life Guard time out") with error register 1, and 1001h
 * reads 1; the fault reset sends the error reset EMCY with register 0. */
START_TEST(life_guarding_fault_and_emcy)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    static const bench_exchange_t session[] = {
        {"T58-08", "604#230C1000F4010000", 0, {"584#600C100000000000"}},
        {"T58-10", "604#2F0D100004000000", 0, {"584#600D100000000000"}},
        {"T58-12", "704#R", 1999000, {"704#7F00000000000000"}},
        {"T58-12", "704#R8", 1999000, {"704#FF00000000000000"}},
        {"T58-15", NULL, 1000, {"084#3081010000000000"}},
        {"1001h", "604#4001100000000000", 0, {"584#4301100001000000"}},
        {"ETAD", "604#4041600000000000", 0, {"584#4B41600008060000"}},
        {"reset", "604#2B40600080000000", 0, {"084#0000000000000000", "584#6040600000000000"}},
        {"1001h", "604#4001100000000000", 0, {"584#4301100000000000"}},
    };
    BENCH_PLAY(&b, session);
}
END_TEST

/* NMT command 3, Disconnect remote node: Stopped (no SDO, no PDO), guarding answers 04 / 84;
 * the broadcast form and a start bring it back. */
START_TEST(nmt_disconnect)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    static const bench_exchange_t session[] = {
        {"start", "000#0104000000000000", 0, {"184#4006000000000000"}},
        {"disconnect", "000#0304000000000000", 0, {NULL}},
        {"no SDO", "604#4000100000000000", 0, {NULL}},
        {"no PDO", "204#0600000000000000", 0, {NULL}},
        {"guarding", "704#R8", 0, {"704#0400000000000000"}},
        {"start", "000#0100000000000000", 0, {"184#4006000000000000"}},
        {"guarding", "704#R8", 0, {"704#8500000000000000"}},
        {"broadcast", "000#0300", 0, {NULL}},
        {"guarding", "704#R8", 0, {"704#0400000000000000"}},
    };
    BENCH_PLAY(&b, session);
}
END_TEST

/* Every code of the card's EMCY table can fault the drive: its EMCY frame, 8 bytes with error
 * register 1 ("=1 fault"), 1001h = 1, the status word in Fault, and the fault reset of a command
 * class fault once its cause is gone. Codes and frames from the manual's table (B.5.3). */
static const struct {
    const char *code;
    const char *emcy;
} atv58_table[] = {
    {"CnF", "084#3081010000000000"}, {"CrF", "084#0010010000000000"},
    {"OLF", "084#0010010000000000"}, {"SOF", "084#0010010000000000"},
    {"OCF", "084#1023010000000000"}, {"SCF", "084#2023010000000000"},
    {"OSF", "084#1031010000000000"}, {"USF", "084#2031010000000000"},
    {"PHF", "084#3031010000000000"}, {"ObF", "084#1033010000000000"},
    {"OPF", "084#1033010000000000"}, {"OHF", "084#1042010000000000"},
    {"OtF", "084#1043010000000000"}, {"EEF", "084#2055010000000000"},
    {"InF", "084#0061010000000000"}, {"CFF", "084#0063010000000000"},
    {"CFI", "084#0063010000000000"}, {"AnF", "084#0073010000000000"},
    {"LFF", "084#0073010000000000"}, {"tSF", "084#0073010000000000"},
    {"SPF", "084#1073010000000000"}, {"SLF", "084#1075010000000000"},
    {"ILF", "084#2075010000000000"}, {"EPF", "084#0090010000000000"},
};

START_TEST(every_fault_of_its_table)
{
    ck_assert_uint_eq(atv58_faults.count, sizeof atv58_table / sizeof atv58_table[0]);
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    int index = drive_fault_find(&b.drive, atv58_table[_i].code);
    ck_assert_int_eq(index, _i);
    drive_fault_inject(&b.drive, (uint8_t)index, b.now);
    b.deadline = drive_process(&b.drive, b.now);
    bench_expect(&b, atv58_table[_i].emcy);
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 1);
    /* Freewheel, the project's choice: the card's manual gives no fault a stop. */
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0608);
    ck_assert_int_eq(bench_speed(&b), 0);
    drive_fault_remove_cause(&b.drive, (uint8_t)index, b.now);
    b.deadline = drive_process(&b.drive, b.now);
    if (atv58_faults.faults[index].reset == DRIVE_FAULT_RESET_COMMAND) {
        ck_assert_uint_eq(bench_command(&b, 0x0080), 0x0640);
        bench_expect(&b, "084#0000000000000000");
        ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 0);
    }
}
END_TEST

/* CAN bus conditions keep their CiA 301 codes (the card's table has none) with the card's error
 * register: 1 ("=1 fault"), not the family's 0x11; they do not fault the drive. */
START_TEST(bus_condition_emcy_has_error_register_1)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    drive_bus_event(&b.drive, 0x8110, true);
    b.deadline = drive_process(&b.drive, b.now);
    bench_expect(&b, "084#1081010000000000");
    bench_expect_none(&b);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x06C0); /* a warning (D-STATUS-ALARM) */
    drive_bus_event(&b.drive, 0x8110, false);
    b.deadline = drive_process(&b.drive, b.now);
    bench_expect(&b, "084#0000000000000000");
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
}
END_TEST

/* The card's 1001h "=0 no fault, =1 fault" in the EMCY the core raises itself too: an RPDO of 2
 * bytes where CMDD and LFRD need 4 (8210h) carries 01h, not CiA 301's 11h (D-ERROR-REGISTER). */
START_TEST(core_emcy_error_register_is_1)
{
    bench_t b;
    bench_start_model(&b, &atv58_profile, NULL);
    bench_rx(&b, "000#0104");
    b.next = b.count; /* its TPDO on entering Operational */
    bench_rx(&b, "204#0600");
    bench_expect(&b, "084#1082010100020400");
    ck_assert_uint_eq(bench_read(&b, 0x1001, 0), 1);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv58_network");
    TCase *tc = tcase_create("network");
    tcase_add_test(tc, dictionary_as_built);
    tcase_add_test(tc, manual_vectors_frame_for_frame);
    tcase_add_test(tc, sdo_error_layout);
    tcase_add_test(tc, life_guarding_fault_and_emcy);
    tcase_add_test(tc, nmt_disconnect);
    tcase_add_test(tc, bus_condition_emcy_has_error_register_1);
    tcase_add_test(tc, core_emcy_error_register_is_1);
    tcase_add_loop_test(tc, every_fault_of_its_table, 0,
                        (int)(sizeof atv58_table / sizeof atv58_table[0]));
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
