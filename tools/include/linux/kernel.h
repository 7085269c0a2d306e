/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for the parts of <linux/kernel.h> the shared units use. */
#ifndef AS9888_SHIM_LINUX_KERNEL_H
#define AS9888_SHIM_LINUX_KERNEL_H

#include_next <linux/kernel.h>
#include <linux/limits.h>
#include <linux/types.h>

#define ARRAY_SIZE(a)	(sizeof(a) / sizeof((a)[0]))

/* Like the kernel's abs(): works on any signed integer type. */
#define abs(x) ({ __typeof__(x) __x = (x); __x < 0 ? -__x : __x; })


#define min(a, b)	((a) < (b) ? (a) : (b))
#define max(a, b)	((a) > (b) ? (a) : (b))
#define clamp(v, lo, hi) min(max(v, lo), hi)
#define min_t(type, a, b)	min((type)(a), (type)(b))
#define max_t(type, a, b)	max((type)(a), (type)(b))
#define clamp_t(type, v, lo, hi) clamp((type)(v), (type)(lo), (type)(hi))

#endif
