// SPDX-License-Identifier: GPL-2.0
/* The AS9888's two IIO devices and its trigger (hal_find.h) */
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal_find.h"
#include "iio_sysfs.h"

/* The name of the directory @path's real path is in ("1-000c") */
static int parent_name(const char *path, char *name, size_t len)
{
	char real[PATH_MAX], *slash;

	if (!realpath(path, real))
		return -errno;
	slash = strrchr(real, '/');
	if (!slash || slash == real)
		return -ENOENT;
	*slash = '\0';
	slash = strrchr(real, '/');
	snprintf(name, len, "%s", slash + 1);
	return 0;
}

/* @src into @dst, cut short if need be (sysfs paths are short) */
static void copy(char *dst, size_t len, const char *src)
{
	size_t n = strnlen(src, len - 1);

	memcpy(dst, src, n);
	dst[n] = '\0';
}

/* The device number of "iio:deviceN", or -1 */
static int device_number(const char *entry)
{
	char *end;
	long n;

	if (strncmp(entry, "iio:device", 10) || !entry[10])
		return -1;
	n = strtol(entry + 10, &end, 10);
	return *end || n < 0 || n > 65535 ? -1 : (int)n;
}

/* @dir's IIO device is named @want */
static int named(const char *dir, const char *want)
{
	char name[64];

	return iio_read_attr(dir, "name", name, sizeof(name)) > 0 &&
	       !strcmp(name, want);
}

int hal_find_devices(const char *sysfs, const char *dev, const char *parent,
		     const char *trigger, struct hal_devices *out,
		     char *err, size_t errlen)
{
	char bus[200], path[PATH_MAX], chip[64] = "";
	struct hal_devices found;
	int accel_n = -1, n;
	struct dirent *e;
	DIR *d;

	memset(&found, 0, sizeof(found));
	snprintf(bus, sizeof(bus), "%s/bus/iio/devices", sysfs);
	d = opendir(bus);
	if (!d) {
		n = -errno;
		snprintf(err, errlen, "%s: cannot list: %s (no IIO in this kernel?)",
			 bus, strerror(errno));
		return n;
	}
	/* the accelerometer first: it names the chip (its bus device) */
	while ((e = readdir(d))) {
		n = device_number(e->d_name);
		snprintf(path, sizeof(path), "%s/%s", bus, e->d_name);
		if (n < 0 || !named(path, "as9888-accel") ||
		    parent_name(path, chip, sizeof(chip)) ||
		    (*parent && strcmp(chip, parent)))
			continue;
		if (accel_n < 0 || n < accel_n) {
			accel_n = n;
			copy(found.accel, sizeof(found.accel), path);
			snprintf(found.accel_node, sizeof(found.accel_node),
				 "%s/iio:device%d", dev, n);
		}
	}
	closedir(d);
	if (accel_n < 0) {
		snprintf(err, errlen, "%s: no IIO device named as9888-accel%s%s (is the as9888 driver loaded?)",
			 bus, *parent ? " below bus device " : "", parent);
		return -ENODEV;
	}
	parent_name(found.accel, chip, sizeof(chip));
	/* its sibling as9888-magn */
	if (iio_find_sibling(found.accel, "as9888-magn", path, sizeof(path),
			     NULL, 0) ||
	    (n = device_number(strrchr(path, '/') + 1)) < 0) {
		snprintf(err, errlen, "%s: no as9888-magn beside as9888-accel below bus device %s",
			 bus, chip);
		return -ENODEV;
	}
	copy(found.magn, sizeof(found.magn), path);
	snprintf(found.magn_node, sizeof(found.magn_node), "%s/iio:device%d",
		 dev, n);
	if (*trigger) {
		snprintf(found.trigger, sizeof(found.trigger), "%s", trigger);
	} else {
		/* the data-ready trigger, when the chip has its interrupt wired */
		char want[32];

		snprintf(want, sizeof(want), "as9888-dev%d", accel_n);
		if (!iio_find_trigger(sysfs, want))
			snprintf(found.trigger, sizeof(found.trigger), "%s", want);
	}
	*out = found;
	return 0;
}
