// SPDX-License-Identifier: GPL-2.0
/* The IIO sysfs ABI as files (iio_sysfs.h). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "iio_attr.h"
#include "iio_sysfs.h"

bool iio_is_device(const char *entry)
{
	return !strncmp(entry, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX));
}

int iio_dir_open(const char *dir)
{
	int fd = open(dir, O_PATH | O_DIRECTORY | O_CLOEXEC);

	return fd < 0 ? -errno : fd;
}

int iio_read_attr(const char *dir, const char *name, char *buf, size_t size)
{
	char path[IIO_PATH_MAX];

	if ((size_t)snprintf(path, sizeof(path), "%s/%s", dir, name) >= sizeof(path))
		return -ENAMETOOLONG;

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

int iio_write_attr(const char *dir, const char *name, const char *value)
{
	char path[IIO_PATH_MAX];

	if ((size_t)snprintf(path, sizeof(path), "%s/%s", dir, name) >= sizeof(path))
		return -ENAMETOOLONG;

	return iio_write_attr_at(AT_FDCWD, path, value);
}

int iio_write_attr_at(int dfd, const char *name, const char *value)
{
	size_t len = strlen(value);
	ssize_t n;
	int fd, ret;

	/* as a shell's "echo >": sysfs ignores O_TRUNC, a plain file needs it */
	fd = openat(dfd, name, O_WRONLY | O_TRUNC | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	n = write(fd, value, len);
	ret = n < 0 ? -errno : (size_t)n == len ? 0 : -EIO;
	/* a store's error can come at close (a plain file's, a FUSE one's) */
	if (close(fd) && !ret && errno != EINTR)
		ret = -errno;

	return ret;
}

int iio_find_sibling(const char *dir, const char *name, char *out,
		     size_t size, char *parent, size_t parent_size)
{
	const char *base = strrchr(dir, '/');
	char bus[IIO_PATH_MAX], rel[IIO_PATH_MAX], found[128];
	char real[PATH_MAX];
	struct dirent *de;
	int ret = -ENOENT;
	DIR *d;

	if (!base || base == dir)
		return -ENOENT;
	/*
	 * The bus device is @dir/..: the kernel takes ".." from where the
	 * bus link leads. No realpath(): it reads every link on the way,
	 * which is slow on a slow system; the devices are found by their
	 * entries, and named by @dir's own directory (the bus links of
	 * /sys/bus/iio/devices, or the bus device itself)
	 */
	snprintf(bus, sizeof(bus), "%s/..", dir);
	d = opendir(bus);
	if (d) {
		while ((de = readdir(d))) {
			if (!iio_is_device(de->d_name) ||
			    !strcmp(de->d_name, base + 1))
				continue;
			snprintf(rel, sizeof(rel), "%s/name", de->d_name);
			if (iio_read_attr_at(dirfd(d), rel, found, sizeof(found)) > 0 &&
			    !strcmp(found, name)) {
				snprintf(out, size, "%.*s/%s", (int)(base - dir),
					 dir, de->d_name);
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

int iio_find_trigger(const char *sysfs, const char *name)
{
	char bus[IIO_PATH_MAX], rel[IIO_PATH_MAX], found[128];
	struct dirent *de;
	int ret = -ENOENT;
	DIR *d;

	if ((size_t)snprintf(bus, sizeof(bus), "%s/bus/iio/devices", sysfs) >=
	    sizeof(bus))
		return -ENAMETOOLONG;
	d = opendir(bus);
	if (!d)
		return -errno;
	while ((de = readdir(d))) {
		if (strncmp(de->d_name, IIO_TRIGGER_PREFIX,
			    strlen(IIO_TRIGGER_PREFIX)))
			continue;
		snprintf(rel, sizeof(rel), "%s/name", de->d_name);
		if (iio_read_attr_at(dirfd(d), rel, found, sizeof(found)) > 0 &&
		    !strcmp(found, name)) {
			ret = 0;
			break;
		}
	}
	closedir(d);

	return ret;
}
