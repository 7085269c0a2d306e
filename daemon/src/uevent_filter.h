/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A classic BPF socket filter for the kernel uevent netlink socket that
 * drops every uevent of a subsystem other than "iio" in the kernel, before
 * it is queued: other devices' uevents no longer wake the daemon.
 */
#ifndef AS9888_UEVENT_FILTER_H
#define AS9888_UEVENT_FILTER_H

#include <linux/filter.h>
#include <stddef.h>

/* Bytes of "ACTION@DEVPATH" the filter searches for its NUL */
#define UEVENT_FILTER_SCAN	1000
/* Instructions: 4 per byte scanned, and the tail */
#define UEVENT_FILTER_LEN	(4 * UEVENT_FILTER_SCAN + 11)

/* Fill @prog (UEVENT_FILTER_LEN instructions); returns the count */
size_t uevent_filter_build(struct sock_filter *prog);

/* Attach it to @fd (SO_ATTACH_FILTER); 0 or -errno */
int uevent_filter_attach(int fd);

#endif
