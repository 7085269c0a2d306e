/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The HAL tests' additions to the fake sysfs tree (tests/daemon/
 * fake_sysfs.h): the buffer attributes and scan elements of both
 * devices as the driver has them, and the data-ready trigger.
 */
#ifndef AS9888_HAL_TEST_TREE_H
#define AS9888_HAL_TEST_TREE_H

#include "fake_sysfs.h"

/* The example EEPROM's magnetometer scales, gauss per LSB */
#define TREE_MAGN_SCALE_X	0.003
#define TREE_MAGN_SCALE_Y	0.00305859
#define TREE_MAGN_SCALE_Z	0.00294141
#define TREE_ACCEL_SCALE	0.009576806

/* Both devices' channels, buffer and rates, as after probe (again) */
void hal_tree_channels(const struct fake_sysfs *f);

/* Remove @dir/@name */
void hal_tree_remove(const char *dir, const char *name);

#endif
