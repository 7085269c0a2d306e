// SPDX-License-Identifier: GPL-2.0
/*
 * The factory test through the driver takes the driver's compensated
 * samples back to the chip's own output (accel_raw.h). Compensated samples
 * are made here as the driver makes them, from known raw values with a
 * known calibration, a DAC value in use other than the factory one and
 * temperatures away from the calibration's: every raw value must come back
 * exactly, and a sample at the limit of the driver's output must be
 * refused as saturated, never passed on.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "chip/accel_raw.h"

static const uint8_t example[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

/* 85, 55, 25, -5 and -30 degC; the calibration is at 25 degC */
static const uint8_t tmps_codes[] = { 0x28, 0x58, 0x88, 0xb8, 0xe0 };
/* The DAC in use, in linear codes away from the factory value */
static const int dac_moved[AS9888_AXES] = { 9, -7, 20 };

/* The example chip with a calibbias, DAC moved from the factory's */
static void make_comp(struct accel_comp *c)
{
	int axis;

	memset(c, 0, sizeof(*c));
	assert_int_equal(as9888_eeprom_decode(example, &c->ee), 0);
	c->cal.bias[0] = 49;		/* -12.4 chip LSB at St_RT 260 */
	c->cal.bias[1] = -139;
	c->cal.bias[2] = 593;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		const struct as9888_axis_trim *trim = &c->ee.axis[axis];

		c->da[axis] = as9888_lin2dac(trim->ga,
					     as9888_dac2lin(trim->ga, trim->da) +
					     dac_moved[axis]);
		assert_true(as9888_dac_valid(c->da[axis]));
		assert_int_not_equal(c->da[axis], trim->da);
	}
}

/* What the driver delivers for @raw on every axis at @tmps, with @c */
static void compensate(const struct accel_comp *c, const int16_t raw[AS9888_AXES],
		       uint8_t tmps, int16_t out[AS9888_AXES])
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		int32_t ot, st;

		assert_int_equal(as9888_accel_correction(&c->ee, &c->cal, axis,
							 c->da[axis],
							 as9888_tmps_to_mdegc(tmps),
							 &ot, &st), 0);
		assert_int_equal(as9888_accel_compensate(raw[axis], ot, st,
							 &out[axis]), 0);
	}
}

static void raw_sample(int32_t r, int16_t raw[AS9888_AXES])
{
	/* a different value on each axis, every one of them over the loop */
	raw[0] = (int16_t)r;
	raw[1] = (int16_t)(AS9888_ACC_MIN + AS9888_ACC_MAX - r);
	raw[2] = (int16_t)(AS9888_ACC_MIN + (r - AS9888_ACC_MIN + 1000) %
			   (AS9888_ACC_MAX - AS9888_ACC_MIN + 1));
}

static void every_raw_value_comes_back(void **state)
{
	struct accel_comp c;
	int16_t raw[AS9888_AXES], out[AS9888_AXES], got[AS9888_AXES];
	char why[256];
	size_t i;
	int32_t r;

	make_comp(&c);
	for (i = 0; i < sizeof(tmps_codes); i++) {
		for (r = AS9888_ACC_MIN; r <= AS9888_ACC_MAX; r++) {
			raw_sample(r, raw);
			compensate(&c, raw, tmps_codes[i], out);
			if (accel_raw_recover(&c, out, tmps_codes[i], got, why,
					      sizeof(why)))
				fail_msg("TMPS 0x%02x raw %d: %s", tmps_codes[i], r,
					 why);
			if (memcmp(got, raw, sizeof(raw)))
				fail_msg("TMPS 0x%02x: raw %d %d %d came back as %d %d %d",
					 tmps_codes[i], raw[0], raw[1], raw[2],
					 got[0], got[1], got[2]);
		}
	}
}

/*
 * Counts the samples that a recovery with @wrong (another DAC, another
 * temperature) does not take back to their raw values: the test above
 * must be able to see such a mistake.
 */
static unsigned int misrecovered(const struct accel_comp *wrong, int tmps_delta)
{
	struct accel_comp c;
	int16_t raw[AS9888_AXES], out[AS9888_AXES], got[AS9888_AXES];
	unsigned int bad = 0;
	char why[256];
	int32_t r;

	make_comp(&c);
	for (r = AS9888_ACC_MIN; r <= AS9888_ACC_MAX; r += 16) {
		raw_sample(r, raw);
		compensate(&c, raw, 0xb8, out);
		if (accel_raw_recover(wrong, out, (uint8_t)(0xb8 + tmps_delta),
				      got, why, sizeof(why)) ||
		    memcmp(got, raw, sizeof(raw)))
			bad++;
	}

	return bad;
}

static void wrong_parameters_are_visible(void **state)
{
	struct accel_comp wrong;
	int axis;

	make_comp(&wrong);
	assert_int_equal(misrecovered(&wrong, 0), 0);
	/* the factory DAC value instead of the one in use */
	for (axis = 0; axis < AS9888_AXES; axis++)
		wrong.da[axis] = wrong.ee.axis[axis].da;
	assert_int_equal(misrecovered(&wrong, 0), 256);
	/* another temperature (0x88) instead of the sample's (0xb8) */
	make_comp(&wrong);
	assert_int_equal(misrecovered(&wrong, 0x88 - 0xb8), 256);
	/* one TMPS code off */
	assert_true(misrecovered(&wrong, 1) > 0);
	/* another offset */
	wrong.cal.bias[1] += 8;		/* two chip LSB */
	assert_int_equal(misrecovered(&wrong, 0), 256);
}

/* @out is refused with @err, @why_part in the message, @got untouched */
static void refused(const struct accel_comp *c, const int16_t out[AS9888_AXES],
		    int err, const char *why_part)
{
	int16_t got[AS9888_AXES] = { 1, 2, 3 };
	char why[256];

	assert_int_equal(accel_raw_recover(c, out, 0x88, got, why, sizeof(why)),
			 err);
	if (!strstr(why, why_part))
		fail_msg("\"%s\" does not say \"%s\"", why, why_part);
	assert_int_equal(got[0], 1);
	assert_int_equal(got[1], 2);
	assert_int_equal(got[2], 3);
}

static void saturated_sample_refused(void **state)
{
	static const int16_t raw[AS9888_AXES] = { 100, 200, 300 };
	struct accel_comp c;
	int16_t top[AS9888_AXES], bottom[AS9888_AXES];

	int16_t got[AS9888_AXES];
	char why[256];

	/*
	 * the driver pushes a chip reading at its rail as the output's limit:
	 * it comes back as that rail, for the note's saturation judgment
	 */
	make_comp(&c);
	compensate(&c, raw, 0x88, top);
	compensate(&c, raw, 0x88, bottom);
	top[2] = AS9888_ACC_OUT_MAX;
	bottom[0] = AS9888_ACC_OUT_MIN;
	assert_int_equal(accel_raw_recover(&c, top, 0x88, got, why, sizeof(why)), 0);
	assert_int_equal(got[0], raw[0]);
	assert_int_equal(got[1], raw[1]);
	assert_int_equal(got[2], AS9888_ACC_MAX);
	assert_int_equal(accel_raw_recover(&c, bottom, 0x88, got, why, sizeof(why)), 0);
	assert_int_equal(got[0], AS9888_ACC_MIN);
	assert_int_equal(got[2], raw[2]);
}

/*
 * The inverse is the daemon's own: a value the driver's compensation (as
 * this daemon computes it) does not give is refused, not taken back
 */
static void other_rounding_refused(void **state)
{
	struct accel_comp c;
	int16_t raw[AS9888_AXES] = { 100, -200, 300 }, out[AS9888_AXES];
	int16_t got[AS9888_AXES];
	char why[256];

	make_comp(&c);
	compensate(&c, raw, 0x88, out);
	assert_int_equal(accel_raw_recover(&c, out, 0x88, got, why, sizeof(why)), 0);
	assert_memory_equal(got, raw, sizeof(raw));
	/* one output LSB more is a quarter chip LSB: rounds back to 300 */
	out[2]++;
	refused(&c, out, -ERANGE, "Z reads");
	refused(&c, out, -ERANGE, "the driver does not compensate as this daemon does");
}

static void impossible_sample_refused(void **state)
{
	static const int16_t raw[AS9888_AXES] = { 0, 0, 0 };
	struct accel_comp c;
	int16_t out[AS9888_AXES];

	/* 32000 / 1024 g is about 7800 raw LSB: no chip gives it */
	make_comp(&c);
	compensate(&c, raw, 0x88, out);
	out[1] = 32000;
	refused(&c, out, -ERANGE, "Y reads 32000, which no chip reading gives");
}

static void uncomputable_correction_refused(void **state)
{
	static const int16_t raw[AS9888_AXES] = { 0, 0, 0 };
	struct accel_comp c;
	int16_t out[AS9888_AXES];

	make_comp(&c);
	compensate(&c, raw, 0x88, out);
	c.cal.bias[1] = AS9888_CALIBBIAS_MAX + 1;
	refused(&c, out, -EINVAL, "Y: no offset/sensitivity at TMPS 0x88");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(every_raw_value_comes_back),
		cmocka_unit_test(wrong_parameters_are_visible),
		cmocka_unit_test(saturated_sample_refused),
		cmocka_unit_test(other_rounding_refused),
		cmocka_unit_test(impossible_sample_refused),
		cmocka_unit_test(uncomputable_correction_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
