/* SPDX-License-Identifier: GPL-2.0 */
/* Userspace stand-in for <linux/errno.h>: the C library's errno values. */
#ifndef AS9888_SHIM_LINUX_ERRNO_H
#define AS9888_SHIM_LINUX_ERRNO_H

#include_next <linux/errno.h>
#include <errno.h>

#endif
