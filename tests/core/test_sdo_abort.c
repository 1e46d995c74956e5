/* SPDX-License-Identifier: Apache-2.0 */
/* Every CiA 301 abort code has its own meaning for logs and tools; anything else is unknown. */
#include "check_main.h"
#include "co/co_types.h"

#include <string.h>

static const uint32_t codes[] = {
    CO_SDO_ABORT_TOGGLE,
    CO_SDO_ABORT_TIMEOUT,
    CO_SDO_ABORT_COMMAND,
    CO_SDO_ABORT_BLOCK_SIZE,
    CO_SDO_ABORT_SEQUENCE,
    CO_SDO_ABORT_CRC,
    CO_SDO_ABORT_NO_MEMORY,
    CO_SDO_ABORT_UNSUPPORTED_ACCESS,
    CO_SDO_ABORT_WRITE_ONLY,
    CO_SDO_ABORT_READ_ONLY,
    CO_SDO_ABORT_NO_OBJECT,
    CO_SDO_ABORT_NOT_MAPPABLE,
    CO_SDO_ABORT_PDO_LENGTH,
    CO_SDO_ABORT_PARAM_INCOMPATIBLE,
    CO_SDO_ABORT_INTERNAL_INCOMPATIBLE,
    CO_SDO_ABORT_HARDWARE,
    CO_SDO_ABORT_TYPE_LENGTH,
    CO_SDO_ABORT_LENGTH_HIGH,
    CO_SDO_ABORT_LENGTH_LOW,
    CO_SDO_ABORT_NO_SUBINDEX,
    CO_SDO_ABORT_VALUE_RANGE,
    CO_SDO_ABORT_VALUE_HIGH,
    CO_SDO_ABORT_VALUE_LOW,
    CO_SDO_ABORT_MAX_LESS_MIN,
    CO_SDO_ABORT_NO_RESOURCE,
    CO_SDO_ABORT_GENERAL,
    CO_SDO_ABORT_DATA_STORE,
    CO_SDO_ABORT_DATA_LOCAL,
    CO_SDO_ABORT_DATA_STATE,
    CO_SDO_ABORT_OD_MISSING,
    CO_SDO_ABORT_NO_DATA,
};

START_TEST(every_code_has_its_own_text)
{
    const size_t n = sizeof(codes) / sizeof(codes[0]);
    for (size_t i = 0; i < n; i++) {
        const char *text = co_sdo_abort_text(codes[i]);
        ck_assert_str_ne(text, "unknown abort code");
        for (size_t j = 0; j < i; j++)
            ck_assert_msg(strcmp(text, co_sdo_abort_text(codes[j])) != 0, "%08X and %08X share %s",
                          codes[i], codes[j], text);
    }
    ck_assert_str_eq(co_sdo_abort_text(CO_SDO_ABORT_VALUE_LOW),
                     "value of parameter written too low");
}
END_TEST

/* The names of release 0.1 stay for one release as aliases of the CO_ names, code for code. */
START_TEST(release_0_1_names_are_aliases)
{
    static const uint32_t old_names[] = {
        SDO_ABORT_TOGGLE,
        SDO_ABORT_TIMEOUT,
        SDO_ABORT_COMMAND,
        SDO_ABORT_BLOCK_SIZE,
        SDO_ABORT_SEQUENCE,
        SDO_ABORT_CRC,
        SDO_ABORT_NO_MEMORY,
        SDO_ABORT_UNSUPPORTED_ACCESS,
        SDO_ABORT_WRITE_ONLY,
        SDO_ABORT_READ_ONLY,
        SDO_ABORT_NO_OBJECT,
        SDO_ABORT_NOT_MAPPABLE,
        SDO_ABORT_PDO_LENGTH,
        SDO_ABORT_PARAM_INCOMPATIBLE,
        SDO_ABORT_INTERNAL_INCOMPATIBLE,
        SDO_ABORT_HARDWARE,
        SDO_ABORT_TYPE_LENGTH,
        SDO_ABORT_LENGTH_HIGH,
        SDO_ABORT_LENGTH_LOW,
        SDO_ABORT_NO_SUBINDEX,
        SDO_ABORT_VALUE_RANGE,
        SDO_ABORT_VALUE_HIGH,
        SDO_ABORT_VALUE_LOW,
        SDO_ABORT_MAX_LESS_MIN,
        SDO_ABORT_NO_RESOURCE,
        SDO_ABORT_GENERAL,
        SDO_ABORT_DATA_STORE,
        SDO_ABORT_DATA_LOCAL,
        SDO_ABORT_DATA_STATE,
        SDO_ABORT_OD_MISSING,
        SDO_ABORT_NO_DATA,
    };
    ck_assert_uint_eq(sizeof old_names, sizeof codes);
    for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++)
        ck_assert_uint_eq(old_names[i], codes[i]);
}
END_TEST

START_TEST(other_codes_are_unknown)
{
    ck_assert_str_eq(co_sdo_abort_text(0), "unknown abort code");
    ck_assert_str_eq(co_sdo_abort_text(0x06090033), "unknown abort code");
    ck_assert_str_eq(co_sdo_abort_text(0xFFFFFFFF), "unknown abort code");
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sdo_abort");
    TCase *tc = tcase_create("sdo_abort");
    tcase_add_test(tc, every_code_has_its_own_text);
    tcase_add_test(tc, release_0_1_names_are_aliases);
    tcase_add_test(tc, other_codes_are_unknown);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
