/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 IIO driver's interfaces as the daemon uses them: finding the
 * chip's two IIO devices in sysfs (the accelerometer's and, beside it, the
 * magnetometer's), their attributes and debugfs files, and the EEPROM
 * through NVMEM (Documentation/iio/as9888.rst). The calibration through
 * them, and applying a record, are iio_cal.h's.
 */
#ifndef AS9888_IIO_H
#define AS9888_IIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "iio_attr.h"
#include "iio_root.h"
#include "iio_sysfs.h"
#include "common/record.h"

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

/*
 * The sysfs directory of an AS9888 accelerometer IIO device
 * (IIO_ACCEL_NAME): the one at or below /sys@devpath, or with @devpath
 * NULL the first one present. The sysfs root is $AS9888_SYSFS (default
 * /sys). Returns 0 or -ENOENT.
 */
int iio_find_device(const char *devpath, char *out, size_t size);

/*
 * The same chip's magnetometer IIO device (IIO_MAGN_NAME) for the
 * accelerometer device at @accel_dir, as iio_find_sibling() finds it
 */
int iio_find_magn(const char *accel_dir, char *out, size_t size,
		  char *parent, size_t parent_size);

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

#endif
