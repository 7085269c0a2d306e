// SPDX-License-Identifier: GPL-2.0
/*
 * The field mode's decisions: when a refined calibration replaces the
 * record's (a meaningful change, at most once per MAGN_FIELD_MIN_AGE_S),
 * the driver's output turned back into the uncalibrated field, the
 * magn-feed request line, and the samples file keeping coverage.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "commands/magn_field.h"
#include "common/magn_cal.h"
#include "magn/magn_session.h"
#include "magn_example.h"
#include "common/request.h"


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
	/*
	 * the turn (none stored: the identity): 0.5 deg about Z is below the
	 * step, 0.6 deg is not (sin 0.6 deg = 0.0105); the same turn stored
	 * as it was is no change
	 */
	next = magn_example;
	next.has_rotation = true;
	next.rotation_micro[0][0] = next.rotation_micro[1][1] = 999962;
	next.rotation_micro[2][2] = 1000000;
	next.rotation_micro[0][1] = -8727;
	next.rotation_micro[1][0] = 8727;
	assert_false(magn_field_should_replace(&magn_example, &next, old));
	next.rotation_micro[0][0] = next.rotation_micro[1][1] = 999945;
	next.rotation_micro[0][1] = -10472;
	next.rotation_micro[1][0] = 10472;
	assert_true(magn_field_should_replace(&magn_example, &next, old));
	assert_false(magn_field_should_replace(&next, &next, old));
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
	static const struct magn_driver_cal d = {
		.calibbias = { -100, 149, -341 },
		.calibscale_micro = { 1020000, 985000, 1003000 },
	};
	static const double s[3] = { 0.3, 0.3 * 261 / 256, 0.3 * 251 / 256 };
	double m[3] = { 12.5, -300.25, 77 }, y;
	int i;

	(void)state;
	for (i = 0; i < 3; i++) {
		y = d.calibscale_micro[i] / 1e6 * (m[i] + d.calibbias[i] * s[i]);
		assert_true(fabs(magn_uncorrect_driver(&d, i, y, s[i]) - m[i]) < 1e-9);
	}
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

/* One feed through a session of its own, as cmd_magn_feed() makes */
static int feed(const char *path, const double m[3], const double a[3])
{
	struct magcal_session *fit = magcal_new(NULL);
	char err[512];
	int ret;

	assert_non_null(fit);
	ret = magn_field_store_sample(path, m, a, fit, err, sizeof(err));
	if (ret < 0)
		fail_msg("%s", err);
	magcal_free(fit);

	return ret;
}

/* The file's samples (after its count), as read back */
static unsigned int file_samples(const char *path, double (*v)[6],
				 unsigned int max)
{
	char line[256];
	unsigned int n = 0;
	FILE *f = fopen(path, "r");

	assert_non_null(f);
	while (fgets(line, sizeof(line), f) && n < max)
		if (line[0] != '#')
			assert_int_equal(sscanf(line, "%lf %lf %lf %lf %lf %lf",
						&v[n][0], &v[n][1], &v[n][2],
						&v[n][3], &v[n][4], &v[n][5]), 6), n++;
	fclose(f);

	return n;
}

/*
 * The samples file keeps coverage: a board turned through 80 directions,
 * then held for 400 samples near one posture (its field wandering 15 deg
 * about one direction), still has all 80 in the file, oldest first; the
 * old file (the last 300 samples) had none of them left
 */
static void samples_keep_directions(void **state)
{
	static const double h[3] = { 120, -80, 45 }, up[3] = { 0, 0, 1024 };
	static double v[MAGN_FIELD_KEEP + 8][6];
	double dirs[80][3], m[3];
	char dir[] = "/tmp/as9888-field-XXXXXX", path[64];
	unsigned int i, n, fits = 0;
	int k;

	(void)state;
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof(path), "%s/magn-samples", dir);
	for (i = 0; i < 80; i++) {
		/* a Fibonacci sphere: directions about 19 uT apart at 48 uT */
		double z = 1 - (2 * i + 1) / 80.0, r = sqrt(1 - z * z);
		double phi = i * M_PI * (3 - sqrt(5));

		dirs[i][0] = h[0] + 48 * r * cos(phi);
		dirs[i][1] = h[1] + 48 * r * sin(phi);
		dirs[i][2] = h[2] + 48 * z;
		fits += feed(path, dirs[i], up) == 1;
	}
	srand(7);
	for (i = 0; i < 400; i++) {
		/* within 15 deg of +x */
		double t = 15 * M_PI / 180 * rand() / RAND_MAX;
		double p = 2 * M_PI * rand() / RAND_MAX;

		m[0] = h[0] + 48 * cos(t);
		m[1] = h[1] + 48 * sin(t) * cos(p);
		m[2] = h[2] + 48 * sin(t) * sin(p);
		fits += feed(path, m, up) == 1;
	}
	/* a fit every 50 samples */
	assert_int_equal(fits, 480 / MAGN_FIELD_FIT_EVERY);
	n = file_samples(path, v, MAGN_FIELD_KEEP + 8);
	assert_true(n <= MAGN_FIELD_KEEP);
	/* the posture has its share too: more than the directions */
	assert_true(n > 80 + 40);
	for (i = 0; i < 80; i++)
		for (k = 0; k < 3; k++)
			if (fabs(v[i][k] - dirs[i][k]) > 0.001)
				fail_msg("sample %u of the file is %.3f %.3f %.3f, not direction %u (%.3f %.3f %.3f): pushed out",
					 i, v[i][0], v[i][1], v[i][2], i,
					 dirs[i][0], dirs[i][1], dirs[i][2]);
	assert_true(v[0][5] == 1024);
	unlink(path);
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(replace_rules),
		cmocka_unit_test(reference_from_record),
		cmocka_unit_test(uncorrect_inverts_driver),
		cmocka_unit_test(feed_line),
		cmocka_unit_test(samples_keep_directions),
	};

	return cmocka_run_group_tests_name("magn-field", tests, NULL, NULL);
}
