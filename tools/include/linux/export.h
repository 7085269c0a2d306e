/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for <linux/export.h>: symbols need no export. */
#ifndef AS9888_SHIM_LINUX_EXPORT_H
#define AS9888_SHIM_LINUX_EXPORT_H

#define EXPORT_SYMBOL_NS_GPL(sym, ns)
#define EXPORT_SYMBOL_GPL(sym)

#endif
