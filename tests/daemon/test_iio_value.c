// SPDX-License-Identifier: GPL-2.0
/*
 * The driver's attribute values as text (iio_value.h): Q16 offsets as
 * decimals with six places round-trip exactly (negative values above -1
 * included), integers, the self-test verdict and readings; anything
 * malformed or out of range is refused whole with its own error.
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

#include "iio_value.h"

#define ARRAY_LEN(a)	(sizeof(a) / sizeof((a)[0]))
/* 8192 LSB in Q16, a value with six exact decimal places */
#define Q16_8192	(8192 * 65536)

static void q16_text(int32_t q16, const char *want)
{
	char buf[IIO_Q16_TEXT_MAX];

	assert_int_equal(iio_q16_format(q16, buf, sizeof(buf)), 0);
	assert_string_equal(buf, want);
}

static void q16_format_examples(void **state)
{
	q16_text(0, "0.000000");
	/* between -1 and 0 the sign is still there */
	q16_text(-1, "-0.000015");
	q16_text(-32768, "-0.500000");
	q16_text(-65535, "-0.999985");
	q16_text(1, "0.000015");
	q16_text(-65536, "-1.000000");
	q16_text(-813056, "-12.406250");
	q16_text(-813057, "-12.406265");
	q16_text(Q16_8192, "8192.000000");
	q16_text(INT32_MIN, "-32768.000000");
	q16_text(INT32_MAX, "32767.999985");
}

static void q16_format_small_buffer(void **state)
{
	char buf[9];

	assert_int_equal(iio_q16_format(-813056, buf, sizeof(buf)), -ENOSPC);
	assert_int_equal(iio_q16_format(0, buf, sizeof(buf) - 1), -ENOSPC);
	assert_int_equal(iio_q16_format(0, buf, sizeof(buf)), 0);
	assert_string_equal(buf, "0.000000");
}

/*
 * parse(format(q)) == q, and the text says q in its own right: its sign,
 * and its value within half a millionth
 */
static void q16_round_trip_one(int32_t q)
{
	char buf[IIO_Q16_TEXT_MAX];
	int32_t back = ~q;

	assert_int_equal(iio_q16_format(q, buf, sizeof(buf)), 0);
	if (iio_q16_parse(buf, &back) || back != q)
		fail_msg("%d -> \"%s\" -> %d", q, buf, back);
	if ((q < 0) != (buf[0] == '-') ||
	    fabs(strtod(buf, NULL) - q / 65536.0) > 0.5e-6 + 1e-12)
		fail_msg("%d printed as \"%s\"", q, buf);
	assert_int_equal(strlen(strchr(buf, '.') + 1), 6);
}

static void q16_round_trip(void **state)
{
	int64_t q;

	/* every value within +-4 LSB, then the whole s32 range in steps */
	for (q = -(4 << 16); q <= 4 << 16; q++)
		q16_round_trip_one((int32_t)q);
	for (q = INT32_MIN; q <= INT32_MAX; q += 9973)
		q16_round_trip_one((int32_t)q);
	q16_round_trip_one(INT32_MIN);
	q16_round_trip_one(INT32_MAX);
	q16_round_trip_one(Q16_8192);
	q16_round_trip_one(-Q16_8192);
}

static void q16_parse_accepts(void **state)
{
	static const struct { const char *s; int32_t q16; } ok[] = {
		{ "3", 3 << 16 }, { "0.5", 32768 }, { "-0.5", -32768 },
		{ "-0", 0 }, { "0.000000", 0 }, { "-0.000015", -1 },
		{ "12.40625", 813056 }, { "-12.406250", -813056 },
		{ "007", 7 << 16 }, { "8192.000000", Q16_8192 },
		{ "-32768", INT32_MIN },
	};
	size_t i;

	for (i = 0; i < ARRAY_LEN(ok); i++) {
		int32_t q = 0x5a5a;

		if (iio_q16_parse(ok[i].s, &q) || q != ok[i].q16)
			fail_msg("\"%s\" gave %d, not %d", ok[i].s, q, ok[i].q16);
	}
}

static void q16_parse_refuses(void **state)
{
	static const char *const malformed[] = {
		"", "abc", "1.2.3", "-", ".", "1.", ".5", "-.5", "1.1234567",
		" 1", "1 ", "1\n", "+1", "--1", "-+1", "0x10", "1e3", "nan",
		"inf", "-inf", "1,5", "1.-5", "1..0", "12a", "a12", "\t0",
		"99999999999 ", "1.000000x",
	};
	static const char *const out_of_range[] = {
		"99999999999", "-99999999999", "32768", "-32768.000008",
		"32767.999993", "999999999999999999999999999999",
		"-999999999999999999999999999999.5",
	};
	int32_t q = 4242;
	size_t i;

	for (i = 0; i < ARRAY_LEN(malformed); i++)
		if (iio_q16_parse(malformed[i], &q) != -EINVAL)
			fail_msg("\"%s\" not refused as malformed", malformed[i]);
	for (i = 0; i < ARRAY_LEN(out_of_range); i++)
		if (iio_q16_parse(out_of_range[i], &q) != -ERANGE)
			fail_msg("\"%s\" not refused as out of range",
				 out_of_range[i]);
	/* nothing half-parsed */
	assert_int_equal(q, 4242);
}

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
	char s[24], buf[IIO_Q16_TEXT_MAX];
	int32_t q, adj[AS9888_AXES];
	enum iio_selftest_verdict verdict;
	unsigned int seed = 1, i, len, k;
	long v;

	for (i = 0; i < 200000; i++) {
		len = rand_r(&seed) % (sizeof(s) - 1);
		for (k = 0; k < len; k++)
			s[k] = alphabet[rand_r(&seed) % (sizeof(alphabet) - 1)];
		s[len] = '\0';
		if (!iio_q16_parse(s, &q)) {
			/* a decimal: its value within half a Q16 step */
			assert_true(fabs(strtod(s, NULL) * 65536.0 - q) <= 0.5);
			assert_int_equal(iio_q16_format(q, buf, sizeof(buf)), 0);
		}
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

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(q16_format_examples),
		cmocka_unit_test(q16_format_small_buffer),
		cmocka_unit_test(q16_round_trip),
		cmocka_unit_test(q16_parse_accepts),
		cmocka_unit_test(q16_parse_refuses),
		cmocka_unit_test(int_parse),
		cmocka_unit_test(errors_say_why),
		cmocka_unit_test(parsers_survive_garbage),
		cmocka_unit_test(selftest_verdict),
		cmocka_unit_test(selftest_readings),
		cmocka_unit_test(selftest_readings_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
