// SPDX-License-Identifier: GPL-2.0
/* One IIO device's buffer, driven by the HAL (hal_stream.h) */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_attr.h"
#include "hal_stream.h"

int hal_parse_rates(const char *s, long *rates, unsigned int max)
{
	unsigned int n = 0;
	char *end;
	long v;

	while (*s) {
		if (*s < '0' || *s > '9' || n == max)
			return -EINVAL;
		errno = 0;
		v = strtol(s, &end, 10);
		if (errno || v < 1 || (n && v <= rates[n - 1]) ||
		    (*end && *end != ' '))
			return -EINVAL;
		rates[n++] = v;
		s = *end ? end + 1 : end;
	}
	return n ? (int)n : -EINVAL;
}

int hal_stream_init(struct hal_stream *s, const char *dir, const char *node,
		    const char *type, double unit, char *err, size_t errlen)
{
	char text[256];
	int ret;

	memset(s, 0, sizeof(*s));
	s->fd = -1;
	s->type = type;
	s->unit = unit;
	if ((size_t)snprintf(s->dir, sizeof(s->dir), "%s", dir) >= sizeof(s->dir) ||
	    (size_t)snprintf(s->node, sizeof(s->node), "%s", node) >= sizeof(s->node)) {
		snprintf(err, errlen, "%s: path too long", dir);
		return -ENAMETOOLONG;
	}
	ret = hal_attr_read(dir, "sampling_frequency_available", text, sizeof(text),
			    err, errlen);
	if (ret == -ENOENT)
		return 0;	/* no data-ready interrupt: the trigger sets the rate */
	if (ret)
		return ret;
	ret = hal_parse_rates(text, s->rates, sizeof(s->rates) / sizeof(s->rates[0]));
	if (ret < 0) {
		snprintf(err, errlen, "%s/sampling_frequency_available: \"%s\" is no list of whole rates, ascending",
			 dir, text);
		return ret;
	}
	s->nrates = (unsigned int)ret;
	return 0;
}

long hal_stream_pick_rate(const struct hal_stream *s, double hz)
{
	unsigned int i;

	if (!s->nrates)
		return 0;
	for (i = 0; i < s->nrates; i++)
		if (s->rates[i] >= hz * 0.999)
			return s->rates[i];
	return s->rates[s->nrates - 1];
}

/* Our channel: the axes of our type and the timestamp */
static bool scan_element_ours(const struct hal_stream *s, const char *en)
{
	char want[48];
	int i;

	if (!strcmp(en, "in_timestamp_en"))
		return true;
	for (i = 0; i < 3; i++) {
		snprintf(want, sizeof(want), "in_%s_%s_en", s->type, hal_axis_names[i]);
		if (!strcmp(en, want))
			return true;
	}
	return false;
}

/* Exactly our scan elements enabled */
static int set_scan(const struct hal_stream *s, char *err, size_t errlen)
{
	char path[300], name[320], text[8];
	struct dirent *e;
	size_t len;
	DIR *d;
	int ret = 0;

	snprintf(path, sizeof(path), "%s/scan_elements", s->dir);
	d = opendir(path);
	if (!d) {
		ret = -errno;
		snprintf(err, errlen, "%s: cannot list: %s", path, strerror(errno));
		return ret;
	}
	while (!ret && (e = readdir(d))) {
		len = strlen(e->d_name);
		if (len < 4 || strcmp(e->d_name + len - 3, "_en"))
			continue;
		snprintf(name, sizeof(name), "scan_elements/%s", e->d_name);
		ret = hal_attr_read(s->dir, name, text, sizeof(text), err, errlen);
		if (!ret && strcmp(text, scan_element_ours(s, e->d_name) ? "1" : "0"))
			ret = hal_attr_write(s->dir, name,
					     scan_element_ours(s, e->d_name) ? "1" : "0",
					     err, errlen);
	}
	closedir(d);
	return ret;
}

static int write_long(const struct hal_stream *s, const char *name, long v,
		      char *err, size_t errlen)
{
	char text[24];

	snprintf(text, sizeof(text), "%ld", v);
	return hal_attr_write(s->dir, name, text, err, errlen);
}

int hal_stream_set_rate(struct hal_stream *s, long hz, char *err, size_t errlen)
{
	int ret;

	if (!hz || hz == s->hz)
		return 0;
	ret = write_long(s, "sampling_frequency", hz, err, errlen);
	if (!ret)
		s->hz = hz;
	return ret;
}

int hal_stream_start(struct hal_stream *s, const char *trigger, long hz,
		     char *err, size_t errlen)
{
	int ret;

	/* a buffer left on (by this HAL before a restart) is taken over */
	ret = hal_attr_write(s->dir, "buffer/enable", "0", err, errlen);
	if (!ret)
		ret = set_scan(s, err, errlen);
	if (!ret)
		ret = hal_attr_write(s->dir, "current_timestamp_clock", "boottime",
				     err, errlen);
	if (!ret && *trigger)
		ret = hal_attr_write(s->dir, "trigger/current_trigger", trigger,
				     err, errlen);
	s->hz = 0;
	if (!ret)
		ret = hal_stream_set_rate(s, hz, err, errlen);
	if (!ret)
		ret = write_long(s, "buffer/length", HAL_STREAM_LENGTH, err, errlen);
	/* every sample wakes the reader: the queueing is the HAL's */
	if (!ret)
		ret = hal_attr_write(s->dir, "buffer/watermark", "1", err, errlen);
	if (!ret)
		ret = hal_layout_read(s->dir, s->type, s->unit, &s->layout, err, errlen);
	if (!ret && s->layout.sample_bytes > 64) {
		snprintf(err, errlen, "%s: a sample of %u bytes is more than 64",
			 s->dir, s->layout.sample_bytes);
		ret = -EINVAL;
	}
	if (!ret) {
		s->fd = open(s->node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
		if (s->fd < 0) {
			ret = -errno;
			snprintf(err, errlen, "%s: cannot open: %s", s->node,
				 strerror(errno));
		}
	}
	if (!ret)
		ret = hal_attr_write(s->dir, "buffer/enable", "1", err, errlen);
	if (ret)
		hal_stream_stop(s);
	return ret;
}

void hal_stream_stop(struct hal_stream *s)
{
	char ignored[8];

	if (s->fd < 0)
		return;
	hal_attr_write(s->dir, "buffer/enable", "0", ignored, sizeof(ignored));
	close(s->fd);
	s->fd = -1;
}

int hal_stream_read(struct hal_stream *s, uint8_t *buf, size_t len)
{
	size_t want = (size_t)s->layout.sample_bytes * HAL_STREAM_BATCH;
	ssize_t n;

	if (s->fd < 0 || !s->layout.sample_bytes)
		return 0;
	if (want > len)
		want = len / s->layout.sample_bytes * s->layout.sample_bytes;
	n = read(s->fd, buf, want);
	if (n < 0)
		return errno == EAGAIN || errno == EINTR ? 0 : -errno;
	return (int)((size_t)n / s->layout.sample_bytes);
}
