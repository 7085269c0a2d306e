/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888: the few kernel API differences between Linux 6.1 and current
 * kernels, kept in one place.
 */
#ifndef AS9888_COMPAT_H
#define AS9888_COMPAT_H

#include <linux/version.h>

/*
 * Symbol namespaces are string literals since 6.13 and bare identifiers
 * before.
 */
#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 13, 0)
#define AS9888_NS	"IIO_AS9888"
#else
#define AS9888_NS	IIO_AS9888
#endif

#endif /* AS9888_COMPAT_H */
