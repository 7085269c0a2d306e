/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for <linux/array_size.h>: ARRAY_SIZE(). */
#ifndef AS9888_SHIM_LINUX_ARRAY_SIZE_H
#define AS9888_SHIM_LINUX_ARRAY_SIZE_H

#include <linux/kernel.h>

#endif
