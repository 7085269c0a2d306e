/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <kunit/visibility.h>: what the kernel keeps static
 * unless KUnit is enabled is an ordinary function in userspace (see
 * <linux/kconfig.h> here).
 */
#ifndef AS9888_SHIM_KUNIT_VISIBILITY_H
#define AS9888_SHIM_KUNIT_VISIBILITY_H

#define VISIBLE_IF_KUNIT
#define EXPORT_SYMBOL_IF_KUNIT(symbol)

#endif
