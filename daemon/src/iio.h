/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 IIO driver's interfaces as the daemon uses them: finding the
 * chip's two IIO devices in sysfs (the accelerometer's and, beside it, the
 * magnetometer's), the EEPROM through NVMEM, their debugfs files, the
 * calibration (in_accel_*_calibbias, which also sets the offset DAC), and
 * applying a record through it (Documentation/iio/as9888.rst).
 */
#ifndef AS9888_IIO_H
#define AS9888_IIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "iio_attr.h"
#include "record.h"

#define IIO_PATH_MAX	512
/* Longest attribute value the daemon reads or writes */
#define IIO_ATTR_MAX	128
/* Longest message of the functions below that return one */
#define IIO_ERR_LEN	(2 * IIO_PATH_MAX)
/*
 * The driver registers one IIO device per sensor, both children of the
 * chip's bus device: the accelerometer's (with the temperature, the
 * calibration and the data-ready trigger), which the daemon calibrates,
 * and the magnetometer's (with the self-test)
 */
#define IIO_ACCEL_NAME	"as9888-accel"
#define IIO_MAGN_NAME	"as9888-magn"
/*
 * The chip's name in what is named per chip after the accelerometer
 * device's number N: the trigger "as9888-dev<N>"
 */
#define IIO_CHIP_NAME	"as9888"
/*
 * The chip's NVMEM provider, "as9888-eeprom<M>" below the bus device (M
 * numbered by the NVMEM core)
 */
#define IIO_EEPROM_PREFIX	"as9888-eeprom"
#define IIO_DEVICE_PREFIX	"iio:device"
#define IIO_TRIGGER_PREFIX	"trigger"

/* The accelerometer's calibration attributes */
extern const char *const iio_calibbias_attr[AS9888_AXES];

/* The sysfs root: $AS9888_SYSFS, default /sys */
const char *iio_sysfs_root(void);

/* The debugfs root: $AS9888_DEBUGFS, default /sys/kernel/debug */
const char *iio_debugfs_root(void);

/* Where the devices' nodes are: $AS9888_DEVDIR, default /dev */
const char *iio_dev_root(void);

/*
 * The sysfs directory of an AS9888 accelerometer IIO device
 * (IIO_ACCEL_NAME): the one at or below /sys@devpath, or with @devpath
 * NULL the first one present. The sysfs root is $AS9888_SYSFS (default
 * /sys). Returns 0 or -ENOENT.
 */
int iio_find_device(const char *devpath, char *out, size_t size);

/*
 * The same chip's magnetometer IIO device (IIO_MAGN_NAME) for the
 * accelerometer device at @accel_dir: the sibling iio:deviceM below the
 * bus device that holds it (@accel_dir/.., where the bus link
 * /sys/bus/iio/devices/iio:deviceN leads). Its directory goes into @out,
 * named beside @accel_dir (/sys/bus/iio/devices/iio:deviceM for a bus
 * link), or as @accel_dir/../iio:deviceM while its bus link is not there
 * yet. When there is none, @parent, when not NULL, receives the bus
 * device's directory, for messages. Returns 0, -ENOENT when there is no
 * such device, or -errno when @accel_dir cannot be resolved.
 */
int iio_find_magn(const char *accel_dir, char *out, size_t size,
		  char *parent, size_t parent_size);

/*
 * A sysfs attribute @name below @dir: read without its trailing newline
 * (returns the length) or written whole (returns 0); -errno on failure.
 */
int iio_read_attr(const char *dir, const char *name, char *buf, size_t size);
int iio_write_attr(const char *dir, const char *name, const char *value);

/*
 * The same below a directory opened once with iio_dir_open() (an O_PATH
 * descriptor, or -errno): each access then resolves @name alone, not the
 * directory's path through its bus link again, which costs most of an
 * access to a sysfs attribute on a slow system
 */
int iio_dir_open(const char *dir);
int iio_read_attr_at(int dfd, const char *name, char *buf, size_t size);
int iio_write_attr_at(int dfd, const char *name, const char *value);

/*
 * The driver's debugfs file @name of the device at @dir
 * (<debugfs>/iio/iio:deviceN/@name), read like iio_read_attr(). @path
 * receives the file's path, for messages.
 */
int iio_read_debugfs(const char *dir, const char *name, char *buf,
		     size_t size, char *path, size_t path_size);

/*
 * The EEPROM of the device at @dir through the driver's NVMEM provider
 * (IIO_EEPROM_PREFIX), a sibling of the IIO device below the bus device.
 */
int iio_read_eeprom(const char *dir, uint8_t eeprom[AS9888_EEPROM_LEN]);

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
