// SPDX-License-Identifier: GPL-2.0
/* A sysfs attribute kept open (iio_attr.h). */
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

#include "iio_attr.h"
#include "iio_root.h"

int iio_attr_open(struct iio_attr *a, int dfd, const char *name,
		  bool writable)
{
	int fd;

	fd = openat(dfd, name, (writable ? O_RDWR : O_RDONLY) | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	a->fd = fd;
	/*
	 * Below another sysfs root ($AS9888_SYSFS: the tests' tree) the files
	 * are plain ones. Not asked of the file system (fstatfs() wants a
	 * permission a confined daemon need not have); a truncate of a sysfs
	 * attribute would be harmless anyway
	 */
	a->plain = writable && strcmp(iio_sysfs_root(), "/sys");

	return 0;
}

void iio_attr_close(struct iio_attr *a)
{
	if (a->fd >= 0)
		close(a->fd);
	a->fd = -1;
}

int iio_attr_read(const struct iio_attr *a, char *buf, size_t size)
{
	ssize_t n;

	/*
	 * sysfs makes the value anew for a read from offset 0; a file that
	 * cannot seek (a FIFO standing in for one) is read as it comes
	 */
	n = pread(a->fd, buf, size - 1, 0);
	if (n < 0 && errno == ESPIPE)
		n = read(a->fd, buf, size - 1);
	if (n < 0)
		return -errno;
	/* a value cut short is no value: the buffer must hold it whole */
	if ((size_t)n == size - 1)
		return -EOVERFLOW;
	/* some of the IIO core's end in a NUL too (current_timestamp_clock) */
	while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == '\0'))
		n--;
	if (memchr(buf, '\0', (size_t)n))
		return -EINVAL;
	buf[n] = '\0';

	return (int)n;
}

int iio_attr_write(const struct iio_attr *a, const char *value)
{
	size_t len = strlen(value);
	ssize_t n;

	/* sysfs hands a write to the attribute whole, at any offset */
	n = pwrite(a->fd, value, len, 0);
	if (n < 0 && errno == ESPIPE)
		n = write(a->fd, value, len);
	if (n < 0)
		return -errno;
	if ((size_t)n != len)
		return -EIO;
	if (a->plain && ftruncate(a->fd, (off_t)len))
		return -errno;

	return 0;
}
