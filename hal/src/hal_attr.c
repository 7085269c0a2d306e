// SPDX-License-Identifier: GPL-2.0
/* One sysfs attribute read or written whole (hal_attr.h) */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_attr.h"

static int attr_path(const char *dir, const char *name, char *path,
		     size_t len, char *err, size_t errlen)
{
	if ((size_t)snprintf(path, len, "%s/%s", dir, name) >= len) {
		snprintf(err, errlen, "%s/%s: path too long", dir, name);
		return -ENAMETOOLONG;
	}
	return 0;
}

int hal_attr_read(const char *dir, const char *name, char *buf, size_t len,
		  char *err, size_t errlen)
{
	char path[PATH_MAX];
	ssize_t n;
	int fd, ret;

	ret = attr_path(dir, name, path, sizeof(path), err, errlen);
	if (ret)
		return ret;
	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
		return ret;
	}
	n = read(fd, buf, len - 1);
	ret = n < 0 ? -errno : 0;
	close(fd);
	if (ret) {
		snprintf(err, errlen, "%s: cannot read: %s", path, strerror(-ret));
		return ret;
	}
	if ((size_t)n == len - 1) {
		snprintf(err, errlen, "%s: longer than %zu bytes", path, len - 2);
		return -EOVERFLOW;
	}
	if (memchr(buf, '\0', (size_t)n)) {
		snprintf(err, errlen, "%s: holds a NUL byte", path);
		return -EINVAL;
	}
	buf[n] = '\0';
	if (n && buf[n - 1] == '\n')
		buf[n - 1] = '\0';
	return 0;
}

int hal_attr_write(const char *dir, const char *name, const char *value,
		   char *err, size_t errlen)
{
	char path[PATH_MAX];
	size_t len = strlen(value);
	ssize_t n;
	int fd, ret;

	ret = attr_path(dir, name, path, sizeof(path), err, errlen);
	if (ret)
		return ret;
	fd = open(path, O_WRONLY | O_TRUNC | O_CLOEXEC);
	if (fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "%s: cannot open for writing: %s", path,
			 strerror(errno));
		return ret;
	}
	n = write(fd, value, len);
	ret = n < 0 ? -errno : (size_t)n != len ? -EIO : 0;
	if (close(fd) && !ret)
		ret = -errno;
	if (ret)
		snprintf(err, errlen, "%s: writing \"%s\" failed: %s", path, value,
			 strerror(-ret));
	return ret;
}

int hal_parse_double(const char *s, double *out)
{
	char *end;
	double v;

	if (!*s || *s == ' ' || *s == '\t')
		return -EINVAL;
	errno = 0;
	v = strtod(s, &end);
	if (end == s || *end || errno || !isfinite(v))
		return -EINVAL;
	*out = v;
	return 0;
}

int hal_parse_long(const char *s, long *out)
{
	char *end;
	long v;

	if (!*s || *s == ' ' || *s == '\t')
		return -EINVAL;
	errno = 0;
	v = strtol(s, &end, 10);
	if (end == s || *end || errno)
		return -EINVAL;
	*out = v;
	return 0;
}

static int attr_number(const char *dir, const char *name, double *d, long *l,
		       char *err, size_t errlen)
{
	char buf[64];
	int ret;

	ret = hal_attr_read(dir, name, buf, sizeof(buf), err, errlen);
	if (ret)
		return ret;
	ret = d ? hal_parse_double(buf, d) : hal_parse_long(buf, l);
	if (ret)
		snprintf(err, errlen, "%s/%s: \"%s\" is not %s", dir, name, buf,
			 d ? "a decimal number" : "a decimal integer");
	return ret;
}

int hal_attr_double(const char *dir, const char *name, double *out,
		    char *err, size_t errlen)
{
	return attr_number(dir, name, out, NULL, err, errlen);
}

int hal_attr_long(const char *dir, const char *name, long *out,
		  char *err, size_t errlen)
{
	return attr_number(dir, name, NULL, out, err, errlen);
}
