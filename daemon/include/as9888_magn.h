/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 magnetometer calibration for applications and sensor HALs.
 *
 * as9888-calibd keeps the calibration learned by `as9888-calibd
 * magn-calibrate` (and refined by the daemon) beside its record, in
 * <record>.magn (daemon/RECORD.md; a format 2 record's section is read
 * too), and puts what the kernel takes in a standard form into the driver
 * at boot: in_magn_<axis>_calibbias (the hard iron, whole LSB) and
 * in_magn_<axis>_calibscale (the soft iron's diagonal). What the kernel
 * cannot take is the soft iron's cross terms and its turn against the
 * accelerometer (and the part of the hard iron below one LSB): this API
 * applies it.
 *
 *	struct as9888_magn_calibration cal;
 *	char err[256];
 *	double y[3], f[3];
 *
 *	if (as9888_magn_load("/var/lib/as9888/calibration", &cal, err,
 *			     sizeof(err)))
 *		... no calibration: use the driver's output as it is
 *	y[i] = in_magn_<axis>_raw * in_magn_<axis>_scale * 100;  (gauss to uT)
 *	as9888_magn_correct(&cal, y, f);	f: the calibrated field, uT
 *
 * A HAL reports TYPE_MAGNETIC_FIELD = f and TYPE_MAGNETIC_FIELD_UNCALIBRATED
 * = f + bias with the bias as9888_magn_hal_bias() gives (Rrot * W * b: the
 * hard iron in the corrected frame, so that uncalibrated - bias is
 * exactly the calibrated field).
 *
 * Plain C99 with doubles, no global state, thread-safe.
 */
#ifndef AS9888_MAGN_H
#define AS9888_MAGN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/**
 * struct as9888_magn_calibration - one chip's magnetometer calibration
 * @hard_iron_ut: b, the hard iron in the sensor frame, uT
 * @soft_iron:	W (symmetric): the calibrated field is Rrot * W * (m - b)
 *		for a field m read without any calibration
 * @rotation:	Rrot, the soft iron's turn against the accelerometer
 *		(the identity when none was learned or stored)
 * @field_ut:	the field magnitude the fit found
 * @residual_ut: the fit's residual, rms
 * @coverage:	the orientation coverage of the samples it used, 0..1
 * @samples:	how many samples it used
 * @learned:	when it was learned, seconds since the epoch
 * @calibbias:	what restore writes into in_magn_<axis>_calibbias
 * @calibscale:	what restore writes into in_magn_<axis>_calibscale
 * @residual:	R = Rrot * W * D^-1 (D: diag(@calibscale)): what userspace
 *		applies
 * @offset_ut:	e = D * (calibbias * scale + b): the bias below one LSB
 * @hal_bias_ut: Rrot * W * b, the bias of TYPE_MAGNETIC_FIELD_UNCALIBRATED
 */
struct as9888_magn_calibration {
	double hard_iron_ut[3];
	double soft_iron[3][3];
	double field_ut;
	double residual_ut;
	double coverage;
	unsigned int samples;
	long long learned;
	int calibbias[3];
	double calibscale[3];
	double residual[3][3];
	double offset_ut[3];
	double hal_bias_ut[3];
	double rotation[3][3];
};

/*
 * Read the record at @path and the magnetometer's file beside it,
 * <@path>.magn, when there is one (each validated whole, checksum
 * included). 0;
 * -ENOENT (no record), -ENODATA (a record without a magnetometer
 * calibration), -EINVAL (not a valid record), -EPERM (a record made on
 * the simulator, which fits no real chip) or another -errno, with the
 * reason in @err.
 */
int as9888_magn_load(const char *path, struct as9888_magn_calibration *cal,
		     char *err, size_t errlen);

/*
 * The calibrated field @f (uT) from the driver's output @y (uT: raw *
 * scale * 100, with the record's calibbias and calibscale in the driver,
 * as restore leaves them)
 */
void as9888_magn_correct(const struct as9888_magn_calibration *cal, const double y[3],
			 double f[3]);

/*
 * The same from a field @m read without any calibration (a driver without
 * the calibration attributes, or with them at 0 and 1)
 */
void as9888_magn_correct_uncalibrated(const struct as9888_magn_calibration *cal,
				      const double m[3], double f[3]);

/* The bias a HAL reports with TYPE_MAGNETIC_FIELD_UNCALIBRATED (uT) */
void as9888_magn_hal_bias(const struct as9888_magn_calibration *cal, double bias[3]);

/*
 * Hand one sample the application read anyway to the calibration daemon
 * at @socket_path (its "magn-feed" request): @y the driver's output as
 * for as9888_magn_correct() (uT), @accel the accelerometer's raw reading
 * at the same time. The daemon refines the calibration from them (its
 * field mode; it never reads the magnetometer itself) and rewrites the
 * record at most every 6 hours. Call it about once a second while the
 * magnetometer is in use, not for every sample: each call is a round
 * trip to the daemon, given up after 1 s each way (-EAGAIN). 0, or
 * -errno with why in @err.
 */
int as9888_magn_feed(const char *socket_path, const double y[3],
		     const double accel[3], char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
