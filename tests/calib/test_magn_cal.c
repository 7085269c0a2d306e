// SPDX-License-Identifier: GPL-2.0
/*
 * The driver's magnetometer calibration (as9888_magn_calibrate() and the
 * parsing of calibscale) against a double-precision reference:
 *
 *   out = rint((H + calibbias) * calibscale)    (ties to even)
 *
 * kept to -4095..4094, -ERANGE with the rail of its sign outside that or
 * when the count is at the chip's rail. Every count is swept against a grid
 * of biases and scales that includes both ends of each range; the product
 * (H + bias) * scale_micro is an integer below 2^34, so the double quotient
 * is exact at every tie and within 1e-12 of the truth elsewhere: the
 * reference is exact.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/limits.h>

#include "as9888_calib.h"

static const s32 scales[] = {
	500000, 500001, 666667, 750000, 999999, 1000000, 1000001, 1048576,
	1234567, 1500000, 1999999, 2000000,
};

/* The reference: the result and the return value, in double arithmetic */
static int ref_calibrate(int h, int bias, s32 scale_micro, int *out)
{
	double v;

	if (h <= -4096 || h >= 4095) {
		*out = h < 0 ? -4096 : 4095;
		return -ERANGE;
	}
	v = rint((double)(h + bias) * scale_micro / 1e6);
	if (v < -4095) {
		*out = -4096;
		return -ERANGE;
	}
	if (v > 4094) {
		*out = 4095;
		return -ERANGE;
	}
	*out = (int)v;
	return 0;
}

static void check(int h, int bias, s32 scale, unsigned long *ties)
{
	int want, ret_want, ret;
	s16 out = 0x5a5a;

	ret_want = ref_calibrate(h, bias, scale, &want);
	ret = as9888_magn_calibrate(h, bias, scale, &out);
	if (ret != ret_want || out != want)
		fail_msg("H %d bias %d scale %d: got %d (%d), want %d (%d)",
			 h, bias, scale, out, ret, want, ret_want);
	if ((s64)(h + bias) * scale % 1000000 == 500000 ||
	    (s64)(h + bias) * scale % 1000000 == -500000)
		(*ties)++;
}

/* Every count x 225 biases (both ends, 0, odd steps) x 12 scales */
static void sweep_calibrate(void **state)
{
	unsigned long n = 0, ties = 0;
	size_t i;
	int h, bias;

	for (h = -4096; h <= 4095; h++) {
		for (bias = -4096; bias <= 4096; bias += 37) {
			for (i = 0; i < ARRAY_SIZE(scales); i++, n++)
				check(h, bias, scales[i], &ties);
		}
		for (i = 0; i < ARRAY_SIZE(scales); i++, n += 3) {
			check(h, 4096, scales[i], &ties);
			check(h, 0, scales[i], &ties);
			check(h, 1, scales[i], &ties);
		}
	}
	printf("# magn calibrate: %lu cases, %lu exact ties, all equal to rint\n",
	       n, ties);
	assert_true(ties > 1000);
}

/* Every scale of the range on a few counts */
static void sweep_scales(void **state)
{
	static const int hs[] = { -4095, -2047, -1, 1, 3, 1365, 2047, 4094 };
	unsigned long ties = 0;
	s32 scale;
	size_t i;

	for (scale = AS9888_MAGN_CALIBSCALE_MIN;
	     scale <= AS9888_MAGN_CALIBSCALE_MAX; scale++)
		for (i = 0; i < ARRAY_SIZE(hs); i++)
			check(hs[i], -7, scale, &ties);
	assert_true(ties > 0);
}

/* Out-of-range calibration: -EINVAL, the output untouched */
static void bad_calibration(void **state)
{
	static const s32 bad[][2] = {
		{ 4097, 1000000 }, { -4097, 1000000 }, { S32_MAX, 1000000 },
		{ S32_MIN, 1000000 }, { 0, 499999 }, { 0, 2000001 }, { 0, 0 },
		{ 0, -1000000 }, { 0, S32_MAX },
	};
	size_t i;

	for (i = 0; i < ARRAY_SIZE(bad); i++) {
		s16 out = 0x5a5a;

		assert_int_equal(as9888_magn_calibrate(100, bad[i][0], bad[i][1],
						       &out), -EINVAL);
		assert_int_equal(out, 0x5a5a);
	}
}

/*
 * A board's hard iron b (counts) is cancelled by calibbias = -b, and a
 * gain g on the axis by calibscale = 1/g: the Earth's field comes back to
 * within half an LSB and the rounding of the scale.
 */
static void cancels_hard_and_soft_iron(void **state)
{
	static const double gains[] = { 0.9, 0.95, 1.0, 1.03, 1.1 };
	int b, f;
	size_t i;

	for (i = 0; i < ARRAY_SIZE(gains); i++) {
		s32 scale = (s32)lrint(1e6 / gains[i]);

		for (b = -700; b <= 700; b += 7) {
			for (f = -230; f <= 230; f++) {
				int h = (int)lrint(gains[i] * (f + b));
				s16 out;

				assert_int_equal(as9888_magn_calibrate(h,
						(int)lrint(-gains[i] * b), scale,
						&out), 0);
				/* |error| <= (0.5 + 0.5) / g + 0.5 + scale rounding */
				assert_true(abs(out - f) <= 1.0 / gains[i] + 0.51);
			}
		}
	}
}

static void calibscale_values(void **state)
{
	int val, val2;
	s32 micro;

	for (val = -1; val <= 3; val++) {
		for (val2 = -1; val2 <= 1000000; val2++) {
			s64 v = (s64)val * 1000000 + val2;
			bool ok = val >= 0 && val2 >= 0 && val2 < 1000000 &&
				  v >= 500000 && v <= 2000000;

			micro = -1;
			assert_int_equal(as9888_magn_calibscale_micro(val, val2,
								      &micro),
					 ok ? 0 : -EINVAL);
			assert_int_equal(micro, ok ? v : -1);
		}
	}
	assert_int_equal(as9888_magn_calibscale_micro(S32_MAX, 0, &micro),
			 -EINVAL);
	assert_int_equal(as9888_magn_calibscale_micro(S32_MIN, 0, &micro),
			 -EINVAL);
	assert_int_equal(as9888_magn_calibscale_micro(1, S32_MAX, &micro),
			 -EINVAL);
	assert_int_equal(as9888_magn_calibscale_micro(1, S32_MIN, &micro),
			 -EINVAL);
}

static void calibbias_values(void **state)
{
	s64 b;

	for (b = -5000; b <= 5000; b++)
		assert_int_equal(as9888_magn_calibbias_valid(b),
				 b >= -4096 && b <= 4096);
	assert_false(as9888_magn_calibbias_valid(S64_MAX));
	assert_false(as9888_magn_calibbias_valid(S64_MIN));
}

/* Defaults, and the scale: 0.3 uT (0.003 G) per LSB times (EHC + 128) / 256 */
static void defaults_and_scale(void **state)
{
	struct as9888_magn_cal cal;
	int axis, ehc;

	memset(&cal, 0xa5, sizeof(cal));
	as9888_magn_cal_init(&cal);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		assert_int_equal(cal.bias[axis], 0);
		assert_int_equal(cal.scale_micro[axis], 1000000);
	}
	for (ehc = 0; ehc < 256; ehc++)
		assert_true(fabs((double)as9888_mag_scale_num(ehc) /
				 AS9888_MAGN_SCALE_DEN -
				 0.003 * (ehc + 128) / 256) < 1e-15);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(sweep_calibrate),
		cmocka_unit_test(sweep_scales),
		cmocka_unit_test(bad_calibration),
		cmocka_unit_test(cancels_hard_and_soft_iron),
		cmocka_unit_test(calibscale_values),
		cmocka_unit_test(calibbias_values),
		cmocka_unit_test(defaults_and_scale),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
