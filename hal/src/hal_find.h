/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888's two IIO devices, found by name below
 * <sysfs>/bus/iio/devices, and the chip's data-ready trigger.
 */
#ifndef AS9888_HAL_FIND_H
#define AS9888_HAL_FIND_H

#include <stddef.h>

/**
 * struct hal_devices - what was found
 * @accel:	as9888-accel's sysfs directory
 * @magn:	as9888-magn's
 * @accel_node:	its character device
 * @magn_node:	ditto
 * @trigger:	the trigger to use; empty: leave the devices' own
 */
struct hal_devices {
	char accel[256];
	char magn[256];
	char accel_node[256];
	char magn_node[256];
	char trigger[64];
};

/*
 * Find the chip's devices below @sysfs (nodes below @dev): with @parent
 * non-empty the chip whose bus device's directory has that name, else
 * the first; @trigger non-empty is taken as the trigger, else the chip's
 * "as9888-devN" when it exists (N the accelerometer's device number).
 * 0, or -ENODEV / -errno with what was looked for in @err.
 */
int hal_find_devices(const char *sysfs, const char *dev, const char *parent,
		     const char *trigger, struct hal_devices *out,
		     char *err, size_t errlen);

#endif
