// SPDX-License-Identifier: GPL-2.0
/* The magnetometer calibration split between the driver and userspace (magn_cal.h). */
#include <errno.h>
#include <math.h>

#include "common/magn_cal.h"

#define NT_PER_UT		1000.0
#define MICRO			1000000.0
/* datasheet section 5: 0.3 uT per LSB before adjustment, times (EHC + 128) / 256 */
#define MAGN_UT_PER_LSB		0.3
#define MAGN_EHC_OFFSET		128
#define MAGN_EHC_DIV		256.0

void magn_scale_ut(const uint8_t eeprom[AS9888_EEPROM_LEN],
		   double scale[AS9888_AXES])
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++)
		scale[axis] = MAGN_UT_PER_LSB *
			      (eeprom[AS9888_EE_EHC(axis)] + MAGN_EHC_OFFSET) /
			      MAGN_EHC_DIV;
}

void magn_driver_identity(struct magn_driver_cal *d)
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		d->calibbias[axis] = 0;
		d->calibscale_micro[axis] = MAGN_CALIBSCALE_ONE;
	}
}

int magn_driver_split(const struct calib_magn *m,
		      const uint8_t eeprom[AS9888_EEPROM_LEN],
		      struct magn_driver_cal *d)
{
	double scale[AS9888_AXES];
	int axis;

	magn_scale_ut(eeprom, scale);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		double c = rint(-m->hard_iron_nt[axis] / NT_PER_UT / scale[axis]);

		if (c > MAGN_CALIBBIAS_MAX || c < -MAGN_CALIBBIAS_MAX)
			return -ERANGE;
		d->calibbias[axis] = (int32_t)c;
		/* the record keeps W's diagonal within the driver's 0.5..2 */
		d->calibscale_micro[axis] = m->soft_iron_micro[axis][axis];
	}

	return 0;
}

void magn_user_split(const struct calib_magn *m,
		     const uint8_t eeprom[AS9888_EEPROM_LEN],
		     const struct magn_driver_cal *d, struct magn_user_cal *u)
{
	double scale[AS9888_AXES], diag[AS9888_AXES];
	int i, j, k;

	magn_scale_ut(eeprom, scale);
	for (i = 0; i < AS9888_AXES; i++) {
		u->bias_ut[i] = m->hard_iron_nt[i] / NT_PER_UT;
		diag[i] = d->calibscale_micro[i] / MICRO;
		for (j = 0; j < AS9888_AXES; j++) {
			u->soft[i][j] = m->soft_iron_micro[i][j] / MICRO;
			u->rotation[i][j] = m->has_rotation ?
					    m->rotation_micro[i][j] / MICRO :
					    i == j;
		}
	}
	for (i = 0; i < AS9888_AXES; i++) {
		u->hal_bias_ut[i] = 0;
		u->offset_ut[i] = diag[i] *
				  (d->calibbias[i] * scale[i] + u->bias_ut[i]);
		for (j = 0; j < AS9888_AXES; j++) {
			for (k = 0, u->full[i][j] = 0; k < AS9888_AXES; k++)
				u->full[i][j] += u->rotation[i][k] * u->soft[k][j];
			u->residual[i][j] = u->full[i][j] / diag[j];
		}
		for (j = 0; j < AS9888_AXES; j++)
			u->hal_bias_ut[i] += u->full[i][j] * u->bias_ut[j];
	}
}

void magn_affine(const double a[AS9888_AXES][AS9888_AXES],
		   const double v[AS9888_AXES], const double sub[AS9888_AXES],
		   double out[AS9888_AXES])
{
	int i, j;

	for (i = 0; i < AS9888_AXES; i++) {
		out[i] = 0;
		for (j = 0; j < AS9888_AXES; j++)
			out[i] += a[i][j] * (v[j] - sub[j]);
	}
}

double magn_uncorrect_driver(const struct magn_driver_cal *d, int axis,
			     double y_ut, double scale_ut)
{
	return y_ut / (d->calibscale_micro[axis] / MICRO) -
	       d->calibbias[axis] * scale_ut;
}

void magn_correct_driver(const struct magn_user_cal *u,
			 const double y[AS9888_AXES], double f[AS9888_AXES])
{
	magn_affine(u->residual, y, u->offset_ut, f);
}

void magn_correct_raw(const struct magn_user_cal *u,
		      const double m[AS9888_AXES], double f[AS9888_AXES])
{
	magn_affine(u->full, m, u->bias_ut, f);
}
