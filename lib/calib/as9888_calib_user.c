// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 calibration arithmetic that only userspace needs: the factory
 * test's level-test offsets and the calibbias they give (6.5, 6.6), sample
 * statistics (Note 2, D7), posture detection (D8), the judgments of the
 * application note, and the inverse of the driver's
 * compensation (which the daemon's IIO backend uses to get back the chip's
 * own reading, checking it sample by sample: it is no kernel ABI).
 *
 * The kernel never builds this file. It is the one definition for the
 * daemon and the userspace tests, and builds on the driver's unit
 * (drivers/iio/imu/as9888/as9888_calib.c) with the same integer rules: no
 * undefined behaviour for any value of the inputs.
 */

#include <linux/bitfield.h>
#include <linux/bitops.h>
#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/math64.h>

#include "as9888_calib.h"

#define AS9888_UG_PER_G			1000000
#define AS9888_ACC_MEAN_Q16_MAX		(32768LL * AS9888_Q16_ONE)

/**
 * as9888_mdegc_to_tmps() - the TMPS code the chip reports at a temperature
 * @t_mdegc: temperature, millidegrees Celsius
 *
 * Return: rint(176 - 1.6 * t), not limited to the valid code range.
 */
int as9888_mdegc_to_tmps(s32 t_mdegc)
{
	return AS9888_TMPS_ZERO_DEGC -
	       (int)as9888_div_round_s64(t_mdegc, AS9888_MDEGC_PER_TMPS);
}

/**
 * as9888_tmps_mean_to_mdegc() - temperature of the mean of n TMPS codes
 * @tmps_sum: sum of the codes
 * @n: number of codes, 1..AS9888_SAMPLES_MAX
 * @t_mdegc: the temperature, rounded to the nearest millidegree
 *
 * Return: 0, -EINVAL for a bad @n, -ERANGE for a sum no codes can give.
 */
int as9888_tmps_mean_to_mdegc(s64 tmps_sum, u32 n, s32 *t_mdegc)
{
	s64 num;

	if (n == 0 || n > AS9888_SAMPLES_MAX)
		return -EINVAL;
	if (!as9888_in_range(tmps_sum, 0, (s64)U8_MAX * n))
		return -ERANGE;

	num = ((s64)AS9888_TMPS_ZERO_DEGC * n - tmps_sum) *
	      AS9888_MDEGC_PER_TMPS;
	*t_mdegc = (s32)as9888_div_round_s64(num, n);

	return 0;
}

/**
 * as9888_offset_level_q16() - Ot_L = A + St(t_L) * G for one axis
 * @a_mean_q16: mean raw level reading A, Q16
 * @st_level_q16: sensitivity at the level-test temperature, Q16
 * @g: the axis' component of the gravity direction, -1, 0 or 1
 * @ot_l_q16: the level-test offset, Q16
 *
 * Return: 0 or -EINVAL for inputs out of range.
 */
int as9888_offset_level_q16(s32 a_mean_q16, s32 st_level_q16, int g,
			    s32 *ot_l_q16)
{
	if (!as9888_in_range(a_mean_q16, -AS9888_ACC_MEAN_Q16_MAX,
			     AS9888_ACC_MEAN_Q16_MAX) ||
	    !as9888_in_range(st_level_q16, 0, AS9888_ST_Q16_MAX) ||
	    !as9888_in_range(g, -1, 1))
		return -EINVAL;

	*ot_l_q16 = a_mean_q16 + st_level_q16 * g;

	return 0;
}

/**
 * as9888_accel_ug() - compensated reading a = (raw - Ot(t)) / St(t)
 * @raw: raw accelerometer sample
 * @ot_q16: offset at the temperature of the sample, Q16
 * @st_q16: sensitivity at that temperature, Q16, > 0
 * @a_ug: the acceleration, micro-g
 *
 * Return: 0, -EINVAL for a sensitivity <= 0, -ERANGE when the result does
 * not fit.
 */
int as9888_accel_ug(s16 raw, s32 ot_q16, s32 st_q16, s32 *a_ug)
{
	s64 a;

	if (st_q16 <= 0)
		return -EINVAL;

	a = as9888_div_round_s64(((s64)raw * AS9888_Q16_ONE - ot_q16) *
				 AS9888_UG_PER_G, st_q16);
	if (!as9888_in_range(a, S32_MIN, S32_MAX))
		return -ERANGE;

	*a_ug = (s32)a;

	return 0;
}

/*
 * The calibbias that an offset at t_RT with the factory DAC value stands
 * for: -O / St_RT * 1024 output LSB, rounded to nearest. The inverse of
 * as9888_bias_offset_q16() (which is exact; this rounds). -EINVAL for an
 * invalid @trim, -ERANGE beyond +-AS9888_CALIBBIAS_MAX.
 */
static int as9888_offset_bias(const struct as9888_axis_trim *trim, s32 ot_q16,
			      s32 *bias)
{
	s64 b;

	if (!as9888_trim_valid(trim))
		return -EINVAL;

	/* -O / St_RT * 1024 with O in Q16: -O / (St_RT * 64) */
	b = as9888_div_round_s64(-(s64)ot_q16, (s64)trim->st_rt *
				 AS9888_Q16_ONE / AS9888_ACC_OUT_PER_G);
	if (!as9888_in_range(b, -AS9888_CALIBBIAS_MAX, AS9888_CALIBBIAS_MAX))
		return -ERANGE;

	*bias = (s32)b;

	return 0;
}

/**
 * as9888_accel_cal_from_level() - the calibration a level test gives
 * @ee: the decoded EEPROM
 * @a_mean_q16: mean raw level reading A per axis, Q16
 * @t_level_mdegc: the level-test temperature t_L
 * @g: the gravity direction during the level test
 * @da: the DAC register values the level test ran with
 * @cal: the calibbias of each axis: Ot_L = A + St(t_L) * G (6.5), moved
 *	 to the factory DAC value (6.6) and to t_RT with Kote (6.5), as
 *	 output LSB at St_RT, negated and rounded to nearest
 *
 * Return: 0, -EINVAL or -ERANGE for inputs out of range (-ERANGE also
 * for an offset beyond +-AS9888_CALIBBIAS_MAX).
 */
int as9888_accel_cal_from_level(const struct as9888_eeprom *ee,
				const s32 a_mean_q16[AS9888_AXES],
				s32 t_level_mdegc, const s8 g[AS9888_AXES],
				const u8 da[AS9888_AXES],
				struct as9888_accel_cal *cal)
{
	s32 st_q16, ot_l_q16, ref_q16;
	int axis, ret;

	if (!as9888_in_range(t_level_mdegc, as9888_tmps_to_mdegc(AS9888_TMPS_MAX),
			     as9888_tmps_to_mdegc(AS9888_TMPS_MIN)))
		return -ERANGE;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		const struct as9888_axis_trim *trim = &ee->axis[axis];

		ret = as9888_sensitivity_q16(trim, ee->t_rt_mdegc,
					     t_level_mdegc, &st_q16);
		if (ret)
			return ret;
		ret = as9888_offset_level_q16(a_mean_q16[axis], st_q16, g[axis],
					      &ot_l_q16);
		if (ret)
			return ret;
		ret = as9888_offset_dac_shift_q16(trim, ot_l_q16, da[axis],
						  trim->da, &ref_q16);
		if (ret)
			return ret;
		ret = as9888_offset_q16(trim, ref_q16, t_level_mdegc,
					ee->t_rt_mdegc, &ref_q16);
		if (ret)
			return ret;
		ret = as9888_offset_bias(trim, ref_q16, &cal->bias[axis]);
		if (ret)
			return ret;
	}

	return 0;
}

/**
 * as9888_dac_bias() - a calibbias the driver realises with a given DAC
 * @trim: the axis' decoded EEPROM data
 * @da: the DAC register value wanted
 * @bias: a calibbias whose as9888_bias_dac() is @da: the offset of
 *	  (dac2lin(EAxDA) - dac2lin(@da)) DAC steps, at St_RT
 *
 * This is how a factory test through the driver runs the chip with the DAC
 * values it wants: the driver's only calibration attribute is calibbias.
 *
 * Return: 0, -EINVAL for an invalid @da or @trim, -ERANGE when no
 * calibbias within +-AS9888_CALIBBIAS_MAX gives @da.
 */
int as9888_dac_bias(const struct as9888_axis_trim *trim, u8 da, s32 *bias)
{
	s32 ot_q16, b;
	u8 got;
	int ret;

	if (!as9888_trim_valid(trim))
		return -EINVAL;

	/* A zero offset at @da, moved to the factory DAC value */
	ret = as9888_offset_dac_shift_q16(trim, 0, da, trim->da, &ot_q16);
	if (ret)
		return ret;
	ret = as9888_offset_bias(trim, ot_q16, &b);
	if (ret)
		return ret;
	if (as9888_bias_dac(trim, b, &got) ||
	    as9888_dac2lin(trim->ga, got) != as9888_dac2lin(trim->ga, da))
		return -ERANGE;

	*bias = b;

	return 0;
}

/**
 * as9888_accel_uncompensate() - the raw reading behind a compensated one
 * @out: a value of as9888_accel_compensate() that was not clamped
 * @ot_q16: the offset it was compensated with, Q16
 * @st_q16: the sensitivity it was compensated with, Q16, > 0
 * @raw: rint(out * St(t) / AS9888_ACC_OUT_PER_G + Ot(t))
 *
 * Exact inverse of as9888_accel_compensate() for every raw reading of the
 * chip while St(t) < AS9888_ACC_OUT_PER_G LSB/g: the output was rounded by
 * at most half a step, which is then less than half a raw LSB.
 *
 * Return: 0, -EINVAL for a sensitivity <= 0, -ERANGE for an output at a
 * limit (it may have been clamped) or a raw value the chip cannot give.
 */
int as9888_accel_uncompensate(s16 out, s32 ot_q16, s32 st_q16, s16 *raw)
{
	s64 r;

	if (!as9888_in_range(st_q16, 1, AS9888_ST_Q16_MAX))
		return -EINVAL;
	if (out <= AS9888_ACC_OUT_MIN || out >= AS9888_ACC_OUT_MAX)
		return -ERANGE;

	r = as9888_div_round_s64((s64)out * st_q16 +
				 (s64)ot_q16 * AS9888_ACC_OUT_PER_G,
				 (s64)AS9888_ACC_OUT_PER_G * AS9888_Q16_ONE);
	if (!as9888_in_range(r, AS9888_ACC_MIN, AS9888_ACC_MAX))
		return -ERANGE;

	*raw = (s16)r;

	return 0;
}

/**
 * as9888_mean_q16() - mean of n s16 samples in Q16, rounded to nearest
 * @sum: sum of the samples
 * @n: number of samples, 1..AS9888_SAMPLES_MAX
 * @mean_q16: the mean
 *
 * Return: 0, -EINVAL for a bad @n, -ERANGE for a sum no s16 samples give.
 */
int as9888_mean_q16(s64 sum, u32 n, s32 *mean_q16)
{
	if (n == 0 || n > AS9888_SAMPLES_MAX)
		return -EINVAL;
	if (!as9888_in_range(sum, (s64)S16_MIN * n, (s64)S16_MAX * n))
		return -ERANGE;

	*mean_q16 = (s32)as9888_div_round_s64(sum * AS9888_Q16_ONE, n);

	return 0;
}

/* Steps 3-20..3-22: the spread of the averaged samples */
bool as9888_fluctuation_ok(s16 min, s16 max, u32 limit)
{
	return max >= min && (u32)((s32)max - min) <= limit;
}

/**
 * as9888_samples_needed() - N >= n * (sigma / error)^2 (Note 2, D7)
 * @n: number of samples in each pilot average sigma was measured over
 * @sigma_q16: standard deviation of the n-sample averages, LSB in Q16
 * @error_q16: permissible error of the final average, LSB in Q16
 *
 * Return: the number of samples to average, at least AS9888_SAMPLES_MIN;
 * a value above AS9888_SAMPLES_MAX means the environment is too noisy
 * for the permissible error (also returned for @error_q16 == 0).
 */
u32 as9888_samples_needed(u32 n, u32 sigma_q16, u32 error_q16)
{
	u64 var, err2, num, q;

	if (error_q16 == 0)
		return AS9888_SAMPLES_MAX + 1;
	if (n == 0)
		n = 1;

	var = (u64)sigma_q16 * sigma_q16;
	err2 = (u64)error_q16 * error_q16;
	if (var > U64_MAX / n)
		return AS9888_SAMPLES_MAX + 1;

	num = var * n;
	q = div64_u64(num, err2);
	if (q * err2 < num)
		q++;

	if (q > AS9888_SAMPLES_MAX)
		return AS9888_SAMPLES_MAX + 1;

	return max_t(u32, (u32)q, AS9888_SAMPLES_MIN);
}

/**
 * as9888_posture_detect() - gravity direction from a level reading (D8)
 * @a_mean_q16: mean raw reading per axis, Q16
 * @g: the gravity direction: the axis of largest |A|, opposite to A
 *
 * Return: the index of the vertical axis.
 */
int as9888_posture_detect(const s32 a_mean_q16[AS9888_AXES],
			  s8 g[AS9888_AXES])
{
	int axis, vertical = 0;

	for (axis = 1; axis < AS9888_AXES; axis++)
		if (abs((s64)a_mean_q16[axis]) > abs((s64)a_mean_q16[vertical]))
			vertical = axis;

	for (axis = 0; axis < AS9888_AXES; axis++)
		g[axis] = 0;
	g[vertical] = a_mean_q16[vertical] > 0 ? -1 : 1;

	return vertical;
}

/**
 * as9888_posture_check() - is the unit level with gravity along G? (D8)
 * @a_mean_q16: mean raw reading per axis, Q16
 * @st_q16: sensitivity per axis at the level-test temperature, Q16
 * @g: gravity direction, one axis at -1 or +1, the others 0
 *
 * A horizontal axis must read at most St/2, the vertical one at least St/2
 * against the direction of gravity.
 */
enum as9888_posture_error
as9888_posture_check(const s32 a_mean_q16[AS9888_AXES],
		     const s32 st_q16[AS9888_AXES],
		     const s8 g[AS9888_AXES])
{
	int axis, vertical = -1;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		if (g[axis] == 0)
			continue;
		if ((g[axis] != 1 && g[axis] != -1) || vertical >= 0)
			return AS9888_POSTURE_BAD_G;
		vertical = axis;
	}
	if (vertical < 0)
		return AS9888_POSTURE_BAD_G;

	for (axis = 0; axis < AS9888_AXES; axis++)
		if (axis != vertical &&
		    2 * abs((s64)a_mean_q16[axis]) > (s64)st_q16[axis])
			return AS9888_POSTURE_NOT_LEVEL;

	if ((s64)a_mean_q16[vertical] * g[vertical] > 0)
		return AS9888_POSTURE_WRONG_SIGN;
	if (2 * abs((s64)a_mean_q16[vertical]) < (s64)st_q16[vertical])
		return AS9888_POSTURE_NOT_VERTICAL;

	return AS9888_POSTURE_OK;
}
