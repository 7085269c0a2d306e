// SPDX-License-Identifier: GPL-2.0
/*
 * Who holds an IIO device's character device, and waiting for its buffer
 * to be free (iio_busy.h).
 */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "chip/iio.h"
#include "chip/iio_busy.h"

#define PROC_COMM_MAX	64
#define ELLIPSIS	"..."

static bool all_digits(const char *s)
{
	if (!*s)
		return false;
	for (; *s; s++)
		if (!isdigit((unsigned char)*s))
			return false;

	return true;
}

/* Whether process directory @pid_dir has @chardev open */
static bool holds(const char *pid_dir, const char *chardev)
{
	char fd_dir[IIO_PATH_MAX], link[IIO_PATH_MAX], target[IIO_PATH_MAX];
	struct dirent *de;
	bool found = false;
	DIR *dir;

	if (snprintf(fd_dir, sizeof(fd_dir), "%s/fd", pid_dir) >= (int)sizeof(fd_dir))
		return false;
	dir = opendir(fd_dir);
	if (!dir)
		return false;	/* gone, or not ours to look into */
	while (!found && (de = readdir(dir))) {
		ssize_t n;

		if (!all_digits(de->d_name) ||
		    snprintf(link, sizeof(link), "%s/%s", fd_dir, de->d_name) >=
		    (int)sizeof(link))
			continue;
		n = readlink(link, target, sizeof(target) - 1);
		if (n < 0)
			continue;
		target[n] = '\0';
		found = !strcmp(target, chardev);
	}
	closedir(dir);

	return found;
}

/* The command name of @pid_dir, or "?" */
static void comm_of(const char *pid_dir, char *comm, size_t size)
{
	char path[IIO_PATH_MAX];
	FILE *f;

	snprintf(comm, size, "?");
	if (snprintf(path, sizeof(path), "%s/comm", pid_dir) >= (int)sizeof(path))
		return;
	f = fopen(path, "r");
	if (!f)
		return;
	if (fgets(comm, (int)size, f))
		comm[strcspn(comm, "\n")] = '\0';
	else
		snprintf(comm, size, "?");
	fclose(f);
}

/* Append @item to @out, or "..." once it no longer fits */
static void append(char *out, size_t size, const char *item, bool *cut)
{
	size_t len = strlen(out);
	const char *sep = len ? ", " : "";

	if (*cut)
		return;
	if (len + strlen(sep) + strlen(item) + strlen(ELLIPSIS) < size) {
		snprintf(out + len, size - len, "%s%s", sep, item);
		return;
	}
	*cut = true;
	if (len + strlen(ELLIPSIS) < size)
		snprintf(out + len, size - len, "%s", ELLIPSIS);
}

int iio_chardev_holders(const char *proc, const char *chardev, char *out,
			size_t size)
{
	struct dirent *de;
	bool cut = false;
	int found = 0;
	DIR *dir;

	if (size)
		out[0] = '\0';
	dir = opendir(proc);
	if (!dir)
		return -errno;
	while ((de = readdir(dir))) {
		char pid_dir[IIO_PATH_MAX], comm[PROC_COMM_MAX];
		char item[PROC_COMM_MAX + sizeof(" (pid )") + NAME_MAX];

		if (!all_digits(de->d_name) ||
		    snprintf(pid_dir, sizeof(pid_dir), "%s/%s", proc, de->d_name) >=
		    (int)sizeof(pid_dir) || !holds(pid_dir, chardev))
			continue;
		comm_of(pid_dir, comm, sizeof(comm));
		snprintf(item, sizeof(item), "%s (pid %s)", comm, de->d_name);
		if (size)
			append(out, size, item, &cut);
		found++;
	}
	closedir(dir);

	return found;
}

static uint64_t monotonic_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);

	return (uint64_t)ts.tv_sec * 1000 + (uint64_t)ts.tv_nsec / 1000000;
}

int iio_wait_enable_off(const struct iio_attr *enable, uint32_t timeout_ms,
			uint32_t poll_ms)
{
	uint64_t end = monotonic_ms() + timeout_ms;
	char val[IIO_ATTR_MAX];

	for (;;) {
		struct timespec nap = {
			.tv_sec = poll_ms / 1000,
			.tv_nsec = (long)(poll_ms % 1000) * 1000000,
		};
		int ret = iio_attr_read(enable, val, sizeof(val));

		if (ret < 0)
			return ret;
		if (!strcmp(val, "0"))
			return 0;
		if (monotonic_ms() >= end)
			return -EBUSY;
		while (nanosleep(&nap, &nap) && errno == EINTR)
			;
	}
}

int iio_wait_buffer_free(const char *dir, uint32_t timeout_ms,
			 uint32_t poll_ms)
{
	char path[IIO_PATH_MAX];
	struct iio_attr enable;
	int ret;

	snprintf(path, sizeof(path), "%s/buffer/enable", dir);
	ret = iio_attr_open(&enable, AT_FDCWD, path, false);
	if (ret)
		return ret;
	ret = iio_wait_enable_off(&enable, timeout_ms, poll_ms);
	iio_attr_close(&enable);

	return ret;
}
