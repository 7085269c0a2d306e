// SPDX-License-Identifier: GPL-2.0
/*
 * Hand-computed cases for every formula of the datasheet's section 6 and
 * every decision that touches the arithmetic (D1, D4, D5, D6, D7, D8, D9),
 * plus exhaustive checks of the EEPROM field decoding.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>
#include <linux/errno.h>
#include <linux/kernel.h>

#include "as9888_calib.h"

/* The example EEPROM of datasheet section 8 */
static const u8 example[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static void decode_example(void **state)
{
	struct as9888_eeprom ee;

	assert_int_equal(as9888_eeprom_decode(example, &ee), 0);
	assert_int_equal(ee.errors, 0);
	assert_int_equal(ee.warnings, 0);
	assert_int_equal(ee.ref1, 0x9a);
	assert_int_equal(ee.ref2, 0x71);
	assert_int_equal(ee.ref3, 0x1d);	/* 0x18 | (0x15 & 7) */
	assert_int_equal(ee.osc, 0x5c);
	/* EREF3[7:3] = 2: t_RT = T(138) = 23.75 degC */
	assert_int_equal(ee.t_rt_mdegc, 23750);
	/* ET1 0x88 (25 degC), ET2 0x50 (60 degC) */
	assert_int_equal(ee.delta_t_mdegc, 35000);

	/* X: EAXGA 0x1c, EAXDT 0x38, EAXDA 0x0d, EAXGTD 0x04 */
	assert_int_equal(ee.axis[0].ehc, 0x80);
	assert_int_equal(ee.axis[0].ga, 0x1c);
	assert_int_equal(ee.axis[0].gain, 28);
	assert_int_equal(ee.axis[0].da, 0x0d);
	assert_int_equal(ee.axis[0].dt, 56);
	assert_int_equal(ee.axis[0].st_rt, 260);
	assert_int_equal(ee.axis[0].kste_idx, 0);
	/* Kote = 56 * 1.5 / 35 = 2.4 */
	assert_int_equal(ee.axis[0].kote_num * 10, 24 * ee.axis[0].kote_den);

	/* Y: EAYGA 0x63 (polarity, gain 35), EAYDT 0xe6, EAYGTD 0x65 */
	assert_int_equal(ee.axis[1].ehc, 0x85);
	assert_int_equal(ee.axis[1].ga, 0x63);
	assert_int_equal(ee.axis[1].gain, 35);
	assert_int_equal(ee.axis[1].da, 0x8f);
	assert_int_equal(ee.axis[1].dt, 230);
	assert_int_equal(ee.axis[1].st_rt, 261);
	assert_int_equal(ee.axis[1].kste_idx, 3);

	/* Z: EAZGA 0xa2 (DT sign set, gain 34), EAZDT 0x9c: DT = 412 - 512 */
	assert_int_equal(ee.axis[2].ehc, 0x7b);
	assert_int_equal(ee.axis[2].ga, 0x22);
	assert_int_equal(ee.axis[2].gain, 34);
	assert_int_equal(ee.axis[2].da, 0x8c);
	assert_int_equal(ee.axis[2].dt, -100);
	assert_int_equal(ee.axis[2].st_rt, 259);
	assert_int_equal(ee.axis[2].kste_idx, 6);
	/* Kote = -100 * 1.5 / 35 = -30 / 7 */
	assert_int_equal(ee.axis[2].kote_num * 7, -30 * ee.axis[2].kote_den);
}

/* D1: the Z fields come from the EAZ* addresses, not from the X ones */
static void decode_z_addresses(void **state)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memcpy(raw, example, sizeof(raw));
	raw[AS9888_EE_EAGA(2)] = 0x0b;		/* 0x49 */
	raw[AS9888_EE_EADT(2)] = 0x05;		/* 0x4c */
	raw[AS9888_EE_EADA(2)] = 0x30;		/* 0x4f */
	raw[AS9888_EE_EAGTD(2)] = 0x1f;		/* 0x52 */
	assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
	assert_int_equal(AS9888_EE_EAGA(2), 0x49 - 0x40);
	assert_int_equal(AS9888_EE_EADT(2), 0x4c - 0x40);
	assert_int_equal(AS9888_EE_EADA(2), 0x4f - 0x40);
	assert_int_equal(AS9888_EE_EAGTD(2), 0x52 - 0x40);
	assert_int_equal(ee.axis[2].gain, 11);
	assert_int_equal(ee.axis[2].dt, 5);
	assert_int_equal(ee.axis[2].da, 0x30);
	assert_int_equal(ee.axis[2].st_rt, 255);
	/* X untouched */
	assert_int_equal(ee.axis[0].gain, 28);
	assert_int_equal(ee.axis[0].dt, 56);
	assert_int_equal(ee.axis[0].da, 0x0d);
	assert_int_equal(ee.axis[0].st_rt, 260);
}

/* Every byte value of the gain, DT sign and GTD fields, on every axis */
static void decode_fields_exhaustive(void **state)
{
	int axis, v;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		for (v = 0; v < 256; v++) {
			struct as9888_eeprom ee;
			u8 raw[AS9888_EEPROM_LEN];
			int gain = v & 0x3f, detail = v & 0x1f;
			bool gain_ok = gain >= 7 && gain <= 43;

			memcpy(raw, example, sizeof(raw));
			raw[AS9888_EE_EAGA(axis)] = v;
			raw[AS9888_EE_EAGTD(axis)] = v;
			raw[AS9888_EE_EADT(axis)] = 0x80;
			as9888_eeprom_decode(raw, &ee);
			assert_int_equal(ee.axis[axis].ga, v & 0x7f);
			assert_int_equal(ee.axis[axis].gain, gain);
			assert_int_equal(!(ee.errors & (AS9888_EE_ERR_GAIN_X << axis)),
					 gain_ok);
			assert_int_equal(ee.axis[axis].dt, (v & 0x80) ? 0x80 - 256 : 0x80);
			assert_int_equal(ee.axis[axis].st_rt,
					 256 + (detail >= 16 ? detail - 32 : detail));
			assert_int_equal(ee.axis[axis].kste_idx, v >> 5);
		}
	}
}

/* DAC validity 0..67 and 128..195, for every byte value */
static void decode_dac_exhaustive(void **state)
{
	int axis, v;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		for (v = 0; v < 256; v++) {
			struct as9888_eeprom ee;
			u8 raw[AS9888_EEPROM_LEN];
			bool ok = v <= 67 || (v >= 128 && v <= 195);
			int ret;

			memcpy(raw, example, sizeof(raw));
			raw[AS9888_EE_EADA(axis)] = v;
			ret = as9888_eeprom_decode(raw, &ee);
			assert_int_equal(as9888_dac_valid(v), ok);
			assert_int_equal(ret, ok ? 0 : -EINVAL);
			assert_int_equal(ee.errors, ok ? 0 : AS9888_EE_ERR_DAC_X << axis);
		}
	}
}

/* t_RT = T(136 + s5(EREF3[7:3])) and REF3 = 0x18 | EREF3[2:0] */
static void decode_eref3_exhaustive(void **state)
{
	int v;

	for (v = 0; v < 256; v++) {
		struct as9888_eeprom ee;
		u8 raw[AS9888_EEPROM_LEN];
		int s5 = (v >> 3) >= 16 ? (v >> 3) - 32 : (v >> 3);

		memcpy(raw, example, sizeof(raw));
		raw[AS9888_EE_EREF3] = v;
		assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
		assert_int_equal(ee.t_rt_mdegc, (176 - 136 - s5) * 625);
		assert_int_equal(ee.ref3, 0x18 | (v & 7));
	}
}

static void decode_blank(void **state)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memset(raw, 0xff, sizeof(raw));
	assert_int_equal(as9888_eeprom_decode(raw, &ee), -ENODATA);
	assert_true(ee.errors & AS9888_EE_ERR_BLANK);
	memset(raw, 0, sizeof(raw));
	assert_int_equal(as9888_eeprom_decode(raw, &ee), -ENODATA);
	assert_true(ee.errors & AS9888_EE_ERR_ZERO);
	assert_string_equal(as9888_ee_error_str(AS9888_EE_ERR_BLANK),
			    "EEPROM blank (all bytes 0xff)");
}

/* D4: invalid codes or a span outside 10..80 degC fall back to 35 degC */
static void decode_delta_t_fallback(void **state)
{
	static const struct {
		u8 et1, et2;
		bool fallback;
		s32 delta_mdegc;
	} cases[] = {
		{ 0x88, 0x50, false, 35000 },
		{ 0x88, 0x78, false, 10000 },	/* 16 codes = 10 degC: kept */
		{ 0x88, 0x79, true, 35000 },	/* 15 codes = 9.375 degC */
		{ 0xa8, 0x28, false, 80000 },	/* 128 codes = 80 degC: kept */
		{ 0xa9, 0x28, true, 35000 },	/* 80.625 degC */
		{ 0xe1, 0x88, true, 35000 },	/* ET1 beyond 0xe0 */
		{ 0x88, 0x27, true, 35000 },	/* ET2 below 0x28 */
		{ 0x50, 0x88, true, 35000 },	/* reversed */
		{ 0xff, 0xff, true, 35000 },
	};
	unsigned int i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		struct as9888_eeprom ee;
		u8 raw[AS9888_EEPROM_LEN];

		memcpy(raw, example, sizeof(raw));
		raw[AS9888_EE_ET1] = cases[i].et1;
		raw[AS9888_EE_ET2] = cases[i].et2;
		assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
		assert_int_equal(!!(ee.warnings & AS9888_EE_WARN_DELTA_T),
				 cases[i].fallback);
		assert_int_equal(ee.delta_t_mdegc, cases[i].delta_mdegc);
		/* X: DT 56 -> Kote = 56 * 1.5 / dT */
		assert_int_equal((s64)ee.axis[0].kote_num * cases[i].delta_mdegc,
				 (s64)56 * 1500 * ee.axis[0].kote_den);
	}
}

/* D9: |Kote| > 10.2 LSB/degC is a warning; the EEPROM stays usable */
static void decode_kote_warning(void **state)
{
	struct as9888_eeprom ee;
	u8 raw[AS9888_EEPROM_LEN];

	memcpy(raw, example, sizeof(raw));
	/* Y: DT 230 -> 9.857 LSB/degC, no warning; DT 238 -> 10.2 exactly */
	raw[AS9888_EE_EADT(1)] = 238;
	assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
	assert_false(ee.warnings & AS9888_EE_WARN_KOTE_Y);
	raw[AS9888_EE_EADT(1)] = 239;	/* 10.243 */
	assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
	assert_int_equal(ee.warnings, AS9888_EE_WARN_KOTE_Y);
	/* negative side on Z: sign bit set, DT = -239 */
	raw[AS9888_EE_EADT(1)] = 0xe6;
	raw[AS9888_EE_EAGA(2)] |= 0x80;
	raw[AS9888_EE_EADT(2)] = 256 - 239;
	assert_int_equal(as9888_eeprom_decode(raw, &ee), 0);
	assert_int_equal(ee.axis[2].dt, -239);
	assert_int_equal(ee.warnings, AS9888_EE_WARN_KOTE_Z);
}

static void temperature_conversion(void **state)
{
	s32 t;

	assert_int_equal(as9888_tmps_to_mdegc(176), 0);
	assert_int_equal(as9888_tmps_to_mdegc(0x28), 85000);
	assert_int_equal(as9888_tmps_to_mdegc(0xe0), -30000);
	assert_int_equal(as9888_tmps_to_mdegc(136), 25000);
	assert_int_equal(as9888_tmps_to_mdegc(137), 24375);
	assert_true(as9888_tmps_valid(0x28));
	assert_true(as9888_tmps_valid(0xe0));
	assert_false(as9888_tmps_valid(0x27));
	assert_false(as9888_tmps_valid(0xe1));
	/* rint(176 - 1.6 t) */
	assert_int_equal(as9888_mdegc_to_tmps(25000), 136);
	assert_int_equal(as9888_mdegc_to_tmps(31250), 126);
	assert_int_equal(as9888_mdegc_to_tmps(-30000), 0xe0);
	assert_int_equal(as9888_mdegc_to_tmps(25400), 135);	/* 135.36 */
	/* mean of 136, 137, 137: TMPS 136.667 -> 24.583 degC */
	assert_int_equal(as9888_tmps_mean_to_mdegc(410, 3, &t), 0);
	assert_int_equal(t, 24583);
	assert_int_equal(as9888_tmps_mean_to_mdegc(410, 0, &t), -EINVAL);
	assert_int_equal(as9888_tmps_mean_to_mdegc(256 * 3, 3, &t), -ERANGE);
	assert_int_equal(as9888_tmps_mean_to_mdegc(-1, 3, &t), -ERANGE);
}

static void magnetometer_adjust(void **state)
{
	/* H * (EHC + 128) / 256 in Q8 */
	assert_int_equal(as9888_mag_adjust_q8(100, 128), 100 * 256);
	assert_int_equal(as9888_mag_adjust_q8(100, 0), 50 * 256);
	assert_int_equal(as9888_mag_adjust_q8(-4096, 255), -4096 * 383);
	assert_true(as9888_mag_overflow(-4096));
	assert_true(as9888_mag_overflow(4095));
	assert_false(as9888_mag_overflow(-4095));
	assert_false(as9888_mag_overflow(4094));
}

/* Steps 2-17..2-22: windows on the adjusted value, boundaries included */
static void selftest_windows(void **state)
{
	assert_true(as9888_selftest_ok(0, -100, 128));
	assert_false(as9888_selftest_ok(0, -101, 128));
	assert_true(as9888_selftest_ok(1, 100, 128));
	assert_false(as9888_selftest_ok(1, 101, 128));
	assert_true(as9888_selftest_ok(2, 300, 128));
	assert_false(as9888_selftest_ok(2, 299, 128));
	assert_true(as9888_selftest_ok(2, 1000, 128));
	assert_false(as9888_selftest_ok(2, 1001, 128));
	/* EHC 0 halves: 600 -> 300 passes, 599 -> 299.5 fails */
	assert_true(as9888_selftest_ok(2, 600, 0));
	assert_false(as9888_selftest_ok(2, 599, 0));
	/* EHC 255: 784 * 383 / 256 = 1172.9 fails although raw is in window */
	assert_false(as9888_selftest_ok(2, 784, 255));
	/* x = 150 raw with EHC 0 -> 75 passes */
	assert_true(as9888_selftest_ok(0, 150, 0));
	/* an overflowed reading never passes, and axis 3 does not exist */
	assert_false(as9888_selftest_ok(2, 4095, 0));
	assert_false(as9888_selftest_ok(3, 0, 128));
	/* the weak self-test of a faulty unit (Z about 150) fails */
	assert_false(as9888_selftest_ok(2, 150, 128));
	/* the window alone, on adjusted Q8 values: edges included */
	assert_true(as9888_selftest_window_ok(0, -100 * 256));
	assert_false(as9888_selftest_window_ok(0, -100 * 256 - 1));
	assert_true(as9888_selftest_window_ok(1, 100 * 256));
	assert_false(as9888_selftest_window_ok(1, 100 * 256 + 1));
	assert_true(as9888_selftest_window_ok(2, 300 * 256));
	assert_false(as9888_selftest_window_ok(2, 300 * 256 - 1));
	assert_true(as9888_selftest_window_ok(2, 1000 * 256));
	assert_false(as9888_selftest_window_ok(2, 1000 * 256 + 1));
	assert_false(as9888_selftest_window_ok(-1, 0));
}

static void sensitivity(void **state)
{
	struct as9888_eeprom ee;
	s32 st;

	as9888_eeprom_decode(example, &ee);
	/* at t_RT, St = St_RT exactly */
	assert_int_equal(as9888_sensitivity_q16(&ee.axis[0], ee.t_rt_mdegc,
						ee.t_rt_mdegc, &st), 0);
	assert_int_equal(st, 260 * 65536);
	/* X at 60 degC: 260 * (1 - 0.00428125 * 36.25) = 219.64921875 */
	assert_int_equal(as9888_sensitivity_q16(&ee.axis[0], ee.t_rt_mdegc,
						60000, &st), 0);
	assert_int_equal(st, 14394931);
	/* Y at -30 degC: 261 * (1 + 0.00296875 * 53.75) = 302.6478515625 */
	assert_int_equal(as9888_sensitivity_q16(&ee.axis[1], ee.t_rt_mdegc,
						-30000, &st), 0);
	assert_int_equal(st, 19834330);
	/* out of range temperatures and a corrupt trim are refused */
	assert_int_equal(as9888_sensitivity_q16(&ee.axis[1], ee.t_rt_mdegc,
						150001, &st), -ERANGE);
	ee.axis[1].st_rt = 300;
	assert_int_equal(as9888_sensitivity_q16(&ee.axis[1], ee.t_rt_mdegc,
						0, &st), -EINVAL);
}

static void offsets(void **state)
{
	struct as9888_eeprom ee;
	s32 ot_l, ot;

	as9888_eeprom_decode(example, &ee);
	/* Ot_L = A + St * G: Z up, A = 270.5, St = 259 -> 11.5 */
	assert_int_equal(as9888_offset_level_q16(270 * 65536 + 32768,
						 259 * 65536, -1, &ot_l), 0);
	assert_int_equal(ot_l, 11 * 65536 + 32768);
	/* Z down */
	assert_int_equal(as9888_offset_level_q16(-250 * 65536, 259 * 65536, 1,
						 &ot_l), 0);
	assert_int_equal(ot_l, 9 * 65536);
	assert_int_equal(as9888_offset_level_q16(0, 259 * 65536, 2, &ot_l),
			 -EINVAL);

	/* Z: Kote = -30/7; Ot(60) = -30/7 * (60 - 26.25) + 12.5 = -132.142857 */
	assert_int_equal(as9888_offset_q16(&ee.axis[2], 12 * 65536 + 32768,
					   26250, 60000, &ot), 0);
	assert_int_equal(ot, -8660114);
	/* at t_L, Ot = Ot_L */
	assert_int_equal(as9888_offset_q16(&ee.axis[2], 777, 26250, 26250, &ot), 0);
	assert_int_equal(ot, 777);
	assert_int_equal(as9888_offset_q16(&ee.axis[2], 0, 26250, -100001, &ot),
			 -ERANGE);
}

static void compensated_reading(void **state)
{
	s32 a;

	/* (raw - Ot) / St: (271 - 12) / 259 = 1 g */
	assert_int_equal(as9888_accel_ug(271, 12 * 65536, 259 * 65536, &a), 0);
	assert_int_equal(a, 1000000);
	/* (-10 - 2.5) / 250 = -0.05 g */
	assert_int_equal(as9888_accel_ug(-10, 2 * 65536 + 32768, 250 * 65536, &a), 0);
	assert_int_equal(a, -50000);
	assert_int_equal(as9888_accel_ug(1, 0, 0, &a), -EINVAL);
}

static void mean(void **state)
{
	s32 m;

	assert_int_equal(as9888_mean_q16(271 * 3 + 1, 3, &m), 0);
	assert_int_equal(m, 271 * 65536 + 21845);	/* 271.3333 */
	assert_int_equal(as9888_mean_q16(-5, 2, &m), 0);
	assert_int_equal(m, -5 * 32768);
	assert_int_equal(as9888_mean_q16(5, 0, &m), -EINVAL);
	assert_int_equal(as9888_mean_q16(32768LL * 2, 2, &m), -ERANGE);
	assert_int_equal(as9888_mean_q16(0, AS9888_SAMPLES_MAX + 1, &m), -EINVAL);
}

/* 6.6: both directions for every DAC value and both polarities */
static void dac_linear_codes(void **state)
{
	int da, lin;

	assert_int_equal(as9888_dac2lin(0x1c, 0x80), 0);
	assert_int_equal(as9888_dac2lin(0x1c, 0x00), 0);
	assert_int_equal(as9888_dac2lin(0x1c, 0x0d), -13);
	assert_int_equal(as9888_dac2lin(0x1c, 0xc3), 67);
	assert_int_equal(as9888_dac2lin(0x63, 0x8f), -15);	/* polarity */
	assert_int_equal(as9888_dac2lin(0x63, 0x0d), 13);
	assert_int_equal(as9888_lin2dac(0x1c, 0), 0x80);
	assert_int_equal(as9888_lin2dac(0x1c, -67), 67);
	assert_int_equal(as9888_lin2dac(0x63, 14), 14);
	assert_int_equal(as9888_lin2dac(0x63, -14), 0x8e);
	/* beyond the DAC range: clamped */
	assert_int_equal(as9888_lin2dac(0x1c, 500), 0x80 + 67);
	assert_int_equal(as9888_lin2dac(0x1c, -500), 67);

	for (lin = -67; lin <= 67; lin++) {
		assert_int_equal(as9888_dac2lin(0x1c, as9888_lin2dac(0x1c, lin)), lin);
		assert_int_equal(as9888_dac2lin(0x5c, as9888_lin2dac(0x5c, lin)), lin);
		assert_true(as9888_dac_valid(as9888_lin2dac(0x5c, lin)));
	}
	for (da = 0; da < 256; da++) {
		if (!as9888_dac_valid(da) || da == 0)
			continue;
		assert_int_equal(as9888_lin2dac(0x1c, as9888_dac2lin(0x1c, da)), da);
		assert_int_equal(as9888_lin2dac(0x7f, as9888_dac2lin(0x7f, da)), da);
	}
}

static void dac_step(void **state)
{
	/* 2048 / (28 + 16) = 46.545 LSB per code */
	assert_int_equal(as9888_dac_step_q16(0x1c), 3050403);
	/* the polarity bit does not change the step: 2048 / 48 */
	assert_int_equal(as9888_dac_step_q16(0x60), 2796203);
}

static void dac_optimum(void **state)
{
	u8 opt;

	/* X: lin -13, (44 / 2048) * 100 = 2.148 -> 2, lin -15 */
	assert_int_equal(as9888_dac_opt(0x1c, 0x0d, 28, 100 * 65536, &opt), 0);
	assert_int_equal(opt, 15);
	/* Y (polarity): lin -15, 51 / 2048 * -40.2 = -1.001 -> -1, lin -14 */
	assert_int_equal(as9888_dac_opt(0x63, 0x8f, 35, -2634547, &opt), 0);
	assert_int_equal(opt, 0x8e);
	/* D5, ties to even on the whole product: gain 16 -> 32 / 2048 */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, 32 * 65536, &opt), 0);
	assert_int_equal(opt, 0x80);		/* 0.5 -> 0 */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, 96 * 65536, &opt), 0);
	assert_int_equal(opt, 2);		/* 1.5 -> 2 -> lin -2 */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, 160 * 65536, &opt), 0);
	assert_int_equal(opt, 2);		/* 2.5 -> 2 */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, -32 * 65536, &opt), 0);
	assert_int_equal(opt, 0x80);		/* -0.5 -> 0 */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, 32 * 65536 + 1, &opt), 0);
	assert_int_equal(opt, 1);		/* just above the tie -> 1 */
	/* D6: beyond the DAC range: clamped and reported */
	assert_int_equal(as9888_dac_opt(0x1c, 0x0d, 28, 3000 * 65536, &opt),
			 -ERANGE);
	assert_int_equal(opt, 67);
	assert_int_equal(as9888_dac_opt(0x1c, 0xc3, 28, -3000 * 65536, &opt),
			 -ERANGE);
	assert_int_equal(opt, 0x80 + 67);
	/* exactly at the limit is fine: lin 0 - (-67) */
	assert_int_equal(as9888_dac_opt(0x10, 0x80, 16, -67 * 64 * 65536, &opt), 0);
	assert_int_equal(opt, 0x80 + 67);
}

/* Steps 3-14..3-22 */
static void accel_judgments(void **state)
{
	assert_true(as9888_acc_saturated(-2048));
	assert_true(as9888_acc_saturated(2047));
	assert_false(as9888_acc_saturated(-2047));
	assert_false(as9888_acc_saturated(2046));
	assert_true(as9888_fluctuation_ok(10, 25, AS9888_FLUCTUATION_DEFAULT));
	assert_false(as9888_fluctuation_ok(10, 26, AS9888_FLUCTUATION_DEFAULT));
	assert_false(as9888_fluctuation_ok(-2048, 2047, 4094));
	assert_true(as9888_fluctuation_ok(-2048, 2047, 4095));
	assert_false(as9888_fluctuation_ok(5, 4, 100));
}

/* Note 2 and D7 */
static void samples_needed(void **state)
{
	/* the note's example: n = 1, sigma 40, error 10 -> 16 */
	assert_int_equal(as9888_samples_needed(1, 40 * 65536, 10 * 65536), 16);
	/* n = 4, sigma 1, error 0.5: 16 */
	assert_int_equal(as9888_samples_needed(4, 65536, 32768), 16);
	/* 17.0001 rounds up */
	assert_int_equal(as9888_samples_needed(17, 65537, 65536), 18);
	/* quiet: never fewer than 10 */
	assert_int_equal(as9888_samples_needed(1, 1000, 65536), 10);
	/* too noisy */
	assert_true(as9888_samples_needed(1, 100 * 65536, 65536) > AS9888_SAMPLES_MAX);
	assert_true(as9888_samples_needed(4096, U32_MAX, 1) > AS9888_SAMPLES_MAX);
	assert_true(as9888_samples_needed(1, 1, 0) > AS9888_SAMPLES_MAX);
}

/* D8 on all six postures */
static void posture(void **state)
{
	static const struct {
		s32 a[3];
		s8 g[3];
	} cases[] = {
		{ { 10, -3, 260 }, { 0, 0, -1 } },
		{ { 10, -3, -250 }, { 0, 0, 1 } },
		{ { 255, 3, 10 }, { -1, 0, 0 } },
		{ { -262, 3, 10 }, { 1, 0, 0 } },
		{ { 2, 261, 10 }, { 0, -1, 0 } },
		{ { 2, -259, 10 }, { 0, 1, 0 } },
	};
	const s32 st[3] = { 256 * 65536, 256 * 65536, 256 * 65536 };
	unsigned int i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		s32 a[3];
		s8 g[3];
		int axis, vertical;

		for (axis = 0; axis < 3; axis++)
			a[axis] = cases[i].a[axis] * 65536;
		vertical = as9888_posture_detect(a, g);
		assert_int_equal(vertical, i / 2 == 0 ? 2 : i / 2 - 1);
		assert_memory_equal(g, cases[i].g, 3);
		assert_int_equal(as9888_posture_check(a, st, g), AS9888_POSTURE_OK);
	}
}

static void posture_failures(void **state)
{
	const s32 st[3] = { 256 * 65536, 256 * 65536, 256 * 65536 };
	s32 tilted[3] = { 129 * 65536, 0, 221 * 65536 };	/* 30 degrees */
	s32 weak[3] = { 0, 0, 127 * 65536 };
	s32 level[3] = { 0, 0, 256 * 65536 };
	s8 g[3];
	const s8 up_wrong[3] = { 0, 0, 1 };
	const s8 two_axes[3] = { 0, -1, -1 };
	const s8 none[3] = { 0, 0, 0 };
	const s8 two[3] = { 0, 0, 2 };

	as9888_posture_detect(tilted, g);
	assert_int_equal(as9888_posture_check(tilted, st, g),
			 AS9888_POSTURE_NOT_LEVEL);
	tilted[0] = 128 * 65536;	/* exactly half: still level */
	assert_int_equal(as9888_posture_check(tilted, st, g), AS9888_POSTURE_OK);
	as9888_posture_detect(weak, g);
	assert_int_equal(as9888_posture_check(weak, st, g),
			 AS9888_POSTURE_NOT_VERTICAL);
	assert_int_equal(as9888_posture_check(level, st, up_wrong),
			 AS9888_POSTURE_WRONG_SIGN);
	assert_int_equal(as9888_posture_check(level, st, two_axes),
			 AS9888_POSTURE_BAD_G);
	assert_int_equal(as9888_posture_check(level, st, none),
			 AS9888_POSTURE_BAD_G);
	assert_int_equal(as9888_posture_check(level, st, two),
			 AS9888_POSTURE_BAD_G);
}

static void rounding(void **state)
{
	assert_int_equal(as9888_div_round_s64(5, 2), 2);
	assert_int_equal(as9888_div_round_s64(7, 2), 4);
	assert_int_equal(as9888_div_round_s64(-5, 2), -2);
	assert_int_equal(as9888_div_round_s64(-7, 2), -4);
	assert_int_equal(as9888_div_round_s64(-8, 3), -3);
	assert_int_equal(as9888_div_round_s64(8, 3), 3);
	assert_int_equal(as9888_div_round_s64(7, 3), 2);
	assert_int_equal(as9888_div_round_s64(S64_MIN, 1), S64_MIN);
	assert_int_equal(as9888_div_round_s64(1, 0), 0);
}

/*
 * The functions below are userspace-only (lib/calib/as9888_calib_user.c);
 * these cases were the KUnit suite's before those functions left the
 * kernel, with the same assertions.
 */
#define Q16(x)		((s32)((x) * AS9888_Q16_ONE))

/* Temperature, section 5: the TMPS code of a temperature */
static void kunit_tmps_code(void **state)
{
	static const struct {
		u8 tmps;
		s32 mdegc;
	} cases[] = {
		{ 176, 0 }, { 0x28, 85000 }, { 0xe0, -30000 }, { 136, 25000 },
		{ 137, 24375 }, { 0x27, 85625 }, { 0xe1, -30625 }, { 0, 110000 },
		{ 255, -49375 },
	};
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(cases); i++)
		assert_int_equal(as9888_mdegc_to_tmps(cases[i].mdegc),
				 cases[i].tmps);
}

static void kunit_temperature_rounding(void **state)
{
	s32 t;

	/* rint(176 - 1.6 t) */
	assert_int_equal(as9888_mdegc_to_tmps(31250), 126);
	assert_int_equal(as9888_mdegc_to_tmps(25400), 135);
	/* Mean of 136, 137, 137: TMPS 136.667 is 24.583 degC */
	assert_int_equal(as9888_tmps_mean_to_mdegc(410, 3, &t), 0);
	assert_int_equal(t, 24583);
	assert_int_equal(as9888_tmps_mean_to_mdegc(410, 0, &t), -EINVAL);
	assert_int_equal(as9888_tmps_mean_to_mdegc(256 * 3, 3, &t),
			-ERANGE);
	assert_int_equal(as9888_tmps_mean_to_mdegc(-1, 3, &t), -ERANGE);
}

/* 6.5: Ot_L = A + St(t_L) * G */
struct as9888_level_case {
	const char *name;
	s32 a_q16, st_q16;
	int g;
	int ret;
	s32 ot_l_q16;
};

static const struct as9888_level_case as9888_level_cases[] = {
	{ "Z up", Q16(270) + Q16(1) / 2, Q16(259), -1, 0,
	  Q16(11) + Q16(1) / 2 },
	{ "Z down", Q16(-250), Q16(259), 1, 0, Q16(9) },
	{ "horizontal axis", Q16(3), Q16(259), 0, 0, Q16(3) },
	{ "G of 2", 0, Q16(259), 2, -EINVAL, 0 },
	{ "negative St", 0, -1, 1, -EINVAL, 0 },
};

static void check_offset_level(const struct as9888_level_case *c)
{
	s32 ot_l = 0;

	assert_int_equal(as9888_offset_level_q16(c->a_q16, c->st_q16,
						      c->g, &ot_l), c->ret);
	if (!c->ret)
		assert_int_equal(ot_l, c->ot_l_q16);
}

static void kunit_offset_level(void **state)
{
	const struct as9888_level_case *c;

	for (c = as9888_level_cases; c < as9888_level_cases + ARRAY_SIZE(as9888_level_cases);
	     c++)
		check_offset_level(c);
}

/* 6.7: a = (raw - Ot(t)) / St(t) */
struct as9888_accel_case {
	const char *name;
	s16 raw;
	s32 ot_q16, st_q16;
	int ret;
	s32 ug;
};

static const struct as9888_accel_case as9888_accel_cases[] = {
	{ "1 g", 271, Q16(12), Q16(259), 0, 1000000 },
	{ "-0.05 g", -10, Q16(2) + Q16(1) / 2, Q16(250), 0, -50000 },
	{ "zero St", 1, 0, 0, -EINVAL, 0 },
};

static void check_accel(const struct as9888_accel_case *c)
{
	s32 ug = 0;

	assert_int_equal(as9888_accel_ug(c->raw, c->ot_q16, c->st_q16, &ug),
			c->ret);
	if (!c->ret)
		assert_int_equal(ug, c->ug);
}

static void kunit_accel(void **state)
{
	const struct as9888_accel_case *c;

	for (c = as9888_accel_cases; c < as9888_accel_cases + ARRAY_SIZE(as9888_accel_cases);
	     c++)
		check_accel(c);
}

/* Every raw value comes back exactly from its compensated reading */
static void kunit_uncompensate(void **state)
{
	static const s32 sts[] = {
		Q16(141) + 7, Q16(256), Q16(346) - 3, Q16(1023),
	};
	static const s32 ots[] = { 0, Q16(-300) - 12345, Q16(517) + 999 };
	unsigned int i, j;
	s16 out, back;
	int raw;

	for (i = 0; i < ARRAY_SIZE(sts); i++) {
		for (j = 0; j < ARRAY_SIZE(ots); j++) {
			s32 ot = ots[j], st = sts[i];

			for (raw = AS9888_ACC_MIN; raw <= AS9888_ACC_MAX; raw++) {
				int ret;

				if (as9888_accel_compensate(raw, ot, st, &out))
					continue;
				ret = as9888_accel_uncompensate(out, ot, st, &back);
				assert_int_equal(ret, 0);
				assert_int_equal(back, raw);
			}
		}
	}

	/* A value at a limit may have been clamped */
	assert_int_equal(as9888_accel_uncompensate(32767, 0, Q16(256),
							&back), -ERANGE);
	assert_int_equal(as9888_accel_uncompensate(-32768, 0, Q16(256),
							&back), -ERANGE);
	assert_int_equal(as9888_accel_uncompensate(5, 0, 0, &back),
			-EINVAL);
}

/* A level test, Z up, becomes a calibration at the factory DAC values */
static void kunit_cal_from_level(void **state)
{
	const s32 a[AS9888_AXES] = { Q16(10), Q16(-20), Q16(270) };
	const s8 g[AS9888_AXES] = { 0, 0, -1 }, g_bad[AS9888_AXES] = { 0, 0, 2 };
	struct as9888_accel_cal cal;
	struct as9888_eeprom ee;
	u8 da[AS9888_AXES];
	int axis;

	assert_int_equal(as9888_eeprom_decode(example, &ee), 0);
	for (axis = 0; axis < AS9888_AXES; axis++)
		da[axis] = ee.axis[axis].da;

	/* At t_L = t_RT: calibbias = -Ot_L / St_RT * 1024, rounded */
	assert_int_equal(as9888_accel_cal_from_level(&ee, a, 23750, g, da,
							  &cal), 0);
	assert_int_equal(cal.bias[0], -39);	/* -10 * 1024 / 260 */
	assert_int_equal(cal.bias[1], 78);	/* 20 * 1024 / 261 = 78.47 */
	/* Ot_L = A + St(t_L) * G = 270 - 259; -11 * 1024 / 259 = -43.49 */
	assert_int_equal(cal.bias[2], -43);

	/* 10 degC above t_RT: X drifted 2.4 LSB/degC, so -14 LSB at t_RT */
	assert_int_equal(as9888_accel_cal_from_level(&ee, a, 33750, g, da,
							  &cal), 0);
	assert_int_equal(cal.bias[0], 55);	/* 14 * 1024 / 260 = 55.1 */

	/* Measured one code up: the factory DAC reads one step lower */
	da[0] = as9888_lin2dac(ee.axis[0].ga,
			       as9888_dac2lin(ee.axis[0].ga, da[0]) + 1);
	assert_int_equal(as9888_accel_cal_from_level(&ee, a, 23750, g, da,
							  &cal), 0);
	/* (10 - 46.545) LSB: 36.545 * 1024 / 260 = 143.9 */
	assert_int_equal(cal.bias[0], 144);

	assert_int_equal(as9888_accel_cal_from_level(&ee, a, 90000, g, da,
							  &cal), -ERANGE);
	assert_int_equal(as9888_accel_cal_from_level(&ee, a, 23750, g_bad,
							  da, &cal), -EINVAL);
}

/*
 * The calibbias that makes the driver run a DAC value: a zero offset at
 * that value, moved to the factory DAC value, as a calibbias; one trim
 * check, the shared unit's (as9888_trim_valid())
 */
static void dac_bias(void **state)
{
	struct as9888_eeprom ee;
	struct as9888_axis_trim t;
	int axis, lin, n = 0;
	s32 bias;
	u8 da, got;

	assert_int_equal(as9888_eeprom_decode(example, &ee), 0);
	t = ee.axis[0];

	/* The factory DAC value is calibbias 0 */
	assert_int_equal(as9888_dac_bias(&t, t.da, &bias), 0);
	assert_int_equal(bias, 0);
	/* One code up moves the output by -2048 / (gain + 16) = -46.545 LSB
	 * (gain 28): a calibbias of 46.545 * 1024 / 260 = 183.3 */
	da = as9888_lin2dac(t.ga, as9888_dac2lin(t.ga, t.da) + 1);
	assert_int_equal(as9888_dac_bias(&t, da, &bias), 0);
	assert_int_equal(bias, 183);

	/* Every DAC value in reach comes back from its calibbias */
	for (axis = 0; axis < AS9888_AXES; axis++) {
		t = ee.axis[axis];
		for (lin = -AS9888_DAC_LIN_MAX; lin <= AS9888_DAC_LIN_MAX; lin++) {
			da = as9888_lin2dac(t.ga, lin);
			if (as9888_dac_bias(&t, da, &bias))
				continue;
			n++;
			assert_int_equal(as9888_bias_dac(&t, bias, &got), 0);
			assert_int_equal(as9888_dac2lin(t.ga, got), lin);
		}
	}
	assert_true(n > 3 * 40);

	/* An invalid DAC value, or a trim the decoder would not give */
	assert_int_equal(as9888_dac_bias(&ee.axis[0], 0x50, &bias), -EINVAL);
	t = ee.axis[0];
	t.st_rt = 100;
	assert_int_equal(as9888_dac_bias(&t, t.da, &bias), -EINVAL);
	t = ee.axis[0];
	t.kote_den = 0;
	assert_int_equal(as9888_dac_bias(&t, t.da, &bias), -EINVAL);
	t = ee.axis[0];
	t.kste_idx = 8;
	assert_int_equal(as9888_dac_bias(&t, t.da, &bias), -EINVAL);
}

/* The self-test's adjusted readings in thousandths, rounded to nearest */
static void q8_to_milli(void **state)
{
	assert_int_equal(as9888_q8_to_milli(AS9888_Q8_ONE), 1000);
	assert_int_equal(as9888_q8_to_milli(1), 4);
	assert_int_equal(as9888_q8_to_milli(-1), -4);
	assert_int_equal(as9888_q8_to_milli(16), 62);	/* 62.5: to even */
	assert_int_equal(as9888_q8_to_milli(48), 188);	/* 187.5: to even */
	assert_int_equal(as9888_q8_to_milli(4095 * 383), 6126504);
}

static void kunit_mean(void **state)
{
	s32 m;

	assert_int_equal(as9888_mean_q16(271 * 3 + 1, 3, &m), 0);
	assert_int_equal(m, Q16(271) + 21845);
	assert_int_equal(as9888_mean_q16(-5, 2, &m), 0);
	assert_int_equal(m, -5 * 32768);
	assert_int_equal(as9888_mean_q16(5, 0, &m), -EINVAL);
	assert_int_equal(as9888_mean_q16(32768LL * 2, 2, &m), -ERANGE);
	assert_int_equal(as9888_mean_q16(0, AS9888_SAMPLES_MAX + 1, &m),
			-EINVAL);
}

static void kunit_accel_judgments(void **state)
{
	assert_true(as9888_acc_saturated(-2048));
	assert_true(as9888_acc_saturated(2047));
	assert_false(as9888_acc_saturated(-2047));
	assert_false(as9888_acc_saturated(2046));
	assert_true(as9888_fluctuation_ok(10, 25,
						      AS9888_FLUCTUATION_DEFAULT));
	assert_false(as9888_fluctuation_ok(10, 26,
						       AS9888_FLUCTUATION_DEFAULT));
	assert_false(as9888_fluctuation_ok(-2048, 2047, 4094));
	assert_true(as9888_fluctuation_ok(-2048, 2047, 4095));
	assert_false(as9888_fluctuation_ok(5, 4, 100));
}

/* Note 2, D7: N >= n * (sigma / error)^2, at least 10 */
struct as9888_samples_case {
	const char *name;
	u32 n, sigma_q16, error_q16;
	u32 samples;
};

static const struct as9888_samples_case as9888_samples_cases[] = {
	{ "the note's example", 1, Q16(40), Q16(10), 16 },
	{ "n = 4", 4, Q16(1), Q16(1) / 2, 16 },
	{ "rounds up", 17, Q16(1) + 1, Q16(1), 18 },
	{ "never fewer than 10", 1, 1000, Q16(1), 10 },
	{ "too noisy", 1, Q16(100), Q16(1), AS9888_SAMPLES_MAX + 1 },
	{ "no error allowed", 1, 1, 0, AS9888_SAMPLES_MAX + 1 },
};

static void check_samples(const struct as9888_samples_case *c)
{
	assert_int_equal(as9888_samples_needed(c->n, c->sigma_q16,
						    c->error_q16), c->samples);
}

static void kunit_samples(void **state)
{
	const struct as9888_samples_case *c;

	for (c = as9888_samples_cases; c < as9888_samples_cases + ARRAY_SIZE(as9888_samples_cases);
	     c++)
		check_samples(c);
}

/* D8 on all six postures */
struct as9888_posture_case {
	const char *name;
	s32 a[AS9888_AXES];
	s8 g[AS9888_AXES];
	int vertical;
};

static const struct as9888_posture_case as9888_posture_cases[] = {
	{ "Z up", { 10, -3, 260 }, { 0, 0, -1 }, 2 },
	{ "Z down", { 10, -3, -250 }, { 0, 0, 1 }, 2 },
	{ "X up", { 255, 3, 10 }, { -1, 0, 0 }, 0 },
	{ "X down", { -262, 3, 10 }, { 1, 0, 0 }, 0 },
	{ "Y up", { 2, 261, 10 }, { 0, -1, 0 }, 1 },
	{ "Y down", { 2, -259, 10 }, { 0, 1, 0 }, 1 },
};

static void check_posture(const struct as9888_posture_case *c)
{
	const s32 st[AS9888_AXES] = { Q16(256), Q16(256), Q16(256) };
	s32 a[AS9888_AXES];
	s8 g[AS9888_AXES];
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++)
		a[axis] = Q16(c->a[axis]);
	assert_int_equal(as9888_posture_detect(a, g), c->vertical);
	assert_int_equal(memcmp(g, c->g, sizeof(g)), 0);
	assert_int_equal(as9888_posture_check(a, st, g), AS9888_POSTURE_OK);
}

static void kunit_posture(void **state)
{
	const struct as9888_posture_case *c;

	for (c = as9888_posture_cases; c < as9888_posture_cases + ARRAY_SIZE(as9888_posture_cases);
	     c++)
		check_posture(c);
}

static void kunit_posture_failures(void **state)
{
	const s32 st[AS9888_AXES] = { Q16(256), Q16(256), Q16(256) };
	s32 tilted[AS9888_AXES] = { Q16(129), 0, Q16(221) };
	const s32 weak[AS9888_AXES] = { 0, 0, Q16(127) };
	const s32 level[AS9888_AXES] = { 0, 0, Q16(256) };
	static const s8 up_wrong[AS9888_AXES] = { 0, 0, 1 };
	static const s8 two_axes[AS9888_AXES] = { 0, -1, -1 };
	static const s8 none[AS9888_AXES] = { 0, 0, 0 };
	static const s8 two[AS9888_AXES] = { 0, 0, 2 };
	s8 g[AS9888_AXES];

	as9888_posture_detect(tilted, g);
	assert_int_equal(as9888_posture_check(tilted, st, g),
			AS9888_POSTURE_NOT_LEVEL);
	tilted[0] = Q16(128);	/* exactly half: still level */
	assert_int_equal(as9888_posture_check(tilted, st, g),
			AS9888_POSTURE_OK);
	as9888_posture_detect(weak, g);
	assert_int_equal(as9888_posture_check(weak, st, g),
			AS9888_POSTURE_NOT_VERTICAL);
	assert_int_equal(as9888_posture_check(level, st, up_wrong),
			AS9888_POSTURE_WRONG_SIGN);
	assert_int_equal(as9888_posture_check(level, st, two_axes),
			AS9888_POSTURE_BAD_G);
	assert_int_equal(as9888_posture_check(level, st, none),
			AS9888_POSTURE_BAD_G);
	assert_int_equal(as9888_posture_check(level, st, two),
			AS9888_POSTURE_BAD_G);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(decode_example),
		cmocka_unit_test(decode_z_addresses),
		cmocka_unit_test(decode_fields_exhaustive),
		cmocka_unit_test(decode_dac_exhaustive),
		cmocka_unit_test(decode_eref3_exhaustive),
		cmocka_unit_test(decode_blank),
		cmocka_unit_test(decode_delta_t_fallback),
		cmocka_unit_test(decode_kote_warning),
		cmocka_unit_test(temperature_conversion),
		cmocka_unit_test(magnetometer_adjust),
		cmocka_unit_test(selftest_windows),
		cmocka_unit_test(sensitivity),
		cmocka_unit_test(offsets),
		cmocka_unit_test(compensated_reading),
		cmocka_unit_test(mean),
		cmocka_unit_test(dac_linear_codes),
		cmocka_unit_test(dac_step),
		cmocka_unit_test(dac_optimum),
		cmocka_unit_test(accel_judgments),
		cmocka_unit_test(samples_needed),
		cmocka_unit_test(posture),
		cmocka_unit_test(posture_failures),
		cmocka_unit_test(rounding),
		cmocka_unit_test(kunit_tmps_code),
		cmocka_unit_test(kunit_temperature_rounding),
		cmocka_unit_test(kunit_offset_level),
		cmocka_unit_test(kunit_accel),
		cmocka_unit_test(kunit_uncompensate),
		cmocka_unit_test(kunit_cal_from_level),
		cmocka_unit_test(dac_bias),
		cmocka_unit_test(q8_to_milli),
		cmocka_unit_test(kunit_mean),
		cmocka_unit_test(kunit_accel_judgments),
		cmocka_unit_test(kunit_samples),
		cmocka_unit_test(kunit_posture),
		cmocka_unit_test(kunit_posture_failures),
	};

	return cmocka_run_group_tests_name("calib", tests, NULL, NULL);
}
