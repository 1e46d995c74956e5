/* SPDX-License-Identifier: Apache-2.0 */
/* The ATV312's configuration parameters a PLC writes (docs/atv312.md, "Channels, stop type,
 * frequencies"): each at its Schneider address with its range and default, and what the drive
 * layer does with it through atv312_profile: CHCF, rFC, Fr1, Fr2, CCS, Cd1, Cd2 choose where the
 * commands and the reference come from, Stt what CMD bit 12 does, RFR is the output frequency and
 * LFR the reference in 0.1 Hz, tUn runs a simulated auto-tune. */
#include "atv312_bench.h"
#include "check_main.h"

#define ABORT_STATE 0x08000022u
#define ABORT_VALUE_HIGH 0x06090031u
#define ABORT_VALUE_LOW 0x06090032u

/* A parameter at ADL `adl`: 0x2000 + (ADL - 3000) / 100, sub-index ADL mod 100 + 1. */
static uint16_t adl_index(unsigned adl)
{
    return (uint16_t)(0x2000 + (adl - 3000) / 100);
}

static uint8_t adl_sub(unsigned adl)
{
    return (uint8_t)(adl % 100 + 1);
}

static uint32_t read_adl(bench_t *b, unsigned adl)
{
    return bench_read(b, adl_index(adl), adl_sub(adl));
}

static uint32_t write_adl(bench_t *b, unsigned adl, uint16_t value)
{
    return bench_sdo_write(b, adl_index(adl), adl_sub(adl), value, 2);
}

#define CHCF 8401
#define RFC 8411
#define FR1 8413
#define FR2 8414
#define CCS 8421
#define CD1 8423
#define CD2 8424
#define LFR 8502
#define RFR 3202
#define STT 11203
#define TUN 9608

static const struct {
    unsigned adl;
    uint16_t low, high, fallback;
} parameters[] = {
    {CHCF, 1, 3, 1},  {RFC, 1, 315, 1}, {FR1, 1, 6, 6}, {FR2, 1, 6, 2},
    {CCS, 1, 315, 1}, {CD1, 1, 4, 4},   {CD2, 1, 4, 1}, {STT, 0, 3, 0},
};

/* Defaults, limits (the abort codes of a value out of range) at each address. */
START_TEST(parameters_at_their_addresses)
{
    bench_t b;
    bench_start(&b);
    for (size_t i = 0; i < sizeof parameters / sizeof parameters[0]; i++) {
        unsigned adl = parameters[i].adl;
        ck_assert_uint_eq(read_adl(&b, adl), parameters[i].fallback);
        ck_assert_uint_eq(write_adl(&b, adl, (uint16_t)(parameters[i].high + 1)), ABORT_VALUE_HIGH);
        if (parameters[i].low > 0)
            ck_assert_uint_eq(write_adl(&b, adl, (uint16_t)(parameters[i].low - 1)),
                              ABORT_VALUE_LOW);
        ck_assert_uint_eq(read_adl(&b, adl), parameters[i].fallback);
    }
    ck_assert_uint_eq(adl_index(STT), 0x2052);
    ck_assert_uint_eq(adl_sub(STT), 4);
    ck_assert_uint_eq(read_adl(&b, LFR), 0);
    ck_assert_uint_eq(read_adl(&b, RFR), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2002, 3, 1, 2), 0x06010002);
}
END_TEST

static void run_at_1500(bench_t *b)
{
    ck_assert_uint_eq(bench_sdo_write(b, 0x6042, 0, 1500, 2), 0);
    bench_command(b, 0x0006);
    bench_command(b, 0x000F);
    bench_advance(b, 3000000);
    ck_assert_int_eq(bench_speed(b), 1500);
}

/* Cd1 = terminals (CHCF = SEP): bit 9 clears in ETA and ETAD; CMD is recorded, not obeyed. Every
 * channel parameter is a configuration parameter. */
START_TEST(command_channel_terminals_ignores_cmd)
{
    bench_t b;
    bench_start(&b);
    run_at_1500(&b);
    ck_assert_uint_eq(write_adl(&b, CHCF, ATV312_CHCF_SEPARATE), ABORT_STATE);
    ck_assert_uint_eq(write_adl(&b, CD1, 1), ABORT_STATE);
    ck_assert_uint_eq(bench_command(&b, 0x0000), 0x0640);
    ck_assert_uint_eq(write_adl(&b, CHCF, ATV312_CHCF_SEPARATE), 0);
    ck_assert_uint_eq(write_adl(&b, CD1, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0440);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2037, 2, 0x0006, 2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0440);
    ck_assert_uint_eq(bench_read(&b, 0x6040, 0), 0x0006);
    /* CCS = Cd2 with Cd2 = CANopen gives the network back. */
    ck_assert_uint_eq(write_adl(&b, CD2, ATV312_CD_CANOPEN), 0);
    ck_assert_uint_eq(write_adl(&b, CCS, ATV312_CCS_CD2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0640);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

/* CHCF = SIM (the factory setting): the command follows the reference channel, Fr1 (or Fr2 with
 * rFC = Fr2); Cd1 does not count. */
START_TEST(not_separate_follows_fr1)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_adl(&b, CD1, 1), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0640);
    ck_assert_uint_eq(write_adl(&b, RFC, ATV312_RFC_FR2), 0);
    ck_assert_uint_eq(bench_read(&b, 0x2002, 2), 0x0440);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0440);
    ck_assert_uint_eq(write_adl(&b, FR2, ATV312_FR_CANOPEN), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
}
END_TEST

/* Separate mode, Fr1 = AI1 (no analogue input in the emulation): the network commands, the
 * reference is zero, the drive runs at LSP. */
START_TEST(reference_channel_ai1_runs_at_low_speed)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_adl(&b, CHCF, ATV312_CHCF_SEPARATE), 0);
    ck_assert_uint_eq(write_adl(&b, FR1, 1), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x2001, 6, 100, 2), 0);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1500, 2), 0);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    bench_command(&b, 0x000F);
    bench_advance(&b, 3000000);
    ck_assert_int_eq(bench_speed(&b), 300);
    /* At speed, the zero reference held at LSP (bit 11, internal limit). */
    ck_assert_uint_eq(bench_read(&b, 0x6041, 0), 0x0E27);
}
END_TEST

/* Stt: what CMD = 16#100F does ("Stop (configured by Stt)"): ACC = DEC = 3.0 s, 0.75 s after
 * the bit at 1500 rpm: 1125 rpm on the ramp, 0 at once in freewheel, 0 on the fast ramp
 * (DEC / 4 = 0.7 s). */
START_TEST(stop_type_of_cmd_bit_12)
{
    static const struct {
        uint16_t stt;
        int16_t rpm;
    } cases[] = {{0, 1125}, {1, 0}, {2, 0}, {3, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bench_t b;
        bench_start(&b);
        ck_assert_uint_eq(write_adl(&b, STT, cases[i].stt), 0);
        run_at_1500(&b);
        bench_command(&b, 0x100F);
        bench_advance(&b, 375000);
        bool freewheel = cases[i].stt == 2;
        ck_assert_int_eq(bench_speed(&b), freewheel ? 0 : (cases[i].stt == 0 ? 1312 : 696));
        bench_advance(&b, 375000);
        ck_assert_int_eq(bench_speed(&b), cases[i].rpm);
        ck_assert_uint_eq(bench_read(&b, 0x6041, 0) & 0x006F, 0x0027);
    }
}
END_TEST

/* RFR (2002:03) is the output frequency in 0.1 Hz; LFR (2037:03) is 6042h in 0.1 Hz. */
START_TEST(rfr_and_lfr_in_decihertz)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(write_adl(&b, LFR, 500), 0);
    ck_assert_uint_eq(bench_read(&b, 0x6042, 0), 1500);
    bench_command(&b, 0x0006);
    bench_command(&b, 0x000F);
    bench_advance(&b, 1500000);
    ck_assert_uint_eq(read_adl(&b, RFR), 250);
    bench_advance(&b, 1500000);
    ck_assert_uint_eq(read_adl(&b, RFR), 500);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 1200, 2), 0);
    ck_assert_uint_eq(read_adl(&b, LFR), 400);
    ck_assert_uint_eq(bench_command(&b, 0x080F) & 0x006F, 0x0027);
    bench_advance(&b, 6000000);
    ck_assert_int_eq((int16_t)read_adl(&b, RFR), -400);
}
END_TEST

/* 6042h beyond LFR's limits (-5000..5000): LFR reads its limit and takes it back (issue 22). */
START_TEST(lfr_stays_within_its_limits)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, 20000, 2), 0);
    ck_assert_uint_eq(read_adl(&b, LFR), 5000);
    ck_assert_uint_eq(bench_sdo_write(&b, 0x6042, 0, (uint16_t)-20000, 2), 0);
    ck_assert_int_eq((int16_t)read_adl(&b, LFR), -5000);
    ck_assert_uint_eq(write_adl(&b, LFR, (uint16_t)-5000), 0);
    ck_assert_int_eq((int16_t)bench_read(&b, 0x6042, 0), -15000);
}
END_TEST

/* tUn (2042:09): "requires an injection of current. The drive must therefore be in this state"
 * (Operation enabled); YES (1) reads DONE (2) after the simulated tune. */
START_TEST(tun_in_operation_enabled)
{
    bench_t b;
    bench_start(&b);
    ck_assert_uint_eq(adl_index(TUN), 0x2042);
    ck_assert_uint_eq(adl_sub(TUN), 9);
    ck_assert_uint_eq(read_adl(&b, TUN), 0);
    ck_assert_uint_eq(write_adl(&b, TUN, 1), ABORT_STATE);
    ck_assert_uint_eq(bench_command(&b, 0x0006), 0x0621);
    ck_assert_uint_eq(bench_command(&b, 0x000F), 0x0627);
    ck_assert_uint_eq(write_adl(&b, TUN, 1), 0);
    bench_advance(&b, DRIVE_AUTO_TUNE_TIME_US);
    ck_assert_uint_eq(read_adl(&b, TUN), 2);
    ck_assert_uint_eq(write_adl(&b, TUN, 3), ABORT_VALUE_HIGH);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_parameters");
    TCase *tc = tcase_create("parameters");
    tcase_add_test(tc, parameters_at_their_addresses);
    tcase_add_test(tc, command_channel_terminals_ignores_cmd);
    tcase_add_test(tc, not_separate_follows_fr1);
    tcase_add_test(tc, reference_channel_ai1_runs_at_low_speed);
    tcase_add_test(tc, stop_type_of_cmd_bit_12);
    tcase_add_test(tc, rfr_and_lfr_in_decihertz);
    tcase_add_test(tc, lfr_stays_within_its_limits);
    tcase_add_test(tc, tun_in_operation_enabled);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
