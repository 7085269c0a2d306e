/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <linux/types.h>: just enough for the AS9888
 * units that build both in the kernel and in userspace (the calibration
 * arithmetic and the chip model). Nothing here may call into libc.
 */
#ifndef AS9888_SHIM_LINUX_TYPES_H
#define AS9888_SHIM_LINUX_TYPES_H

/* The UAPI header of the same name keeps working for libc users. */
#include_next <linux/types.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef int8_t s8;
typedef uint8_t u8;
typedef int16_t s16;
typedef uint16_t u16;
typedef int32_t s32;
typedef uint32_t u32;
typedef int64_t s64;
typedef uint64_t u64;

#endif
