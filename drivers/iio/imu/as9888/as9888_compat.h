/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888: the few kernel API differences between Linux 6.1 and current
 * kernels, kept in one place.
 *
 * Only macros: this header is also included by the calibration unit when it
 * is built in userspace, so it must not pull in any kernel header but
 * <linux/version.h>. The macros expand where they are used, after the
 * user has included the headers that declare what they name.
 */
#ifndef AS9888_COMPAT_H
#define AS9888_COMPAT_H

#include <linux/version.h>

/*
 * Kernel version tests on major.patchlevel. The userspace stand-in of
 * <linux/version.h> has no LINUX_VERSION_MAJOR: it means the newest kernel.
 */
#ifdef LINUX_VERSION_MAJOR
#define AS9888_KERNEL \
	KERNEL_VERSION(LINUX_VERSION_MAJOR, LINUX_VERSION_PATCHLEVEL, 0)
#else
#define AS9888_KERNEL		KERNEL_VERSION(255, 0, 0)
#endif
#define AS9888_KERNEL_AT_LEAST(major, minor) \
	(KERNEL_VERSION(major, minor, 0) <= AS9888_KERNEL)

/*
 * Symbol namespaces are string literals since 6.13 and bare identifiers
 * before.
 */
#if AS9888_KERNEL_AT_LEAST(6, 13)
#define AS9888_NS	"IIO_AS9888"
#else
#define AS9888_NS	IIO_AS9888
#endif

/* i2c_driver.probe lost its i2c_device_id argument in 6.3 */
#if AS9888_KERNEL_AT_LEAST(6, 3)
#define AS9888_I2C_PROBE(fn)	.probe = (fn)
#else
#define AS9888_I2C_PROBE(fn)	.probe_new = (fn)
#endif

/* The maple tree register cache arrived in 6.4 */
#if AS9888_KERNEL_AT_LEAST(6, 4)
#define AS9888_REGCACHE		REGCACHE_MAPLE
#else
#define AS9888_REGCACHE		REGCACHE_RBTREE
#endif

/* iio_device_claim_direct() returns bool since 6.15 */
#if AS9888_KERNEL_AT_LEAST(6, 15)
#define as9888_claim_direct(indio_dev) \
	iio_device_claim_direct(indio_dev)
#define as9888_release_direct(indio_dev) \
	iio_device_release_direct(indio_dev)
#else
#define as9888_claim_direct(indio_dev) \
	(!iio_device_claim_direct_mode(indio_dev))
#define as9888_release_direct(indio_dev) \
	iio_device_release_direct_mode(indio_dev)
#endif

/* iio_push_to_buffers_with_ts() checks the scan size since 6.16 */
#if AS9888_KERNEL_AT_LEAST(6, 16)
#define as9888_push_to_buffers_with_ts(indio_dev, scan, len, ts) \
	iio_push_to_buffers_with_ts(indio_dev, scan, len, ts)
#else
#define as9888_push_to_buffers_with_ts(indio_dev, scan, len, ts) \
	({ (void)(len); iio_push_to_buffers_with_timestamp(indio_dev, scan, ts); })
#endif

/* pm_runtime_put_autosuspend() marks the device busy itself since 6.17 */
#if AS9888_KERNEL_AT_LEAST(6, 17)
#define as9888_pm_put(dev)	pm_runtime_put_autosuspend(dev)
#else
#define as9888_pm_put(dev)						\
	({								\
		struct device *__dev = (dev);				\
									\
		pm_runtime_mark_last_busy(__dev);			\
		pm_runtime_put_autosuspend(__dev);			\
	})
#endif

#endif /* AS9888_COMPAT_H */
