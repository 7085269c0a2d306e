/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The field and the acceleration of one measurement through the driver:
 * a buffered capture of both IIO devices (as9888-magn and as9888-accel)
 * on the chip's shared data-ready trigger, as9888-dev<N>, at one rate.
 * At equal rates the driver takes both devices' samples in the same
 * measurement and each device's poll function stamps it as the trigger
 * fires, so the two timestamps of one measurement are microseconds apart
 * and those of two measurements a period apart: the samples are paired
 * by their timestamps (within a quarter of the period), a sample without
 * its partner (the first one of a device started while the other ran) is
 * dropped. Documentation/iio/as9888.rst, "Two IIO devices".
 *
 * What it changed is put back by magn_capture_close() and on every error
 * path, from memory: a process killed during a capture leaves both
 * buffers enabled on the trigger, and the next capture then finds
 * "another program has the buffer enabled" (sysfs reads instead) until
 * a buffer/enable of 0 is written or the driver is reloaded.
 */
#ifndef AS9888_MAGN_CAPTURE_H
#define AS9888_MAGN_CAPTURE_H

#include <stddef.h>
#include <stdint.h>

#include "as9888_calib.h"

/*
 * The capture's rate: the magnetometer's fastest (the driver offers 100 Hz
 * with the magnetometer on), MAGN_SOURCE_AVERAGE pairs averaged into each
 * of magn-calibrate's samples, one per 50 ms
 */
#define MAGN_CAPTURE_RATE_HZ	100
/* No pair for this long: the capture has stalled */
#define MAGN_CAPTURE_STALL_MS	3000

struct magn_capture;

/**
 * struct magn_capture_pair - one measurement of both devices
 * @magn:	in_magn_{x,y,z} as buffered (the driver's calibration in it)
 * @accel:	in_accel_{x,y,z} as buffered
 * @t_magn:	the magnetometer device's timestamp, ns
 * @t_accel:	the accelerometer device's
 */
struct magn_capture_pair {
	int32_t magn[AS9888_AXES];
	int32_t accel[AS9888_AXES];
	int64_t t_magn;
	int64_t t_accel;
};

/*
 * Start the capture of the devices at @accel_dir and @magn_dir (their
 * character devices below iio_dev_root()): both buffers on the trigger
 * as9888-dev<N> at MAGN_CAPTURE_RATE_HZ, the scan elements of the three
 * axes and the timestamp. 0, or -errno with why no capture can be had in
 * @why (a buffer another program holds, no data-ready trigger, ...): then
 * every attribute is as it was.
 */
int magn_capture_open(const char *accel_dir, const char *magn_dir,
		      struct magn_capture **out, char *why, size_t whylen);

/*
 * The next pair, waiting for it: 0; -ETIMEDOUT when none came within
 * MAGN_CAPTURE_STALL_MS, -EPIPE when a device's buffer was turned off
 * under the capture (another program), or another -errno; why in @why
 */
int magn_capture_next(struct magn_capture *c, struct magn_capture_pair *p,
		      char *why, size_t whylen);

/* The trigger the capture runs on */
const char *magn_capture_trigger(const struct magn_capture *c);

/* Stop it and put every attribute back as found */
void magn_capture_close(struct magn_capture *c);

#endif
