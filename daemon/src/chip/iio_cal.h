/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The accelerometer's calibration through the AS9888 IIO driver
 * (in_accel_*_calibbias, which also sets the offset DAC), and a record
 * applied to the chip's devices: its accelerometer part here, its
 * magnetometer part through magn_iio.h (Documentation/iio/as9888.rst).
 */
#ifndef AS9888_IIO_CAL_H
#define AS9888_IIO_CAL_H

#include "chip/iio.h"

/* The accelerometer's calibration attributes */
extern const char *const iio_calibbias_attr[AS9888_AXES];

/*
 * Run the chip with the DAC register values @da: write the calibbias
 * values whose DAC they are (as9888_dac_bias()) and read them back; @got
 * receives the DAC values of what reads back (as9888_bias_dac()) and
 * @now the calibration read back, the one in effect. The attributes are
 * reached through @files (in_accel_{x,y,z}_calibbias kept open, a
 * caller's that writes them often) or, with @files NULL, by name below
 * @dir, which names them in messages either way. 0, or -errno with the
 * attribute and the reason in @err.
 */
int iio_write_dac(const char *dir, const struct iio_attr *files,
		  const struct as9888_eeprom *ee,
		  const uint8_t da[AS9888_AXES], uint8_t got[AS9888_AXES],
		  struct as9888_accel_cal *now, char *err, size_t errlen);

/*
 * The driver's calibration: in_accel_{x,y,z}_calibbias, integers within
 * +-AS9888_CALIBBIAS_MAX. 0, or -errno with the attribute, what it reads
 * and why it is refused in @err.
 */
int iio_read_accel_cal(const char *dir, struct as9888_accel_cal *cal,
		       char *err, size_t errlen);

/*
 * Write @cal into those attributes and read every value back: 0 when all
 * read back exactly, else -errno with the reason in @err and the values
 * in effect before written back (all or nothing).
 */
int iio_write_accel_cal(const char *dir, const struct as9888_accel_cal *cal,
			char *err, size_t errlen);

/*
 * Put @rec's accelerometer part in effect in the device at @dir (no
 * identity check): the calibration its level test gives
 * (as9888_accel_cal_from_level() with the DAC values the level test ran
 * with, the record's) into calibbias, read back; the driver chooses the
 * DAC from it. Nothing is written when the record gives no calibration.
 * 0 or -errno, said on stderr.
 */
int iio_apply_accel(const char *dir, const struct calib_record *rec);

/*
 * iio_apply_accel(), then the magnetometer's part on the magnetometer
 * device beside @dir (magn_iio_apply()).
 */
int iio_apply_record(const char *dir, const struct calib_record *rec);

/*
 * Apply @rec (named @what in messages, e.g. its path) to the device at
 * @dir: refuse it unless the device's EEPROM equals the record's, then
 * iio_apply_record(). Returns 0 or -errno; says why on stderr. Loading the
 * record is the command layer's (iio_restore() in session.c).
 */
int iio_apply_checked(const char *dir, const struct calib_record *rec,
		      const char *what);

/*
 * The magnetometer's part of @rec alone (magn_iio_apply()), on the chip
 * of the accelerometer device at @accel_dir: refused when the record was
 * made on the simulator or on another chip (its EEPROM). For commands
 * that changed only that part (magn-calibrate, the field mode). 0 or
 * -errno, said on stderr.
 */
int iio_apply_magn_checked(const char *accel_dir,
			   const struct calib_record *rec, const char *what);

/*
 * The same for one device only, either of the chip's two: @dir is the
 * accelerometer's (its part of @rec, the magnetometer left alone) or the
 * magnetometer's (its part, magn_iio_apply_dev()); any other device is
 * refused with -ENODEV. For restore --device: the restore unit started
 * for a device may write that device's directory only.
 */
int iio_apply_device(const char *dir, const struct calib_record *rec,
		     const char *what);

#endif
