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

#include "iio.h"

int iio_dir_open(const char *dir)
{
	int fd = open(dir, O_PATH | O_DIRECTORY | O_CLOEXEC);

	return fd < 0 ? -errno : fd;
}

int iio_read_attr(const char *dir, const char *name, char *buf, size_t size)
{
	char path[IIO_PATH_MAX];

	snprintf(path, sizeof(path), "%s/%s", dir, name);

	return iio_read_attr_at(AT_FDCWD, path, buf, size);
}

int iio_read_attr_at(int dfd, const char *name, char *buf, size_t size)
{
	struct iio_attr a;
	int ret;

	ret = iio_attr_open(&a, dfd, name, false);
	if (ret)
		return ret;
	ret = iio_attr_read(&a, buf, size);
	iio_attr_close(&a);

	return ret;
}

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

int iio_write_attr(const char *dir, const char *name, const char *value)
{
	char path[IIO_PATH_MAX];

	snprintf(path, sizeof(path), "%s/%s", dir, name);

	return iio_write_attr_at(AT_FDCWD, path, value);
}

int iio_write_attr_at(int dfd, const char *name, const char *value)
{
	size_t len = strlen(value);
	ssize_t n;
	int fd;

	/* as a shell's "echo >": sysfs ignores O_TRUNC, a plain file needs it */
	fd = openat(dfd, name, O_WRONLY | O_TRUNC | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	n = write(fd, value, len);
	if (n < 0)
		n = -errno;
	close(fd);

	return n < 0 ? (int)n : (size_t)n == len ? 0 : -EIO;
}

/* @dir's IIO device is named @want */
static bool has_name(const char *dir, const char *want)
{
	char name[IIO_ATTR_MAX];

	return iio_read_attr(dir, "name", name, sizeof(name)) > 0 &&
	       !strcmp(name, want);
}

static bool is_iio_device(const char *entry)
{
	return !strncmp(entry, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX));
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
		if (!is_iio_device(de->d_name))
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
	if (base && is_iio_device(base + 1)) {
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
	const char *base = strrchr(accel_dir, '/');
	char bus[IIO_PATH_MAX], rel[IIO_PATH_MAX], name[IIO_ATTR_MAX];
	char real[PATH_MAX];
	struct dirent *de;
	int ret = -ENOENT;
	DIR *d;

	if (!base || base == accel_dir)
		return -ENOENT;
	/*
	 * The bus device is @accel_dir/..: the kernel takes ".." from where
	 * the bus link leads. No realpath(): it reads every link on the way,
	 * which is slow on a slow system; the devices are found by their
	 * entries, and named by @accel_dir's own directory (the bus links of
	 * /sys/bus/iio/devices, or the bus device itself)
	 */
	snprintf(bus, sizeof(bus), "%s/..", accel_dir);
	d = opendir(bus);
	if (d) {
		while ((de = readdir(d))) {
			if (!is_iio_device(de->d_name) ||
			    !strcmp(de->d_name, base + 1))
				continue;
			snprintf(rel, sizeof(rel), "%s/name", de->d_name);
			if (iio_read_attr_at(dirfd(d), rel, name, sizeof(name)) > 0 &&
			    !strcmp(name, IIO_MAGN_NAME)) {
				snprintf(out, size, "%.*s/%s", (int)(base - accel_dir),
					 accel_dir, de->d_name);
				/*
				 * a bus link comes a moment after its device's
				 * directory (device_add()): until then, by ..
				 */
				if (access(out, F_OK))
					snprintf(out, size, "%s/%s", bus, de->d_name);
				ret = 0;
				break;
			}
		}
		closedir(d);
	}
	if (ret && parent) {
		/* for the message only */
		if (!realpath(bus, real))
			return -errno;
		snprintf(parent, parent_size, "%s", real);
	}

	return ret;
}

int iio_read_eeprom(const char *dir, uint8_t eeprom[AS9888_EEPROM_LEN])
{
	const char *base = strrchr(dir, '/');
	char bus[IIO_PATH_MAX], path[IIO_PATH_MAX];
	struct dirent *de;
	ssize_t n;
	DIR *d;
	int fd;

	if (!base || !is_iio_device(base + 1))
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
