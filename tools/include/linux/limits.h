/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <linux/limits.h>: the UAPI header of the same name
 * (which libc's <limits.h> includes, so nothing else may come in here) plus
 * the kernel's U8_MAX and friends.
 */
#ifndef AS9888_SHIM_LINUX_LIMITS_H
#define AS9888_SHIM_LINUX_LIMITS_H

#include_next <linux/limits.h>
#include <linux/types.h>

#define U8_MAX		((u8)~0U)
#define S16_MAX		((s16)(U16_MAX >> 1))
#define S16_MIN		((s16)(-S16_MAX - 1))
#define U16_MAX		((u16)~0U)
#define S32_MAX		((s32)(U32_MAX >> 1))
#define S32_MIN		((s32)(-S32_MAX - 1))
#define U32_MAX		((u32)~0U)
#define S64_MAX		((s64)(U64_MAX >> 1))
#define S64_MIN		((s64)(-S64_MAX - 1))
#define U64_MAX		((u64)~0ULL)

#endif
