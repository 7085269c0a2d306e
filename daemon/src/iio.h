/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 IIO driver's interfaces as the daemon uses them: finding the
 * device in sysfs, its EEPROM through NVMEM, and applying a record through
 * in_accel_*_calibbias and in_accel_calibration
 * (Documentation/ABI/testing/sysfs-bus-iio-as9888).
 */
#ifndef AS9888_IIO_H
#define AS9888_IIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "record.h"

#define IIO_PATH_MAX	512
/* Longest attribute value the daemon reads or writes (in_accel_calibration) */
#define IIO_ATTR_MAX	128
#define IIO_DEVICE_NAME	"as9888"
#define IIO_DEVICE_PREFIX	"iio:device"
#define IIO_TRIGGER_PREFIX	"trigger"

/* The sysfs root: $AS9888_SYSFS, default /sys */
const char *iio_sysfs_root(void);

/*
 * The sysfs directory of an AS9888 IIO device: the one at or below
 * /sys@devpath, or with @devpath NULL the first one present. The sysfs
 * root is $AS9888_SYSFS (default /sys). Returns 0 or -ENOENT.
 */
int iio_find_device(const char *devpath, char *out, size_t size);

/*
 * A sysfs attribute @name below @dir: read without its trailing newline
 * (returns the length) or written whole (returns 0); -errno on failure.
 */
int iio_read_attr(const char *dir, const char *name, char *buf, size_t size);
int iio_write_attr(const char *dir, const char *name, const char *value);

/*
 * The EEPROM of the device at @dir through the driver's NVMEM provider
 * "as9888-eeprom<N>", a sibling of iio:device<N> below the bus device.
 */
int iio_read_eeprom(const char *dir, uint8_t eeprom[AS9888_EEPROM_LEN]);

/*
 * The selftest attribute's "pass|fail X Y Z" (readings with three
 * decimals): the verdict and the readings back in Q8, exactly (1/1000 is
 * finer than 1/256). 0 or -EINVAL.
 */
int iio_parse_selftest(const char *s, bool *pass, int32_t adj_q8[AS9888_AXES]);

/*
 * Write @rec's DAC values and level data into the device at @dir (no
 * identity check) and read both back. 0 or -errno, said on stderr.
 */
int iio_apply_record(const char *dir, const struct calib_record *rec);

/*
 * Apply the record at @record_path to the device at @dir: refuse it unless
 * the device's EEPROM equals the record's, then write the DAC values and
 * the level data, and read both back. Returns 0 or -errno; says why on
 * stderr.
 */
int iio_restore(const char *record_path, const char *dir);

#endif
