/* SPDX-License-Identifier: Apache-2.0 */
/* DeviceNet identifiers: the groups composed and taken apart, and the predefined master/slave
 * connection set's CAN-IDs, the manual's worked table for MAC ID 25 and the default 63. */
#include "check_main.h"
#include "dn/dn_link.h"

START_TEST(predefined_set_mac_25)
{
    dn_predefined_ids_t ids = dn_predefined_ids(25);
    ck_assert_uint_eq(ids.poll_command, 0x4CD);
    ck_assert_uint_eq(ids.explicit_request, 0x4CC);
    ck_assert_uint_eq(ids.explicit_response, 0x4CB);
    ck_assert_uint_eq(ids.unconnected, 0x4CE);
    ck_assert_uint_eq(ids.duplicate_mac, 0x4CF);
    ck_assert_uint_eq(ids.cos_ack, 0x4CA);
    ck_assert_uint_eq(ids.poll_response, 0x3D9);
    ck_assert_uint_eq(ids.cos_cyclic, 0x359);
}
END_TEST

START_TEST(predefined_set_mac_63)
{
    dn_predefined_ids_t ids = dn_predefined_ids(DN_MAC_ID_DEFAULT);
    ck_assert_uint_eq(ids.poll_command, 0x5FD);
    ck_assert_uint_eq(ids.explicit_request, 0x5FC);
    ck_assert_uint_eq(ids.explicit_response, 0x5FB);
    ck_assert_uint_eq(ids.unconnected, 0x5FE);
    ck_assert_uint_eq(ids.duplicate_mac, 0x5FF);
    ck_assert_uint_eq(ids.cos_ack, 0x5FA);
    ck_assert_uint_eq(ids.poll_response, 0x3FF);
    ck_assert_uint_eq(ids.cos_cyclic, 0x37F);
}
END_TEST

START_TEST(predefined_set_mac_0)
{
    dn_predefined_ids_t ids = dn_predefined_ids(0);
    ck_assert_uint_eq(ids.poll_command, 0x405);
    ck_assert_uint_eq(ids.duplicate_mac, 0x407);
    ck_assert_uint_eq(ids.poll_response, 0x3C0);
    ck_assert_uint_eq(ids.cos_cyclic, 0x340);
}
END_TEST

/* Every group 1-3 identifier of every MAC ID decodes to what composed it. */
START_TEST(compose_decompose_round_trip)
{
    for (uint8_t mac = 0; mac <= DN_MAC_ID_MAX; mac++) {
        for (uint8_t msg = 0; msg < 16; msg++) {
            dn_can_id_t id = dn_can_id_decode(dn_group1_id(msg, mac));
            ck_assert_uint_eq(id.group, 1);
            ck_assert_uint_eq(id.message_id, msg);
            ck_assert_uint_eq(id.mac_id, mac);
        }
        for (uint8_t msg = 0; msg < 8; msg++) {
            dn_can_id_t id = dn_can_id_decode(dn_group2_id(mac, msg));
            ck_assert_uint_eq(id.group, 2);
            ck_assert_uint_eq(id.message_id, msg);
            ck_assert_uint_eq(id.mac_id, mac);
        }
        for (uint8_t msg = 0; msg < 7; msg++) {
            dn_can_id_t id = dn_can_id_decode(dn_group3_id(msg, mac));
            ck_assert_uint_eq(id.group, 3);
            ck_assert_uint_eq(id.message_id, msg);
            ck_assert_uint_eq(id.mac_id, mac);
        }
    }
}
END_TEST

START_TEST(group_boundaries)
{
    ck_assert_uint_eq(dn_can_id_decode(0x3FF).group, 1);
    ck_assert_uint_eq(dn_can_id_decode(0x400).group, 2);
    ck_assert_uint_eq(dn_can_id_decode(0x5FF).group, 2);
    ck_assert_uint_eq(dn_can_id_decode(0x600).group, 3);
    ck_assert_uint_eq(dn_can_id_decode(0x7BF).group, 3);
    dn_can_id_t g4 = dn_can_id_decode(0x7C0);
    ck_assert_uint_eq(g4.group, 4);
    ck_assert_uint_eq(g4.message_id, 0);
    g4 = dn_can_id_decode(0x7EF);
    ck_assert_uint_eq(g4.group, 4);
    ck_assert_uint_eq(g4.message_id, 0x2F);
    ck_assert_uint_eq(dn_can_id_decode(0x7F0).group, 0);
    ck_assert_uint_eq(dn_can_id_decode(0x7FF).group, 0);
    ck_assert_uint_eq(dn_can_id_decode(0x800).group, 0);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("devicenet identifiers");
    TCase *tc = tcase_create("link");
    tcase_add_test(tc, predefined_set_mac_25);
    tcase_add_test(tc, predefined_set_mac_63);
    tcase_add_test(tc, predefined_set_mac_0);
    tcase_add_test(tc, compose_decompose_round_trip);
    tcase_add_test(tc, group_boundaries);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return check_run_suite(suite());
}
