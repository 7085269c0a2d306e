/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Kernel uevents from the netlink socket: which ones mean "an AS9888 IIO
 * device (re)appeared and needs its calibration".
 */
#ifndef AS9888_UEVENT_H
#define AS9888_UEVENT_H

#include <stdbool.h>
#include <stddef.h>

#define UEVENT_BUF_SIZE	8192

/**
 * struct uevent - the fields of one kernel uevent the daemon looks at
 * @action:	"add", "bind", "change", ...
 * @devpath:	/devices/... path below /sys
 * @subsystem:	"iio", "i2c", ...
 * @devtype:	DEVTYPE, may be empty
 * @driver:	DRIVER, may be empty
 */
struct uevent {
	char action[16];
	char devpath[256];
	char subsystem[32];
	char devtype[32];
	char driver[64];
};

/* Parse one kernel netlink uevent ("action@devpath\0KEY=value\0...") */
int uevent_parse(const char *buf, size_t len, struct uevent *ev);

/* Whether the event is an IIO device (re)appearing: an iio_device add */
bool uevent_is_appearance(const struct uevent *ev);

/* A netlink socket for kernel uevents, non-blocking; -errno on failure */
int uevent_open(void);

#endif
