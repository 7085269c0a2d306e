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

/*
 * Bytes of "ACTION@DEVPATH" the filter searches for its NUL, a multiple of
 * 4. The kernel charges the filter (as eBPF, about 20 instructions of 8
 * bytes per word scanned) to the socket's option memory, at most
 * net.core.optmem_max: 20480 bytes by default up to Linux 6.8. 256 bytes
 * stay well below (a longer header is passed, not dropped).
 */
#define UEVENT_FILTER_SCAN	256
/* Instructions: 12 per word scanned, and the tail */
#define UEVENT_FILTER_LEN	(12 * (UEVENT_FILTER_SCAN / 4) + 40)

/* Fill @prog (UEVENT_FILTER_LEN instructions); returns the count */
size_t uevent_filter_build(struct sock_filter *prog);

/* Attach it to @fd (SO_ATTACH_FILTER); 0 or -errno */
int uevent_filter_attach(int fd);

#endif
