/* SPDX-License-Identifier: Apache-2.0 */
/* The manufacturer parameters in PDO6, as the manual allows: its variables "can also be replaced
 * with any two other variables", from the "Mapable Objects from EDS file". Every parameter of
 * 2000h-5FFFh of the ATV312 and ATV31 dictionaries is mappable, a read-only one into TPDO6, a
 * read-write one either way; mapped, their values travel frame for frame. The ATV58's card has
 * one fixed PDO pair: its one parameter, ACC, is mappable into none. */
#include "atv31/atv31.h"
#include "atv312_bench.h"
#include "atv58/atv58.h"
#include "check_main.h"

/* Each entry of the manufacturer area (sub-index 0, the count, is not a parameter). */
static void expect_every_parameter_mappable(const co_od_t *od)
{
    unsigned parameters = 0;
    for (size_t i = 0; i < od->count; i++) {
        const co_od_entry_t *e = &od->entries[i];
        if (e->index < 0x2000 || e->index > 0x5FFF || e->subindex == 0)
            continue;
        uint16_t wanted = (e->flags & CO_OD_WRITE) ? CO_OD_TPDO | CO_OD_RPDO : CO_OD_TPDO;
        ck_assert_msg((e->flags & (CO_OD_TPDO | CO_OD_RPDO)) == wanted, "%04X:%02X not mappable",
                      e->index, e->subindex);
        parameters++;
    }
    ck_assert_uint_gt(parameters, 20);
}

START_TEST(every_manufacturer_parameter_is_mappable)
{
    expect_every_parameter_mappable(&atv312_od);
    expect_every_parameter_mappable(&atv31_od);
    expect_every_parameter_mappable(&atv31_v11_od);
}
END_TEST

/* TPDO6 remapped to ETAD, HSP (2001:05), Fr1 (2036:0E) and CrL3 (2010:03): every mapping write
 * accepted, and the PDO carries 0x0640, 500, 6, 40 at the NMT start. */
START_TEST(tpdo6_carries_manufacturer_parameters)
{
    bench_t b;
    bench_start(&b);
    static const bench_exchange_t mapping[] = {
        {"1A05h:00 = 0", "604#2F051A0000000000", 0, {"584#60051A0000000000"}},
        {"1A05h:01 ETAD", "604#23051A0110004160", 0, {"584#60051A0100000000"}},
        {"1A05h:02 HSP", "604#23051A0210050120", 0, {"584#60051A0200000000"}},
        {"1A05h:03 Fr1", "604#23051A03100E3620", 0, {"584#60051A0300000000"}},
        {"1A05h:04 CrL3", "604#23051A0410031020", 0, {"584#60051A0400000000"}},
        {"1A05h:00 = 4", "604#2F051A0004000000", 0, {"584#60051A0000000000"}},
        {"1805h:01 valid", "604#2305180184020000", 0, {"584#6005180100000000"}},
        {"1805h:05 off", "604#2B05180500000000", 0, {"584#6005180500000000"}},
        {"1800h:05 off", "604#2B00180500000000", 0, {"584#6000180500000000"}},
        {"start", "000#0104", 0, {"184#4006", "284#4006F40106002800"}},
    };
    bench_play(&b, mapping, sizeof mapping / sizeof mapping[0]);
}
END_TEST

/* RPDO6 remapped to CMDD, HSP (2001:05) and LSP (2001:06): the PDO writes them, SDO reads them
 * back. */
START_TEST(rpdo6_writes_manufacturer_parameters)
{
    bench_t b;
    bench_start(&b);
    static const bench_exchange_t mapping[] = {
        {"1605h:00 = 0", "604#2F05160000000000", 0, {"584#6005160000000000"}},
        {"1605h:02 HSP", "604#2305160210050120", 0, {"584#6005160200000000"}},
        {"1605h:03 LSP", "604#2305160310060120", 0, {"584#6005160300000000"}},
        {"1605h:00 = 3", "604#2F05160003000000", 0, {"584#6005160000000000"}},
        {"1405h:01 valid", "604#2305140104030000", 0, {"584#6005140100000000"}},
    };
    bench_play(&b, mapping, sizeof mapping / sizeof mapping[0]);
    bench_rx(&b, "000#0104");
    b.next = b.count;
    bench_rx(&b, "304#0000E8036400");
    static const bench_exchange_t read[] = {
        {"HSP", "604#4001200500000000", 0, {"584#4B012005E8030000"}},
        {"LSP", "604#4001200600000000", 0, {"584#4B01200664000000"}},
    };
    bench_play(&b, read, sizeof read / sizeof read[0]);
}
END_TEST

/* The ATV58 card's PDOs are fixed: its EDS offers ACC (5FE5:03) to none. */
START_TEST(atv58_acc_is_not_mappable)
{
    const co_od_entry_t *acc = co_od_find(&atv58_od, 0x5FE5, 3);
    ck_assert_ptr_nonnull(acc);
    ck_assert_uint_eq(acc->flags & (CO_OD_TPDO | CO_OD_RPDO), 0);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312_mapping");
    TCase *tc = tcase_create("mapping");
    tcase_add_test(tc, every_manufacturer_parameter_is_mappable);
    tcase_add_test(tc, tpdo6_carries_manufacturer_parameters);
    tcase_add_test(tc, rpdo6_writes_manufacturer_parameters);
    tcase_add_test(tc, atv58_acc_is_not_mappable);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
