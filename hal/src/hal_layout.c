// SPDX-License-Identifier: GPL-2.0
/* One device's three-axis channels from its buffer (hal_layout.h) */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hal_attr.h"
#include "hal_layout.h"
#include "iio_mount.h"

const char *const hal_axis_names[3] = { "x", "y", "z" };

static int read_scan_element(const char *dir, const char *chan,
			     struct iio_scan_channel *c, char *err, size_t errlen)
{
	char name[96], text[64];
	long index;
	int ret;

	snprintf(name, sizeof(name), "scan_elements/%s_index", chan);
	ret = hal_attr_long(dir, name, &index, err, errlen);
	if (ret)
		return ret;
	if (index < 0 || index > 255) {
		snprintf(err, errlen, "%s/%s: %ld is no scan index", dir, name, index);
		return -EINVAL;
	}
	c->index = (unsigned int)index;
	snprintf(name, sizeof(name), "scan_elements/%s_type", chan);
	ret = hal_attr_read(dir, name, text, sizeof(text), err, errlen);
	if (ret)
		return ret;
	if (iio_scan_parse_type(text, c)) {
		snprintf(err, errlen, "%s/%s: \"%s\" is no IIO scan type ([be|le]:[s|u]BITS/STORAGE>>SHIFT)",
			 dir, name, text);
		return -EINVAL;
	}
	return 0;
}

/* in_<type>_<axis>_<what>, else in_<type>_<what>; @fallback when neither is there */
static int read_axis_number(const char *dir, const char *type, const char *axis,
			    const char *what, double fallback, double *out,
			    char *err, size_t errlen)
{
	char name[64];
	int ret;

	snprintf(name, sizeof(name), "in_%s_%s_%s", type, axis, what);
	ret = hal_attr_double(dir, name, out, err, errlen);
	if (ret != -ENOENT)
		return ret;
	snprintf(name, sizeof(name), "in_%s_%s", type, what);
	ret = hal_attr_double(dir, name, out, err, errlen);
	if (ret == -ENOENT && !isnan(fallback)) {
		*out = fallback;
		return 0;
	}
	return ret;
}

static int read_mount(const char *dir, const char *type, double m[3][3],
		      char *err, size_t errlen)
{
	static const double identity[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
	char name[64], text[IIO_MOUNT_TEXT_MAX];
	int ret;

	snprintf(name, sizeof(name), "in_%s_mount_matrix", type);
	ret = hal_attr_read(dir, name, text, sizeof(text), err, errlen);
	if (ret == -ENOENT) {
		/* no mount-matrix in firmware: the sensor frame is the device's */
		memcpy(m, identity, sizeof(identity));
		return 0;
	}
	if (ret)
		return ret;
	if (iio_mount_parse(text, m)) {
		snprintf(err, errlen, "%s/%s: \"%s\" is no mount matrix (\"a, b, c; d, e, f; g, h, i\")",
			 dir, name, text);
		return -EINVAL;
	}
	return 0;
}

int hal_layout_read(const char *dir, const char *type, double unit,
		    struct hal_layout *l, char *err, size_t errlen)
{
	struct hal_layout n = { .unit = unit };
	char chan[32];
	int i, ret, bytes;

	for (i = 0; i < 3; i++) {
		snprintf(chan, sizeof(chan), "in_%s_%s", type, hal_axis_names[i]);
		ret = read_scan_element(dir, chan, &n.chan[i], err, errlen);
		if (!ret)
			ret = read_axis_number(dir, type, hal_axis_names[i], "scale",
					       NAN, &n.scale[i], err, errlen);
		if (!ret)
			ret = read_axis_number(dir, type, hal_axis_names[i], "offset",
					       0, &n.offset[i], err, errlen);
		if (ret)
			return ret;
		if (n.chan[i].realbits > 32) {
			snprintf(err, errlen, "%s: %s has %u bits: more than an axis can have",
				 dir, chan, n.chan[i].realbits);
			return -EINVAL;
		}
		if (n.scale[i] == 0) {
			snprintf(err, errlen, "%s: %s's scale is 0", dir, chan);
			return -EINVAL;
		}
	}
	ret = read_scan_element(dir, "in_timestamp", &n.chan[3], err, errlen);
	if (ret)
		return ret;
	if (n.chan[3].bytes != 8 || n.chan[3].realbits != 64) {
		snprintf(err, errlen, "%s: in_timestamp is not 64 bits", dir);
		return -EINVAL;
	}
	ret = read_mount(dir, type, n.mount, err, errlen);
	if (ret)
		return ret;
	bytes = iio_scan_layout(n.chan, 4);
	if (bytes < 0) {
		snprintf(err, errlen, "%s: two of the %s scan elements share an index",
			 dir, type);
		return -EINVAL;
	}
	n.sample_bytes = (unsigned int)bytes;
	*l = n;
	return 0;
}

bool hal_layout_decode(const struct hal_layout *l, const uint8_t *sample,
		       int32_t raw[3], double sensor[3], int64_t *ts)
{
	bool saturated = false;
	int i;

	for (i = 0; i < 3; i++) {
		const struct iio_scan_channel *c = &l->chan[i];
		int64_t max = c->is_signed ? (INT64_C(1) << (c->realbits - 1)) - 1 :
			      (INT64_C(1) << c->realbits) - 1;
		int64_t min = c->is_signed ? -max - 1 : 0;

		raw[i] = iio_scan_value(c, sample);
		if (c->is_signed && (raw[i] == min || raw[i] == max))
			saturated = true;
		sensor[i] = (raw[i] + l->offset[i]) * l->scale[i] * l->unit;
	}
	*ts = iio_scan_value64(&l->chan[3], sample);
	return saturated;
}
