/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 IIO driver's interfaces as the daemon uses them: finding the
 * device in sysfs, its EEPROM through NVMEM, and applying a record through
 * in_accel_*_calibbias and in_accel_calibration
 * (Documentation/ABI/testing/sysfs-bus-iio-as9888).
 */
#ifndef AS9888_IIO_H
#define AS9888_IIO_H

#include <stddef.h>

#define IIO_PATH_MAX	512
#define IIO_DEVICE_NAME	"as9888"

/*
 * The sysfs directory of an AS9888 IIO device: the one at or below
 * /sys@devpath, or with @devpath NULL the first one present. The sysfs
 * root is $AS9888_SYSFS (default /sys). Returns 0 or -ENOENT.
 */
int iio_find_device(const char *devpath, char *out, size_t size);

/*
 * Apply the record at @record_path to the device at @dir: refuse it unless
 * the device's EEPROM equals the record's, then write the DAC values and
 * the level data, and read both back. Returns 0 or -errno; says why on
 * stderr.
 */
int iio_restore(const char *record_path, const char *dir);

#endif
