/* SPDX-License-Identifier: GPL-2.0 */
/*
 * One IIO device's three-axis channels as the HAL reads them from its
 * buffer: the x, y, z and timestamp scan elements (their _index and
 * _type), each axis's scale and offset (per axis or shared by the type),
 * and the mount matrix; a sample decoded into the device frame.
 * Standard attributes only (Documentation/ABI/testing/sysfs-bus-iio).
 */
#ifndef AS9888_HAL_LAYOUT_H
#define AS9888_HAL_LAYOUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "iio_scan.h"

/**
 * struct hal_layout - what decodes one device's samples
 * @chan:	x, y, z, then the timestamp (offsets set by iio_scan_layout())
 * @scale:	per axis, the IIO unit per LSB (m/s^2, gauss)
 * @offset:	per axis, added to the value before the scale
 * @unit:	the factor from the IIO unit to Android's (1, or 100 for gauss to uT)
 * @mount:	the mount matrix: device frame = mount * sensor frame
 * @sample_bytes: one sample in the buffer
 */
struct hal_layout {
	struct iio_scan_channel chan[4];
	double scale[3];
	double offset[3];
	double unit;
	double mount[3][3];
	unsigned int sample_bytes;
};

/* The scan elements the layout is made of, "in_<type>_x" ... "in_timestamp" */
extern const char *const hal_axis_names[3];

/*
 * Read the layout of the @type ("accel", "magn") channels of the device
 * at @dir, with @unit as above. 0, or -errno with the attribute and why in
 * @err. The buffer must hold those four scan elements only (hal_stream
 * enables exactly them).
 */
int hal_layout_read(const char *dir, const char *type, double unit,
		    struct hal_layout *l, char *err, size_t errlen);

/*
 * One sample: @raw the axes' values as the buffer holds them (for the
 * calibration daemon's feed), @sensor in Android's unit in the sensor
 * frame, @ts the timestamp; true when an axis is at the limit of its
 * range (the driver's saturation mark).
 */
bool hal_layout_decode(const struct hal_layout *l, const uint8_t *sample,
		       int32_t raw[3], double sensor[3], int64_t *ts);

#endif
