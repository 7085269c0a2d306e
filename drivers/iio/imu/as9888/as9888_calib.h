/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 calibration arithmetic: EEPROM decoding, temperature conversion,
 * magnetometer sensitivity adjustment, accelerometer sensitivity and offset
 * estimation, offset DAC optimisation and the judgments of the vendor's
 * on-board function test.
 *
 * This unit is pure integer arithmetic: it calls nothing but 64-bit
 * division helpers and has no undefined behaviour for any value of its
 * inputs. This header declares what the driver uses; the functions only
 * its KUnit test calls are declared when KUnit is enabled.
 *
 * Fixed-point formats (the suffix of a name says which one it carries):
 *
 *   _mdegc  temperature in millidegrees Celsius (s32). TMPS codes convert
 *           exactly: T = (176 - TMPS) * 625 mdegC.
 *   _q16    a quantity in accelerometer LSB (or LSB/g for sensitivities,
 *           LSB/degC for slopes) scaled by 2^16, i.e. 1/65536 LSB per unit
 *           (s32 unless noted). Binary scaling makes the DAC rounding exact:
 *           (gain + 16) * Ot_L / 2048 is an integer over 2^27.
 *   _ug     acceleration in micro-g (s32).
 *
 * Temperatures handed to the estimators must lie within
 * AS9888_CALIB_T_MIN_MDEGC .. AS9888_CALIB_T_MAX_MDEGC; the functions that
 * take one return -ERANGE otherwise, which keeps every product in range.
 */
#ifndef AS9888_CALIB_H
#define AS9888_CALIB_H

#include <linux/bits.h>
#include <linux/types.h>

#include "as9888_regs.h"

#define AS9888_AXES			3

/* EEPROM window 0x40..0x54, read in one burst in EEPROM access mode */
#define AS9888_EEPROM_LEN		21
#define AS9888_EE_EREF1			0
#define AS9888_EE_EREF2			1
#define AS9888_EE_EREF3			2
#define AS9888_EE_EOSC			3
#define AS9888_EE_EHC(axis)		(4 + (axis))
#define AS9888_EE_EAGA(axis)		(7 + (axis))
#define AS9888_EE_EADT(axis)		(10 + (axis))
#define AS9888_EE_EADA(axis)		(13 + (axis))
#define AS9888_EE_EAGTD(axis)		(16 + (axis))
#define AS9888_EE_ET1			19
#define AS9888_EE_ET2			20

/*
 * The bit fields of the EEPROM bytes and of the trim registers are in
 * as9888_regs.h. Valid ranges of the EEPROM fields:
 */
#define AS9888_GAIN_MIN			7
#define AS9888_GAIN_MAX			43
#define AS9888_TMPS_MIN			0x28	/* 85 degC */
#define AS9888_TMPS_MAX			0xe0	/* -30 degC */
#define AS9888_TMPS_ZERO_DEGC		176
#define AS9888_TMPS_RT_BASE		136
#define AS9888_MDEGC_PER_TMPS		625	/* 1 / 1.6 degC */

/* Bounds of the factory temperature span, and the span used outside them */
#define AS9888_DELTA_T_MIN_MDEGC	10000
#define AS9888_DELTA_T_MAX_MDEGC	80000
#define AS9888_DELTA_T_FALLBACK_DEGC	35

/* Accepted temperature range of every estimator input */
#define AS9888_CALIB_T_MIN_MDEGC	(-100000)
#define AS9888_CALIB_T_MAX_MDEGC	150000

/* Raw sample limits */
#define AS9888_MAG_MIN			(-4096)
#define AS9888_MAG_MAX			4095

/* Adjusted magnetometer readings are in 1/256 LSB (Q8) */
#define AS9888_Q8_ONE			256
#define AS9888_MILLI			1000

/* Magnetometer self-test windows after sensitivity adjustment */
#define AS9888_SELFTEST_XY_MIN		(-100)
#define AS9888_SELFTEST_XY_MAX		100
#define AS9888_SELFTEST_Z_MIN		300
#define AS9888_SELFTEST_Z_MAX		1000

/* Offset temperature slope beyond this (LSB/degC, x10) is a warning */
#define AS9888_KOTE_WARN_X10		102

#define AS9888_Q16_ONE			65536
/* Largest sensitivity accepted by the estimators, LSB/g in Q16 */
#define AS9888_ST_Q16_MAX		(1024 * AS9888_Q16_ONE)
/* Output change per linear DAC code: 2048 / (GA[5:0] + 16) LSB */
#define AS9888_DAC_GAIN_OFFSET		16

/* Problems found while decoding the EEPROM (as9888_eeprom.errors) */
enum as9888_ee_error {
	AS9888_EE_ERR_BLANK		= BIT(0),	/* all bytes 0xff */
	AS9888_EE_ERR_ZERO		= BIT(1),	/* all bytes 0x00 */
	AS9888_EE_ERR_GAIN_X		= BIT(2),	/* EAxGA gain not 7..43 */
	AS9888_EE_ERR_GAIN_Y		= BIT(3),
	AS9888_EE_ERR_GAIN_Z		= BIT(4),
	AS9888_EE_ERR_DAC_X		= BIT(5),	/* EAxDA not 0..67, 128..195 */
	AS9888_EE_ERR_DAC_Y		= BIT(6),
	AS9888_EE_ERR_DAC_Z		= BIT(7),
};

/* Conditions worth reporting that do not stop the calibration */
enum as9888_ee_warning {
	/* ET1/ET2 invalid or span not 10..80 degC, 35 degC used */
	AS9888_EE_WARN_DELTA_T		= BIT(0),
	/* |Kote| beyond 10.2 LSB/degC on an axis */
	AS9888_EE_WARN_KOTE_X		= BIT(1),
	AS9888_EE_WARN_KOTE_Y		= BIT(2),
	AS9888_EE_WARN_KOTE_Z		= BIT(3),
};

/**
 * struct as9888_axis_trim - per-axis factory data decoded from the EEPROM
 * @ehc:	magnetometer sensitivity adjustment EHCx
 * @ga:		accelerometer gain register value, EAxGA[6:0] (polarity + gain)
 * @da:		factory offset DAC register value EAxDA
 * @gain:	EAxGA[5:0]
 * @st_rt:	sensitivity at t_RT, LSB/g (256 + detail, 240..271)
 * @kste_idx:	sensitivity temperature coefficient index, 0..7
 * @dt:		offset temperature property, 9-bit signed (-256..255)
 * @kote_num:	offset temperature slope Kote = @kote_num / @kote_den LSB/degC
 * @kote_den:	always > 0
 */
struct as9888_axis_trim {
	u8 ehc;
	u8 ga;
	u8 da;
	u8 gain;
	s32 st_rt;
	u8 kste_idx;
	s32 dt;
	s32 kote_num;
	s32 kote_den;
};

/**
 * struct as9888_eeprom - the decoded factory trim
 * @raw:	the 21 EEPROM bytes as read, 0x40 first
 * @ref1:	value for REF1
 * @ref2:	value for REF2
 * @ref3:	value for REF3, 0x18 | EREF3[2:0]
 * @osc:	value for OSC
 * @t_rt_mdegc:	factory room-temperature test temperature t_RT
 * @delta_t_mdegc: factory temperature span used for Kote (or the fallback)
 * @axis:	per-axis data, X, Y, Z
 * @errors:	enum as9888_ee_error bits; non-zero means unusable
 * @warnings:	enum as9888_ee_warning bits
 */
struct as9888_eeprom {
	u8 raw[AS9888_EEPROM_LEN];
	u8 ref1;
	u8 ref2;
	u8 ref3;
	u8 osc;
	s32 t_rt_mdegc;
	s32 delta_t_mdegc;
	struct as9888_axis_trim axis[AS9888_AXES];
	u32 errors;
	u32 warnings;
};

int as9888_eeprom_decode(const u8 raw[AS9888_EEPROM_LEN],
			 struct as9888_eeprom *ee);
const char *as9888_ee_error_str(u32 error_bit);
const char *as9888_ee_warning_str(u32 warning_bit);

/* Temperature */
s32 as9888_tmps_to_mdegc(u8 tmps);

/* Magnetometer: H_adj = H * (EHC + 128) / 256, returned in 1/256 LSB */
s32 as9888_mag_adjust_q8(s16 h, u8 ehc);
bool as9888_mag_overflow(s16 h);
bool as9888_selftest_ok(int axis, s16 h, u8 ehc);

/*
 * Compensated accelerometer output (6.7 on a constant scale): what the
 * driver returns for every accelerometer reading.
 */
#define AS9888_ACC_OUT_PER_G		1024
#define AS9888_ACC_OUT_MIN		(-32768)
#define AS9888_ACC_OUT_MAX		32767
/* The chip's own accelerometer output; -2048 and 2047 mean saturation */
#define AS9888_ACC_MIN			(-2048)
#define AS9888_ACC_MAX			2047
/*
 * Largest |calibbias|, output LSB: 8 g, the chip's whole range (2048 raw
 * LSB at about 256 LSB/g). The offset it stands for, bias * St_RT * 64 in
 * Q16, stays below 2^28.
 */
#define AS9888_CALIBBIAS_MAX		(8 * AS9888_ACC_OUT_PER_G)

/**
 * struct as9888_accel_cal - the accelerometer calibration
 * @bias:	in_accel_{x,y,z}_calibbias, output LSB (1/1024 g) at the
 *		EEPROM's reference temperature t_RT: minus the axis' zero-g
 *		offset there with its factory DAC value (EAxDA). All zero
 *		(the state after probe) is the factory's state.
 */
struct as9888_accel_cal {
	s32 bias[AS9888_AXES];
};

int as9888_bias_offset_q16(const struct as9888_axis_trim *trim, s32 bias,
			   s32 *ot_q16);
int as9888_bias_dac(const struct as9888_axis_trim *trim, s32 bias, u8 *da);
int as9888_accel_correction(const struct as9888_eeprom *ee,
			    const struct as9888_accel_cal *cal, int axis,
			    u8 da, s32 t_mdegc, s32 *ot_q16, s32 *st_q16);
int as9888_accel_compensate(s16 raw, s32 ot_q16, s32 st_q16, s16 *out);
bool as9888_acc_saturated(s16 a);

/* Offset DAC */
int as9888_dac2lin(u8 ga, u8 da);
u8 as9888_lin2dac(u8 ga, int lin);
int as9888_dac_opt(u8 ga, u8 da, u8 ee_gain, s32 ot_l_q16, u8 *da_opt);

/* Rounding helper shared with the users of this unit */
s64 as9888_div_round_s64(s64 num, s64 den);
s64 as9888_q8_to_milli(s32 q8);

static inline bool as9888_in_range(s64 value, s64 lo, s64 hi)
{
	return value >= lo && value <= hi;
}

#if IS_ENABLED(CONFIG_KUNIT)
/* Internal to as9888_calib.c, visible to its KUnit test */
bool as9888_trim_valid(const struct as9888_axis_trim *trim);
bool as9888_tmps_valid(u8 tmps);
bool as9888_selftest_window_ok(int axis, s32 adj_q8);
int as9888_sensitivity_q16(const struct as9888_axis_trim *trim,
			   s32 t_rt_mdegc, s32 t_mdegc, s32 *st_q16);
bool as9888_kote(s32 dt, u8 et1, u8 et2, s32 *kote_num, s32 *kote_den);
int as9888_offset_q16(const struct as9888_axis_trim *trim, s32 ot_l_q16,
		      s32 t_level_mdegc, s32 t_mdegc, s32 *ot_q16);
int as9888_offset_dac_shift_q16(const struct as9888_axis_trim *trim,
				s32 ot_q16, u8 from_da, u8 to_da, s32 *out_q16);
bool as9888_dac_valid(u8 da);
s32 as9888_dac_step_q16(u8 ga);
#endif

/*
 * Magnetometer scale and calibration.
 *
 * in_magn_<axis>_scale is 0.3 uT/LSB times the EEPROM's sensitivity
 * adjustment (EHC + 128) / 256, in gauss (1 G = 100 uT):
 * as9888_mag_scale_num(ehc) / AS9888_MAGN_SCALE_DEN.
 *
 * The calibration (in_magn_<axis>_calibbias, _calibscale) lives in the
 * driver, not in the chip: a reading is
 *
 *   out = rint((H + calibbias) * calibscale)
 *
 * with H the chip's count, calibbias an integer in chip LSB
 * (|calibbias| <= AS9888_MAGN_CALIBBIAS_MAX) and calibscale in millionths
 * (AS9888_MAGN_CALIBSCALE_MIN..MAX), ties to even. The product is at most
 * 8192 * 2000000 in magnitude, well inside s64. The output keeps the chip's
 * range: AS9888_MAGN_OUT_MIN..MAX, the rails excluded, so that -4096 and
 * 4095 still mean "out of range" wherever they appear.
 */
#define AS9888_MAGN_SCALE_NUM		3
#define AS9888_MAGN_SCALE_DEN		256000
#define AS9888_MAGN_CALIBBIAS_MAX	4096
#define AS9888_MAGN_CALIBSCALE_ONE	1000000		/* 1.000000 */
#define AS9888_MAGN_CALIBSCALE_MIN	(AS9888_MAGN_CALIBSCALE_ONE / 2)
#define AS9888_MAGN_CALIBSCALE_MAX	(AS9888_MAGN_CALIBSCALE_ONE * 2)
#define AS9888_MAGN_OUT_MIN		(AS9888_MAG_MIN + 1)
#define AS9888_MAGN_OUT_MAX		(AS9888_MAG_MAX - 1)

/**
 * struct as9888_magn_cal - the magnetometer calibration, per axis
 * @bias:	in_magn_<axis>_calibbias, chip LSB, added to the count
 * @scale_micro: in_magn_<axis>_calibscale in millionths, multiplies after
 *		the bias
 */
struct as9888_magn_cal {
	s32 bias[AS9888_AXES];
	s32 scale_micro[AS9888_AXES];
};

s32 as9888_mag_scale_num(u8 ehc);
void as9888_magn_cal_init(struct as9888_magn_cal *cal);
bool as9888_magn_calibbias_valid(s64 bias);
int as9888_magn_calibscale_micro(int val, int val2, s32 *micro);
int as9888_magn_calibrate(s16 h, s32 bias, s32 scale_micro, s16 *out);

#endif /* AS9888_CALIB_H */
