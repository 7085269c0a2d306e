/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for <linux/bitops.h>: sign extension. */
#ifndef AS9888_SHIM_LINUX_BITOPS_H
#define AS9888_SHIM_LINUX_BITOPS_H

#include <linux/bits.h>
#include <linux/types.h>

/* Sign-extend the bits 0..index of value; same contract as the kernel's. */
static inline s32 sign_extend32(u32 value, int index)
{
	u8 shift = 31 - index;

	return (s32)(value << shift) >> shift;
}

#endif
