// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 calibration arithmetic, integer only.
 *
 * Every formula here is from section 6 of the AS9888 datasheet and the
 * vendor's application note on the on-board function test; the fixed-point
 * formats are described in as9888_calib.h. Inputs are range checked first so
 * that no product can overflow, whatever the caller passes.
 */

#include <linux/bitfield.h>
#include <linux/bitops.h>
#include <linux/errno.h>
#include <linux/export.h>
#include <linux/limits.h>
#include <linux/math.h>
#include <linux/math64.h>
#include <linux/minmax.h>
#include <linux/types.h>

#include <kunit/visibility.h>

#include "as9888_calib.h"

/*
 * Kste / 100 per degC in units of 1e-8: -0.428125 %/degC for index 0, then
 * +0.04375 %/degC per step (section 6.4).
 */
#define AS9888_KSTE_BASE_E8		(-428125)
#define AS9888_KSTE_STEP_E8		43750
#define AS9888_KSTE_UNIT		100000000000LL	/* 1e8 * mdegC/degC */
#define AS9888_MDEGC_PER_DEGC		1000
#define AS9888_ST_NOMINAL		256
#define AS9888_ST_RT_MIN		(AS9888_ST_NOMINAL - 16)
#define AS9888_ST_RT_MAX		(AS9888_ST_NOMINAL + 15)
#define AS9888_KSTE_IDX_MAX		7
#define AS9888_EHC_OFFSET		128
#define AS9888_DAC_FULL_SCALE		2048
/*
 * Kote = s9 * 1.5 / dT with dT = dTMPS / 1.6 degC, that is
 * s9 * 12 / (5 * dTMPS); the fallback span dT = 35 degC (factory
 * temperatures unusable) gives s9 * 3 / 70.
 */
#define AS9888_KOTE_NUM			12
#define AS9888_KOTE_DEN			5
#define AS9888_KOTE_FALLBACK_NUM	3
#define AS9888_KOTE_FALLBACK_DEN	70
#define AS9888_KOTE_NUM_MAX		(256 * AS9888_KOTE_NUM)
#define AS9888_KOTE_DEN_MAX		(255 * AS9888_KOTE_DEN)
/* EAxGA[7] is bit 8 of the 9-bit offset temperature property DT */
#define AS9888_DT_SIGN_MSK		BIT(8)
#define AS9888_DT_LOW_MSK		GENMASK(7, 0)
/* DAC rounding: (gain + 16) / 2048 * Ot_L with Ot_L in Q16 */
#define AS9888_DAC_ROUND_DIV		BIT_ULL(27)	/* 2048 * 65536 */
/* calibbias to Q16 raw LSB at St_RT: bias * St_RT * 2^16 / 1024 */
#define AS9888_Q16_PER_OUT		(AS9888_Q16_ONE / AS9888_ACC_OUT_PER_G)

/**
 * as9888_div_round_s64() - divide and round to nearest, ties to even
 * @num: dividend
 * @den: divisor, must be > 0 (0 is returned otherwise)
 *
 * This is rint() of the exact quotient, the rounding of the DAC estimate.
 *
 * Return: the rounded quotient, or 0 when @den is not positive.
 */
s64 as9888_div_round_s64(s64 num, s64 den)
{
	s64 q, r;

	if (den <= 0)
		return 0;

	q = div64_s64(num, den);
	r = num - q * den;
	if (r < 0) {
		q--;
		r += den;
	}
	/* Now q = floor(num / den) and 0 <= r < den. */
	if (r > den - r || (r == den - r && (q & 1)))
		q++;

	return q;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_div_round_s64);

/**
 * as9888_q8_to_milli() - a Q8 value in thousandths, rounded to nearest
 * @q8: the value in 1/256 (for example as9888_mag_adjust_q8())
 *
 * Ties go to even (as9888_div_round_s64()). Exact for every s32 @q8:
 * |@q8 * 1000| < 2^42.
 *
 * Return: round(@q8 * 1000 / 256).
 */
s64 as9888_q8_to_milli(s32 q8)
{
	return as9888_div_round_s64((s64)q8 * AS9888_MILLI, AS9888_Q8_ONE);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_q8_to_milli);

static bool as9888_t_valid(s32 t_mdegc)
{
	return as9888_in_range(t_mdegc, AS9888_CALIB_T_MIN_MDEGC,
			       AS9888_CALIB_T_MAX_MDEGC);
}

VISIBLE_IF_KUNIT bool as9888_tmps_valid(u8 tmps)
{
	return tmps >= AS9888_TMPS_MIN && tmps <= AS9888_TMPS_MAX;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_tmps_valid);

/* T = (176 - TMPS) / 1.6 degC, exact in millidegrees */
s32 as9888_tmps_to_mdegc(u8 tmps)
{
	return (AS9888_TMPS_ZERO_DEGC - (s32)tmps) * AS9888_MDEGC_PER_TMPS;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_tmps_to_mdegc);

/* Magnetometer sensitivity adjustment: H * (EHC + 128) / 256, in Q8 */
s32 as9888_mag_adjust_q8(s16 h, u8 ehc)
{
	return (s32)h * ((s32)ehc + AS9888_EHC_OFFSET);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_mag_adjust_q8);

/* Magnetometer overflow (section 5): -4096 and 4095, or anything beyond */
bool as9888_mag_overflow(s16 h)
{
	return h <= AS9888_MAG_MIN || h >= AS9888_MAG_MAX;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_mag_overflow);

/**
 * as9888_selftest_window_ok() - an axis' magnetometer self-test window
 * @axis: 0 (X), 1 (Y) or 2 (Z)
 * @adj_q8: the adjusted self-test reading of that axis, in 1/256 LSB
 *
 * Comparing in Q8 is exact.
 *
 * Return: true when @adj_q8 is inside the window of @axis.
 */
VISIBLE_IF_KUNIT bool as9888_selftest_window_ok(int axis, s32 adj_q8)
{
	s32 lo, hi;

	switch (axis) {
	case 0:
	case 1:
		lo = AS9888_SELFTEST_XY_MIN;
		hi = AS9888_SELFTEST_XY_MAX;
		break;
	case 2:
		lo = AS9888_SELFTEST_Z_MIN;
		hi = AS9888_SELFTEST_Z_MAX;
		break;
	default:
		return false;
	}

	return adj_q8 >= lo * AS9888_Q8_ONE && adj_q8 <= hi * AS9888_Q8_ONE;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_selftest_window_ok);

/**
 * as9888_selftest_ok() - magnetometer self-test judgment of one axis
 * @axis: 0 (X), 1 (Y) or 2 (Z)
 * @h: raw self-test reading of that axis
 * @ehc: the axis' sensitivity adjustment from the EEPROM
 *
 * The reading must not overflow, and adjusted it must be in its window.
 *
 * Return: true when the axis passes.
 */
bool as9888_selftest_ok(int axis, s16 h, u8 ehc)
{
	return !as9888_mag_overflow(h) &&
	       as9888_selftest_window_ok(axis, as9888_mag_adjust_q8(h, ehc));
}
EXPORT_SYMBOL_IF_KUNIT(as9888_selftest_ok);

VISIBLE_IF_KUNIT bool as9888_trim_valid(const struct as9888_axis_trim *trim)
{
	return as9888_in_range(trim->st_rt, AS9888_ST_RT_MIN, AS9888_ST_RT_MAX) &&
	       trim->kste_idx <= AS9888_KSTE_IDX_MAX &&
	       as9888_in_range(trim->kote_num, -AS9888_KOTE_NUM_MAX,
			       AS9888_KOTE_NUM_MAX) &&
	       as9888_in_range(trim->kote_den, 1, AS9888_KOTE_DEN_MAX);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_trim_valid);

/**
 * as9888_sensitivity_q16() - St(t) = St_RT * (1 + Kste / 100 * (t - t_RT))
 * @trim: the axis' decoded EEPROM data
 * @t_rt_mdegc: the factory room temperature t_RT
 * @t_mdegc: the temperature t
 * @st_q16: the sensitivity, LSB/g in Q16
 *
 * Return: 0, -EINVAL for an invalid @trim, -ERANGE for a temperature out of
 * the accepted range.
 */
VISIBLE_IF_KUNIT int
as9888_sensitivity_q16(const struct as9888_axis_trim *trim, s32 t_rt_mdegc,
		       s32 t_mdegc, s32 *st_q16)
{
	s64 kste_e8, factor;

	if (!as9888_trim_valid(trim))
		return -EINVAL;
	if (!as9888_t_valid(t_rt_mdegc) || !as9888_t_valid(t_mdegc))
		return -ERANGE;

	kste_e8 = AS9888_KSTE_BASE_E8 + AS9888_KSTE_STEP_E8 * trim->kste_idx;
	/* |kste_e8 * dt| <= 428125 * 250000, so factor stays below 2.1e11 */
	factor = AS9888_KSTE_UNIT + kste_e8 * ((s64)t_mdegc - t_rt_mdegc);
	/* st_rt * 2^16 * factor <= 271 * 2^16 * 2.1e11 < 2^62 */
	*st_q16 = (s32)as9888_div_round_s64((s64)trim->st_rt * AS9888_Q16_ONE *
					    factor, AS9888_KSTE_UNIT);

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_sensitivity_q16);

/**
 * as9888_offset_q16() - Ot(t) = Kote * (t - t_L) + Ot_L for one axis
 * @trim: the axis' decoded EEPROM data (for Kote)
 * @ot_l_q16: the level-test offset Ot_L, Q16
 * @t_level_mdegc: the level-test temperature t_L
 * @t_mdegc: the temperature t
 * @ot_q16: the offset at @t_mdegc, Q16
 *
 * Return: 0, -EINVAL for an invalid @trim, -ERANGE for a temperature out of
 * range or an offset that does not fit.
 */
VISIBLE_IF_KUNIT int
as9888_offset_q16(const struct as9888_axis_trim *trim, s32 ot_l_q16,
		  s32 t_level_mdegc, s32 t_mdegc, s32 *ot_q16)
{
	s64 drift, ot;

	if (!as9888_trim_valid(trim))
		return -EINVAL;
	if (!as9888_t_valid(t_level_mdegc) || !as9888_t_valid(t_mdegc))
		return -ERANGE;

	/* |num * dt * 2^16| <= 3072 * 250000 * 2^16 < 2^56 */
	drift = as9888_div_round_s64((s64)trim->kote_num *
				     ((s64)t_mdegc - t_level_mdegc) *
				     AS9888_Q16_ONE,
				     (s64)trim->kote_den * AS9888_MDEGC_PER_DEGC);
	ot = drift + ot_l_q16;
	if (!as9888_in_range(ot, S32_MIN, S32_MAX))
		return -ERANGE;

	*ot_q16 = (s32)ot;

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_offset_q16);

/**
 * as9888_dac2lin() - DAC register value to signed linear code (6.6)
 * @ga: the axis' gain register value (bit 6 is the polarity)
 * @da: the DAC register value
 *
 * Return: the linear code, -67..67 for a valid @da.
 */
int as9888_dac2lin(u8 ga, u8 da)
{
	int lin = da >= AS9888_DAC_ZERO ? da - AS9888_DAC_ZERO : -(int)da;

	return ga & AS9888_GA_POLARITY_MSK ? -lin : lin;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_dac2lin);

/**
 * as9888_lin2dac() - signed linear code to DAC register value (6.6)
 * @ga: the axis' gain register value (bit 6 is the polarity)
 * @lin: linear code; values beyond +-AS9888_DAC_LIN_MAX are clamped
 *
 * Return: the DAC register value.
 */
u8 as9888_lin2dac(u8 ga, int lin)
{
	lin = clamp(lin, -AS9888_DAC_LIN_MAX, AS9888_DAC_LIN_MAX);
	if (ga & AS9888_GA_POLARITY_MSK)
		lin = -lin;

	return lin >= 0 ? AS9888_DAC_ZERO + lin : -lin;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_lin2dac);

VISIBLE_IF_KUNIT bool as9888_dac_valid(u8 da)
{
	return da <= AS9888_DAC_NEG_MAX ||
	       (da >= AS9888_DAC_ZERO && da <= AS9888_DAC_POS_MAX);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_dac_valid);

/* Output change per linear DAC code: 2048 / (GA[5:0] + 16) LSB, in Q16 */
VISIBLE_IF_KUNIT s32 as9888_dac_step_q16(u8 ga)
{
	return (s32)as9888_div_round_s64((s64)AS9888_DAC_FULL_SCALE *
					 AS9888_Q16_ONE,
					 FIELD_GET(AS9888_GA_GAIN_MSK, ga) +
					 AS9888_DAC_GAIN_OFFSET);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_dac_step_q16);

/**
 * as9888_offset_dac_shift_q16() - an offset as another DAC value gives it
 * @trim: the axis' decoded EEPROM data (its gain register value)
 * @ot_q16: the offset measured with DAC register value @from_da, Q16
 * @from_da: the DAC register value @ot_q16 was measured with
 * @to_da: another DAC register value
 * @out_q16: the offset the axis has with @to_da, Q16
 *
 * One linear DAC code moves the output by as9888_dac_step_q16() in the
 * direction of the code (section 6.6), so the offset moves by the change
 * of the linear code times that step.
 *
 * Return: 0, -EINVAL for an invalid DAC value, -ERANGE when the result
 * does not fit.
 */
VISIBLE_IF_KUNIT int
as9888_offset_dac_shift_q16(const struct as9888_axis_trim *trim, s32 ot_q16,
			    u8 from_da, u8 to_da, s32 *out_q16)
{
	s64 out;

	if (!as9888_dac_valid(from_da) || !as9888_dac_valid(to_da))
		return -EINVAL;

	out = (s64)ot_q16 + (s64)(as9888_dac2lin(trim->ga, to_da) -
				  as9888_dac2lin(trim->ga, from_da)) *
			    as9888_dac_step_q16(trim->ga);
	if (!as9888_in_range(out, S32_MIN, S32_MAX))
		return -ERANGE;

	*out_q16 = (s32)out;

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_offset_dac_shift_q16);

/**
 * as9888_dac_opt() - the optimal offset DAC value (datasheet 6.6)
 * @ga: the gain register value AxGA
 * @da: the DAC register value ADA the offset was measured with
 * @ee_gain: EAxGA[5:0]
 * @ot_l_q16: the offset measured with @da, Q16
 * @da_opt: DACopt
 *
 * lin_opt = dac2lin(ga, da) - rint((ee_gain + 16) / 2048 * Ot_L), clamped
 * to the DAC range.
 *
 * Return: 0, or -ERANGE when lin_opt had to be clamped (the function test
 * fails then; @da_opt holds the clamped value).
 */
int as9888_dac_opt(u8 ga, u8 da, u8 ee_gain, s32 ot_l_q16, u8 *da_opt)
{
	s64 shift, lin;

	/* |(63 + 16) * Ot_L| < 2^38: exact, and the division is exact rint */
	shift = as9888_div_round_s64(((s64)FIELD_GET(AS9888_GA_GAIN_MSK, ee_gain) +
				      AS9888_DAC_GAIN_OFFSET) * ot_l_q16,
				     (s64)AS9888_DAC_ROUND_DIV);
	lin = as9888_dac2lin(ga, da) - shift;
	*da_opt = as9888_lin2dac(ga, (int)clamp_t(s64, lin, -AS9888_DAC_LIN_MAX,
						  AS9888_DAC_LIN_MAX));

	return abs(lin) > AS9888_DAC_LIN_MAX ? -ERANGE : 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_dac_opt);

/**
 * as9888_bias_offset_q16() - the zero-g offset a calibbias stands for
 * @trim: the axis' decoded EEPROM data
 * @bias: the calibbias, output LSB (1/AS9888_ACC_OUT_PER_G g)
 * @ot_q16: the raw offset at t_RT with the factory DAC value, Q16
 *
 * At t_RT the sensitivity is St_RT exactly, so an offset O reads as
 * O / St_RT * 1024 output LSB: @ot_q16 = -@bias * St_RT / 1024, exact.
 *
 * Return: 0, -EINVAL for an invalid @trim, -ERANGE for @bias beyond
 * +-AS9888_CALIBBIAS_MAX.
 */
int as9888_bias_offset_q16(const struct as9888_axis_trim *trim, s32 bias,
			   s32 *ot_q16)
{
	if (!as9888_trim_valid(trim))
		return -EINVAL;
	if (!as9888_in_range(bias, -AS9888_CALIBBIAS_MAX, AS9888_CALIBBIAS_MAX))
		return -ERANGE;

	/* |8192 * 271 * 64| < 2^28 */
	*ot_q16 = -bias * trim->st_rt * AS9888_Q16_PER_OUT;

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_bias_offset_q16);

/**
 * as9888_bias_dac() - the offset DAC value that realises a calibbias
 * @trim: the axis' decoded EEPROM data
 * @bias: the calibbias, output LSB
 * @da: the DAC register value: the application note's DACopt
 *	(as9888_dac_opt()) for the offset @bias stands for, measured with
 *	the factory DAC value, so that the chip's own output is centred at
 *	t_RT; clamped to the DAC range
 *
 * The DAC is the coarse part of the correction, in the chip; the driver
 * compensates the rest (as9888_accel_correction()). A clamped DAC only
 * leaves the chip less headroom.
 *
 * Return: 0, -EINVAL for an invalid @trim, -ERANGE for @bias out of range.
 */
int as9888_bias_dac(const struct as9888_axis_trim *trim, s32 bias, u8 *da)
{
	s32 ot_q16;
	int ret;

	ret = as9888_bias_offset_q16(trim, bias, &ot_q16);
	if (ret)
		return ret;

	as9888_dac_opt(trim->ga, trim->da, trim->gain, ot_q16, da);

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_bias_dac);

/**
 * as9888_accel_correction() - offset and sensitivity of one axis now
 * @ee: the decoded EEPROM
 * @cal: the calibration (calibbias)
 * @axis: 0..2 for X..Z
 * @da: the DAC register value of the axis
 * @t_mdegc: the temperature of the sample
 * @ot_q16: the offset Ot(t) with @da (6.5), Q16
 * @st_q16: the sensitivity St(t) (6.4), Q16
 *
 * Ot(t) = Kote * (t - t_RT) + O_bias, O_bias the offset the calibbias
 * stands for, moved from the factory DAC value to @da.
 *
 * Return: 0, -EINVAL or -ERANGE for inputs out of range.
 */
int as9888_accel_correction(const struct as9888_eeprom *ee,
			    const struct as9888_accel_cal *cal, int axis,
			    u8 da, s32 t_mdegc, s32 *ot_q16, s32 *st_q16)
{
	const struct as9888_axis_trim *trim;
	s32 ref_q16;
	int ret;

	if (axis < 0 || axis >= AS9888_AXES)
		return -EINVAL;
	trim = &ee->axis[axis];

	ret = as9888_bias_offset_q16(trim, cal->bias[axis], &ref_q16);
	if (ret)
		return ret;
	ret = as9888_offset_q16(trim, ref_q16, ee->t_rt_mdegc, t_mdegc,
				&ref_q16);
	if (ret)
		return ret;
	ret = as9888_offset_dac_shift_q16(trim, ref_q16, trim->da, da, ot_q16);
	if (ret)
		return ret;

	return as9888_sensitivity_q16(trim, ee->t_rt_mdegc, t_mdegc, st_q16);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_accel_correction);

/**
 * as9888_accel_compensate() - a raw reading on the constant output scale
 * @raw: raw accelerometer sample
 * @ot_q16: offset at the temperature of the sample, Q16
 * @st_q16: sensitivity at that temperature, Q16, > 0
 * @out: (raw - Ot(t)) / St(t) * AS9888_ACC_OUT_PER_G (6.7), rounded to
 *	 nearest, half-way cases up
 *
 * The caller deals with a saturated @raw (as9888_acc_saturated()) first.
 *
 * Return: 0, -EINVAL for a sensitivity <= 0, or -ERANGE when the value
 * is beyond the s16 output range (@out then holds the nearer limit).
 */
int as9888_accel_compensate(s16 raw, s32 ot_q16, s32 st_q16, s16 *out)
{
	s64 num, a;

	if (!as9888_in_range(st_q16, 1, AS9888_ST_Q16_MAX))
		return -EINVAL;

	/*
	 * Half-way cases round up, so that a calibbias, an integer added to
	 * the quotient at t_RT, moves the result by exactly its value:
	 * floor((2 * num + st) / (2 * st)), |2 * num + st| < 2^60.
	 */
	num = 2 * ((s64)raw * AS9888_Q16_ONE - ot_q16) * AS9888_ACC_OUT_PER_G +
	      st_q16;
	a = div64_s64(num, 2 * (s64)st_q16);
	if (a * 2 * st_q16 > num)
		a--;
	*out = (s16)clamp_t(s64, a, AS9888_ACC_OUT_MIN, AS9888_ACC_OUT_MAX);

	return as9888_in_range(a, AS9888_ACC_OUT_MIN, AS9888_ACC_OUT_MAX) ?
	       0 : -ERANGE;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_accel_compensate);

/* Accelerometer saturation (section 5): -2048 and 2047, or anything beyond */
bool as9888_acc_saturated(s16 a)
{
	return a <= AS9888_ACC_MIN || a >= AS9888_ACC_MAX;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_acc_saturated);

static void as9888_decode_axis(const u8 *raw, int axis,
			       struct as9888_axis_trim *trim)
{
	u8 eaga = raw[AS9888_EE_EAGA(axis)];
	u8 eagtd = raw[AS9888_EE_EAGTD(axis)];
	u32 dt9;

	trim->ehc = raw[AS9888_EE_EHC(axis)];
	trim->ga = FIELD_GET(AS9888_EAGA_REG_MSK, eaga);
	trim->gain = FIELD_GET(AS9888_GA_GAIN_MSK, eaga);
	trim->da = raw[AS9888_EE_EADA(axis)];
	trim->st_rt = AS9888_ST_NOMINAL +
		      sign_extend32(FIELD_GET(AS9888_EAGTD_DETAIL_MSK, eagtd), 4);
	trim->kste_idx = FIELD_GET(AS9888_EAGTD_KSTE_MSK, eagtd);
	dt9 = FIELD_PREP(AS9888_DT_SIGN_MSK,
			 FIELD_GET(AS9888_EAGA_DT_SIGN_MSK, eaga)) |
	      FIELD_PREP(AS9888_DT_LOW_MSK, raw[AS9888_EE_EADT(axis)]);
	trim->dt = sign_extend32(dt9, 8);
}

/**
 * as9888_kote() - offset temperature slope of one axis (datasheet 6.5)
 * @dt: the axis' 9-bit signed offset temperature property
 * @et1: TMPS code of the factory room-temperature test
 * @et2: TMPS code of the factory high-temperature test
 * @kote_num: Kote = @kote_num / @kote_den LSB/degC
 * @kote_den: always > 0
 *
 * Return: true when ET1/ET2 could not be used (invalid, or a span outside
 * 10..80 degC) and a span of 35 degC was taken instead.
 */
VISIBLE_IF_KUNIT bool as9888_kote(s32 dt, u8 et1, u8 et2, s32 *kote_num,
				  s32 *kote_den)
{
	s32 dtmps = (s32)et1 - et2;
	s32 delta_t = dtmps * AS9888_MDEGC_PER_TMPS;

	dt = clamp_t(s32, dt, -(AS9888_KOTE_NUM_MAX / AS9888_KOTE_NUM),
		     AS9888_KOTE_NUM_MAX / AS9888_KOTE_NUM - 1);
	if (!as9888_tmps_valid(et1) || !as9888_tmps_valid(et2) ||
	    !as9888_in_range(delta_t, AS9888_DELTA_T_MIN_MDEGC,
			     AS9888_DELTA_T_MAX_MDEGC)) {
		*kote_num = dt * AS9888_KOTE_FALLBACK_NUM;
		*kote_den = AS9888_KOTE_FALLBACK_DEN;
		return true;
	}

	*kote_num = dt * AS9888_KOTE_NUM;
	*kote_den = dtmps * AS9888_KOTE_DEN;

	return false;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_kote);

/* Kote of every axis, with the warnings of the fallback span and |Kote| */
static void as9888_decode_kote(struct as9888_eeprom *ee)
{
	u8 et1 = ee->raw[AS9888_EE_ET1], et2 = ee->raw[AS9888_EE_ET2];
	bool fallback = false;
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		struct as9888_axis_trim *trim = &ee->axis[axis];

		fallback = as9888_kote(trim->dt, et1, et2, &trim->kote_num,
				       &trim->kote_den);
		/* |Kote| > 10.2 LSB/degC (datasheet note 4b) is a warning */
		if (abs(trim->kote_num) * 10 > AS9888_KOTE_WARN_X10 * trim->kote_den)
			ee->warnings |= AS9888_EE_WARN_KOTE_X << axis;
	}

	if (fallback) {
		ee->warnings |= AS9888_EE_WARN_DELTA_T;
		ee->delta_t_mdegc = AS9888_DELTA_T_FALLBACK_DEGC *
				    AS9888_MDEGC_PER_DEGC;
	} else {
		ee->delta_t_mdegc = ((s32)et1 - et2) * AS9888_MDEGC_PER_TMPS;
	}
}

/**
 * as9888_eeprom_decode() - decode and validate the factory EEPROM
 * @raw: the 21 bytes of 0x40..0x54
 * @ee: the decoded data; filled in even when the EEPROM is unusable
 *
 * Return: 0 when the data can be used (possibly with warnings), -ENODATA
 * for a blank (all 0xff) or unreadable (all 0x00) EEPROM, -EINVAL when a
 * field is out of its valid range. @ee->errors says which.
 */
int as9888_eeprom_decode(const u8 raw[AS9888_EEPROM_LEN],
			 struct as9888_eeprom *ee)
{
	bool all_ff = true, all_00 = true;
	int i, axis;

	for (i = 0; i < AS9888_EEPROM_LEN; i++) {
		ee->raw[i] = raw[i];
		all_ff &= raw[i] == U8_MAX;
		all_00 &= raw[i] == 0;
	}

	ee->errors = 0;
	ee->warnings = 0;
	ee->ref1 = raw[AS9888_EE_EREF1];
	ee->ref2 = raw[AS9888_EE_EREF2];
	ee->ref3 = AS9888_REF3_FIXED |
		   FIELD_GET(AS9888_EREF3_TRIM_MSK, raw[AS9888_EE_EREF3]);
	ee->osc = raw[AS9888_EE_EOSC];
	ee->t_rt_mdegc =
		as9888_tmps_to_mdegc(AS9888_TMPS_RT_BASE +
				     sign_extend32(FIELD_GET(AS9888_EREF3_TRT_MSK,
							     raw[AS9888_EE_EREF3]),
						   4));

	for (axis = 0; axis < AS9888_AXES; axis++) {
		struct as9888_axis_trim *trim = &ee->axis[axis];

		as9888_decode_axis(raw, axis, trim);
		if (!as9888_in_range(trim->gain, AS9888_GAIN_MIN,
				     AS9888_GAIN_MAX))
			ee->errors |= AS9888_EE_ERR_GAIN_X << axis;
		if (!as9888_dac_valid(trim->da))
			ee->errors |= AS9888_EE_ERR_DAC_X << axis;
	}
	as9888_decode_kote(ee);

	if (all_ff)
		ee->errors |= AS9888_EE_ERR_BLANK;
	if (all_00)
		ee->errors |= AS9888_EE_ERR_ZERO;

	if (ee->errors & (AS9888_EE_ERR_BLANK | AS9888_EE_ERR_ZERO))
		return -ENODATA;

	return ee->errors ? -EINVAL : 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_eeprom_decode);

/* as9888_ee_error_str() - what one enum as9888_ee_error bit means */
const char *as9888_ee_error_str(u32 error_bit)
{
	switch (error_bit) {
	case AS9888_EE_ERR_BLANK:
		return "EEPROM blank (all bytes 0xff)";
	case AS9888_EE_ERR_ZERO:
		return "EEPROM reads all 0x00 (not in EEPROM access mode?)";
	case AS9888_EE_ERR_GAIN_X:
		return "EAXGA gain outside 7..43";
	case AS9888_EE_ERR_GAIN_Y:
		return "EAYGA gain outside 7..43";
	case AS9888_EE_ERR_GAIN_Z:
		return "EAZGA gain outside 7..43";
	case AS9888_EE_ERR_DAC_X:
		return "EAXDA outside 0..67 and 128..195";
	case AS9888_EE_ERR_DAC_Y:
		return "EAYDA outside 0..67 and 128..195";
	case AS9888_EE_ERR_DAC_Z:
		return "EAZDA outside 0..67 and 128..195";
	default:
		return "unknown EEPROM error";
	}
}
EXPORT_SYMBOL_IF_KUNIT(as9888_ee_error_str);

/* as9888_ee_warning_str() - what one enum as9888_ee_warning bit means */
const char *as9888_ee_warning_str(u32 warning_bit)
{
	switch (warning_bit) {
	case AS9888_EE_WARN_DELTA_T:
		return "ET1/ET2 invalid or span not 10..80 degC: 35 degC used";
	case AS9888_EE_WARN_KOTE_X:
		return "X offset temperature slope beyond 10.2 LSB/degC";
	case AS9888_EE_WARN_KOTE_Y:
		return "Y offset temperature slope beyond 10.2 LSB/degC";
	case AS9888_EE_WARN_KOTE_Z:
		return "Z offset temperature slope beyond 10.2 LSB/degC";
	default:
		return "unknown EEPROM warning";
	}
}

/* Magnetometer scale: 3 * (EHC + 128) / 256000 gauss per LSB */
s32 as9888_mag_scale_num(u8 ehc)
{
	return AS9888_MAGN_SCALE_NUM * ((s32)ehc + AS9888_EHC_OFFSET);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_mag_scale_num);

/* The calibration after probe: bias 0, scale 1.000000 on every axis */
void as9888_magn_cal_init(struct as9888_magn_cal *cal)
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		cal->bias[axis] = 0;
		cal->scale_micro[axis] = AS9888_MAGN_CALIBSCALE_ONE;
	}
}
EXPORT_SYMBOL_IF_KUNIT(as9888_magn_cal_init);

/* in_magn_<axis>_calibbias: -4096..4096 chip LSB */
bool as9888_magn_calibbias_valid(s64 bias)
{
	return as9888_in_range(bias, -AS9888_MAGN_CALIBBIAS_MAX,
			       AS9888_MAGN_CALIBBIAS_MAX);
}
EXPORT_SYMBOL_IF_KUNIT(as9888_magn_calibbias_valid);

/**
 * as9888_magn_calibscale_micro() - a calibscale as written, in millionths
 * @val: integer part, as IIO_VAL_INT_PLUS_MICRO hands it
 * @val2: micro part, 0..999999, or negative for -0.xxxxxx
 * @micro: the value in millionths
 *
 * Return: 0, or -EINVAL when the value is outside 0.5..2 (checked before
 * anything is multiplied, so any @val is safe).
 */
int as9888_magn_calibscale_micro(int val, int val2, s32 *micro)
{
	s32 v;

	if (val < 0 || val2 < 0 || val2 >= AS9888_MAGN_CALIBSCALE_ONE ||
	    val > AS9888_MAGN_CALIBSCALE_MAX / AS9888_MAGN_CALIBSCALE_ONE)
		return -EINVAL;

	v = val * AS9888_MAGN_CALIBSCALE_ONE + val2;
	if (!as9888_in_range(v, AS9888_MAGN_CALIBSCALE_MIN,
			     AS9888_MAGN_CALIBSCALE_MAX))
		return -EINVAL;

	*micro = v;

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_magn_calibscale_micro);

/**
 * as9888_magn_calibrate() - one magnetometer axis, calibrated
 * @h: the chip's count
 * @bias: calibbias, chip LSB, |@bias| <= AS9888_MAGN_CALIBBIAS_MAX
 * @scale_micro: calibscale in millionths, AS9888_MAGN_CALIBSCALE_MIN..MAX
 * @out: rint((@h + @bias) * @scale_micro / 10^6), or on -ERANGE the rail of
 *	 the same sign (AS9888_MAG_MIN or AS9888_MAG_MAX)
 *
 * A count at the chip's rail (overflow) is not calibrated: it says nothing
 * about the field.
 *
 * Return: 0; -ERANGE when @h is at a rail or the result is outside
 * AS9888_MAGN_OUT_MIN..AS9888_MAGN_OUT_MAX; -EINVAL when @bias or
 * @scale_micro is out of range (@out untouched).
 */
int as9888_magn_calibrate(s16 h, s32 bias, s32 scale_micro, s16 *out)
{
	s64 v;

	if (!as9888_magn_calibbias_valid(bias) ||
	    !as9888_in_range(scale_micro, AS9888_MAGN_CALIBSCALE_MIN,
			     AS9888_MAGN_CALIBSCALE_MAX))
		return -EINVAL;

	if (as9888_mag_overflow(h)) {
		*out = h < 0 ? AS9888_MAG_MIN : AS9888_MAG_MAX;
		return -ERANGE;
	}

	v = as9888_div_round_s64(((s64)h + bias) * scale_micro,
				 AS9888_MAGN_CALIBSCALE_ONE);
	if (v < AS9888_MAGN_OUT_MIN) {
		*out = AS9888_MAG_MIN;
		return -ERANGE;
	}
	if (v > AS9888_MAGN_OUT_MAX) {
		*out = AS9888_MAG_MAX;
		return -ERANGE;
	}

	*out = v;

	return 0;
}
EXPORT_SYMBOL_IF_KUNIT(as9888_magn_calibrate);
