/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 calibration arithmetic, as userspace sees it: the unit the kernel
 * driver builds (drivers/iio/imu/as9888/as9888_calib.[ch]) plus what only
 * the factory test and the daemon need (as9888_calib_user.c): level-test
 * offsets and the calibbias they give, sample statistics, the posture and
 * judgment helpers, and the inverse of the driver's compensation.
 *
 * Userspace includes "as9888_calib.h" and finds this file first (it comes
 * before the driver directory in the include path); the driver's own
 * sources find the driver's header next to them. Both units build through
 * the stand-ins under tools/include, which also make the driver's
 * KUnit-only internals visible here (tools/include/linux/kconfig.h).
 */
#ifndef AS9888_CALIB_USER_H
#define AS9888_CALIB_USER_H

#include "../../drivers/iio/imu/as9888/as9888_calib.h"

/* Note 3: recommended fluctuation judgment (max - min), LSB */
#define AS9888_FLUCTUATION_DEFAULT	15
/* D7: at least this many samples are averaged */
#define AS9888_SAMPLES_MIN		10
/* Largest N the estimators and the record accept */
#define AS9888_SAMPLES_MAX		4096

/* Temperature */
int as9888_mdegc_to_tmps(s32 t_mdegc);
int as9888_tmps_mean_to_mdegc(s64 tmps_sum, u32 n, s32 *t_mdegc);

/* Accelerometer sensitivity and offset (section 6 of the datasheet) */
int as9888_offset_level_q16(s32 a_mean_q16, s32 st_level_q16, int g,
			    s32 *ot_l_q16);
int as9888_accel_ug(s16 raw, s32 ot_q16, s32 st_q16, s32 *a_ug);
int as9888_mean_q16(s64 sum, u32 n, s32 *mean_q16);
int as9888_accel_cal_from_level(const struct as9888_eeprom *ee,
				const s32 a_mean_q16[AS9888_AXES],
				s32 t_level_mdegc, const s8 g[AS9888_AXES],
				const u8 da[AS9888_AXES],
				struct as9888_accel_cal *cal);
int as9888_accel_uncompensate(s16 out, s32 ot_q16, s32 st_q16, s16 *raw);
int as9888_dac_bias(const struct as9888_axis_trim *trim, u8 da, s32 *bias);

/* Judgments of the application note */
bool as9888_fluctuation_ok(s16 min, s16 max, u32 limit);

/* Note 2 / D7: number of samples to average */
u32 as9888_samples_needed(u32 n, u32 sigma_q16, u32 error_q16);

/* D8: posture detection */
enum as9888_posture_error {
	AS9888_POSTURE_OK = 0,
	AS9888_POSTURE_NOT_LEVEL,	/* a horizontal axis reads > St/2 */
	AS9888_POSTURE_NOT_VERTICAL,	/* the vertical axis reads < St/2 */
	AS9888_POSTURE_WRONG_SIGN,	/* given G and the reading disagree */
	AS9888_POSTURE_BAD_G,		/* G is not one axis, +1 or -1 */
};

int as9888_posture_detect(const s32 a_mean_q16[AS9888_AXES],
			  s8 g[AS9888_AXES]);
enum as9888_posture_error
as9888_posture_check(const s32 a_mean_q16[AS9888_AXES],
		     const s32 st_q16[AS9888_AXES],
		     const s8 g[AS9888_AXES]);

#endif /* AS9888_CALIB_USER_H */
