/* SPDX-License-Identifier: Apache-2.0 */
/* The end of every Check test program's main(): runs the suite and turns its result into the
 * exit status ctest reads. Header-only so that test programs without the test bus use it too. */
#ifndef CHECK_MAIN_H
#define CHECK_MAIN_H

#include <check.h>
#include <stdlib.h>

static inline int check_run_suite(Suite *suite)
{
    SRunner *runner = srunner_create(suite);
    srunner_run_all(runner, CK_NORMAL);
    int failed = srunner_ntests_failed(runner);
    srunner_free(runner);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

#endif
