// SPDX-License-Identifier: GPL-2.0
/*
 * The HAL core (as9888_hal.h): the sensors, the framework's calls, and the
 * reader thread that reads both devices' buffers. activate() and batch()
 * set a buffer up or stop it on the caller's thread (the framework's,
 * which may block), so that a device already running keeps flowing while
 * the other one's sysfs writes are made.
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "as9888_hal.h"
#include "as9888_magn.h"
#include "hal_attr.h"
#include "hal_feed.h"
#include "hal_find.h"
#include "hal_queue.h"
#include "hal_stream.h"
#include "iio_mount.h"

#define NSEC_PER_SEC	INT64_C(1000000000)
#define NSEC_PER_MSEC	INT64_C(1000000)
/* The events posted at once, at most */
#define OUT_EVENTS	256
/* How often the record is looked at for a new calibration */
#define RECORD_CHECK_NS	NSEC_PER_SEC
/* An accelerometer reading this recent goes with a magnetometer sample */
#define ACCEL_FRESH_NS	NSEC_PER_SEC
/* The Android units' factor: gauss to uT */
#define UT_PER_GAUSS	100.0
#define STANDARD_GRAVITY 9.80665

/**
 * struct sensor - one sensor's state
 * @active:	activated by the framework
 * @period_ns:	the sampling period asked (batch)
 * @latency_ns:	the max report latency asked
 * @next_due:	the timestamp the next delivered sample should have
 * @flushes:	flush-complete events owed
 * @batch_since: when the oldest queued event was queued (CLOCK_BOOTTIME)
 * @queue:	the events held back for @latency_ns
 */
struct sensor {
	bool active;
	int64_t period_ns;
	int64_t latency_ns;
	int64_t next_due;
	unsigned int flushes;
	int64_t batch_since;
	struct hal_queue queue;
};

/*
 * Locking: @config serializes the framework's activate() and batch()
 * (and close()), which set the buffers up on the caller's thread: the
 * sysfs writes of a buffer's start (enable, scan elements, clock, trigger,
 * rate, length, watermark; slow on a loaded or emulated machine) and stop
 * are made with @lock released, on a copy of the stream, so the reader
 * goes on delivering the running device's samples meanwhile. @lock guards
 * everything else. A started stream is handed to the reader (copied in,
 * its fd set) under @lock; a stream is taken from it (fd set to -1) under
 * @lock, and its descriptor closed only once the reader is out of the
 * poll() that may watch it (@polling, @polls). Each such hand-in and
 * take-out bumps the stream's generation (@gen): the reader drops the lock
 * after a poll() (to post), so a stream stopped and started meanwhile may
 * have the old one's descriptor number, and what poll() said is acted on
 * only for the generation it watched. The reader itself makes no sysfs
 * write but a gone device's buffer stop. Order: @config, then @lock.
 */
struct as9888_hal {
	struct as9888_hal_config cfg;
	struct hal_devices devs;
	struct hal_stream accel;
	struct hal_stream magn;
	struct as9888_sensor_info info[AS9888_SENSOR_COUNT];
	struct sensor sensor[AS9888_SENSOR_COUNT];
	as9888_hal_post_fn post;
	void *ctx;

	pthread_mutex_t config;
	pthread_mutex_t lock;
	pthread_cond_t polled;		/* the reader came back from a poll() */
	pthread_t reader;
	int wake[2];
	bool stop;
	bool polling;			/* the reader is in poll() */
	unsigned long polls;		/* the poll()s it came back from */
	unsigned long gen[2];		/* each stream's hand-ins and take-outs */
	bool record_due;		/* the magnetometer started: read the record */
	char err[256];

	/* the reader's alone (@prev_ts also reset by a start, under @lock) */
	struct as9888_event out[OUT_EVENTS];
	size_t nout;
	int64_t prev_ts[2];		/* each device's previous sample */
	int32_t accel_raw[3];
	int64_t accel_raw_at;		/* CLOCK_BOOTTIME; 0: none */
	struct as9888_magn_calibration cal;
	bool have_cal;
	struct stat record_st;
	int64_t record_checked;
	struct hal_feed *feed;
};

static int64_t now_ns(void)
{
	struct timespec t;

	clock_gettime(CLOCK_BOOTTIME, &t);
	return t.tv_sec * NSEC_PER_SEC + t.tv_nsec;
}

static struct sensor *sensor_of(struct as9888_hal *h, int handle)
{
	return handle >= 1 && handle <= AS9888_SENSOR_COUNT ? &h->sensor[handle - 1] : NULL;
}

/* The last error, cut to fit */
static void set_error(struct as9888_hal *h, const char *msg)
{
	size_t n = strnlen(msg, sizeof(h->err) - 1);

	memcpy(h->err, msg, n);
	h->err[n] = '\0';
}

/* ---- the sensor list ---- */

static void rate_bounds(const struct hal_stream *s, int32_t *min_us, int32_t *max_us)
{
	*min_us = s->nrates ? (int32_t)(1000000 / s->rates[s->nrates - 1]) : 10000;
	*max_us = s->nrates ? (int32_t)(1000000 / s->rates[0]) : 1000000;
}

static void fill_info(struct as9888_hal *h, double magn_lsb_ut)
{
	struct as9888_sensor_info *a = &h->info[0], *m = &h->info[1], *u = &h->info[2];

	*a = (struct as9888_sensor_info) {
		.handle = AS9888_HANDLE_ACCEL,
		.type = AS9888_TYPE_ACCELEROMETER,
		.name = "AS9888 Accelerometer",
		.vendor = "ALSEN",
		.type_name = "android.sensor.accelerometer",
		/* the chip's rails: +-2048 counts at about 256 per g */
		.max_range = (float)(8 * STANDARD_GRAVITY),
		.resolution = (float)(STANDARD_GRAVITY / 256),
		/* the datasheet gives no supply current: a board measures it */
		.power_ma = 0.2f,
		.fifo_max = HAL_QUEUE_EVENTS,
	};
	rate_bounds(&h->accel, &a->min_delay_us, &a->max_delay_us);
	*m = (struct as9888_sensor_info) {
		.handle = AS9888_HANDLE_MAGN,
		.type = AS9888_TYPE_MAGNETIC_FIELD,
		.name = "AS9888 Magnetometer",
		.vendor = "ALSEN",
		.type_name = "android.sensor.magnetic_field",
		.max_range = 1200.0f,
		.resolution = (float)magn_lsb_ut,
		.power_ma = 0.5f,
		.fifo_max = HAL_QUEUE_EVENTS,
	};
	rate_bounds(&h->magn, &m->min_delay_us, &m->max_delay_us);
	*u = *m;
	u->handle = AS9888_HANDLE_MAGN_UNCAL;
	u->type = AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED;
	u->name = "AS9888 Magnetometer Uncalibrated";
	u->type_name = "android.sensor.magnetic_field_uncalibrated";
}

size_t as9888_hal_sensors(const struct as9888_hal *h,
			  const struct as9888_sensor_info **list)
{
	*list = h->info;
	return AS9888_SENSOR_COUNT;
}

/* ---- applying the configuration (the caller's thread, @config held) ---- */

/* The rate @s must run at for its active sensors @first..@last; 0: off */
static double wanted_hz(struct as9888_hal *h, int first, int last)
{
	double hz = 0;
	int i;

	for (i = first; i <= last; i++) {
		struct sensor *s = sensor_of(h, i);

		if (s->active && NSEC_PER_SEC / (double)s->period_ns > hz)
			hz = NSEC_PER_SEC / (double)s->period_ns;
	}
	return hz;
}

static void wake(struct as9888_hal *h)
{
	char c = 1;

	/* a full pipe already wakes the reader */
	if (write(h->wake[1], &c, 1) < 0)
		return;
}

/* Wait until the reader is out of any poll() that began before this call */
static void leave_poll(struct as9888_hal *h)
{
	unsigned long polls = h->polls;

	if (!h->polling)
		return;
	wake(h);
	while (h->polling && h->polls == polls)
		pthread_cond_wait(&h->polled, &h->lock);
}

/*
 * Bring @s (device @dev) to @hz (0: off), @h->lock held: the sysfs writes
 * are made on a copy with the lock released; the copy is handed to the
 * reader, or the running stream taken from it, under the lock
 */
static int apply_stream(struct as9888_hal *h, struct hal_stream *s, double hz, int dev)
{
	long rate = hal_stream_pick_rate(s, hz);
	bool running = s->fd >= 0;
	struct hal_stream tmp;
	char err[256];
	int ret = 0;

	if (hz == 0 ? !running : running && (!rate || rate == s->hz))
		return 0;
	tmp = *s;
	if (hz == 0) {
		s->fd = -1;
		h->gen[dev]++;
		leave_poll(h);
	}
	pthread_mutex_unlock(&h->lock);
	if (hz == 0)
		hal_stream_stop(&tmp);
	else if (running)
		ret = hal_stream_set_rate(&tmp, rate, err, sizeof(err));
	else
		ret = hal_stream_start(&tmp, h->devs.trigger, rate, err, sizeof(err));
	pthread_mutex_lock(&h->lock);
	if (ret) {
		set_error(h, err);
	} else if (hz != 0 && running) {
		/* unless the reader stopped it meanwhile (the device went away) */
		if (s->fd >= 0)
			s->hz = tmp.hz;
	} else if (hz != 0) {
		*s = tmp;
		h->gen[dev]++;
		h->prev_ts[dev] = 0;
		if (dev)
			h->record_due = true;
		wake(h);
	}
	return ret;
}

static int apply(struct as9888_hal *h)
{
	int ret, ret2;

	ret = apply_stream(h, &h->accel, wanted_hz(h, AS9888_HANDLE_ACCEL,
						     AS9888_HANDLE_ACCEL), 0);
	ret2 = apply_stream(h, &h->magn, wanted_hz(h, AS9888_HANDLE_MAGN,
						     AS9888_HANDLE_MAGN_UNCAL), 1);
	return ret ? ret : ret2;
}

/* ---- events ---- */

static void post_out(struct as9888_hal *h)
{
	size_t n = h->nout;

	if (!n)
		return;
	h->nout = 0;
	pthread_mutex_unlock(&h->lock);
	h->post(h->ctx, h->out, n);
	pthread_mutex_lock(&h->lock);
}

static void emit(struct as9888_hal *h, const struct as9888_event *e)
{
	if (h->nout == OUT_EVENTS)
		post_out(h);
	h->out[h->nout++] = *e;
}

static void deliver_queue(struct as9888_hal *h, struct sensor *s)
{
	struct as9888_event e;

	while (hal_queue_take(&s->queue, &e, 1))
		emit(h, &e);
}

/* @e of sensor @s: now, or into its batch */
static void report(struct as9888_hal *h, struct sensor *s, const struct as9888_event *e)
{
	if (!s->latency_ns) {
		emit(h, e);
		return;
	}
	if (hal_queue_full(&s->queue))
		deliver_queue(h, s);
	if (!s->queue.count)
		s->batch_since = now_ns();
	hal_queue_push(&s->queue, e);
}

/*
 * Whether a sample at @ts is one of @s's: the samples are taken at the
 * fastest rate a sensor of the device asks (@dev_period, 0: the trigger's
 * own), which that sensor gets whole; a slower one gets those nearest
 * its own period (@half: half the time since the device's last sample)
 */
static bool due(struct sensor *s, int64_t ts, int64_t half, int64_t dev_period)
{
	if (dev_period && s->period_ns <= dev_period + dev_period / 1000)
		return true;
	if (s->next_due && ts < s->next_due - half)
		return false;
	/* a gap (a restart, a stall) starts the schedule again */
	if (!s->next_due || ts > s->next_due + s->period_ns)
		s->next_due = ts;
	s->next_due += s->period_ns;
	return true;
}

static void check_record(struct as9888_hal *h, bool force)
{
	char err[256];
	struct stat st;
	int64_t now = now_ns();

	if (!*h->cfg.record || (!force && now - h->record_checked < RECORD_CHECK_NS))
		return;
	h->record_checked = now;
	if (stat(h->cfg.record, &st)) {
		memset(&h->record_st, 0, sizeof(h->record_st));
		h->have_cal = false;
		return;
	}
	if (!force && st.st_ino == h->record_st.st_ino && st.st_size == h->record_st.st_size &&
	    st.st_mtim.tv_sec == h->record_st.st_mtim.tv_sec &&
	    st.st_mtim.tv_nsec == h->record_st.st_mtim.tv_nsec)
		return;
	h->record_st = st;
	/* the driver already applies the record's calibbias and calibscale */
	h->have_cal = !as9888_magn_load(h->cfg.record, &h->cal, err, sizeof(err));
	if (!h->have_cal)
		set_error(h, err);
}

static void accel_sample(struct as9888_hal *h, const uint8_t *sample, int64_t half,
			 int64_t dev_period)
{
	struct sensor *s = sensor_of(h, AS9888_HANDLE_ACCEL);
	struct as9888_event e = { .handle = AS9888_HANDLE_ACCEL,
				  .type = AS9888_TYPE_ACCELEROMETER };
	double v[3], d[3];
	bool saturated;
	int i;

	saturated = hal_layout_decode(&h->accel.layout, sample, h->accel_raw, v,
				      &e.timestamp_ns);
	h->accel_raw_at = now_ns();
	if (!s->active || !due(s, e.timestamp_ns, half, dev_period))
		return;
	iio_mount_apply(h->accel.layout.mount, v, d);
	for (i = 0; i < 3; i++)
		e.v[i] = (float)d[i];
	e.status = saturated ? AS9888_STATUS_UNRELIABLE : AS9888_STATUS_ACCURACY_HIGH;
	report(h, s, &e);
}

static void magn_sample(struct as9888_hal *h, const uint8_t *sample, int64_t half,
			int64_t dev_period)
{
	struct sensor *cal = sensor_of(h, AS9888_HANDLE_MAGN);
	struct sensor *uncal = sensor_of(h, AS9888_HANDLE_MAGN_UNCAL);
	struct as9888_event e = { 0 };
	double y[3], f[3], b[3] = { 0 }, d[3], db[3];
	int32_t raw[3];
	bool saturated;
	int64_t ts, now = now_ns();
	int i, status;

	saturated = hal_layout_decode(&h->magn.layout, sample, raw, y, &ts);
	if (!saturated)
		hal_feed_offer(h->feed, y,
			       h->accel_raw_at && now - h->accel_raw_at < ACCEL_FRESH_NS ?
			       h->accel_raw : NULL, now);
	if (h->have_cal) {
		as9888_magn_correct(&h->cal, y, f);
		as9888_magn_hal_bias(&h->cal, b);
	} else {
		memcpy(f, y, sizeof(f));
	}
	status = saturated ? AS9888_STATUS_UNRELIABLE :
		 h->have_cal ? AS9888_STATUS_ACCURACY_HIGH : AS9888_STATUS_ACCURACY_LOW;
	e.timestamp_ns = ts;
	e.status = status;
	if (cal->active && due(cal, ts, half, dev_period)) {
		iio_mount_apply(h->magn.layout.mount, f, d);
		e.handle = AS9888_HANDLE_MAGN;
		e.type = AS9888_TYPE_MAGNETIC_FIELD;
		for (i = 0; i < 3; i++)
			e.v[i] = (float)d[i];
		report(h, cal, &e);
	}
	if (uncal->active && due(uncal, ts, half, dev_period)) {
		/* uncalibrated - bias = calibrated, in either frame */
		for (i = 0; i < 3; i++)
			f[i] += b[i];
		iio_mount_apply(h->magn.layout.mount, f, d);
		iio_mount_apply(h->magn.layout.mount, b, db);
		e.handle = AS9888_HANDLE_MAGN_UNCAL;
		e.type = AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED;
		for (i = 0; i < 3; i++) {
			e.v[i] = (float)d[i];
			e.v[3 + i] = (float)db[i];
		}
		report(h, uncal, &e);
	}
}

/* Everything waiting in @s's buffer; false when the read failed */
static bool read_stream(struct as9888_hal *h, struct hal_stream *s, int dev)
{
	uint8_t buf[HAL_STREAM_BATCH * 64];
	int64_t dev_period = s->hz ? NSEC_PER_SEC / s->hz : 0;
	char msg[300];
	int n, i;

	do {
		n = hal_stream_read(s, buf, sizeof(buf));
		if (n < 0) {
			snprintf(msg, sizeof(msg), "%s: read failed: %s", s->node, strerror(-n));
			set_error(h, msg);
			return false;
		}
		for (i = 0; i < n; i++) {
			const uint8_t *sample = buf + (size_t)i * s->layout.sample_bytes;
			int64_t ts = iio_scan_value64(&s->layout.chan[3], sample);
			int64_t half = h->prev_ts[dev] && ts > h->prev_ts[dev] ?
				       (ts - h->prev_ts[dev]) / 2 : 0;

			h->prev_ts[dev] = ts;
			if (dev)
				magn_sample(h, sample, half, dev_period);
			else
				accel_sample(h, sample, half, dev_period);
		}
	} while (n == HAL_STREAM_BATCH);
	return true;
}

/* Batches whose latency ran out, and the flushes asked; the next deadline */
static int64_t deliver_due(struct as9888_hal *h)
{
	int64_t now = now_ns(), next = INT64_MAX;
	int i;

	for (i = 1; i <= AS9888_SENSOR_COUNT; i++) {
		struct sensor *s = sensor_of(h, i);

		if (s->queue.count && (now - s->batch_since >= s->latency_ns || s->flushes))
			deliver_queue(h, s);
		else if (s->queue.count && s->batch_since + s->latency_ns < next)
			next = s->batch_since + s->latency_ns;
		for (; s->flushes; s->flushes--) {
			struct as9888_event e = {
				.handle = i,
				.type = AS9888_TYPE_META_DATA,
			};

			emit(h, &e);
		}
	}
	return next;
}

static void *reader_thread(void *arg)
{
	struct as9888_hal *h = arg;
	struct pollfd pfd[3];
	struct hal_stream *streams[2] = { &h->accel, &h->magn };
	unsigned long gen[2];
	int64_t deadline;
	char drain[64];
	bool ok;
	int timeout, i, n;

	pthread_mutex_lock(&h->lock);
	while (!h->stop) {
		deadline = deliver_due(h);
		post_out(h);
		if (h->stop)
			break;
		/* before the first sample of a magnetometer just started */
		if (h->magn.fd >= 0)
			check_record(h, h->record_due);
		h->record_due = false;

		pfd[0] = (struct pollfd) { .fd = h->wake[0], .events = POLLIN };
		for (i = 0; i < 2; i++) {
			pfd[i + 1] = (struct pollfd) { .fd = streams[i]->fd, .events = POLLIN };
			gen[i] = h->gen[i];
		}
		if (deadline == INT64_MAX) {
			/* the record is looked at once a second while the magnetometer runs */
			timeout = h->magn.fd >= 0 ? 1000 : -1;
		} else {
			int64_t left = deadline - now_ns();

			timeout = left <= 0 ? 0 : (int)((left + NSEC_PER_MSEC - 1) / NSEC_PER_MSEC);
			if (timeout > 1000)
				timeout = 1000;
		}
		h->polling = true;
		pthread_mutex_unlock(&h->lock);
		n = poll(pfd, 3, timeout);
		pthread_mutex_lock(&h->lock);
		h->polling = false;
		h->polls++;
		pthread_cond_broadcast(&h->polled);
		if (n < 0)
			continue;	/* EINTR */
		if (pfd[0].revents & POLLIN)
			while (read(h->wake[0], drain, sizeof(drain)) > 0)
				;
		for (i = 0; i < 2; i++) {
			/* a stream stopped or started since (a post drops the lock) is
			 * not the one polled, whatever its descriptor's number */
			if (!(pfd[i + 1].revents & (POLLIN | POLLERR | POLLHUP)) ||
			    gen[i] != h->gen[i])
				continue;
			ok = read_stream(h, streams[i], i);
			/* restarted while it was read (its posts drop the lock) */
			if (gen[i] != h->gen[i])
				continue;
			if (!ok || (pfd[i + 1].revents & (POLLERR | POLLHUP)))
				/* the device went away: stop it rather than spin */
				hal_stream_stop(streams[i]);
		}
	}
	pthread_mutex_unlock(&h->lock);
	return NULL;
}

/* ---- the framework's calls ---- */

int as9888_hal_activate(struct as9888_hal *h, int handle, bool enable)
{
	struct sensor *s = sensor_of(h, handle);
	int ret = 0;

	if (!s)
		return -EINVAL;
	pthread_mutex_lock(&h->config);
	pthread_mutex_lock(&h->lock);
	if (s->active != enable) {
		s->active = enable;
		s->next_due = 0;
		if (!enable) {
			/* what was batched is dropped with the sensor, as on a FIFO */
			s->queue.count = 0;
			s->flushes = 0;
		}
		ret = apply(h);
		if (ret && enable) {
			s->active = false;
			apply(h);
		}
	}
	pthread_mutex_unlock(&h->lock);
	pthread_mutex_unlock(&h->config);
	return ret;
}

int as9888_hal_batch(struct as9888_hal *h, int handle, int64_t period_ns,
		     int64_t max_latency_ns)
{
	struct sensor *s = sensor_of(h, handle);
	const struct as9888_sensor_info *info;
	int ret = 0;

	if (!s || period_ns < 0 || max_latency_ns < 0)
		return -EINVAL;
	info = &h->info[handle - 1];
	/* Android: clamp to the sensor's bounds */
	if (period_ns < (int64_t)info->min_delay_us * 1000)
		period_ns = (int64_t)info->min_delay_us * 1000;
	if (period_ns > (int64_t)info->max_delay_us * 1000)
		period_ns = (int64_t)info->max_delay_us * 1000;
	pthread_mutex_lock(&h->config);
	pthread_mutex_lock(&h->lock);
	s->period_ns = period_ns;
	s->next_due = 0;
	s->latency_ns = max_latency_ns;
	if (s->active)
		ret = apply(h);
	/* the reader takes the new latency's deadline */
	wake(h);
	pthread_mutex_unlock(&h->lock);
	pthread_mutex_unlock(&h->config);
	return ret;
}

int as9888_hal_flush(struct as9888_hal *h, int handle)
{
	struct sensor *s = sensor_of(h, handle);
	int ret = 0;

	if (!s)
		return -EINVAL;
	pthread_mutex_lock(&h->lock);
	if (!s->active) {
		ret = -EINVAL;
	} else {
		s->flushes++;
		wake(h);
	}
	pthread_mutex_unlock(&h->lock);
	return ret;
}

void as9888_hal_error(struct as9888_hal *h, char *buf, size_t len)
{
	pthread_mutex_lock(&h->lock);
	snprintf(buf, len, "%s", h->err);
	pthread_mutex_unlock(&h->lock);
}

/* ---- open and close ---- */

int as9888_hal_open(const struct as9888_hal_config *cfg, as9888_hal_post_fn post,
		    void *ctx, struct as9888_hal **out, char *err, size_t errlen)
{
	struct as9888_hal *h = calloc(1, sizeof(*h));
	double lsb;
	int ret, i;

	if (!h) {
		snprintf(err, errlen, "out of memory");
		return -ENOMEM;
	}
	h->cfg = *cfg;
	h->post = post;
	h->ctx = ctx;
	h->wake[0] = h->wake[1] = -1;
	h->accel.fd = h->magn.fd = -1;
	ret = hal_find_devices(cfg->sysfs, cfg->dev, cfg->parent, cfg->trigger,
			       &h->devs, err, errlen);
	if (!ret)
		ret = hal_stream_init(&h->accel, h->devs.accel, h->devs.accel_node,
				      "accel", 1.0, err, errlen);
	if (!ret)
		ret = hal_stream_init(&h->magn, h->devs.magn, h->devs.magn_node,
				      "magn", UT_PER_GAUSS, err, errlen);
	/* the magnetometer's resolution: one LSB of its x axis */
	if (!ret && hal_attr_double(h->devs.magn, "in_magn_x_scale", &lsb, err, errlen))
		ret = hal_attr_double(h->devs.magn, "in_magn_scale", &lsb, err, errlen);
	if (ret)
		goto fail;
	fill_info(h, lsb * UT_PER_GAUSS);
	for (i = 1; i <= AS9888_SENSOR_COUNT; i++)
		h->sensor[i - 1].period_ns = (int64_t)h->info[i - 1].max_delay_us * 1000;
	if (*cfg->socket) {
		ret = hal_feed_start(cfg->socket, h->devs.accel, cfg->feed_interval_ms,
				     &h->feed, err, errlen);
		if (ret)
			goto fail;
	}
	if (pipe2(h->wake, O_CLOEXEC | O_NONBLOCK)) {
		ret = -errno;
		snprintf(err, errlen, "cannot make the reader's wake-up pipe: %s",
			 strerror(errno));
		goto fail;
	}
	pthread_mutex_init(&h->config, NULL);
	pthread_mutex_init(&h->lock, NULL);
	pthread_cond_init(&h->polled, NULL);
	ret = -pthread_create(&h->reader, NULL, reader_thread, h);
	if (ret) {
		snprintf(err, errlen, "cannot start the reader thread: %s", strerror(-ret));
		pthread_cond_destroy(&h->polled);
		pthread_mutex_destroy(&h->lock);
		pthread_mutex_destroy(&h->config);
		goto fail;
	}
	*out = h;
	return 0;
fail:
	hal_feed_stop(h->feed);
	if (h->wake[0] >= 0) {
		close(h->wake[0]);
		close(h->wake[1]);
	}
	free(h);
	return ret;
}

void as9888_hal_close(struct as9888_hal *h)
{
	if (!h)
		return;
	/* no set-up under way */
	pthread_mutex_lock(&h->config);
	pthread_mutex_lock(&h->lock);
	h->stop = true;
	wake(h);
	pthread_mutex_unlock(&h->lock);
	pthread_join(h->reader, NULL);
	hal_stream_stop(&h->accel);
	hal_stream_stop(&h->magn);
	pthread_mutex_unlock(&h->config);
	hal_feed_stop(h->feed);
	close(h->wake[0]);
	close(h->wake[1]);
	pthread_cond_destroy(&h->polled);
	pthread_mutex_destroy(&h->lock);
	pthread_mutex_destroy(&h->config);
	free(h);
}
