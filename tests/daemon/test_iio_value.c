// SPDX-License-Identifier: GPL-2.0
/*
 * The driver's attribute values as text (iio_value.h): integers, the
 * self-test verdict and readings; anything malformed or out of range is
 * refused whole with its own error.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "chip/iio_value.h"

#define ARRAY_LEN(a)	(sizeof(a) / sizeof((a)[0]))

static void int_parse(void **state)
{
	static const char *const malformed[] = {
		"", "abc", "1.5", "1.2.3", "-", " 1", "1 ", "+1", "0x10", "1e3",
	};
	long v = 77;
	size_t i;

	assert_int_equal(iio_int_parse("25000", -30000, 85000, &v), 0);
	assert_int_equal(v, 25000);
	assert_int_equal(iio_int_parse("-67", -67, 67, &v), 0);
	assert_int_equal(v, -67);
	assert_int_equal(iio_int_parse("-0", -67, 67, &v), 0);
	assert_int_equal(v, 0);
	v = 77;
	assert_int_equal(iio_int_parse("68", -67, 67, &v), -ERANGE);
	assert_int_equal(iio_int_parse("-68", -67, 67, &v), -ERANGE);
	assert_int_equal(iio_int_parse("99999999999", -30000, 85000, &v), -ERANGE);
	assert_int_equal(iio_int_parse("99999999999999999999999", 0, 1, &v),
			 -ERANGE);
	for (i = 0; i < ARRAY_LEN(malformed); i++)
		if (iio_int_parse(malformed[i], -30000, 85000, &v) != -EINVAL)
			fail_msg("\"%s\" not refused as malformed", malformed[i]);
	assert_int_equal(v, 77);
}

static void errors_say_why(void **state)
{
	assert_non_null(strstr(iio_value_strerror(-EINVAL), "malformed"));
	assert_non_null(strstr(iio_value_strerror(-ERANGE), "range"));
	assert_string_equal(iio_value_strerror(-EIO), strerror(EIO));
}

/* Random text through every parser: no crash, and what is accepted is sane */
static void parsers_survive_garbage(void **state)
{
	static const char alphabet[] = "0123456789-.. x";
	char s[24];
	int32_t adj[AS9888_AXES];
	enum iio_selftest_verdict verdict;
	unsigned int seed = 1, i, len, k;
	long v;

	for (i = 0; i < 200000; i++) {
		len = rand_r(&seed) % (sizeof(s) - 1);
		for (k = 0; k < len; k++)
			s[k] = alphabet[rand_r(&seed) % (sizeof(alphabet) - 1)];
		s[len] = '\0';
		if (!iio_int_parse(s, -100, 100, &v))
			assert_true(strtol(s, NULL, 10) == v);
		iio_parse_selftest_verdict(s, &verdict);
		iio_parse_selftest_readings(s, adj);
	}
}

static void selftest_verdict(void **state)
{
	static const char *const bad[] = {
		"", "Pass", "pass ", " pass", "passed", "PASS", "ok", "1",
		"pass -19.922 15.234 598.828",
	};
	enum iio_selftest_verdict v;
	size_t i;

	assert_int_equal(iio_parse_selftest_verdict("pass", &v), 0);
	assert_int_equal(v, IIO_SELFTEST_PASS);
	assert_int_equal(iio_parse_selftest_verdict("fail", &v), 0);
	assert_int_equal(v, IIO_SELFTEST_FAIL);
	assert_int_equal(iio_parse_selftest_verdict("none", &v), 0);
	assert_int_equal(v, IIO_SELFTEST_NONE);
	for (i = 0; i < ARRAY_LEN(bad); i++)
		if (iio_parse_selftest_verdict(bad[i], &v) != -EINVAL)
			fail_msg("accepted \"%s\"", bad[i]);
}

static void selftest_readings(void **state)
{
	int32_t adj[AS9888_AXES] = { 0 };
	char text[64];
	int32_t k;

	assert_int_equal(iio_parse_selftest_readings("-19.922 15.234 598.828",
						     adj), 0);
	/* the exact Q8 readings the driver printed rounded to 1/1000 */
	assert_int_equal(adj[0], -5100);
	assert_int_equal(adj[1], 3900);
	assert_int_equal(adj[2], 153300);
	assert_int_equal(iio_parse_selftest_readings("0.000 -0.004 16.668", adj), 0);
	assert_int_equal(adj[1], -1);
	assert_int_equal(adj[2], 4267);
	assert_int_equal(iio_parse_selftest_readings("none", adj), -ENODATA);

	/* every Q8 reading in the windows' neighbourhood comes back exactly */
	for (k = -300 * 256; k <= 1100 * 256; k++) {
		snprintf(text, sizeof(text), "%.3f %.3f %.3f", k / 256.0,
			 -k / 256.0, k / 256.0);
		if (iio_parse_selftest_readings(text, adj) || adj[0] != k ||
		    adj[1] != -k || adj[2] != k)
			fail_msg("%d printed \"%s\" read back %d %d %d", k, text,
				 adj[0], adj[1], adj[2]);
	}
}

static void selftest_readings_refused(void **state)
{
	static const char *const bad[] = {
		"", "None", "pass", "1 2", "1 2 3 4", "1  2 3", " 1 2 3",
		"1 2 3 ", "1 2 x", "nan 0 0", "inf 0 0", "1e9 0 0", "8192 0 0",
		"-8192.000 0 0", "1.2345 0 0", "pass 1 2 3", "1,0 2 3",
		"1\t2\t3", "99999999999 0 0",
	};
	int32_t adj[AS9888_AXES] = { 7, 7, 7 };
	size_t i;

	for (i = 0; i < ARRAY_LEN(bad); i++)
		if (iio_parse_selftest_readings(bad[i], adj) != -EINVAL)
			fail_msg("accepted \"%s\"", bad[i]);
	assert_int_equal(adj[0], 7);
	assert_int_equal(adj[2], 7);
}

static void rate_max(void **state)
{
	static const char *const malformed[] = {
		"", " ", "1 ", " 1", "1  2", "1,2", "1.5", "12.5 400", "x",
		"1 2 x", "1\t2", "400\n",
	};
	static const char *const out_of_range[] = {
		"0", "1 0 5", "-1", "401", "1 2 99999999999999",
	};
	long hz = 77;
	size_t i;

	assert_int_equal(iio_parse_rate_max("1 2 5 10 20 25 50 100 125 200 250 400",
					    400, &hz), 0);
	assert_int_equal(hz, 400);
	assert_int_equal(iio_parse_rate_max("125", 400, &hz), 0);
	assert_int_equal(hz, 125);
	/* the fastest wherever it is in the list */
	assert_int_equal(iio_parse_rate_max("100 1 50", 400, &hz), 0);
	assert_int_equal(hz, 100);
	hz = 77;
	for (i = 0; i < ARRAY_LEN(malformed); i++)
		if (iio_parse_rate_max(malformed[i], 400, &hz) != -EINVAL)
			fail_msg("\"%s\" not refused as malformed", malformed[i]);
	for (i = 0; i < ARRAY_LEN(out_of_range); i++)
		if (iio_parse_rate_max(out_of_range[i], 400, &hz) != -ERANGE)
			fail_msg("\"%s\" not refused as out of range", out_of_range[i]);
	assert_int_equal(hz, 77);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(int_parse),
		cmocka_unit_test(errors_say_why),
		cmocka_unit_test(parsers_survive_garbage),
		cmocka_unit_test(selftest_verdict),
		cmocka_unit_test(selftest_readings),
		cmocka_unit_test(selftest_readings_refused),
		cmocka_unit_test(rate_max),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
