// SPDX-License-Identifier: GPL-2.0
/* The AS9888 IIO driver's interfaces as the daemon uses them (iio.h). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "chip/iio.h"

int iio_read_debugfs(const char *dir, const char *name, char *buf,
		     size_t size, char *path, size_t path_size)
{
	const char *base = strrchr(dir, '/');
	char ddir[IIO_PATH_MAX];

	base = base ? base + 1 : dir;
	snprintf(ddir, sizeof(ddir), "%s/iio/%s", iio_debugfs_root(), base);
	snprintf(path, path_size, "%s/%s", ddir, name);

	return iio_read_attr(ddir, name, buf, size);
}

/* @dir's IIO device is named @want */
static bool has_name(const char *dir, const char *want)
{
	char name[IIO_ATTR_MAX];

	return iio_read_attr(dir, "name", name, sizeof(name)) > 0 &&
	       !strcmp(name, want);
}

/* The first iio:deviceN directly below @dir named @want */
static int scan(const char *dir, const char *want, char *out, size_t size)
{
	struct dirent *de;
	DIR *d = opendir(dir);
	int ret = -ENOENT;

	if (!d)
		return -ENOENT;
	while ((de = readdir(d))) {
		if (!iio_is_device(de->d_name))
			continue;
		snprintf(out, size, "%s/%s", dir, de->d_name);
		if (has_name(out, want)) {
			ret = 0;
			break;
		}
	}
	closedir(d);

	return ret;
}

int iio_find_device(const char *devpath, char *out, size_t size)
{
	char dir[IIO_PATH_MAX];
	const char *base;

	if (!devpath) {
		snprintf(dir, sizeof(dir), "%s/bus/iio/devices", iio_sysfs_root());
		return scan(dir, IIO_ACCEL_NAME, out, size);
	}
	if (strstr(devpath, "/.."))
		return -ENOENT;
	snprintf(dir, sizeof(dir), "%s%s", iio_sysfs_root(), devpath);
	base = strrchr(dir, '/');
	if (base && iio_is_device(base + 1)) {
		if (!has_name(dir, IIO_ACCEL_NAME))
			return -ENOENT;
		snprintf(out, size, "%s", dir);
		return 0;
	}

	return scan(dir, IIO_ACCEL_NAME, out, size);
}

int iio_find_magn(const char *accel_dir, char *out, size_t size,
		  char *parent, size_t parent_size)
{
	return iio_find_sibling(accel_dir, IIO_MAGN_NAME, out, size, parent,
				parent_size);
}

int iio_read_eeprom(const char *dir, uint8_t eeprom[AS9888_EEPROM_LEN])
{
	const char *base = strrchr(dir, '/');
	char bus[IIO_PATH_MAX], path[IIO_PATH_MAX];
	struct dirent *de;
	ssize_t n;
	DIR *d;
	int fd;

	if (!base || !iio_is_device(base + 1))
		return -EINVAL;
	/* The chip's only NVMEM provider, numbered by the NVMEM core */
	if ((size_t)snprintf(bus, sizeof(bus), "%s/..", dir) >= sizeof(bus))
		return -ENAMETOOLONG;
	d = opendir(bus);
	if (!d)
		return -errno;
	fd = -ENOENT;
	while ((de = readdir(d))) {
		if (strncmp(de->d_name, IIO_EEPROM_PREFIX,
			    strlen(IIO_EEPROM_PREFIX)))
			continue;
		if ((size_t)snprintf(path, sizeof(path), "%s/%s/nvmem", bus,
				     de->d_name) >= sizeof(path)) {
			fd = -ENAMETOOLONG;
			break;
		}
		fd = open(path, O_RDONLY | O_CLOEXEC);
		if (fd < 0)
			fd = -errno;
		break;
	}
	closedir(d);
	if (fd < 0)
		return fd;
	n = read(fd, eeprom, AS9888_EEPROM_LEN);
	close(fd);
	if (n < 0)
		return -errno;

	return n == AS9888_EEPROM_LEN ? 0 : -EIO;
}
