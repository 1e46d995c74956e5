/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV312's [COMMAND] menu beyond the channels (docs/atv312.md, "Access level, switching, ramp
 * switching"): LAC at 2036:01, the switching sources of rFC (2036:0C) and CCS (2036:16), rPS
 * (203C:0B) with AC2 (203C:0D) and dE2 (203C:0E), frame for frame at their addresses: the DeviceNet
 * manual's configurations (CCS = C212, rFC = C213; rFC = LI3; rPS = Cd15 with LAC = L3). */
#include "atv312_bench.h"
#include "check_main.h"

#define ABORT_VALUE_HIGH 0x06090031u
#define ABORT_VALUE_LOW 0x06090032u

static void run_at_1500(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

/* LAC 8400, rPS 9010, AC2 9012, dE2 9013: defaults and limits. */
START_TEST(new_parameters_at_their_addresses)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_read(&b, 0x2036, 1), ATV312_LAC_L3);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 11), 0);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 13), 50);
    ck_assert_uint_eq(bench_read(&b, 0x203C, 14), 50);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 1, 0, 2), ABORT_VALUE_LOW);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 1, 4, 2), ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 11, 316, 2), ABORT_VALUE_HIGH);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 13, 0, 2), ABORT_VALUE_LOW);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 14, 10000, 2), ABORT_VALUE_HIGH);
    /* Between the fixed values and the sources: the value range. */
    bench_rx(&b, "604#2B36201603000000");
    bench_expect(&b, "584#8036201630000906");
    /* LI4: the VW3A31208 card has LI1-LI3. */
    bench_rx(&b, "604#2B36200C68000000");
    bench_expect(&b, "584#8036200C30000906");
}
END_TEST

/* The manual's ODVA configuration: CHCF = SEP, Cd1 = network, Cd2 = terminals, CCS = C212, Fr1 =
 * network, Fr2 = AI2, rFC = C213. Bit 13 (DC injection stop by default) switches the reference to
 * AI2 (0: LSP) on the DEC ramp, still Operation enabled; bit 12 (Stt stop by default) gives the
 * command to the terminals: a freewheel stop, ETA 0x0440 on TPDO1. */
START_TEST(c212_and_c213_switch_command_and_reference)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 2, ATV312_CHCF_SEPARATE, 2), 0);
    bench_rx(&b, "604#2B362016D4000000"); /* CCS = C212 */
    bench_expect(&b, "584#6036201600000000");
    bench_rx(&b, "604#2B36200CD5000000"); /* rFC = C213 */
    bench_expect(&b, "584#6036200C00000000");
    run_at_1500(&b);
    bench_operational(&b);
    bench_expect(&b, "184#2706");
    bench_advance(&b, 100000);
    bench_command(&b, 0x200F);
    bench_expect(&b, "184#2702"); /* ramping: bit 10 clear */
    bench_advance(&b, 750000);
    ck_assert_int_eq(bench_speed(&b), 1125);
    bench_advance(&b, 2250000);
    ck_assert_int_eq(bench_speed(&b), 0);
    bench_expect(&b, "184#2706");
    bench_command(&b, 0x300F);
    bench_advance(&b, 100000);
    bench_expect(&b, "184#4004");
    /* Bit 12 back to 0: the network commands again, from Switch on disabled. */
    bench_command(&b, 0x000F);
    bench_advance(&b, 100000);
    bench_expect(&b, "184#4006");
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

/* CHCF = SIM, Fr2 = AI2, rFC = LI3: "Input LI3 switches the target (1 <-> 2) and the command". */
START_TEST(li3_switches_reference_and_command)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 12, DRIVE_SOURCE_INPUT(3), 2), 0);
    run_at_1500(&b);
    ck_assert(drive_set_input(&b.drive, 3, true, b.now));
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0440);
    ck_assert(drive_set_input(&b.drive, 3, false, b.now));
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0640);
    ck_assert(!drive_set_input(&b.drive, 4, true, b.now));
}
END_TEST

/* rPS = Cd15 under LAC = L3 ("to use bit 15 to switch the ramp, simply configure LAC = L3 ... and
 * set ... (rPS) to Cd15"): AC2 = dE2 = 1.0 s while CMD bit 15 is 1. */
START_TEST(rps_cd15_switches_to_ac2_de2)
{
    bench_t b;
    bench_start(&b);
    bench_rx(&b, "604#2B3C200B3B010000"); /* rPS = Cd15 */
    bench_expect(&b, "584#603C200B00000000");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 13, 10, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x203C, 14, 10, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x800F);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
    /* Bit 15 clear: DEC (3.0 s). */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 0, 2), 0);
    bench_command(&b, 0x000F);
    bench_advance(&b, 1000000);
    ck_assert_int_eq(bench_speed(&b), 1000);
}
END_TEST

/* L1/L2: SEP and control word bits refused (0x06040043), nor LAC lowered while they are set; the
 * network has priority; CMD = 0x000F starts the drive without the status chart procedure. */
START_TEST(lac_l1_rules)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 2, ATV312_CHCF_SEPARATE, 2), 0);
    bench_rx(&b, "604#2B36200101000000"); /* LAC = L1 while CHCF = SEP */
    bench_expect(&b, "584#8036200143000406");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 2, 1, 2), 0);
    bench_rx(&b, "604#2B36200101000000");
    bench_expect(&b, "584#6036200100000000");
    bench_rx(&b, "604#2B36200202000000"); /* CHCF = SEP under L1 */
    bench_expect(&b, "584#8036200243000406");
    bench_rx(&b, "604#2B3C200B3B010000"); /* rPS = Cd15 under L1 */
    bench_expect(&b, "584#803C200B43000406");
    /* Fr1 = AI1 does not count under L1: the network commands and gives the reference. */
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2036, 14, 1, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0640);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0227);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 1500);
}
END_TEST

/* CHCF = 3 (I/O, the project's): CMD bit 0 runs, 0 stops on DEC to Switched on; TPDO1 frames. */
START_TEST(chcf_io_runs_on_bit_0)
{
    bench_t b;
    bench_start(&b);
    bench_rx(&b, "604#2B36200203000000");
    bench_expect(&b, "584#6036200200000000");
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    bench_operational(&b);
    bench_expect(&b, "184#4006");
    bench_advance(&b, 100000);
    bench_rx(&b, "204#0100");
    bench_expect(&b, "184#2702");
    bench_advance(&b, 3100000);
    bench_expect(&b, "184#2706");
    bench_rx(&b, "204#0000"); /* disable operation: DEC, then Switched on */
    bench_expect(&b, "184#2702");
    bench_advance(&b, 3000000);
    bench_expect(&b, "184#2306");
    ck_assert_int_eq(bench_speed(&b), 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_switching");
    TCase *tc = tcase_create("switching");
    tcase_add_test(tc, new_parameters_at_their_addresses);
    tcase_add_test(tc, c212_and_c213_switch_command_and_reference);
    tcase_add_test(tc, li3_switches_reference_and_command);
    tcase_add_test(tc, rps_cd15_switches_to_ac2_de2);
    tcase_add_test(tc, lac_l1_rules);
    tcase_add_test(tc, chcf_io_runs_on_bit_0);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
