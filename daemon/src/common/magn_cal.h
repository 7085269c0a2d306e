/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The magnetometer calibration of a record (struct calib_magn) split
 * between the driver and userspace (docs/DECISIONS.md, "Magnetometer
 * calibration in the daemon"):
 *
 *   calibrated field  f = Rrot * W * (m - b)	(W: soft iron, b: hard iron, uT,
 *						 Rrot: the soft iron's turn)
 *   the driver gets   calibbias c = rint(-b / s)	(s: that axis's uT per LSB)
 *                     calibscale D = diag(W)
 *   so its output     y = D * (m + c * s)		(raw * scale, in uT)
 *   userspace adds    f = R * (y - e), R = Rrot * W * D^-1, e = D * (c * s + b)
 *
 * e is what rounding the bias to whole LSB leaves (at most half an LSB
 * per axis, times D). Pure arithmetic, no files.
 */
#ifndef AS9888_MAGN_CAL_H
#define AS9888_MAGN_CAL_H

#include <stdint.h>

#include "common/record.h"

/* The driver's in_magn_<axis>_calibbias range (raw LSB) */
#define MAGN_CALIBBIAS_MAX		4096
/* in_magn_<axis>_calibscale: IIO_VAL_INT_PLUS_MICRO, 0.5..2, default 1 */
#define MAGN_CALIBSCALE_ONE		1000000

/**
 * struct magn_driver_cal - what the driver's attributes hold
 * @calibbias:	in_magn_<axis>_calibbias, raw LSB
 * @calibscale_micro: in_magn_<axis>_calibscale in 1e-6
 */
struct magn_driver_cal {
	int32_t calibbias[AS9888_AXES];
	int32_t calibscale_micro[AS9888_AXES];
};

/*
 * uT per raw LSB of each axis, as the driver's in_magn_<axis>_scale says
 * it in gauss: 0.3 uT * (EHC + 128) / 256 (datasheet section 5), from the
 * chip's EEPROM (the record's: restore checks they are the same chip)
 */
void magn_scale_ut(const uint8_t eeprom[AS9888_EEPROM_LEN],
		   double scale[AS9888_AXES]);

/* The driver's defaults: no correction (calibbias 0, calibscale 1) */
void magn_driver_identity(struct magn_driver_cal *d);

/*
 * The driver's part of @m for the chip with @eeprom. 0, or -ERANGE when a
 * calibbias falls outside +-MAGN_CALIBBIAS_MAX (a hard iron beyond what
 * the driver can cancel: about +-1200 uT).
 */
int magn_driver_split(const struct calib_magn *m,
		      const uint8_t eeprom[AS9888_EEPROM_LEN],
		      struct magn_driver_cal *d);

/**
 * struct magn_user_cal - userspace's part, in doubles
 * @bias_ut:	hard iron b, sensor frame
 * @soft:	soft-iron correction W (symmetric, as stored)
 * @rotation:	Rrot, the soft iron's turn (the identity when the record
 *		has none: a format 2 record)
 * @full:	Rrot * W: the whole correction of m - b
 * @residual:	R = Rrot * W * D^-1: what the driver's diagonal leaves
 * @offset_ut:	e = D * (c * s + b): what its whole-LSB bias leaves
 * @hal_bias_ut: Rrot * W * b: the bias an Android HAL reports with
 *		TYPE_MAGNETIC_FIELD_UNCALIBRATED (uncalibrated = Rrot * W * m,
 *		uncalibrated - bias = the calibrated field)
 */
struct magn_user_cal {
	double bias_ut[AS9888_AXES];
	double soft[AS9888_AXES][AS9888_AXES];
	double rotation[AS9888_AXES][AS9888_AXES];
	double full[AS9888_AXES][AS9888_AXES];
	double residual[AS9888_AXES][AS9888_AXES];
	double offset_ut[AS9888_AXES];
	double hal_bias_ut[AS9888_AXES];
};

/* Userspace's part of @m, given the driver's part @d (magn_driver_split()) */
void magn_user_split(const struct calib_magn *m,
		     const uint8_t eeprom[AS9888_EEPROM_LEN],
		     const struct magn_driver_cal *d, struct magn_user_cal *u);

/*
 * The field before the driver's calibration on @axis: m = y / D - c * s
 * from the driver's output @y_ut (uT) with @d's calibbias and calibscale
 * and @scale_ut uT per LSB (the inverse of y = D * (m + c * s))
 */
double magn_uncorrect_driver(const struct magn_driver_cal *d, int axis,
			     double y_ut, double scale_ut);

/* f = R * (y - e): the calibrated field from the driver's output @y (uT) */
void magn_correct_driver(const struct magn_user_cal *u,
			 const double y[AS9888_AXES], double f[AS9888_AXES]);

/* out = @a * (@v - @sub) */
void magn_affine(const double a[AS9888_AXES][AS9888_AXES],
		 const double v[AS9888_AXES], const double sub[AS9888_AXES],
		 double out[AS9888_AXES]);

/* f = Rrot * W * (m - b): the calibrated field from an uncorrected field @m (uT) */
void magn_correct_raw(const struct magn_user_cal *u,
		      const double m[AS9888_AXES], double f[AS9888_AXES]);

#endif
