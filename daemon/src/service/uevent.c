// SPDX-License-Identifier: GPL-2.0
/* Kernel uevents from the netlink socket (see uevent.h). */
#include <errno.h>
#include <linux/netlink.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "service/uevent.h"
#include "service/uevent_filter.h"

/* The kernel's own multicast group (udev's is 2) */
#define UEVENT_GROUP_KERNEL	1
#define UEVENT_RCVBUF		(256 * 1024)

static void copy_field(char *dst, size_t size, const char *src, size_t len)
{
	if (len >= size)
		len = size - 1;
	memcpy(dst, src, len);
	dst[len] = '\0';
}

int uevent_parse(const char *buf, size_t len, struct uevent *ev)
{
	const char *p = buf, *end = buf + len, *at, *nul;

	memset(ev, 0, sizeof(*ev));
	nul = memchr(p, '\0', len);
	at = nul ? memchr(p, '@', (size_t)(nul - p)) : NULL;
	/* udev's own messages start with "libudev": not ours */
	if (!nul || !at || at == p)
		return -EINVAL;
	copy_field(ev->action, sizeof(ev->action), p, (size_t)(at - p));
	copy_field(ev->devpath, sizeof(ev->devpath), at + 1,
		   (size_t)(nul - at - 1));

	for (p = nul + 1; p < end; p = nul + 1) {
		const char *eq;
		size_t klen;

		nul = memchr(p, '\0', (size_t)(end - p));
		if (!nul)
			nul = end;
		eq = memchr(p, '=', (size_t)(nul - p));
		if (!eq)
			continue;
		klen = (size_t)(eq - p);
		if (klen == 9 && !memcmp(p, "SUBSYSTEM", 9))
			copy_field(ev->subsystem, sizeof(ev->subsystem), eq + 1,
				   (size_t)(nul - eq - 1));
		else if (klen == 7 && !memcmp(p, "DEVTYPE", 7))
			copy_field(ev->devtype, sizeof(ev->devtype), eq + 1,
				   (size_t)(nul - eq - 1));
		else if (klen == 6 && !memcmp(p, "DRIVER", 6))
			copy_field(ev->driver, sizeof(ev->driver), eq + 1,
				   (size_t)(nul - eq - 1));
	}

	return 0;
}

bool uevent_is_appearance(const struct uevent *ev)
{
	/*
	 * Every probe of the driver (boot, module load, rebind) registers the
	 * IIO device anew; a resume restores the chip in the driver itself
	 */
	return !strcmp(ev->subsystem, "iio") && !strcmp(ev->action, "add") &&
	       !strcmp(ev->devtype, "iio_device");
}

int uevent_open(void)
{
	struct sockaddr_nl addr = {
		.nl_family = AF_NETLINK,
		.nl_groups = UEVENT_GROUP_KERNEL,
	};
	int fd, size = UEVENT_RCVBUF;

	fd = socket(AF_NETLINK, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK,
		    NETLINK_KOBJECT_UEVENT);
	if (fd < 0)
		return -errno;
	setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size));
	/*
	 * Other subsystems' uevents dropped in the kernel: no wake-up. Should
	 * the kernel refuse the filter, every uevent wakes us, none is lost.
	 */
	(void)uevent_filter_attach(fd);
	if (bind(fd, (struct sockaddr *)&addr, sizeof(addr))) {
		int ret = -errno;

		close(fd);
		return ret;
	}

	return fd;
}
