/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A sysfs attribute kept open for many reads and writes. In a slow system
 * (a TCG guest with KASAN: 2.5-5 ms an access) opening and closing the
 * file is most of an access's cost; a test that reads and writes the same
 * few attributes again and again opens each once.
 */
#ifndef AS9888_IIO_ATTR_H
#define AS9888_IIO_ATTR_H

#include <stdbool.h>
#include <stddef.h>

/**
 * struct iio_attr - an attribute file, open
 * @fd:		its descriptor, -1 when closed
 * @plain:	a plain file, not sysfs (below $AS9888_SYSFS: the tests'
 *		tree): a write truncates it to the value written, as sysfs
 *		replaces the value whole
 */
struct iio_attr {
	int fd;
	bool plain;
};

#define IIO_ATTR_CLOSED	((struct iio_attr){ .fd = -1 })

/*
 * Open @name below the directory @dfd (iio_dir_open(), or AT_FDCWD for a
 * path), for reading and, when @writable, writing. 0 or -errno.
 */
int iio_attr_open(struct iio_attr *a, int dfd, const char *name,
		  bool writable);

/* Close it (a closed one is left alone) */
void iio_attr_close(struct iio_attr *a);

/*
 * Its value now, from the start, without its trailing newline (and the
 * NUL some of the IIO core's attributes end in): the length, -EOVERFLOW
 * when it does not fit in @size with its newline, -EINVAL when it holds
 * a NUL byte, or -errno
 */
int iio_attr_read(const struct iio_attr *a, char *buf, size_t size);

/* Write @value whole: 0 or -errno (-EIO: written in part) */
int iio_attr_write(const struct iio_attr *a, const char *value);

#endif
