/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The magnetometer's calibration in the driver: in_magn_<axis>_calibbias
 * and in_magn_<axis>_calibscale on the chip's as9888-magn IIO device
 * (magn_cal.h says what they get from a record).
 */
#ifndef AS9888_MAGN_IIO_H
#define AS9888_MAGN_IIO_H

#include <stdbool.h>
#include <stddef.h>

#include "common/magn_cal.h"
#include "common/record.h"

/* The driver's attributes, per axis */
extern const char *const magn_calibbias_attr[AS9888_AXES];
extern const char *const magn_calibscale_attr[AS9888_AXES];

/* The magnetometer device at @magn_dir has the calibration attributes */
bool magn_iio_has_calibration(const char *magn_dir);

/*
 * Write @d into the device at @magn_dir and read every value back. 0 when
 * all read back exactly, else -errno with the attribute and why in @err.
 */
int magn_iio_write(const char *magn_dir, const struct magn_driver_cal *d,
		   char *err, size_t errlen);

/* What the attributes hold now: 0 or -errno with why in @err */
int magn_iio_read(const char *magn_dir, struct magn_driver_cal *d,
		  char *err, size_t errlen);

/*
 * Put @rec's magnetometer part in effect beside the accelerometer device
 * at @accel_dir: its calibration (a record without one: the driver's
 * defaults, so that the driver holds what the record says). A chip
 * without the magnetometer device, or a driver without the attributes
 * (older than the magnetometer calibration), is said on stderr as a
 * warning when the record has a calibration, and is not an error: the
 * accelerometer's part stands. 0 or -errno (said on stderr).
 */
int magn_iio_apply(const char *accel_dir, const struct calib_record *rec);

/*
 * The same on the magnetometer device at @magn_dir itself (restore
 * --device: the restore unit started for that device may write its
 * directory only). 0 or -errno (said on stderr).
 */
int magn_iio_apply_dev(const char *magn_dir, const struct calib_record *rec);

#endif
