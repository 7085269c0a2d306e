/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A sysfs tree laid out like the AS9888 driver's, in a temporary directory
 * for the tests that read and write the driver's attributes: one chip, its
 * two IIO devices siblings below the bus device
 *
 *   <root>/devices/i2c/1-000c/iio:device0/	as9888-accel, its attributes
 *   <root>/devices/i2c/1-000c/iio:device1/	as9888-magn
 *   <root>/devices/i2c/1-000c/as9888-eeprom0/nvmem	the example EEPROM
 *   <root>/bus/iio/devices/iio:device{0,1} ->	the bus links
 *
 * $AS9888_SYSFS points at <root>. Failures end the calling cmocka test.
 */
#ifndef AS9888_FAKE_SYSFS_H
#define AS9888_FAKE_SYSFS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "as9888_calib.h"

/* The EEPROM of the built-in simulated unit: chip 676f64b435a720ba */
extern const uint8_t fake_example_eeprom[AS9888_EEPROM_LEN];

/**
 * struct fake_sysfs - one tree
 * @root:	its top, $AS9888_SYSFS
 * @dev:	the accelerometer IIO device's directory
 * @magn:	the magnetometer IIO device's directory
 */
struct fake_sysfs {
	char root[64];
	char dev[256];
	char magn[256];
};

/* cmocka group set-up and tear-down: *@state is a struct fake_sysfs */
int fake_sysfs_setup(void **state);
int fake_sysfs_teardown(void **state);

/* Write @text (or @len bytes of @data) as @dir/@name, replacing it */
void fake_put(const char *dir, const char *name, const char *text);
void fake_put_bytes(const char *dir, const char *name, const void *data,
		    size_t len);
/* @dir/@name's whole contents, NUL-terminated */
void fake_get(const char *dir, const char *name, char *buf, size_t size);
/* mkdir -p @dir/@sub */
void fake_mkdir(const char *dir, const char *sub);

/*
 * Take the magnetometer device away (@present false: its directory and
 * bus link are moved aside, as with a driver that registers none) or put
 * it back
 */
void fake_magn_present(const struct fake_sysfs *f, bool present);

/* The driver's calibration after probe: zero offsets at t_RT (23.750 degC) */
void fake_reset_calibration(const struct fake_sysfs *f);

/*
 * Give the magnetometer device the calibration attributes of a driver
 * with the magnetometer calibration (in_magn_<axis>_calibbias 0,
 * _calibscale 1.000000), or (@present false) take them away, as an older
 * driver has none
 */
void fake_magn_calibration(const struct fake_sysfs *f, bool present);

#endif
