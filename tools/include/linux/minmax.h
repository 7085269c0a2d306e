/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for <linux/minmax.h>: defined with the rest in <linux/kernel.h>. */
#ifndef AS9888_SHIM_LINUX_MINMAX_H
#define AS9888_SHIM_LINUX_MINMAX_H

#include <linux/kernel.h>

#endif
