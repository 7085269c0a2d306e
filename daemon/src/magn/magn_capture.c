// SPDX-License-Identifier: GPL-2.0
/* Both devices' buffers on the shared data-ready trigger (magn_capture.h). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "chip/iio.h"
#include "chip/iio_busy.h"
#include "iio_scan.h"
#include "magn/magn_capture.h"

#define NS_PER_MS	1000000LL
#define NS_PER_S	1000000000LL
#define RATE_TEXT_(n)	#n
#define RATE_TEXT(n)	RATE_TEXT_(n)
/* Samples the kernel keeps per device: three seconds at the rate */
#define CAPTURE_LENGTH	RATE_TEXT(300)
_Static_assert(300 == 3 * MAGN_CAPTURE_RATE_HZ,
	       "CAPTURE_LENGTH is three seconds at MAGN_CAPTURE_RATE_HZ");
/* The channels taken, in this order: three axes and the timestamp */
#define CAPTURE_CHANNELS	4
#define CAPTURE_TS		3
#define CAPTURE_SAMPLE_MAX	32
/* Samples read at once per device */
#define CAPTURE_READ_SAMPLES	16
#define CAPTURE_SAVED_MAX	24
#define CAPTURE_NAME_MAX	64
#define SCAN_DIR		"scan_elements"
#define TRIGGER_ATTR		"trigger/current_trigger"
#define CLOCK_ATTR		"current_timestamp_clock"
#define DEV_ACCEL		0
#define DEV_MAGN		1
#define DEVS			2

struct saved {
	char name[IIO_PATH_MAX];
	char value[IIO_ATTR_MAX];
};

/**
 * struct capture_dev - one device's side of the capture
 * @dir:	its sysfs directory
 * @dfd:	@dir, open
 * @prefix:	its channels' prefix, "in_accel" or "in_magn"
 * @chardev:	its character device's path
 * @fd:		that, open, or -1
 * @enabled:	the capture turned its buffer on
 * @ch:		where the three axes and the timestamp sit in a sample
 * @sample_bytes: a sample's size
 * @buf:	samples read and not yet taken, @have bytes of them
 * @saved:	attributes changed, with the values to put back
 * @n_saved:	how many
 */
struct capture_dev {
	char dir[IIO_PATH_MAX];
	int dfd;
	const char *prefix;
	char chardev[IIO_PATH_MAX];
	int fd;
	bool enabled;
	struct iio_scan_channel ch[CAPTURE_CHANNELS];
	unsigned int sample_bytes;
	uint8_t buf[CAPTURE_READ_SAMPLES * CAPTURE_SAMPLE_MAX];
	size_t have;
	struct saved saved[CAPTURE_SAVED_MAX];
	unsigned int n_saved;
};

struct magn_capture {
	struct capture_dev dev[DEVS];
	char trigger[CAPTURE_NAME_MAX];
};

static int64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);

	return (int64_t)ts.tv_sec * NS_PER_S + ts.tv_nsec;
}

/* Write @value to @name, saving what it held first (put back at close) */
static int change(struct capture_dev *d, const char *name, const char *value)
{
	struct saved *s;
	int ret;

	if (d->n_saved == CAPTURE_SAVED_MAX)
		return -ENOSPC;
	s = &d->saved[d->n_saved];
	if (snprintf(s->name, sizeof(s->name), "%s", name) >= (int)sizeof(s->name))
		return -ENAMETOOLONG;
	ret = iio_read_attr_at(d->dfd, name, s->value, sizeof(s->value));
	if (ret < 0)
		return ret;
	if (!strcmp(s->value, value))
		return 0;
	ret = iio_write_attr_at(d->dfd, name, value);
	if (!ret)
		d->n_saved++;

	return ret;
}

/* The attributes back as found, the last changed first */
static void put_back(struct capture_dev *d)
{
	while (d->n_saved) {
		struct saved *s = &d->saved[--d->n_saved];

		/*
		 * An empty value (no trigger) as a newline: sysfs never calls
		 * the attribute's store for a write of nothing
		 */
		iio_write_attr_at(d->dfd, s->name, *s->value ? s->value : "\n");
	}
}

/* Is @en ("in_magn_x_en") one of the channels the capture takes? */
static bool wanted(const struct capture_dev *d, const char *en)
{
	size_t n = strlen(d->prefix);

	if (!strcmp(en, "in_timestamp_en"))
		return true;

	return !strncmp(en, d->prefix, n) && en[n] == '_' &&
	       strchr("xyz", en[n + 1]) && !strcmp(en + n + 2, "_en");
}

/* The three axes and the timestamp on, every other channel off */
static int scan_enable(struct capture_dev *d, char *why, size_t whylen)
{
	char name[IIO_PATH_MAX];
	struct dirent *de;
	DIR *dir;
	int fd, ret = 0;

	fd = openat(d->dfd, SCAN_DIR, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	dir = fd < 0 ? NULL : fdopendir(fd);
	if (!dir) {
		ret = -errno;
		if (fd >= 0)
			close(fd);
		snprintf(why, whylen, "%s/%s: %s (no buffer)", d->dir, SCAN_DIR,
			 strerror(-ret));
		return ret;
	}
	while (!ret && (de = readdir(dir))) {
		size_t len = strlen(de->d_name);

		if (len < 4 || strcmp(de->d_name + len - 3, "_en"))
			continue;
		snprintf(name, sizeof(name), "%s/%s", SCAN_DIR, de->d_name);
		ret = change(d, name, wanted(d, de->d_name) ? "1" : "0");
		if (ret)
			snprintf(why, whylen, "%s/%s: %s", d->dir, name,
				 strerror(-ret));
	}
	closedir(dir);

	return ret;
}

/* Where the axes and the timestamp sit in a sample, from _index and _type */
static int layout(struct capture_dev *d, char *why, size_t whylen)
{
	char name[IIO_PATH_MAX], val[IIO_ATTR_MAX];
	unsigned int i;
	int ret;

	for (i = 0; i < CAPTURE_CHANNELS; i++) {
		struct iio_scan_channel *c = &d->ch[i];
		char chan[CAPTURE_NAME_MAX];

		if (i == CAPTURE_TS)
			snprintf(chan, sizeof(chan), "in_timestamp");
		else
			snprintf(chan, sizeof(chan), "%s_%c", d->prefix, "xyz"[i]);
		snprintf(name, sizeof(name), "%s/%s_index", SCAN_DIR, chan);
		ret = iio_read_attr_at(d->dfd, name, val, sizeof(val));
		if (ret > 0 && sscanf(val, "%u", &c->index) == 1) {
			snprintf(name, sizeof(name), "%s/%s_type", SCAN_DIR, chan);
			ret = iio_read_attr_at(d->dfd, name, val, sizeof(val));
			if (ret > 0)
				ret = iio_scan_parse_type(val, c);
		} else {
			ret = ret < 0 ? ret : -EINVAL;
		}
		if (ret) {
			snprintf(why, whylen, "%s/%s: %s", d->dir, name,
				 strerror(-ret));
			return ret;
		}
	}
	ret = iio_scan_layout(d->ch, CAPTURE_CHANNELS);
	if (ret > CAPTURE_SAMPLE_MAX)
		ret = -E2BIG;
	if (ret < 0) {
		snprintf(why, whylen, "%s: the scan elements' layout: %s",
			 d->dir, strerror(-ret));
		return ret;
	}
	d->sample_bytes = (unsigned int)ret;

	return 0;
}

/* The buffer free (not enabled by another program) and set up */
static int dev_setup(struct magn_capture *c, struct capture_dev *d,
		     char *why, size_t whylen)
{
	char val[IIO_ATTR_MAX];
	int ret;

	ret = iio_read_attr_at(d->dfd, "buffer/enable", val, sizeof(val));
	if (ret < 0) {
		snprintf(why, whylen, "%s/buffer/enable: %s (no buffer)", d->dir,
			 strerror(-ret));
		return ret;
	}
	if (strcmp(val, "0")) {
		snprintf(why, whylen, "%s: another program has the buffer enabled (a HAL, iio-sensor-proxy)",
			 d->dir);
		return -EBUSY;
	}
	ret = scan_enable(d, why, whylen);
	if (!ret)
		ret = layout(d, why, whylen);
	if (ret)
		return ret;
	ret = change(d, TRIGGER_ATTR, c->trigger);
	if (ret) {
		snprintf(why, whylen, "%s/%s: %s cannot be set (%s): no data-ready interrupt wired?",
			 d->dir, TRIGGER_ATTR, c->trigger, strerror(-ret));
		return ret;
	}
	ret = change(d, "sampling_frequency", RATE_TEXT(MAGN_CAPTURE_RATE_HZ));
	if (ret) {
		snprintf(why, whylen, "%s/sampling_frequency %d Hz: %s", d->dir,
			 MAGN_CAPTURE_RATE_HZ, strerror(-ret));
		return ret;
	}
	ret = change(d, "buffer/length", CAPTURE_LENGTH);
	/* both timestamps on one clock, where the kernel lets it be chosen */
	if (!ret && !faccessat(d->dfd, CLOCK_ATTR, F_OK, 0))
		ret = change(d, CLOCK_ATTR, "monotonic");
	if (ret)
		snprintf(why, whylen, "%s: buffer set-up: %s", d->dir,
			 strerror(-ret));

	return ret;
}

/* Its character device open and its buffer on */
static int dev_start(struct capture_dev *d, char *why, size_t whylen)
{
	char who[IIO_ERR_LEN];
	int ret;

	d->fd = open(d->chardev, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (d->fd < 0 && errno == EBUSY) {
		if (iio_chardev_holders("/proc", d->chardev, who, sizeof(who)) <= 0)
			snprintf(who, sizeof(who), "no process this user can see");
		snprintf(why, whylen, "%s is open in another program (%s)",
			 d->chardev, who);
		return -EBUSY;
	}
	if (d->fd < 0) {
		ret = -errno;
		snprintf(why, whylen, "%s: %s", d->chardev, strerror(-ret));
		return ret;
	}
	ret = iio_write_attr_at(d->dfd, "buffer/enable", "1");
	if (ret) {
		snprintf(why, whylen, "%s/buffer/enable: %s%s", d->dir,
			 strerror(-ret), ret == -EBUSY ?
			 " (the trigger takes one consumer only? CONFIG_IIO_CONSUMERS_PER_TRIGGER)" : "");
		return ret;
	}
	d->enabled = true;

	return 0;
}

static void dev_stop(struct capture_dev *d)
{
	if (d->enabled)
		iio_write_attr_at(d->dfd, "buffer/enable", "0");
	d->enabled = false;
	if (d->fd >= 0)
		close(d->fd);
	d->fd = -1;
}

int magn_capture_open(const char *accel_dir, const char *magn_dir,
		      struct magn_capture **out, char *why, size_t whylen)
{
	const char *dirs[DEVS] = { [DEV_ACCEL] = accel_dir, [DEV_MAGN] = magn_dir };
	const char *base = strrchr(accel_dir, '/');
	struct magn_capture *c;
	int i, ret = 0;

	if (!base || strncmp(base + 1, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX))) {
		snprintf(why, whylen, "%s is not an IIO device's directory", accel_dir);
		return -EINVAL;
	}
	c = calloc(1, sizeof(*c));
	if (!c) {
		snprintf(why, whylen, "out of memory");
		return -ENOMEM;
	}
	snprintf(c->trigger, sizeof(c->trigger), "%s-dev%s", IIO_CHIP_NAME,
		 base + 1 + strlen(IIO_DEVICE_PREFIX));
	for (i = 0; i < DEVS; i++) {
		struct capture_dev *d = &c->dev[i];
		const char *name = strrchr(dirs[i], '/');

		d->fd = -1;
		d->prefix = i == DEV_MAGN ? "in_magn" : "in_accel";
		snprintf(d->dir, sizeof(d->dir), "%s", dirs[i]);
		snprintf(d->chardev, sizeof(d->chardev), "%s/%s", iio_dev_root(),
			 name ? name + 1 : dirs[i]);
		d->dfd = iio_dir_open(dirs[i]);
	}
	for (i = 0; !ret && i < DEVS; i++) {
		ret = c->dev[i].dfd;
		if (ret < 0)
			snprintf(why, whylen, "%s: %s", dirs[i], strerror(-ret));
		else
			ret = dev_setup(c, &c->dev[i], why, whylen);
	}
	/* the magnetometer first: an accelerometer sample has its partner */
	if (!ret)
		ret = dev_start(&c->dev[DEV_MAGN], why, whylen);
	if (!ret)
		ret = dev_start(&c->dev[DEV_ACCEL], why, whylen);
	if (ret) {
		magn_capture_close(c);
		return ret;
	}
	*out = c;

	return 0;
}

/* Read what @d's buffer holds; -EPIPE at its end, -errno */
static int fill(struct capture_dev *d, char *why, size_t whylen)
{
	ssize_t got = read(d->fd, d->buf + d->have, sizeof(d->buf) - d->have);

	if (got > 0) {
		d->have += (size_t)got;
		return 0;
	}
	if (got < 0 && (errno == EAGAIN || errno == EINTR))
		return 0;
	snprintf(why, whylen, "%s: %s", d->chardev,
		 got ? strerror(errno) : "the capture ended");

	return got ? -errno : -EPIPE;
}

static bool has_sample(const struct capture_dev *d)
{
	return d->have >= d->sample_bytes;
}

static int64_t head_ts(const struct capture_dev *d)
{
	return iio_scan_value64(&d->ch[CAPTURE_TS], d->buf);
}

static void drop_head(struct capture_dev *d)
{
	d->have -= d->sample_bytes;
	memmove(d->buf, d->buf + d->sample_bytes, d->have);
}

/* Its buffer turned off under the capture (another program did so)? */
static bool turned_off(const struct capture_dev *d)
{
	char val[IIO_ATTR_MAX];

	return iio_read_attr_at(d->dfd, "buffer/enable", val, sizeof(val)) > 0 &&
	       !strcmp(val, "0");
}

/* Both devices' next samples there, waiting at most until @deadline */
static int wait_both(struct magn_capture *c, int64_t deadline, char *why,
		     size_t whylen)
{
	while (!has_sample(&c->dev[DEV_ACCEL]) || !has_sample(&c->dev[DEV_MAGN])) {
		struct pollfd pfd[DEVS];
		int64_t left = deadline - now_ns();
		int i, n = 0, ret;

		if (left <= 0) {
			for (i = 0; i < DEVS; i++)
				if (turned_off(&c->dev[i])) {
					snprintf(why, whylen, "%s: another program turned the buffer off",
						 c->dev[i].dir);
					return -EPIPE;
				}
			snprintf(why, whylen, "no pair of samples on %s for %d ms",
				 c->trigger, MAGN_CAPTURE_STALL_MS);
			return -ETIMEDOUT;
		}
		for (i = 0; i < DEVS; i++)
			if (!has_sample(&c->dev[i]))
				pfd[n++] = (struct pollfd){ .fd = c->dev[i].fd,
							    .events = POLLIN };
		if (poll(pfd, (nfds_t)n, (int)(left / NS_PER_MS) + 1) < 0 &&
		    errno != EINTR) {
			ret = -errno;
			snprintf(why, whylen, "poll: %s", strerror(-ret));
			return ret;
		}
		for (i = 0; i < DEVS; i++) {
			if (has_sample(&c->dev[i]))
				continue;
			ret = fill(&c->dev[i], why, whylen);
			if (ret)
				return ret;
		}
	}

	return 0;
}

int magn_capture_next(struct magn_capture *c, struct magn_capture_pair *p,
		      char *why, size_t whylen)
{
	const int64_t tolerance = NS_PER_S / MAGN_CAPTURE_RATE_HZ / 4;
	struct capture_dev *a = &c->dev[DEV_ACCEL], *m = &c->dev[DEV_MAGN];
	int64_t deadline = now_ns() + MAGN_CAPTURE_STALL_MS * NS_PER_MS;
	int axis, ret;

	for (;;) {
		int64_t ta, tm;

		ret = wait_both(c, deadline, why, whylen);
		if (ret)
			return ret;
		ta = head_ts(a);
		tm = head_ts(m);
		if (ta - tm <= tolerance && tm - ta <= tolerance)
			break;
		/* the older one has no partner: the other device's is later */
		drop_head(ta < tm ? a : m);
	}
	for (axis = 0; axis < AS9888_AXES; axis++) {
		p->magn[axis] = iio_scan_value(&m->ch[axis], m->buf);
		p->accel[axis] = iio_scan_value(&a->ch[axis], a->buf);
	}
	p->t_magn = head_ts(m);
	p->t_accel = head_ts(a);
	drop_head(a);
	drop_head(m);

	return 0;
}

const char *magn_capture_trigger(const struct magn_capture *c)
{
	return c->trigger;
}

void magn_capture_close(struct magn_capture *c)
{
	int i;

	if (!c)
		return;
	for (i = 0; i < DEVS; i++)
		dev_stop(&c->dev[i]);
	for (i = 0; i < DEVS; i++) {
		if (c->dev[i].dfd < 0)
			continue;
		put_back(&c->dev[i]);
		close(c->dev[i].dfd);
	}
	free(c);
}
