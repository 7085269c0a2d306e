/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Where magn-calibrate's samples come from: the magnetometer (in uT,
 * without any calibration: what the fit needs) and the accelerometer (the
 * direction of gravity, for the coverage of orientations) of the same
 * measurements, averaged, either from the chip's registers (the
 * simulator, the raw bus) or from the bound driver (its buffers, or its
 * sysfs attributes).
 */
#ifndef AS9888_MAGN_SOURCE_H
#define AS9888_MAGN_SOURCE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "as9888_calib.h"
#include "common/record.h"
#include "chip/transport.h"

/*
 * Measurements averaged into one sample where they come one after the
 * other (the chip's registers, the driver's buffered capture at
 * MAGN_CAPTURE_RATE_HZ): the magnetometer measures in 7.3 ms, so five fit
 * in magn-calibrate's 50 ms between samples where the data-ready
 * interrupt ends each (polling DRDY over the bus, as the simulator's
 * transport does, five take about 65 ms and the session runs a little
 * slower), and the mean has the magnetometer's noise over sqrt(5). The fit at partial coverage and the
 * consistency gate are both limited by that noise (docs/DECISIONS.md,
 * "Compass v3: five measurements a sample"). A turning hand moves the
 * device a few degrees in those 40 ms: the mean is off the field's
 * sphere by less than 0.05 uT. Sysfs reads take one measurement a sample.
 */
#define MAGN_SOURCE_AVERAGE	5

/**
 * struct magn_reading - one sample
 * @field_ut:	the magnetic field, sensor frame, uT, uncalibrated
 *		(the driver's calibbias/calibscale, if any, taken out)
 * @accel:	the accelerometer's reading, LSB: gravity's direction
 * @t_ns:	when, on the source's clock (its last measurement)
 * @measurements: how many measurements @field_ut and @accel are the mean
 *		of (MAGN_SOURCE_AVERAGE, or 1 from sysfs reads)
 */
struct magn_reading {
	double field_ut[AS9888_AXES];
	double accel[AS9888_AXES];
	uint64_t t_ns;
	unsigned int measurements;
};

struct magn_source;

/*
 * Measure through the registers behind @t (taken over: closed with the
 * source), after step 1 of the application note with @rec's DAC values
 * (the chip's EEPROM must be @rec's). 0 or -errno with why in @err.
 */
int magn_source_open_chip(struct transport *t, const struct calib_record *rec,
			  struct magn_source **out, char *err, size_t errlen);

/*
 * Measure through the driver, the driver's own magnetometer calibration
 * undone, from the devices at @magn_dir and @accel_dir: the field and the
 * acceleration of each measurement from a buffered capture of both on the
 * shared data-ready trigger (magn_capture.h), MAGN_SOURCE_AVERAGE of them
 * a sample, or where that cannot be had
 * (another program holds a buffer, no trigger) or stops, in_magn_*_raw and
 * in_accel_*_raw read axis by axis (each read a measurement of its own).
 * Which, and why not the capture, is said on @log (may be NULL). The
 * EEPROM (NVMEM) must equal @eeprom. 0 or -errno with why in @err.
 */
int magn_source_open_iio(const char *accel_dir, const char *magn_dir,
			 const uint8_t eeprom[AS9888_EEPROM_LEN], FILE *log,
			 struct magn_source **out, char *err, size_t errlen);

/*
 * One sample: the mean of MAGN_SOURCE_AVERAGE measurements (one through
 * sysfs reads). 0; -ERANGE when the magnetometer overflowed in one of
 * them (a strong magnet: no sample, try again); other -errno with why in
 * @err.
 */
int magn_source_read(struct magn_source *s, struct magn_reading *r,
		     char *err, size_t errlen);

/*
 * The device's frame: true with the driver's mount matrix in @m (device =
 * m * sensor); false when only the chip's axes are known (its registers,
 * or a driver without a mount matrix)
 */
bool magn_source_mount(const struct magn_source *s,
		       double m[AS9888_AXES][AS9888_AXES]);

/* Wait @ns on the source's clock (virtual on a virtual-clock simulator) */
void magn_source_sleep(struct magn_source *s, uint64_t ns);

/* The source's clock, ns */
uint64_t magn_source_now_ns(struct magn_source *s);

void magn_source_close(struct magn_source *s);

#endif
