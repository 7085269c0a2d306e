// SPDX-License-Identifier: GPL-2.0
/*
 * Tests of the fixed-point geometry of the model's magnetic world
 * (as9888_magworld.c) against double-precision references.
 */

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include <linux/errno.h>
#include <linux/kernel.h>

#include "as9888_magworld.h"
#include "as9888_unit.h"

#define Q30		1073741824.0
#define DEG		(M_PI / 180.0)

static double q30(s64 v)
{
	return v / Q30;
}

/* Every 7.001 degrees over several turns, both signs: error < 4e-9 */
static void test_sincos(void **state)
{
	s64 mdeg;
	s32 s, c;

	for (mdeg = -1200000; mdeg <= 1200000; mdeg += 7001) {
		as9888_mw_sincos(mdeg, &s, &c);
		if (fabs(q30(s) - sin(mdeg / 1000.0 * DEG)) > 4e-9 ||
		    fabs(q30(c) - cos(mdeg / 1000.0 * DEG)) > 4e-9)
			fail_msg("%lld mdeg: %.10f %.10f", (long long)mdeg,
				 q30(s), q30(c));
	}
	/* the octant edges and the quadrants exactly */
	as9888_mw_sincos(90000, &s, &c);
	assert_int_equal(s, 1 << 30);
	assert_true(c == 0 || c == 1 || c == -1);
	as9888_mw_sincos(-180000, &s, &c);
	assert_int_equal(c, -(1 << 30));
	as9888_mw_sincos(45000, &s, &c);
	assert_true(fabs(q30(s) - sqrt(0.5)) < 3e-9);
	assert_true(fabs(q30(c) - sqrt(0.5)) < 3e-9);
}

/* v_world = R(q) v_sensor, from the quaternion in doubles */
static void ref_rotate(const s32 q[4], const double v[3], double out[3])
{
	double w = q30(q[0]), x = q30(q[1]), y = q30(q[2]), z = q30(q[3]);
	double r[3][3] = {
		{ 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
		{ 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
		{ 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) },
	};
	int i;

	for (i = 0; i < 3; i++)
		out[i] = r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2];
}

static void expect_vec(const double got[3], double x, double y, double z,
		       double tol)
{
	if (fabs(got[0] - x) > tol || fabs(got[1] - y) > tol ||
	    fabs(got[2] - z) > tol)
		fail_msg("got (%.7f %.7f %.7f), want (%.7f %.7f %.7f)", got[0],
			 got[1], got[2], x, y, z);
}

/* Level: heading is the azimuth of +Y, clockwise from north */
static void test_heading_level(void **state)
{
	static const s32 up[3] = { 0, 0, 1000000 };
	static const double ey[3] = { 0, 1, 0 }, ez[3] = { 0, 0, 1 };
	double w[3];
	s32 q[4];
	int h;

	as9888_mw_quat_from_up(up, 0, q);
	assert_true(abs(q[0] - (1 << 30)) <= 1);
	for (h = -350; h <= 350; h += 35) {
		as9888_mw_quat_from_up(up, h * 1000, q);
		ref_rotate(q, ey, w);
		expect_vec(w, sin(h * DEG), cos(h * DEG), 0, 1e-8);
		ref_rotate(q, ez, w);
		expect_vec(w, 0, 0, 1, 1e-8);
	}
}

/* Tilted: the sensor's up goes to the world's up, for any heading */
static void test_up_tilted(void **state)
{
	static const s32 ups[][3] = {
		{ 1000000, 0, 0 }, { 0, -1000000, 0 }, { 0, 0, -1000000 },
		{ 577350, 577350, 577350 }, { -3, 4, -12 }, { 1, 0, -1000 },
	};
	double u[3], w[3];
	s32 q[4], back[3];
	unsigned int i;
	double n;

	for (i = 0; i < ARRAY_SIZE(ups); i++) {
		n = sqrt((double)ups[i][0] * ups[i][0] +
			 (double)ups[i][1] * ups[i][1] +
			 (double)ups[i][2] * ups[i][2]);
		u[0] = ups[i][0] / n;
		u[1] = ups[i][1] / n;
		u[2] = ups[i][2] / n;
		as9888_mw_quat_from_up(ups[i], 123456, q);
		ref_rotate(q, u, w);
		/* near upside down the tilt's half angle loses a few bits */
		expect_vec(w, 0, 0, 1, 1e-6);
		as9888_mw_up_from_quat(q, back);
		expect_vec((double[3]){ back[0] / 1e6, back[1] / 1e6,
					back[2] / 1e6 }, u[0], u[1], u[2],
			   1.5e-6);
	}
}

/* The sensor frame sees R^T of the world */
static void test_to_sensor(void **state)
{
	static const s32 raw[4] = { 3, -1, 2, 5 };
	s64 v[4] = { raw[0], raw[1], raw[2], raw[3] };
	s64 world[3] = { 12345, -40000, 33333 }, sensor[3];
	double ds[3], back[3];
	s32 q[4];

	assert_int_equal(as9888_mw_normalise_q30(v, 4, q), 0);
	as9888_mw_to_sensor(q, world, sensor);
	ds[0] = sensor[0];
	ds[1] = sensor[1];
	ds[2] = sensor[2];
	ref_rotate(q, ds, back);
	expect_vec(back, 12345, -40000, 33333, 1.5);
}

static void test_normalise(void **state)
{
	s64 zero[4] = { 0 }, big[3] = { INT32_MAX, INT32_MIN, 1 };
	s64 tiny[2] = { 0, -1 };
	s32 out[4] = { 7, 7, 7, 7 };

	assert_int_equal(as9888_mw_normalise_q30(zero, 4, out), -EINVAL);
	assert_int_equal(out[0], 7);
	assert_int_equal(as9888_mw_normalise_q30(tiny, 2, out), 0);
	assert_int_equal(out[0], 0);
	assert_int_equal(out[1], -(1 << 30));
	assert_int_equal(as9888_mw_normalise_q30(big, 3, out), 0);
	assert_true(fabs(q30(out[0]) - sqrt(0.5)) < 3e-9);
	assert_true(fabs(q30(out[1]) + sqrt(0.5)) < 3e-9);
	assert_int_equal(as9888_mw_normalise_q30(big, 5, out), -EINVAL);
}

/* Composition and axis-angle agree with the doubles */
static void test_quat_mul_axis_angle(void **state)
{
	static const s32 zaxis[3] = { 0, 0, 1 << 30 }, xaxis[3] = { 1 << 30 };
	static const double ex[3] = { 1, 0, 0 };
	s32 a[4], b[4], q[4];
	double w[3];

	as9888_mw_quat_axis_angle(zaxis, 90000, a);	/* x -> y */
	as9888_mw_quat_axis_angle(xaxis, 90000, b);	/* y -> z */
	as9888_mw_quat_mul(b, a, q);			/* a first, then b */
	ref_rotate(q, ex, w);
	expect_vec(w, 0, 0, 1, 1e-8);
	as9888_mw_quat_mul(a, b, q);			/* x stays under b */
	ref_rotate(q, ex, w);
	expect_vec(w, 0, 1, 0, 1e-8);
}

/* F (cos I sin D, cos I cos D, -sin I), East-North-Up */
static void test_earth_world(void **state)
{
	s64 w[3];

	as9888_mw_earth_world_nt(50000, 60000, 0, w);
	assert_int_equal(w[0], 0);
	assert_int_equal(w[1], 25000);
	assert_int_equal(w[2], -43301);
	as9888_mw_earth_world_nt(48000, -30000, 10000, w);
	assert_true(llabs(w[0] - (s64)lround(48000 * cos(30 * DEG) *
					     sin(10 * DEG))) <= 1);
	assert_true(llabs(w[1] - (s64)lround(48000 * cos(30 * DEG) *
					     cos(10 * DEG))) <= 1);
	assert_int_equal(w[2], 24000);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sincos),
		cmocka_unit_test(test_heading_level),
		cmocka_unit_test(test_up_tilted),
		cmocka_unit_test(test_to_sensor),
		cmocka_unit_test(test_normalise),
		cmocka_unit_test(test_quat_mul_axis_angle),
		cmocka_unit_test(test_earth_world),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
