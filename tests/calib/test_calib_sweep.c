// SPDX-License-Identifier: GPL-2.0
/*
 * Accuracy sweep of the fixed-point calibration arithmetic against the
 * double-precision reference, over every input space small enough to
 * enumerate. Each test prints the worst error it found and fails above the
 * bar of the foundation issue: 1e-4 relative for sensitivities, 0.5 LSB for
 * offsets, DACopt identical but at exact rint ties; and for the driver's
 * compensated readings, 0.5 output LSB (the final rounding) with the raw
 * reading recovered exactly from every one of them.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>
#include <linux/errno.h>
#include <linux/kernel.h>

#include "as9888_calib.h"
#include "calib_ref.h"

#define SENS_REL_BAR	1e-4
#define OFFSET_LSB_BAR	0.5
/*
 * Compensated output: its final rint (0.5 output LSB, an eighth of a raw
 * LSB at 256 LSB/g) plus the Q16 steps of Ot, St and the DAC step.
 */
#define OUT_LSB_BAR	0.501

static double q16(s64 v)
{
	return (double)v / AS9888_Q16_ONE;
}

/* All EAxGTD x EREF3 x valid TMPS codes */
static void sweep_sensitivity(void **state)
{
	double worst = 0.0;
	unsigned long count = 0;
	int gtd, eref3, tmps;

	for (gtd = 0; gtd < 256; gtd++) {
		for (eref3 = 0; eref3 < 256; eref3++) {
			u8 raw[AS9888_EEPROM_LEN] = { 0 };
			struct as9888_eeprom ee;

			raw[AS9888_EE_EREF3] = eref3;
			raw[AS9888_EE_EAGTD(0)] = gtd;
			as9888_eeprom_decode(raw, &ee);

			for (tmps = AS9888_TMPS_MIN; tmps <= AS9888_TMPS_MAX; tmps++) {
				double ref = ref_sensitivity(gtd, eref3,
							     ref_tmps_to_degc(tmps));
				s32 st;
				double err;

				assert_int_equal(as9888_sensitivity_q16(&ee.axis[0],
						ee.t_rt_mdegc,
						as9888_tmps_to_mdegc(tmps), &st), 0);
				err = fabs(q16(st) - ref) / ref;
				if (err > worst)
					worst = err;
				count++;
			}
		}
	}
	print_message("sensitivity: %lu cases, worst relative error %.3g (bar %.0e)\n",
		      count, worst, SENS_REL_BAR);
	assert_true(worst <= SENS_REL_BAR);
}

/*
 * All sign/DT combinations x all ET1/ET2 x temperatures; Kote is exact
 * (a ratio of integers), so Ot(t) carries one rounding to 1/65536 LSB.
 */
static void sweep_offset(void **state)
{
	static const s32 temps_mdegc[] = { -30000, 24375, 85000 };
	const s32 t_l = 23750, ot_l_q16 = 1234567;
	double worst = 0.0, worst_kote = 0.0;
	unsigned long count = 0;
	int dt9, et1, et2;
	unsigned int i;

	for (dt9 = 0; dt9 < 512; dt9++) {
		u8 eaga = (dt9 >> 8) << 7 | 28, eadt = dt9 & 0xff;
		struct as9888_axis_trim trim = {
			.st_rt = 256,
			.dt = dt9 >= 256 ? dt9 - 512 : dt9,
		};

		for (et1 = 0; et1 < 256; et1++) {
			for (et2 = 0; et2 < 256; et2++) {
				double kote = ref_kote(eaga, eadt, et1, et2);
				double kerr;

				as9888_kote(trim.dt, et1, et2, &trim.kote_num,
					    &trim.kote_den);
				kerr = fabs((double)trim.kote_num / trim.kote_den - kote);
				if (kerr > worst_kote)
					worst_kote = kerr;

				for (i = 0; i < sizeof(temps_mdegc) / sizeof(temps_mdegc[0]); i++) {
					double ref = ref_offset(kote, q16(ot_l_q16),
								t_l / 1000.0,
								temps_mdegc[i] / 1000.0);
					double err;
					s32 ot;

					assert_int_equal(as9888_offset_q16(&trim, ot_l_q16,
							t_l, temps_mdegc[i], &ot), 0);
					err = fabs(q16(ot) - ref);
					if (err > worst)
						worst = err;
					count++;
				}
			}
		}
	}
	print_message("offset: %lu cases, worst error %.3g LSB (bar %.1f), Kote worst %.3g LSB/degC\n",
		      count, worst, OFFSET_LSB_BAR, worst_kote);
	assert_true(worst <= OFFSET_LSB_BAR);
	assert_true(worst_kote <= 1e-9);
}

static int dac_clamped_ref(double lin)
{
	if (lin > AS9888_DAC_LIN_MAX)
		return AS9888_DAC_LIN_MAX;
	if (lin < -AS9888_DAC_LIN_MAX)
		return -AS9888_DAC_LIN_MAX;
	return (int)lin;
}

static void check_dac(u8 ga, u8 da, s32 ot_l_q16, unsigned long *mismatches,
		      unsigned long *ties, unsigned long *tie_mismatches)
{
	double ot_l = q16(ot_l_q16);
	double x = ((ga & 0x3f) + 16) / 2048.0 * ot_l;
	double lin = ref_dac_opt_lin(ga, da, ga & 0x3f, ot_l);
	int want = ref_lin2dac(ga, dac_clamped_ref(lin));
	u8 got;
	int ret;

	if (x - floor(x) == 0.5)
		(*ties)++;
	ret = as9888_dac_opt(ga, da, ga & 0x3f, ot_l_q16, &got);
	if (got != want || (ret == -ERANGE) != (fabs(lin) > AS9888_DAC_LIN_MAX)) {
		if (x - floor(x) != 0.5)
			(*mismatches)++;
		else
			(*tie_mismatches)++;
	}
}

/*
 * All GA x all DA x a sweep of Ot_L; then all gains x a dense sweep of Ot_L
 * (1/64 LSB steps over +-3000 LSB) for every rounding boundary.
 */
static void sweep_dac(void **state)
{
	unsigned long mismatches = 0, ties = 0, tie_mismatches = 0, count = 0;
	int ga, da, k;
	s32 ot;

	for (ga = 0; ga < 128; ga++)
		for (da = 0; da < 256; da++)
			for (k = -64; k <= 64; k++) {
				/* includes exact ties: multiples of 2048 / (2 (g + 16)) */
				ot = k * (s32)(AS9888_Q16_ONE * 1000 / 64) + k * 977;
				check_dac(ga, da, ot, &mismatches, &ties, &tie_mismatches);
				count++;
			}

	for (ga = 0; ga < 128; ga++)
		for (ot = -3000 * AS9888_Q16_ONE; ot <= 3000 * AS9888_Q16_ONE;
		     ot += AS9888_Q16_ONE / 64) {
			check_dac(ga, 0x80, ot, &mismatches, &ties, &tie_mismatches);
			count++;
		}

	print_message("DACopt: %lu cases, %lu exact ties (%lu differ), %lu mismatches outside ties\n",
		      count, ties, tie_mismatches, mismatches);
	assert_true(ties > 0);
	assert_int_equal(mismatches, 0);
}

/*
 * The driver's compensated reading of one axis: every raw value at every
 * valid TMPS code (-30..85 degC), for every sensitivity coefficient, both
 * ends of the sensitivity detail, a DAC away from the factory value and a
 * calibbias. Bar: OUT_LSB_BAR from the double reference,
 * and the raw value back exactly.
 */
static void sweep_compensation(void **state)
{
	static const int details[] = { 0x10, 0x0f };	/* -16 and +15 */
	static const s32 biases[] = { 0, 487, -AS9888_CALIBBIAS_MAX };
	const u8 eaga = 0x80 | 0x40 | 28, eadt = 0x38, eada = 0x0d;
	const u8 et1 = 0x88, et2 = 0x50, eref3 = 0x15;
	double worst = 0.0;
	unsigned long count = 0, lost = 0;
	int kste, d, lin_shift, tmps, raw;
	unsigned int c;

	for (kste = 0; kste < 8; kste++)
	for (d = 0; d < 2; d++)
	for (lin_shift = -20; lin_shift <= 20; lin_shift += 40)
	for (c = 0; c < ARRAY_SIZE(biases); c++) {
		u8 ee_raw[AS9888_EEPROM_LEN] = { 0 };
		u8 gtd = kste << 5 | details[d];
		struct as9888_accel_cal cal = { };
		struct as9888_eeprom ee;
		double kote, ot_ref;
		u8 da;
		int axis;

		for (axis = 0; axis < AS9888_AXES; axis++) {
			ee_raw[AS9888_EE_EAGA(axis)] = eaga;
			ee_raw[AS9888_EE_EADT(axis)] = eadt;
			ee_raw[AS9888_EE_EADA(axis)] = eada;
			ee_raw[AS9888_EE_EAGTD(axis)] = gtd;
		}
		ee_raw[AS9888_EE_EREF3] = eref3;
		ee_raw[AS9888_EE_ET1] = et1;
		ee_raw[AS9888_EE_ET2] = et2;
		assert_int_equal(as9888_eeprom_decode(ee_raw, &ee), 0);
		cal.bias[0] = biases[c];

		da = ref_lin2dac(ee.axis[0].ga,
				 ref_dac2lin(ee.axis[0].ga, eada) + lin_shift);
		kote = ref_kote(eaga, eadt, et1, et2);
		/* the offset the DAC in use gives, 6.6 */
		ot_ref = -cal.bias[0] * (double)ee.axis[0].st_rt /
			 AS9888_ACC_OUT_PER_G +
			 (ref_dac2lin(ee.axis[0].ga, da) -
			  ref_dac2lin(ee.axis[0].ga, eada)) * 2048.0 /
			 ((eaga & 0x3f) + 16);

		for (tmps = AS9888_TMPS_MIN; tmps <= AS9888_TMPS_MAX; tmps++) {
			double t = ref_tmps_to_degc(tmps);
			double st = ref_sensitivity(gtd, eref3, t);
			double ot = ref_offset(kote, ot_ref,
					       ee.t_rt_mdegc / 1000.0, t);
			s32 ot_q16, st_q16;

			assert_int_equal(as9888_accel_correction(&ee, &cal, 0, da,
					as9888_tmps_to_mdegc(tmps), &ot_q16,
					&st_q16), 0);
			for (raw = AS9888_ACC_MIN; raw <= AS9888_ACC_MAX; raw++) {
				double ref = (raw - ot) / st * AS9888_ACC_OUT_PER_G;
				s16 out, back;
				double err;

				if (as9888_accel_compensate(raw, ot_q16, st_q16, &out))
					continue;	/* beyond s16, clamped */
				err = fabs(out - ref);
				if (err > worst)
					worst = err;
				if (as9888_accel_uncompensate(out, ot_q16, st_q16, &back) ||
				    back != raw)
					lost++;
				count++;
			}
		}
	}
	print_message("compensation: %lu cases, worst error %.6f output LSB (bar %.3f), %lu raw values not recovered\n",
		      count, worst, OUT_LSB_BAR, lost);
	assert_true(count > 0);
	assert_true(worst <= OUT_LSB_BAR);
	assert_int_equal(lost, 0);
}

/*
 * At t_RT a calibbias moves the compensated reading by exactly its value:
 * every axis of the example EEPROM, every DAC code, every raw value. With
 * half-way cases rounded to even instead of up, 1196 of these miss by one.
 */
static void sweep_bias_moves_output(void **state)
{
	static const u8 example[AS9888_EEPROM_LEN] = {
		0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
		0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
	};
	static const s32 biases[] = {
		1, -1, 7, -300, 1024, -2047, AS9888_CALIBBIAS_MAX,
		-AS9888_CALIBBIAS_MAX,
	};
	struct as9888_eeprom ee;
	unsigned long count = 0, missed = 0;
	unsigned int i;
	int axis, lin, raw;

	assert_int_equal(as9888_eeprom_decode(example, &ee), 0);
	for (axis = 0; axis < AS9888_AXES; axis++)
	for (lin = -AS9888_DAC_LIN_MAX; lin <= AS9888_DAC_LIN_MAX; lin++)
	for (i = 0; i < ARRAY_SIZE(biases); i++) {
		struct as9888_accel_cal cal0 = { }, cal = { };
		u8 da = as9888_lin2dac(ee.axis[axis].ga, lin);
		s32 ot0, st0, ot, st;

		cal.bias[axis] = biases[i];
		assert_int_equal(as9888_accel_correction(&ee, &cal0, axis, da,
							 ee.t_rt_mdegc, &ot0,
							 &st0), 0);
		assert_int_equal(as9888_accel_correction(&ee, &cal, axis, da,
							 ee.t_rt_mdegc, &ot, &st),
				 0);
		for (raw = AS9888_ACC_MIN + 1; raw < AS9888_ACC_MAX; raw++) {
			s16 out0, out;

			if (as9888_accel_compensate(raw, ot0, st0, &out0) ||
			    as9888_accel_compensate(raw, ot, st, &out))
				continue;	/* clamped */
			count++;
			if (out - out0 != biases[i])
				missed++;
		}
	}
	print_message("calibbias at t_RT: %lu cases, %lu not moved by exactly the calibbias\n",
		      count, missed);
	assert_true(count > 0);
	assert_int_equal(missed, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(sweep_sensitivity),
		cmocka_unit_test(sweep_offset),
		cmocka_unit_test(sweep_dac),
		cmocka_unit_test(sweep_compensation),
		cmocka_unit_test(sweep_bias_moves_output),
	};

	return cmocka_run_group_tests_name("calib-sweep", tests, NULL, NULL);
}
