/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <linux/bitfield.h>: FIELD_GET/FIELD_PREP for
 * constant masks, without the kernel's compile-time checks.
 */
#ifndef AS9888_SHIM_LINUX_BITFIELD_H
#define AS9888_SHIM_LINUX_BITFIELD_H

#include <linux/bits.h>

#define __bf_shf(x)		(__builtin_ffsll(x) - 1)
#define FIELD_GET(mask, reg)	((typeof(mask))(((reg) & (mask)) >> __bf_shf(mask)))
#define FIELD_PREP(mask, val)	((((typeof(mask))(val)) << __bf_shf(mask)) & (mask))

#endif
