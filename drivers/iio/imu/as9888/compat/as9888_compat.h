/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 out-of-tree builds on older kernels: the driver is written against
 * the current kernel API (Linux 7.2) and carries no version tests. For
 * kernels before 6.17, Kbuild (this directory's, which only out-of-tree
 * builds read) force-includes this header into every object, so that the
 * same sources build on Linux 6.1 LTS and Debian 12's kernel.
 *
 * Not part of the upstream series. Each block maps one newer interface
 * onto its older form; the version test is the kernel that introduced it.
 */
#ifndef AS9888_COMPAT_H
#define AS9888_COMPAT_H

#include <linux/version.h>

/* Symbol namespaces are string literals since 6.13 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 13, 0)
#include <linux/export.h>
#include <linux/module.h>

#undef EXPORT_SYMBOL_NS_GPL
#define EXPORT_SYMBOL_NS_GPL(sym, ns)	__EXPORT_SYMBOL(sym, "_gpl", ns)
#undef MODULE_IMPORT_NS
#define MODULE_IMPORT_NS(ns)		MODULE_INFO(import_ns, ns)
#endif

/* The maple tree register cache arrived in 6.4 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 4, 0)
#define REGCACHE_MAPLE			REGCACHE_RBTREE
#endif

/* iio_device_claim_direct() returns bool since 6.15 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 15, 0)
#include <linux/iio/iio.h>

static inline bool as9888_compat_claim_direct(struct iio_dev *indio_dev)
{
	return !iio_device_claim_direct_mode(indio_dev);
}

#define iio_device_claim_direct		as9888_compat_claim_direct
#define iio_device_release_direct	iio_device_release_direct_mode
#endif

/* iio_push_to_buffers_with_ts() checks the scan size since 6.16 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 16, 0)
#include <linux/iio/buffer.h>

static inline int as9888_compat_push_with_ts(struct iio_dev *indio_dev,
					     void *data, size_t data_total_len,
					     s64 timestamp)
{
	return iio_push_to_buffers_with_timestamp(indio_dev, data, timestamp);
}

#define iio_push_to_buffers_with_ts	as9888_compat_push_with_ts
#endif

/* pm_runtime_put_autosuspend() marks the device busy itself since 6.17 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 17, 0)
#include <linux/pm_runtime.h>

static inline int as9888_compat_put_autosuspend(struct device *dev)
{
	pm_runtime_mark_last_busy(dev);
	return pm_runtime_put_autosuspend(dev);
}

#define pm_runtime_put_autosuspend	as9888_compat_put_autosuspend
#endif

/* hrtimer_setup() replaces hrtimer_init() and setting .function in 6.13 */
#if LINUX_VERSION_CODE < KERNEL_VERSION(6, 13, 0)
#include <linux/hrtimer.h>

static inline void
as9888_compat_hrtimer_setup(struct hrtimer *timer,
			    enum hrtimer_restart (*function)(struct hrtimer *),
			    clockid_t clock_id, enum hrtimer_mode mode)
{
	hrtimer_init(timer, clock_id, mode);
	timer->function = function;
}

#define hrtimer_setup			as9888_compat_hrtimer_setup
#endif

/* iio_for_each_active_channel() hides masklength since 6.12 */
#ifndef iio_for_each_active_channel
#include <linux/iio/iio.h>

#define iio_for_each_active_channel(indio_dev, chan) \
	for_each_set_bit(chan, (indio_dev)->active_scan_mask, \
			 (indio_dev)->masklength)
#endif

#endif /* AS9888_COMPAT_H */
