// SPDX-License-Identifier: GPL-2.0
/*
 * KUnit tests of the AS9888 calibration arithmetic (as9888_calib.c): the
 * EEPROM decoding, every formula of section 6 of the datasheet and the
 * judgments of the application note, against hand-computed values.
 */

#include <kunit/test.h>
#include <linux/array_size.h>
#include <linux/errno.h>
#include <linux/limits.h>
#include <linux/module.h>
#include <linux/string.h>

#include "as9888_calib.h"

#define Q16(x)		((s32)((x) * AS9888_Q16_ONE))

/* The example EEPROM of section 8 of the datasheet */
static const u8 as9888_example_ee[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static void as9888_decode_example(struct kunit *test, struct as9888_eeprom *ee)
{
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(as9888_example_ee, ee), 0);
}

/* EEPROM decoding */

static void as9888_test_decode_example(struct kunit *test)
{
	struct as9888_eeprom ee;

	as9888_decode_example(test, &ee);
	KUNIT_EXPECT_EQ(test, ee.errors, 0);
	KUNIT_EXPECT_EQ(test, ee.warnings, 0);
	KUNIT_EXPECT_EQ(test, memcmp(ee.raw, as9888_example_ee, AS9888_EEPROM_LEN),
			0);
	KUNIT_EXPECT_EQ(test, ee.ref1, 0x9a);
	KUNIT_EXPECT_EQ(test, ee.ref2, 0x71);
	KUNIT_EXPECT_EQ(test, ee.ref3, 0x1d);
	KUNIT_EXPECT_EQ(test, ee.osc, 0x5c);
	/* EREF3[7:3] = 2: t_RT = T(138) = 23.75 degC */
	KUNIT_EXPECT_EQ(test, ee.t_rt_mdegc, 23750);
	/* ET1 0x88 (25 degC), ET2 0x50 (60 degC) */
	KUNIT_EXPECT_EQ(test, ee.delta_t_mdegc, 35000);

	KUNIT_EXPECT_EQ(test, ee.axis[0].ehc, 0x80);
	KUNIT_EXPECT_EQ(test, ee.axis[0].ga, 0x1c);
	KUNIT_EXPECT_EQ(test, ee.axis[0].gain, 28);
	KUNIT_EXPECT_EQ(test, ee.axis[0].da, 0x0d);
	KUNIT_EXPECT_EQ(test, ee.axis[0].dt, 56);
	KUNIT_EXPECT_EQ(test, ee.axis[0].st_rt, 260);
	KUNIT_EXPECT_EQ(test, ee.axis[0].kste_idx, 0);
	/* Kote = 56 * 1.5 / 35 = 2.4 LSB/degC */
	KUNIT_EXPECT_EQ(test, ee.axis[0].kote_num * 10,
			24 * ee.axis[0].kote_den);

	KUNIT_EXPECT_EQ(test, ee.axis[1].ehc, 0x85);
	KUNIT_EXPECT_EQ(test, ee.axis[1].ga, 0x63);
	KUNIT_EXPECT_EQ(test, ee.axis[1].gain, 35);
	KUNIT_EXPECT_EQ(test, ee.axis[1].da, 0x8f);
	KUNIT_EXPECT_EQ(test, ee.axis[1].dt, 230);
	KUNIT_EXPECT_EQ(test, ee.axis[1].st_rt, 261);
	KUNIT_EXPECT_EQ(test, ee.axis[1].kste_idx, 3);

	/* EAZGA 0xa2: DT sign set, so DT = 0x19c - 512 = -100 */
	KUNIT_EXPECT_EQ(test, ee.axis[2].ehc, 0x7b);
	KUNIT_EXPECT_EQ(test, ee.axis[2].ga, 0x22);
	KUNIT_EXPECT_EQ(test, ee.axis[2].gain, 34);
	KUNIT_EXPECT_EQ(test, ee.axis[2].da, 0x8c);
	KUNIT_EXPECT_EQ(test, ee.axis[2].dt, -100);
	KUNIT_EXPECT_EQ(test, ee.axis[2].st_rt, 259);
	KUNIT_EXPECT_EQ(test, ee.axis[2].kste_idx, 6);
	/* Kote = -100 * 1.5 / 35 = -30 / 7 LSB/degC */
	KUNIT_EXPECT_EQ(test, ee.axis[2].kote_num * 7,
			-30 * ee.axis[2].kote_den);
}

/* The Z axis's fields are read from the EAZ* addresses */
static void as9888_test_decode_z_addresses(struct kunit *test)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	KUNIT_EXPECT_EQ(test, AS9888_EE_EAGA(2), 0x49 - 0x40);
	KUNIT_EXPECT_EQ(test, AS9888_EE_EADT(2), 0x4c - 0x40);
	KUNIT_EXPECT_EQ(test, AS9888_EE_EADA(2), 0x4f - 0x40);
	KUNIT_EXPECT_EQ(test, AS9888_EE_EAGTD(2), 0x52 - 0x40);

	memcpy(raw, as9888_example_ee, sizeof(raw));
	raw[AS9888_EE_EAGA(2)] = 0x0b;
	raw[AS9888_EE_EADT(2)] = 0x05;
	raw[AS9888_EE_EADA(2)] = 0x30;
	raw[AS9888_EE_EAGTD(2)] = 0x1f;
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
	KUNIT_EXPECT_EQ(test, ee.axis[2].gain, 11);
	KUNIT_EXPECT_EQ(test, ee.axis[2].dt, 5);
	KUNIT_EXPECT_EQ(test, ee.axis[2].da, 0x30);
	KUNIT_EXPECT_EQ(test, ee.axis[2].st_rt, 255);
	/* X untouched */
	KUNIT_EXPECT_EQ(test, ee.axis[0].gain, 28);
	KUNIT_EXPECT_EQ(test, ee.axis[0].dt, 56);
	KUNIT_EXPECT_EQ(test, ee.axis[0].da, 0x0d);
	KUNIT_EXPECT_EQ(test, ee.axis[0].st_rt, 260);
}

/* Every byte value of the EAxGA and EAxGTD fields, on every axis */
static void as9888_test_decode_fields(struct kunit *test)
{
	int axis, v;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		for (v = 0; v <= U8_MAX; v++) {
			int gain = v & 0x3f, detail = v & 0x1f;
			bool gain_ok = gain >= 7 && gain <= 43;
			struct as9888_eeprom ee;
			u8 raw[AS9888_EEPROM_LEN];

			memcpy(raw, as9888_example_ee, sizeof(raw));
			raw[AS9888_EE_EAGA(axis)] = v;
			raw[AS9888_EE_EAGTD(axis)] = v;
			raw[AS9888_EE_EADT(axis)] = 0x80;
			as9888_eeprom_decode(raw, &ee);
			KUNIT_EXPECT_EQ(test, ee.axis[axis].ga, v & 0x7f);
			KUNIT_EXPECT_EQ(test, ee.axis[axis].gain, gain);
			KUNIT_EXPECT_EQ(test,
					!(ee.errors & (AS9888_EE_ERR_GAIN_X << axis)),
					gain_ok);
			KUNIT_EXPECT_EQ(test, ee.axis[axis].dt,
					(v & 0x80) ? 0x80 - 256 : 0x80);
			KUNIT_EXPECT_EQ(test, ee.axis[axis].st_rt,
					256 + (detail >= 16 ? detail - 32 : detail));
			KUNIT_EXPECT_EQ(test, ee.axis[axis].kste_idx, v >> 5);
		}
	}
}

/* DAC validity (0..67, 128..195) for every byte value on every axis */
static void as9888_test_decode_dac(struct kunit *test)
{
	int axis, v;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		for (v = 0; v <= U8_MAX; v++) {
			bool ok = v <= 67 || (v >= 128 && v <= 195);
			struct as9888_eeprom ee;
			u8 raw[AS9888_EEPROM_LEN];

			memcpy(raw, as9888_example_ee, sizeof(raw));
			raw[AS9888_EE_EADA(axis)] = v;
			KUNIT_EXPECT_EQ(test, as9888_dac_valid(v), ok);
			KUNIT_EXPECT_EQ(test, as9888_eeprom_decode(raw, &ee),
					ok ? 0 : -EINVAL);
			KUNIT_EXPECT_EQ(test, ee.errors,
					ok ? 0 : AS9888_EE_ERR_DAC_X << axis);
		}
	}
}

/* t_RT = T(136 + s5(EREF3[7:3])) and REF3 = 0x18 | EREF3[2:0] */
static void as9888_test_decode_eref3(struct kunit *test)
{
	int v;

	for (v = 0; v <= U8_MAX; v++) {
		int s5 = (v >> 3) >= 16 ? (v >> 3) - 32 : (v >> 3);
		struct as9888_eeprom ee;
		u8 raw[AS9888_EEPROM_LEN];

		memcpy(raw, as9888_example_ee, sizeof(raw));
		raw[AS9888_EE_EREF3] = v;
		KUNIT_EXPECT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
		KUNIT_EXPECT_EQ(test, ee.t_rt_mdegc, (176 - 136 - s5) * 625);
		KUNIT_EXPECT_EQ(test, ee.ref3, 0x18 | (v & 7));
	}
}

static void as9888_test_decode_blank(struct kunit *test)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memset(raw, 0xff, sizeof(raw));
	KUNIT_EXPECT_EQ(test, as9888_eeprom_decode(raw, &ee), -ENODATA);
	KUNIT_EXPECT_TRUE(test, ee.errors & AS9888_EE_ERR_BLANK);
	memset(raw, 0, sizeof(raw));
	KUNIT_EXPECT_EQ(test, as9888_eeprom_decode(raw, &ee), -ENODATA);
	KUNIT_EXPECT_TRUE(test, ee.errors & AS9888_EE_ERR_ZERO);
	KUNIT_EXPECT_STREQ(test, as9888_ee_error_str(AS9888_EE_ERR_BLANK),
			   "EEPROM blank (all bytes 0xff)");
}

/* ET1/ET2 out of range, or a span beyond 10..80 degC: delta-T is 35 degC */
struct as9888_delta_t_case {
	const char *name;
	u8 et1, et2;
	bool fallback;
	s32 delta_mdegc;
};

static const struct as9888_delta_t_case as9888_delta_t_cases[] = {
	{ "factory 25..60 degC", 0x88, 0x50, false, 35000 },
	{ "16 codes = 10 degC kept", 0x88, 0x78, false, 10000 },
	{ "15 codes = 9.375 degC", 0x88, 0x79, true, 35000 },
	{ "128 codes = 80 degC kept", 0xa8, 0x28, false, 80000 },
	{ "80.625 degC", 0xa9, 0x28, true, 35000 },
	{ "ET1 beyond 0xe0", 0xe1, 0x88, true, 35000 },
	{ "ET2 below 0x28", 0x88, 0x27, true, 35000 },
	{ "reversed", 0x50, 0x88, true, 35000 },
	{ "blank", 0xff, 0xff, true, 35000 },
};

static void as9888_delta_t_desc(const struct as9888_delta_t_case *c,
				char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_delta_t, as9888_delta_t_cases, as9888_delta_t_desc);

static void as9888_test_delta_t(struct kunit *test)
{
	const struct as9888_delta_t_case *c = test->param_value;
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memcpy(raw, as9888_example_ee, sizeof(raw));
	raw[AS9888_EE_ET1] = c->et1;
	raw[AS9888_EE_ET2] = c->et2;
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
	KUNIT_EXPECT_EQ(test, !!(ee.warnings & AS9888_EE_WARN_DELTA_T),
			c->fallback);
	KUNIT_EXPECT_EQ(test, ee.delta_t_mdegc, c->delta_mdegc);
	/* X: DT 56, Kote = 56 * 1.5 / dT */
	KUNIT_EXPECT_EQ(test, (s64)ee.axis[0].kote_num * c->delta_mdegc,
			(s64)56 * 1500 * ee.axis[0].kote_den);
}

/* |Kote| > 10.2 LSB/degC is a warning: the EEPROM stays usable */
static void as9888_test_kote_warning(struct kunit *test)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memcpy(raw, as9888_example_ee, sizeof(raw));
	raw[AS9888_EE_EADT(1)] = 238;	/* 10.2 exactly */
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
	KUNIT_EXPECT_FALSE(test, ee.warnings & AS9888_EE_WARN_KOTE_Y);
	raw[AS9888_EE_EADT(1)] = 239;	/* 10.243 */
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
	KUNIT_EXPECT_EQ(test, ee.warnings, AS9888_EE_WARN_KOTE_Y);
	/* Negative on Z: sign bit set, DT = -239 */
	raw[AS9888_EE_EADT(1)] = 0xe6;
	raw[AS9888_EE_EAGA(2)] |= 0x80;
	raw[AS9888_EE_EADT(2)] = 256 - 239;
	KUNIT_ASSERT_EQ(test, as9888_eeprom_decode(raw, &ee), 0);
	KUNIT_EXPECT_EQ(test, ee.axis[2].dt, -239);
	KUNIT_EXPECT_EQ(test, ee.warnings, AS9888_EE_WARN_KOTE_Z);
}

/* Temperature, section 5: T = (176 - TMPS) / 1.6 degC */
struct as9888_tmps_case {
	const char *name;
	u8 tmps;
	s32 mdegc;
	bool valid;
};

static const struct as9888_tmps_case as9888_tmps_cases[] = {
	{ "0 degC", 176, 0, true },
	{ "85 degC, first valid", 0x28, 85000, true },
	{ "-30 degC, last valid", 0xe0, -30000, true },
	{ "25 degC", 136, 25000, true },
	{ "one code", 137, 24375, true },
	{ "below range", 0x27, 85625, false },
	{ "beyond range", 0xe1, -30625, false },
	{ "code 0", 0, 110000, false },
	{ "code 255", 255, -49375, false },
};

static void as9888_tmps_desc(const struct as9888_tmps_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_tmps, as9888_tmps_cases, as9888_tmps_desc);

static void as9888_test_tmps(struct kunit *test)
{
	const struct as9888_tmps_case *c = test->param_value;

	KUNIT_EXPECT_EQ(test, as9888_tmps_to_mdegc(c->tmps), c->mdegc);
	KUNIT_EXPECT_EQ(test, as9888_tmps_valid(c->tmps), c->valid);
}

/* Magnetometer, section 5: H * (EHC + 128) / 256 */
struct as9888_mag_case {
	const char *name;
	s16 h;
	u8 ehc;
	s32 adj_q8;
	bool overflow;
};

static const struct as9888_mag_case as9888_mag_cases[] = {
	{ "EHC 128 is 1", 100, 128, 100 * 256, false },
	{ "EHC 0 halves", 100, 0, 50 * 256, false },
	{ "EHC 255", -4096, 255, -4096 * 383, true },
	{ "max", 4095, 128, 4095 * 256, true },
	{ "one below max", 4094, 128, 4094 * 256, false },
	{ "one above min", -4095, 128, -4095 * 256, false },
	{ "odd product", 7, 1, 7 * 129, false },
};

static void as9888_mag_desc(const struct as9888_mag_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_mag, as9888_mag_cases, as9888_mag_desc);

static void as9888_test_mag(struct kunit *test)
{
	const struct as9888_mag_case *c = test->param_value;

	KUNIT_EXPECT_EQ(test, as9888_mag_adjust_q8(c->h, c->ehc), c->adj_q8);
	KUNIT_EXPECT_EQ(test, as9888_mag_overflow(c->h), c->overflow);
}

/* The self-test windows on the adjusted value, bounds included */
struct as9888_selftest_case {
	const char *name;
	int axis;
	s16 h;
	u8 ehc;
	bool ok;
};

static const struct as9888_selftest_case as9888_selftest_cases[] = {
	{ "X at -100", 0, -100, 128, true },
	{ "X at -101", 0, -101, 128, false },
	{ "Y at 100", 1, 100, 128, true },
	{ "Y at 101", 1, 101, 128, false },
	{ "Z at 300", 2, 300, 128, true },
	{ "Z at 299", 2, 299, 128, false },
	{ "Z at 1000", 2, 1000, 128, true },
	{ "Z at 1001", 2, 1001, 128, false },
	{ "Z 600 halved is 300", 2, 600, 0, true },
	{ "Z 599 halved is 299.5", 2, 599, 0, false },
	{ "Z 784 adjusted is 1172.9", 2, 784, 255, false },
	{ "X 150 halved is 75", 0, 150, 0, true },
	{ "overflow never passes", 2, 4095, 0, false },
	{ "no axis 3", 3, 0, 128, false },
	{ "weak Z of a faulty unit", 2, 150, 128, false },
};

static void as9888_selftest_desc(const struct as9888_selftest_case *c,
				 char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_selftest, as9888_selftest_cases,
		  as9888_selftest_desc);

static void as9888_test_selftest(struct kunit *test)
{
	const struct as9888_selftest_case *c = test->param_value;

	KUNIT_EXPECT_EQ(test, as9888_selftest_ok(c->axis, c->h, c->ehc), c->ok);
}

/* The windows alone, on adjusted Q8 readings: both edges belong to them */
static void as9888_test_selftest_window(struct kunit *test)
{
	KUNIT_EXPECT_TRUE(test, as9888_selftest_window_ok(0, -100 * AS9888_Q8_ONE));
	KUNIT_EXPECT_FALSE(test,
			   as9888_selftest_window_ok(0, -100 * AS9888_Q8_ONE - 1));
	KUNIT_EXPECT_TRUE(test, as9888_selftest_window_ok(1, 100 * AS9888_Q8_ONE));
	KUNIT_EXPECT_FALSE(test,
			   as9888_selftest_window_ok(1, 100 * AS9888_Q8_ONE + 1));
	KUNIT_EXPECT_TRUE(test, as9888_selftest_window_ok(2, 300 * AS9888_Q8_ONE));
	KUNIT_EXPECT_FALSE(test,
			   as9888_selftest_window_ok(2, 300 * AS9888_Q8_ONE - 1));
	KUNIT_EXPECT_TRUE(test, as9888_selftest_window_ok(2, 1000 * AS9888_Q8_ONE));
	KUNIT_EXPECT_FALSE(test,
			   as9888_selftest_window_ok(2, 1000 * AS9888_Q8_ONE + 1));
	KUNIT_EXPECT_FALSE(test, as9888_selftest_window_ok(-1, 0));
}

/* Adjusted readings in thousandths (the self-test's debugfs file) */
static void as9888_test_q8_to_milli(struct kunit *test)
{
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(0), 0);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(AS9888_Q8_ONE), 1000);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(-AS9888_Q8_ONE), -1000);
	/* 1/256 = 0.00390625 */
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(1), 4);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(-1), -4);
	/* 16/256 = 0.0625 and 48/256 = 0.1875: ties to even */
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(16), 62);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(48), 188);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(-16), -62);
	/* The largest adjusted reading, 4095 * (255 + 128), and beyond */
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(4095 * 383), 6126504);
	KUNIT_EXPECT_EQ(test, as9888_q8_to_milli(S32_MIN), -8388608000LL);
}

/* The trim the decoder accepts, and nothing beyond it */
static void as9888_test_trim_valid(struct kunit *test)
{
	struct as9888_eeprom ee;
	struct as9888_axis_trim t;

	as9888_decode_example(test, &ee);
	t = ee.axis[0];
	KUNIT_EXPECT_TRUE(test, as9888_trim_valid(&t));
	t.st_rt = 256 - 16;
	KUNIT_EXPECT_TRUE(test, as9888_trim_valid(&t));
	t.st_rt = 256 + 15;
	KUNIT_EXPECT_TRUE(test, as9888_trim_valid(&t));
	t.st_rt = 256 - 17;
	KUNIT_EXPECT_FALSE(test, as9888_trim_valid(&t));
	t.st_rt = 256 + 16;
	KUNIT_EXPECT_FALSE(test, as9888_trim_valid(&t));
	t = ee.axis[0];
	t.kste_idx = 8;
	KUNIT_EXPECT_FALSE(test, as9888_trim_valid(&t));
	t = ee.axis[0];
	t.kote_den = 0;
	KUNIT_EXPECT_FALSE(test, as9888_trim_valid(&t));
}

/* 6.3, 6.4: St(t) = St_RT * (1 + Kste / 100 * (t - t_RT)) */
struct as9888_st_case {
	const char *name;
	int axis;
	s32 t_mdegc;
	int ret;
	s32 st_q16;
};

static const struct as9888_st_case as9888_st_cases[] = {
	{ "X at t_RT is St_RT", 0, 23750, 0, 260 * AS9888_Q16_ONE },
	/* 260 * (1 - 0.00428125 * 36.25) = 219.64921875 */
	{ "X at 60 degC", 0, 60000, 0, 14394931 },
	/* 261 * (1 + 0.00296875 * 53.75) = 302.6478515625 */
	{ "Y at -30 degC", 1, -30000, 0, 19834330 },
	/* 259 * (1 - 0.00165625 * 61.25) = 232.7256640625 */
	{ "Z at 85 degC", 2, 85000, 0, 15251909 },
	{ "beyond 150 degC", 1, 150001, -ERANGE, 0 },
	{ "below -100 degC", 1, -100001, -ERANGE, 0 },
};

static void as9888_st_desc(const struct as9888_st_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_st, as9888_st_cases, as9888_st_desc);

static void as9888_test_sensitivity(struct kunit *test)
{
	const struct as9888_st_case *c = test->param_value;
	struct as9888_eeprom ee;
	s32 st = 0;

	as9888_decode_example(test, &ee);
	KUNIT_ASSERT_EQ(test, as9888_sensitivity_q16(&ee.axis[c->axis],
						     ee.t_rt_mdegc, c->t_mdegc,
						     &st), c->ret);
	if (!c->ret)
		KUNIT_EXPECT_EQ(test, st, c->st_q16);
}

static void as9888_test_sensitivity_bad_trim(struct kunit *test)
{
	struct as9888_eeprom ee;
	s32 st;

	as9888_decode_example(test, &ee);
	ee.axis[1].st_rt = 300;
	KUNIT_EXPECT_EQ(test, as9888_sensitivity_q16(&ee.axis[1],
						     ee.t_rt_mdegc, 0, &st),
			-EINVAL);
}

/* 6.5: Ot(t) = Kote * (t - t_L) + Ot_L */
struct as9888_offset_case {
	const char *name;
	int axis;
	s32 ot_l_q16, t_l_mdegc, t_mdegc;
	int ret;
	s32 ot_q16;
};

static const struct as9888_offset_case as9888_offset_cases[] = {
	/* -30/7 * (60 - 26.25) + 12.5 = -132.142857 */
	{ "Z at 60 degC", 2, Q16(12) + Q16(1) / 2, 26250, 60000, 0, -8660114 },
	{ "Z at t_L is Ot_L", 2, 777, 26250, 26250, 0, 777 },
	/* 2.4 * (0 - 25) - 3 = -63 */
	{ "X at 0 degC", 0, Q16(-3), 25000, 0, 0, Q16(-63) },
	{ "below -100 degC", 2, 0, 26250, -100001, -ERANGE, 0 },
};

static void as9888_offset_desc(const struct as9888_offset_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_offset, as9888_offset_cases, as9888_offset_desc);

static void as9888_test_offset(struct kunit *test)
{
	const struct as9888_offset_case *c = test->param_value;
	struct as9888_eeprom ee;
	s32 ot = 0;

	as9888_decode_example(test, &ee);
	KUNIT_ASSERT_EQ(test, as9888_offset_q16(&ee.axis[c->axis], c->ot_l_q16,
						c->t_l_mdegc, c->t_mdegc, &ot),
			c->ret);
	if (!c->ret)
		KUNIT_EXPECT_EQ(test, ot, c->ot_q16);
}

/* 6.7 on the driver's constant output scale, AS9888_ACC_OUT_PER_G per g */
struct as9888_comp_case {
	const char *name;
	s16 raw;
	s32 ot_q16, st_q16;
	int ret;
	s16 out;
};

static const struct as9888_comp_case as9888_comp_cases[] = {
	{ "1 g", 272, Q16(16), Q16(256), 0, 1024 },
	{ "-1 g", -240, Q16(16), Q16(256), 0, -1024 },
	{ "rounded up", 1, 0, Q16(260), 0, 4 },		/* 3.938 */
	{ "rounded down", 0, Q16(1) / 2, Q16(300), 0, -2 },	/* -1.707 */
	/* half-way cases round up: a calibbias moves the result exactly */
	{ "2.5 up", 0, -Q16(5) / 8, Q16(256), 0, 3 },
	{ "-1.5 up", 0, Q16(3) / 8, Q16(256), 0, -1 },
	{ "clamped high", 2047, Q16(-2000), Q16(100), -ERANGE, 32767 },
	{ "clamped low", -2048, Q16(2000), Q16(100), -ERANGE, -32768 },
	{ "zero St", 1, 0, 0, -EINVAL, 0 },
};

static void as9888_comp_desc(const struct as9888_comp_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_comp, as9888_comp_cases, as9888_comp_desc);

static void as9888_test_compensate(struct kunit *test)
{
	const struct as9888_comp_case *c = test->param_value;
	s16 out = 0;

	KUNIT_ASSERT_EQ(test, as9888_accel_compensate(c->raw, c->ot_q16,
						      c->st_q16, &out), c->ret);
	if (c->ret != -EINVAL)
		KUNIT_EXPECT_EQ(test, out, c->out);
}

/* Offset and sensitivity of an axis now, on the example EEPROM's X axis */
static void as9888_test_correction(struct kunit *test)
{
	struct as9888_accel_cal cal = { };
	struct as9888_eeprom ee;
	s32 ot, st;
	u8 da_up;

	as9888_decode_example(test, &ee);
	da_up = as9888_lin2dac(ee.axis[0].ga,
			       as9888_dac2lin(ee.axis[0].ga, ee.axis[0].da) + 1);

	/* The factory's state at t_RT: no offset, St_RT = 260 */
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 23750,
						      &ot, &st), 0);
	KUNIT_EXPECT_EQ(test, ot, 0);
	KUNIT_EXPECT_EQ(test, st, Q16(260));

	/* 10 degC warmer: Kote 2.4 LSB/degC, St = 260 * (1 - 0.0428125) */
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 33750,
						      &ot, &st), 0);
	KUNIT_EXPECT_EQ(test, ot, Q16(24));
	KUNIT_EXPECT_EQ(test, st, 16309862);

	/* One DAC code up moves the output by 2048 / 44 LSB */
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0, da_up,
						      33750, &ot, &st), 0);
	KUNIT_EXPECT_EQ(test, ot, 4623267);

	/* calibbias 1 g: an offset of -St_RT at t_RT, then Kote on top */
	cal.bias[0] = AS9888_ACC_OUT_PER_G;
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 23750,
						      &ot, &st), 0);
	KUNIT_EXPECT_EQ(test, ot, Q16(-260));
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 33750,
						      &ot, &st), 0);
	KUNIT_EXPECT_EQ(test, ot, Q16(-260 + 24));

	cal.bias[0] = AS9888_CALIBBIAS_MAX + 1;
	KUNIT_EXPECT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 33750,
						      &ot, &st), -ERANGE);
	cal.bias[0] = 0;
	KUNIT_EXPECT_EQ(test, as9888_accel_correction(&ee, &cal, 3,
						      ee.axis[0].da, 33750,
						      &ot, &st), -EINVAL);
}

/*
 * At t_RT a calibbias moves the compensated reading by exactly its value,
 * for every raw reading and every DAC value; elsewhere by bias * St_RT /
 * St(t) before rounding, as an offset in the chip does.
 */
static void as9888_test_bias_moves_output(struct kunit *test)
{
	static const s32 biases[] = {
		1, -1, 7, -300, 1024, -2047, AS9888_CALIBBIAS_MAX,
		-AS9888_CALIBBIAS_MAX,
	};
	struct as9888_accel_cal cal = { };
	struct as9888_eeprom ee;
	s32 ot0, ot, st0, st;
	s16 out0, out;
	unsigned int i;
	int raw, lin;
	u8 da;

	as9888_decode_example(test, &ee);
	for (lin = -AS9888_DAC_LIN_MAX; lin <= AS9888_DAC_LIN_MAX; lin += 19) {
		da = as9888_lin2dac(ee.axis[1].ga, lin);
		for (i = 0; i < ARRAY_SIZE(biases); i++) {
			cal.bias[1] = 0;
			KUNIT_ASSERT_EQ(test,
					as9888_accel_correction(&ee, &cal, 1, da,
								ee.t_rt_mdegc,
								&ot0, &st0), 0);
			cal.bias[1] = biases[i];
			KUNIT_ASSERT_EQ(test,
					as9888_accel_correction(&ee, &cal, 1, da,
								ee.t_rt_mdegc,
								&ot, &st), 0);
			KUNIT_ASSERT_EQ(test, st, st0);
			for (raw = AS9888_ACC_MIN + 1; raw < AS9888_ACC_MAX;
			     raw += 97) {
				if (as9888_accel_compensate(raw, ot0, st0, &out0) ||
				    as9888_accel_compensate(raw, ot, st, &out))
					continue;
				KUNIT_ASSERT_EQ(test, out - out0, biases[i]);
			}
		}
	}

	/*
	 * A half-way case: Y at DAC code -67 reads -1956, which compensates
	 * to 518.5 exactly; 519 and 520 with the calibbias 1 (ties to even
	 * would give 518 and 520)
	 */
	da = as9888_lin2dac(ee.axis[1].ga, -AS9888_DAC_LIN_MAX);
	cal.bias[1] = 0;
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 1, da,
						      ee.t_rt_mdegc, &ot0, &st0), 0);
	KUNIT_ASSERT_EQ(test, as9888_accel_compensate(-1956, ot0, st0, &out0), 0);
	KUNIT_EXPECT_EQ(test, out0, 519);
	cal.bias[1] = 1;
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 1, da,
						      ee.t_rt_mdegc, &ot, &st), 0);
	KUNIT_ASSERT_EQ(test, as9888_accel_compensate(-1956, ot, st, &out), 0);
	KUNIT_EXPECT_EQ(test, out, 520);
	cal.bias[1] = 0;

	/* 10 degC warmer the same offset reads St_RT / St(t) times larger */
	cal.bias[0] = -1024;
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 33750,
						      &ot, &st), 0);
	KUNIT_ASSERT_EQ(test, as9888_accel_compensate(0, ot, st, &out), 0);
	cal.bias[0] = 0;
	KUNIT_ASSERT_EQ(test, as9888_accel_correction(&ee, &cal, 0,
						      ee.axis[0].da, 33750,
						      &ot0, &st0), 0);
	KUNIT_ASSERT_EQ(test, as9888_accel_compensate(0, ot0, st0, &out0), 0);
	/* -1024 * 260 / 248.868 = -1069.8 */
	KUNIT_EXPECT_EQ(test, out - out0, -1070);
}

/* The DAC that realises a calibbias: DACopt for its offset at t_RT */
static void as9888_test_bias_dac(struct kunit *test)
{
	struct as9888_axis_trim trim;
	struct as9888_eeprom ee;
	s32 ot;
	u8 da;

	as9888_decode_example(test, &ee);
	trim = ee.axis[0];

	/* No calibbias: the factory DAC value (linear code -13) */
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, 0, &da), 0);
	KUNIT_EXPECT_EQ(test, da, trim.da);

	/* -367: 93.2 LSB at St_RT 260, 2.002 codes of 2048 / 44: -15 */
	KUNIT_ASSERT_EQ(test, as9888_bias_offset_q16(&trim, -367, &ot), 0);
	KUNIT_EXPECT_EQ(test, ot, 367 * 260 * 64);
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, -367, &da), 0);
	KUNIT_EXPECT_EQ(test, da, 15);
	/* -366 is 1.997 codes: the same; -256 (65 LSB) is 1.4: -14 */
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, -366, &da), 0);
	KUNIT_EXPECT_EQ(test, da, 15);
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, -256, &da), 0);
	KUNIT_EXPECT_EQ(test, da, 14);
	/* The other way: +2 codes of offset down is linear code -11 */
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, 367, &da), 0);
	KUNIT_EXPECT_EQ(test, da, 11);

	/* Beyond the DAC's range the DAC is clamped, the bias still taken */
	trim.da = AS9888_DAC_ZERO + 60;
	KUNIT_ASSERT_EQ(test, as9888_bias_dac(&trim, AS9888_CALIBBIAS_MAX,
					      &da), 0);
	KUNIT_EXPECT_EQ(test, da, AS9888_DAC_POS_MAX);

	KUNIT_EXPECT_EQ(test, as9888_bias_dac(&trim, AS9888_CALIBBIAS_MAX + 1,
					      &da), -ERANGE);
	KUNIT_EXPECT_EQ(test, as9888_bias_dac(&trim, -AS9888_CALIBBIAS_MAX - 1,
					      &da), -ERANGE);
	trim.st_rt = 0;
	KUNIT_EXPECT_EQ(test, as9888_bias_dac(&trim, 0, &da), -EINVAL);
}

/* The optimal DAC code: rounded to nearest, ties to even, then clamped */
struct as9888_dac_opt_case {
	const char *name;
	u8 ga, da, ee_gain;
	s32 ot_l_q16;
	int ret;
	u8 opt;
};

static const struct as9888_dac_opt_case as9888_dac_opt_cases[] = {
	/* lin -13 - rint(44 / 2048 * 100 = 2.148) = -15 */
	{ "X", 0x1c, 0x0d, 28, Q16(100), 0, 15 },
	/* polarity: lin -15 - rint(51 / 2048 * -40.2 = -1.001) = -14 */
	{ "Y with polarity", 0x63, 0x8f, 35, -2634547, 0, 0x8e },
	{ "tie 0.5 to 0", 0x10, 0x80, 16, Q16(32), 0, 0x80 },
	{ "tie 1.5 to 2", 0x10, 0x80, 16, Q16(96), 0, 2 },
	{ "tie 2.5 to 2", 0x10, 0x80, 16, Q16(160), 0, 2 },
	{ "just above a tie", 0x10, 0x80, 16, Q16(32) + 1, 0, 1 },
	{ "clamped low", 0x1c, 0x0d, 28, Q16(3000), -ERANGE, 67 },
	{ "clamped high", 0x1c, 0xc3, 28, Q16(-3000), -ERANGE, 0x80 + 67 },
};

static void as9888_dac_opt_desc(const struct as9888_dac_opt_case *c,
				char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_dac_opt, as9888_dac_opt_cases, as9888_dac_opt_desc);

static void as9888_test_dac_opt(struct kunit *test)
{
	const struct as9888_dac_opt_case *c = test->param_value;
	u8 opt = 0;

	KUNIT_EXPECT_EQ(test, as9888_dac_opt(c->ga, c->da, c->ee_gain,
					     c->ot_l_q16, &opt), c->ret);
	KUNIT_EXPECT_EQ(test, opt, c->opt);
}

/* Accelerometer saturation (section 5): the output's rails */
static void as9888_test_acc_saturated(struct kunit *test)
{
	KUNIT_EXPECT_TRUE(test, as9888_acc_saturated(AS9888_ACC_MIN));
	KUNIT_EXPECT_TRUE(test, as9888_acc_saturated(AS9888_ACC_MAX));
	KUNIT_EXPECT_FALSE(test, as9888_acc_saturated(AS9888_ACC_MIN + 1));
	KUNIT_EXPECT_FALSE(test, as9888_acc_saturated(AS9888_ACC_MAX - 1));
	KUNIT_EXPECT_FALSE(test, as9888_acc_saturated(0));
}

/* 6.6: DAC register values and linear codes */
struct as9888_dac_case {
	const char *name;
	u8 ga, da;
	int lin;
};

static const struct as9888_dac_case as9888_dac_cases[] = {
	{ "zero", 0x1c, 0x80, 0 },
	{ "negative", 0x1c, 0x0d, -13 },
	{ "positive max", 0x1c, 0xc3, 67 },
	{ "negative max", 0x1c, 67, -67 },
	{ "polarity, negative", 0x63, 0x8f, -15 },
	{ "polarity, positive", 0x63, 0x0d, 13 },
	{ "polarity, max", 0x5c, 0xc3, -67 },
};

static void as9888_dac_desc(const struct as9888_dac_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_dac, as9888_dac_cases, as9888_dac_desc);

static void as9888_test_dac(struct kunit *test)
{
	const struct as9888_dac_case *c = test->param_value;

	KUNIT_EXPECT_EQ(test, as9888_dac2lin(c->ga, c->da), c->lin);
	KUNIT_EXPECT_EQ(test, as9888_lin2dac(c->ga, c->lin), c->da);
}

/* Both directions for every code, both polarities, and the clamping */
static void as9888_test_dac_round_trip(struct kunit *test)
{
	static const u8 gas[] = { 0x1c, 0x5c, 0x07, 0x6b };
	unsigned int i;
	int lin, da;

	for (i = 0; i < ARRAY_SIZE(gas); i++) {
		for (lin = -AS9888_DAC_LIN_MAX; lin <= AS9888_DAC_LIN_MAX; lin++) {
			u8 reg = as9888_lin2dac(gas[i], lin);

			KUNIT_EXPECT_TRUE(test, as9888_dac_valid(reg));
			KUNIT_EXPECT_EQ(test, as9888_dac2lin(gas[i], reg), lin);
		}
		/* 0x00 is a second zero: it maps back to 0x80 */
		for (da = 1; da <= U8_MAX; da++) {
			if (!as9888_dac_valid(da))
				continue;
			KUNIT_EXPECT_EQ(test,
					as9888_lin2dac(gas[i],
						       as9888_dac2lin(gas[i], da)),
					da);
		}
		KUNIT_EXPECT_EQ(test, as9888_dac2lin(gas[i], 0), 0);
		KUNIT_EXPECT_EQ(test, as9888_lin2dac(gas[i], 500),
				as9888_lin2dac(gas[i], AS9888_DAC_LIN_MAX));
		KUNIT_EXPECT_EQ(test, as9888_lin2dac(gas[i], -500),
				as9888_lin2dac(gas[i], -AS9888_DAC_LIN_MAX));
	}
}

static void as9888_test_dac_step(struct kunit *test)
{
	/* 2048 / (28 + 16) = 46.545 LSB per code */
	KUNIT_EXPECT_EQ(test, as9888_dac_step_q16(0x1c), 3050403);
	/* The polarity bit does not change the step: 2048 / 48 */
	KUNIT_EXPECT_EQ(test, as9888_dac_step_q16(0x60), 2796203);
	/* 2048 / 23 */
	KUNIT_EXPECT_EQ(test, as9888_dac_step_q16(0x07), 5835553);
}

/* Rounding to nearest, ties to even */
struct as9888_round_case {
	const char *name;
	s64 num, den, q;
};

static const struct as9888_round_case as9888_round_cases[] = {
	{ "2.5 to 2", 5, 2, 2 },
	{ "3.5 to 4", 7, 2, 4 },
	{ "-2.5 to -2", -5, 2, -2 },
	{ "-3.5 to -4", -7, 2, -4 },
	{ "-2.67 to -3", -8, 3, -3 },
	{ "2.67 to 3", 8, 3, 3 },
	{ "2.33 to 2", 7, 3, 2 },
	{ "S64_MIN", S64_MIN, 1, S64_MIN },
	{ "zero divisor", 1, 0, 0 },
};

static void as9888_round_desc(const struct as9888_round_case *c, char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_round, as9888_round_cases, as9888_round_desc);

static void as9888_test_round(struct kunit *test)
{
	const struct as9888_round_case *c = test->param_value;

	KUNIT_EXPECT_EQ(test, as9888_div_round_s64(c->num, c->den), c->q);
}

/* Magnetometer scale: 3 * (EHC + 128) / 256000 G per LSB */
static void as9888_test_mag_scale(struct kunit *test)
{
	KUNIT_EXPECT_EQ(test, AS9888_MAGN_SCALE_DEN, 256000);
	/* EHC 128: 768 / 256000 = 0.003 G = 0.3 uT */
	KUNIT_EXPECT_EQ(test, as9888_mag_scale_num(128), 768);
	KUNIT_EXPECT_EQ(test, as9888_mag_scale_num(0), 384);
	KUNIT_EXPECT_EQ(test, as9888_mag_scale_num(255), 1149);
	/* The same factor as the sensitivity adjustment */
	KUNIT_EXPECT_EQ(test, as9888_mag_scale_num(0x85) * AS9888_Q8_ONE,
			AS9888_MAGN_SCALE_NUM * as9888_mag_adjust_q8(256, 0x85));
}

/* Magnetometer calibration: rint((H + calibbias) * calibscale) */
struct as9888_magn_cal_case {
	const char *name;
	s16 h;
	s32 bias;
	s32 scale_micro;
	int ret;
	s16 out;
};

#define AS9888_MAGN_UNTOUCHED	0x5a5a

static const struct as9888_magn_cal_case as9888_magn_cal_cases[] = {
	{ "defaults: the count", 67, 0, 1000000, 0, 67 },
	{ "defaults: negative count", -136, 0, 1000000, 0, -136 },
	{ "bias adds", 67, -100, 1000000, 0, -33 },
	{ "scale after bias", 100, 20, 1500000, 0, 180 },
	{ "scale below 1", -250, 50, 750000, 0, -150 },
	{ "1.5 to 2 (even)", 3, 0, 500000, 0, 2 },
	{ "2.5 to 2 (even)", 5, 0, 500000, 0, 2 },
	{ "-2.5 to -2 (even)", -5, 0, 500000, 0, -2 },
	{ "-3.5 to -4 (even)", -7, 0, 500000, 0, -4 },
	{ "1023.5 to 1024", 2047, 0, 500000, 0, 1024 },
	{ "1.999999 to 2", 1, 0, 1999999, 0, 2 },
	{ "7.000007 to 7", 7, 0, 1000001, 0, 7 },
	{ "bias cancels a large offset", 4000, -4096, 2000000, 0, -192 },
	{ "sum 0", 1234, -1234, 1999999, 0, 0 },
	{ "top of the output range", 4094, 0, 1000000, 0, 4094 },
	{ "bottom of the output range", -4095, 0, 1000000, 0, -4095 },
	{ "beyond the top", 4094, 1, 1000000, -ERANGE, 4095 },
	{ "beyond the bottom", -4095, -1, 1000000, -ERANGE, -4096 },
	{ "scaled beyond the top", 2048, 0, 2000000, -ERANGE, 4095 },
	{ "largest product", 4094, 4096, 2000000, -ERANGE, 4095 },
	{ "smallest product", -4095, -4096, 2000000, -ERANGE, -4096 },
	{ "count at the top rail", 4095, -4096, 500000, -ERANGE, 4095 },
	{ "count at the bottom rail", -4096, 4096, 500000, -ERANGE, -4096 },
	{ "bias too large", 10, 4097, 1000000, -EINVAL, AS9888_MAGN_UNTOUCHED },
	{ "bias too small", 10, -4097, 1000000, -EINVAL,
	  AS9888_MAGN_UNTOUCHED },
	{ "scale too small", 10, 0, 499999, -EINVAL, AS9888_MAGN_UNTOUCHED },
	{ "scale too large", 10, 0, 2000001, -EINVAL, AS9888_MAGN_UNTOUCHED },
	{ "scale 0", 10, 0, 0, -EINVAL, AS9888_MAGN_UNTOUCHED },
};

static void as9888_magn_cal_desc(const struct as9888_magn_cal_case *c,
				 char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_magn_cal, as9888_magn_cal_cases,
		  as9888_magn_cal_desc);

static void as9888_test_magn_calibrate(struct kunit *test)
{
	const struct as9888_magn_cal_case *c = test->param_value;
	s16 out = AS9888_MAGN_UNTOUCHED;

	KUNIT_EXPECT_EQ(test, as9888_magn_calibrate(c->h, c->bias,
						    c->scale_micro, &out),
			c->ret);
	KUNIT_EXPECT_EQ(test, out, c->out);
}

/* Every count with the defaults is the count, or -ERANGE at the rails */
static void as9888_test_magn_calibrate_identity(struct kunit *test)
{
	struct as9888_magn_cal cal;
	int h, ret;
	s16 out;

	memset(&cal, 0xa5, sizeof(cal));
	as9888_magn_cal_init(&cal);
	for (h = AS9888_MAG_MIN; h <= AS9888_MAG_MAX; h++) {
		ret = as9888_magn_calibrate(h, cal.bias[1], cal.scale_micro[1],
					    &out);
		KUNIT_EXPECT_EQ(test, out, h);
		KUNIT_EXPECT_EQ(test, ret, as9888_mag_overflow(h) ? -ERANGE : 0);
	}
}

static void as9888_test_magn_cal_init(struct kunit *test)
{
	struct as9888_magn_cal cal;
	int axis;

	memset(&cal, 0xff, sizeof(cal));
	as9888_magn_cal_init(&cal);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		KUNIT_EXPECT_EQ(test, cal.bias[axis], 0);
		KUNIT_EXPECT_EQ(test, cal.scale_micro[axis], 1000000);
	}
}

/* calibscale as IIO_VAL_INT_PLUS_MICRO hands it, and calibbias */
struct as9888_calibscale_case {
	const char *name;
	int val, val2;
	int ret;
	s32 micro;
};

static const struct as9888_calibscale_case as9888_calibscale_cases[] = {
	{ "1", 1, 0, 0, 1000000 },
	{ "0.5 (lowest)", 0, 500000, 0, 500000 },
	{ "2 (highest)", 2, 0, 0, 2000000 },
	{ "1.999999", 1, 999999, 0, 1999999 },
	{ "1.000001", 1, 1, 0, 1000001 },
	{ "0.499999", 0, 499999, -EINVAL, -1 },
	{ "2.000001", 2, 1, -EINVAL, -1 },
	{ "0", 0, 0, -EINVAL, -1 },
	{ "-0.5", 0, -500000, -EINVAL, -1 },
	{ "-1.5", -1, 500000, -EINVAL, -1 },
	{ "3", 3, 0, -EINVAL, -1 },
	{ "INT_MAX", INT_MAX, 0, -EINVAL, -1 },
	{ "INT_MIN", INT_MIN, 0, -EINVAL, -1 },
	{ "micro part 10^6", 0, 1000000, -EINVAL, -1 },
	{ "micro part INT_MAX", 1, INT_MAX, -EINVAL, -1 },
};

static void as9888_calibscale_desc(const struct as9888_calibscale_case *c,
				   char *desc)
{
	strscpy(desc, c->name, KUNIT_PARAM_DESC_SIZE);
}

KUNIT_ARRAY_PARAM(as9888_calibscale, as9888_calibscale_cases,
		  as9888_calibscale_desc);

static void as9888_test_magn_calibscale(struct kunit *test)
{
	const struct as9888_calibscale_case *c = test->param_value;
	s32 micro = -1;

	KUNIT_EXPECT_EQ(test, as9888_magn_calibscale_micro(c->val, c->val2,
							   &micro),
			c->ret);
	KUNIT_EXPECT_EQ(test, micro, c->micro);
}

static void as9888_test_magn_calibbias(struct kunit *test)
{
	KUNIT_EXPECT_TRUE(test, as9888_magn_calibbias_valid(0));
	KUNIT_EXPECT_TRUE(test, as9888_magn_calibbias_valid(4096));
	KUNIT_EXPECT_TRUE(test, as9888_magn_calibbias_valid(-4096));
	KUNIT_EXPECT_FALSE(test, as9888_magn_calibbias_valid(4097));
	KUNIT_EXPECT_FALSE(test, as9888_magn_calibbias_valid(-4097));
	KUNIT_EXPECT_FALSE(test, as9888_magn_calibbias_valid(S64_MAX));
	KUNIT_EXPECT_FALSE(test, as9888_magn_calibbias_valid(S64_MIN));
}

static struct kunit_case as9888_calib_test_cases[] = {
	KUNIT_CASE(as9888_test_decode_example),
	KUNIT_CASE(as9888_test_decode_z_addresses),
	KUNIT_CASE(as9888_test_decode_fields),
	KUNIT_CASE(as9888_test_decode_dac),
	KUNIT_CASE(as9888_test_decode_eref3),
	KUNIT_CASE(as9888_test_decode_blank),
	KUNIT_CASE_PARAM(as9888_test_delta_t, as9888_delta_t_gen_params),
	KUNIT_CASE(as9888_test_kote_warning),
	KUNIT_CASE_PARAM(as9888_test_tmps, as9888_tmps_gen_params),
	KUNIT_CASE_PARAM(as9888_test_mag, as9888_mag_gen_params),
	KUNIT_CASE_PARAM(as9888_test_selftest, as9888_selftest_gen_params),
	KUNIT_CASE(as9888_test_selftest_window),
	KUNIT_CASE(as9888_test_q8_to_milli),
	KUNIT_CASE(as9888_test_trim_valid),
	KUNIT_CASE_PARAM(as9888_test_sensitivity, as9888_st_gen_params),
	KUNIT_CASE(as9888_test_sensitivity_bad_trim),
	KUNIT_CASE_PARAM(as9888_test_offset, as9888_offset_gen_params),
	KUNIT_CASE_PARAM(as9888_test_compensate, as9888_comp_gen_params),
	KUNIT_CASE(as9888_test_correction),
	KUNIT_CASE(as9888_test_bias_moves_output),
	KUNIT_CASE(as9888_test_bias_dac),
	KUNIT_CASE_PARAM(as9888_test_dac_opt, as9888_dac_opt_gen_params),
	KUNIT_CASE(as9888_test_acc_saturated),
	KUNIT_CASE_PARAM(as9888_test_dac, as9888_dac_gen_params),
	KUNIT_CASE(as9888_test_dac_round_trip),
	KUNIT_CASE(as9888_test_dac_step),
	KUNIT_CASE_PARAM(as9888_test_round, as9888_round_gen_params),
	KUNIT_CASE(as9888_test_mag_scale),
	KUNIT_CASE_PARAM(as9888_test_magn_calibrate, as9888_magn_cal_gen_params),
	KUNIT_CASE(as9888_test_magn_calibrate_identity),
	KUNIT_CASE(as9888_test_magn_cal_init),
	KUNIT_CASE_PARAM(as9888_test_magn_calibscale,
			 as9888_calibscale_gen_params),
	KUNIT_CASE(as9888_test_magn_calibbias),
	{ }
};

static struct kunit_suite as9888_calib_test_suite = {
	.name = "as9888-calib",
	.test_cases = as9888_calib_test_cases,
};

kunit_test_suite(as9888_calib_test_suite);

MODULE_DESCRIPTION("KUnit tests for the AS9888 calibration arithmetic");
MODULE_LICENSE("GPL");
MODULE_IMPORT_NS("EXPORTED_FOR_KUNIT_TESTING");
