// SPDX-License-Identifier: GPL-2.0
/*
 * The field mode's decisions: when a refined calibration replaces the
 * record's (a meaningful change, at most once per MAGN_FIELD_MIN_AGE_S),
 * the driver's output turned back into the uncalibrated field, and the
 * magn-feed request line.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "magn_field.h"
#include "magn_session.h"
#include "magn_example.h"
#include "request.h"


static void replace_rules(void **state)
{
	int64_t old = magn_example.learned + MAGN_FIELD_MIN_AGE_S;
	struct calib_magn next = magn_example, none = { 0 };

	(void)state;
	/* nothing yet: anything good is taken at once */
	assert_true(magn_field_should_replace(&none, &next, magn_example.learned));
	/* the same, or a change below the steps: never rewritten */
	assert_false(magn_field_should_replace(&magn_example, &next, old));
	next.hard_iron_nt[2] += MAGN_FIELD_BIAS_STEP_NT - 1;
	next.soft_iron_micro[0][1] -= MAGN_FIELD_W_STEP_MICRO - 1;
	assert_false(magn_field_should_replace(&magn_example, &next, old));
	/* a hard iron 1 uT off: rewritten, but not within 6 hours */
	next = magn_example;
	next.hard_iron_nt[1] -= MAGN_FIELD_BIAS_STEP_NT;
	assert_true(magn_field_should_replace(&magn_example, &next, old));
	assert_false(magn_field_should_replace(&magn_example, &next, old - 1));
	assert_false(magn_field_should_replace(&magn_example, &next, magn_example.learned));
	/* a clock set back: not rewritten until it is past again */
	assert_false(magn_field_should_replace(&magn_example, &next, magn_example.learned - 3600));
	/* a soft-iron term 0.01 off */
	next = magn_example;
	next.soft_iron_micro[2][0] += MAGN_FIELD_W_STEP_MICRO;
	assert_true(magn_field_should_replace(&magn_example, &next, old));
}

/* A calibration scaled to the site's field is recognised by det(W) != 1 */
static void reference_from_record(void **state)
{
	struct magcal_result fit = { .status = MAGCAL_OK, .field_ut = 48.3,
				     .residual_ut = 0.3, .coverage = 0.7,
				     .used = 250, .scale = 1 };
	struct calib_magn m, none = { 0 };
	char err[256];
	int i;

	(void)state;
	/* det(W) = 1: the fit's own scale, no reference */
	fit.w[0][0] = 1.05;
	fit.w[1][1] = 1 / 1.05;
	fit.w[2][2] = 1;
	fit.w[0][1] = fit.w[1][0] = 0;
	assert_int_equal(magn_session_to_record(&fit, 1795392000, &m, err,
						sizeof(err)), 0);
	assert_true(magn_field_reference_ut(&m) == 0);
	assert_true(magn_field_reference_ut(&none) == 0);
	/* scaled to a 48.5 uT site: the reference comes back */
	fit.scale = 48.5 / fit.field_ut;
	for (i = 0; i < 3; i++)
		fit.w[i][i] *= fit.scale;
	fit.field_ut = 48.5;
	assert_int_equal(magn_session_to_record(&fit, 1795392000, &m, err,
						sizeof(err)), 0);
	assert_true(fabs(magn_field_reference_ut(&m) - 48.5) < 1e-9);
}

static void uncorrect_inverts_driver(void **state)
{
	static const int32_t bias[3] = { -100, 149, -341 };
	static const int32_t scale[3] = { 1020000, 985000, 1003000 };
	static const double s[3] = { 0.3, 0.3 * 261 / 256, 0.3 * 251 / 256 };
	double m[3] = { 12.5, -300.25, 77 }, y[3], back[3];
	int i;

	(void)state;
	for (i = 0; i < 3; i++)
		y[i] = scale[i] / 1e6 * (m[i] + bias[i] * s[i]);
	magn_field_uncorrect(y, bias, scale, s, back);
	for (i = 0; i < 3; i++)
		assert_true(fabs(back[i] - m[i]) < 1e-9);
}

static void feed_line(void **state)
{
	static const char *const bad[] = {
		"magn-feed", "magn-feed 1 2 3 4 5", "magn-feed 1 2 3 4 5 6 7",
		"magn-feed 1 2 3 4 5 x", "magn-feed  1 2 3 4 5 6",
		"magn-feed 1 2 3 4 5 6 ", "magn-feed 1e3 2 3 4 5 6",
		"magn-feed 1 2 3 4 5 100001", "magn-feed 1..2 2 3 4 5 6",
		"magn-feed 1 2 3 4 5 6 --json", "magn-feed nan 2 3 4 5 6",
	};
	struct request r;
	char err[256];
	const char *good = "magn-feed 12.345 -0.5 40 3 -1 255";
	unsigned int i;

	(void)state;
	assert_int_equal(request_parse(good, strlen(good), &r, err, sizeof(err)), 0);
	assert_int_equal(r.kind, REQUEST_MAGN_FEED);
	assert_true(r.feed[0] == 12.345 && r.feed[1] == -0.5 && r.feed[5] == 255);
	assert_true(request_quiet(REQUEST_MAGN_FEED));
	assert_false(request_exclusive(REQUEST_MAGN_FEED));
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		if (request_parse(bad[i], strlen(bad[i]), &r, err, sizeof(err)) !=
		    -EINVAL)
			fail_msg("\"%s\" accepted", bad[i]);
	assert_non_null(strstr(err, "magn-feed takes 6 numbers"));
	/* the other requests parse as before */
	assert_int_equal(request_parse("magn --json", 11, &r, err, sizeof(err)), 0);
	assert_true(r.kind == REQUEST_MAGN && r.json);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(replace_rules),
		cmocka_unit_test(reference_from_record),
		cmocka_unit_test(uncorrect_inverts_driver),
		cmocka_unit_test(feed_line),
	};

	return cmocka_run_group_tests_name("magn-field", tests, NULL, NULL);
}
