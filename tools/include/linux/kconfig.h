/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <linux/kconfig.h>, force-included into the units
 * shared with the kernel as Kbuild force-includes the real one.
 *
 * CONFIG_KUNIT is "enabled": in the kernel, the calibration unit's internal
 * functions are visible only to its KUnit test (VISIBLE_IF_KUNIT); in
 * userspace the factory test, the daemon and the cmocka tests are their
 * other users, so they are visible here too.
 */
#ifndef AS9888_SHIM_LINUX_KCONFIG_H
#define AS9888_SHIM_LINUX_KCONFIG_H

#define CONFIG_KUNIT 1

/* IS_ENABLED() as the kernel defines it: 1 for an option defined to 1 */
#define __ARG_PLACEHOLDER_1 0,
#define __take_second_arg(__ignored, val, ...) val
#define __is_defined(x)			___is_defined(x)
#define ___is_defined(val)		____is_defined(__ARG_PLACEHOLDER_##val)
#define ____is_defined(arg1_or_junk)	__take_second_arg(arg1_or_junk 1, 0)
#define IS_ENABLED(option)		__is_defined(option)

#endif
