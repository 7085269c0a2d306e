/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The IIO sysfs ABI as files: an attribute read or written whole, an IIO
 * device's sibling below its bus device and a trigger found by name. The
 * daemon and the sensors HAL both go through these.
 */
#ifndef AS9888_IIO_SYSFS_H
#define AS9888_IIO_SYSFS_H

#include <stdbool.h>
#include <stddef.h>

#define IIO_PATH_MAX	512
#define IIO_DEVICE_PREFIX	"iio:device"
#define IIO_TRIGGER_PREFIX	"trigger"

/* @entry names an IIO device ("iio:deviceN") */
bool iio_is_device(const char *entry);

/*
 * A sysfs attribute @name below @dir: read without its trailing newline
 * (returns the length) or written whole (returns 0); -errno on failure,
 * as iio_attr_read() and iio_attr_write() say.
 */
int iio_read_attr(const char *dir, const char *name, char *buf, size_t size);
int iio_write_attr(const char *dir, const char *name, const char *value);

/*
 * The same below a directory opened once with iio_dir_open() (an O_PATH
 * descriptor, or -errno): each access then resolves @name alone, not the
 * directory's path through its bus link again, which costs most of an
 * access to a sysfs attribute on a slow system
 */
int iio_dir_open(const char *dir);
int iio_read_attr_at(int dfd, const char *name, char *buf, size_t size);
int iio_write_attr_at(int dfd, const char *name, const char *value);

/*
 * The IIO device named @name beside the one at @dir: the sibling
 * iio:deviceM below the bus device that holds both (@dir/.., where the bus
 * link /sys/bus/iio/devices/iio:deviceN leads). Its directory goes into
 * @out, named beside @dir (/sys/bus/iio/devices/iio:deviceM for a bus
 * link), or as @dir/../iio:deviceM while its bus link is not there yet.
 * When there is none, @parent, when not NULL, receives the bus device's
 * directory, for messages. Returns 0, -ENOENT when there is no such
 * device, or -errno when @dir cannot be resolved.
 */
int iio_find_sibling(const char *dir, const char *name, char *out,
		     size_t size, char *parent, size_t parent_size);

/*
 * A trigger named @name is registered below @sysfs (the sysfs root):
 * 0, -ENOENT when none is, or -errno when the IIO bus cannot be listed
 */
int iio_find_trigger(const char *sysfs, const char *name);

#endif
