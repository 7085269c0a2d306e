/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <linux/version.h>: the shared units are built for
 * "the newest kernel" in userspace so that compat branches pick current APIs.
 */
#ifndef AS9888_SHIM_LINUX_VERSION_H
#define AS9888_SHIM_LINUX_VERSION_H

#define KERNEL_VERSION(a, b, c)	(((a) << 16) + ((b) << 8) + ((c) > 255 ? 255 : (c)))
#define LINUX_VERSION_CODE	KERNEL_VERSION(255, 0, 0)

#endif
