// SPDX-License-Identifier: GPL-2.0
/* One sysfs attribute read or written whole, with a message (hal_attr.h) */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal_attr.h"
#include "iio_sysfs.h"

int hal_attr_read(const char *dir, const char *name, char *buf, size_t len,
		  char *err, size_t errlen)
{
	int ret = iio_read_attr(dir, name, buf, len);

	if (ret >= 0)
		return 0;
	snprintf(err, errlen, "%s/%s: cannot read: %s", dir, name,
		 ret == -EOVERFLOW ? "longer than its buffer" :
		 ret == -EINVAL ? "holds a NUL byte" : strerror(-ret));
	return ret;
}

int hal_attr_write(const char *dir, const char *name, const char *value,
		   char *err, size_t errlen)
{
	int ret = iio_write_attr(dir, name, value);

	if (ret)
		snprintf(err, errlen, "%s/%s: writing \"%s\" failed: %s", dir, name,
			 value, strerror(-ret));
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
