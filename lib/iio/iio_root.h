/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Where the kernel's file systems are: the real ones, or the fake trees
 * the tests name in the environment
 */
#ifndef AS9888_IIO_ROOT_H
#define AS9888_IIO_ROOT_H

/* The sysfs root: $AS9888_SYSFS, default /sys */
const char *iio_sysfs_root(void);

/* The debugfs root: $AS9888_DEBUGFS, default /sys/kernel/debug */
const char *iio_debugfs_root(void);

/* Where the devices' nodes are: $AS9888_DEVDIR, default /dev */
const char *iio_dev_root(void);

#endif
