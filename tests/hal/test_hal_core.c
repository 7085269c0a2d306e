// SPDX-License-Identifier: GPL-2.0
/*
 * The HAL core through its API (as9888_hal.h), the calls the Android
 * adapter makes, against a fake sysfs tree with FIFOs for the
 * /dev/iio:deviceN nodes: the test writes samples as the driver lays them
 * out and checks the events, the attributes the core set, batching,
 * flush, the magnetometer calibration and the daemon feed.
 * Waits detect a stall (10 s without progress), never time a result.
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "as9888_hal.h"
#include "as9888_magn.h"
#include "fake_sysfs.h"
#include "hal_test_tree.h"
#include "magn_example.h"
#include "common/record.h"

#define MAX_EVENTS	4096
#define STALL_S		10

struct fixture {
	struct fake_sysfs *f;
	char dir[64];			/* the nodes, the record, the socket */
	struct as9888_hal_config cfg;
	struct as9888_hal *h;
	int fifo[2];			/* write ends, accel and magn */
	pthread_mutex_t lock;
	pthread_cond_t cond;
	struct as9888_event ev[MAX_EVENTS];
	size_t nev;
	unsigned int posts;
	/* the reader kept in a post (the HAL's lock released) by the test */
	bool hold;			/* the next post waits */
	bool held;			/* a post waits until this is false */
	/* the daemon stand-in */
	int listen_fd;
	pthread_t server;
	char feed_line[256];
	unsigned int feeds;
};

static void post(void *ctx, const struct as9888_event *ev, size_t n)
{
	struct fixture *x = ctx;

	pthread_mutex_lock(&x->lock);
	for (size_t i = 0; i < n && x->nev < MAX_EVENTS; i++)
		x->ev[x->nev++] = ev[i];
	x->posts++;
	if (x->hold) {
		x->hold = false;
		x->held = true;
	}
	pthread_cond_broadcast(&x->cond);
	while (x->held)
		pthread_cond_wait(&x->cond, &x->lock);
	pthread_mutex_unlock(&x->lock);
}

/* The reader's next post waits (until release_post) */
static void hold_next_post(struct fixture *x)
{
	pthread_mutex_lock(&x->lock);
	x->hold = true;
	pthread_mutex_unlock(&x->lock);
}

/* Wait for the reader to be held in a post; fails on a stall */
static void wait_held(struct fixture *x)
{
	struct timespec until;

	pthread_mutex_lock(&x->lock);
	clock_gettime(CLOCK_REALTIME, &until);
	until.tv_sec += STALL_S;
	while (!x->held)
		if (pthread_cond_timedwait(&x->cond, &x->lock, &until) == ETIMEDOUT && !x->held) {
			pthread_mutex_unlock(&x->lock);
			fail_msg("no post to hold the reader in for %d s", STALL_S);
		}
	pthread_mutex_unlock(&x->lock);
}

/* Let a held post return */
static void release_post(struct fixture *x)
{
	pthread_mutex_lock(&x->lock);
	x->held = false;
	pthread_cond_broadcast(&x->cond);
	pthread_mutex_unlock(&x->lock);
}

/* Whether @n events came in all; false after a stall (STALL_S without one) */
static bool events_came(struct fixture *x, size_t n)
{
	struct timespec until;
	bool ok = true;

	pthread_mutex_lock(&x->lock);
	while (ok && x->nev < n) {
		size_t had = x->nev;

		clock_gettime(CLOCK_REALTIME, &until);
		until.tv_sec += STALL_S;
		if (pthread_cond_timedwait(&x->cond, &x->lock, &until) == ETIMEDOUT &&
		    x->nev == had)
			ok = false;
	}
	pthread_mutex_unlock(&x->lock);
	return ok;
}

/* Wait for @n events in all; fails on a stall */
static void wait_events(struct fixture *x, size_t n)
{
	if (!events_came(x, n))
		fail_msg("stalled at %zu events of %zu", x->nev, n);
}

static size_t count_of(struct fixture *x, int handle)
{
	size_t n = 0;

	pthread_mutex_lock(&x->lock);
	for (size_t i = 0; i < x->nev; i++)
		n += x->ev[i].handle == handle && x->ev[i].type != AS9888_TYPE_META_DATA;
	pthread_mutex_unlock(&x->lock);
	return n;
}

static void *serve(void *arg)
{
	struct fixture *x = arg;
	char line[256];
	int c;

	while ((c = accept(x->listen_fd, NULL, NULL)) >= 0) {
		ssize_t n = read(c, line, sizeof(line) - 1);

		if (n > 0) {
			line[n] = '\0';
			pthread_mutex_lock(&x->lock);
			snprintf(x->feed_line, sizeof(x->feed_line), "%s", line);
			x->feeds++;
			pthread_cond_broadcast(&x->cond);
			pthread_mutex_unlock(&x->lock);
		}
		if (write(c, "exit status 0\n", 14) < 0)
			break;
		close(c);
	}
	return NULL;
}

static int setup(void **state)
{
	struct fixture *x = calloc(1, sizeof(*x));
	struct sockaddr_un sa = { .sun_family = AF_UNIX };
	char path[128];

	assert_non_null(x);
	fake_sysfs_setup((void **)&x->f);
	hal_tree_channels(x->f);
	snprintf(x->dir, sizeof(x->dir), "/tmp/as9888-hal-XXXXXX");
	assert_non_null(mkdtemp(x->dir));
	for (int i = 0; i < 2; i++) {
		snprintf(path, sizeof(path), "%s/iio:device%d", x->dir, i);
		assert_int_equal(mkfifo(path, 0600), 0);
		x->fifo[i] = -1;
	}
	pthread_mutex_init(&x->lock, NULL);
	pthread_cond_init(&x->cond, NULL);
	as9888_hal_config_defaults(&x->cfg);
	snprintf(x->cfg.sysfs, sizeof(x->cfg.sysfs), "%s", x->f->root);
	snprintf(x->cfg.dev, sizeof(x->cfg.dev), "%s", x->dir);
	snprintf(x->cfg.record, sizeof(x->cfg.record), "%s/record", x->dir);
	snprintf(x->cfg.socket, sizeof(x->cfg.socket), "%s/sock", x->dir);
	x->cfg.feed_interval_ms = 100;
	x->listen_fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	snprintf(sa.sun_path, sizeof(sa.sun_path), "%s", x->cfg.socket);
	assert_int_equal(bind(x->listen_fd, (struct sockaddr *)&sa, sizeof(sa)), 0);
	assert_int_equal(listen(x->listen_fd, 4), 0);
	assert_int_equal(pthread_create(&x->server, NULL, serve, x), 0);
	*state = x;
	return 0;
}

static int teardown(void **state)
{
	struct fixture *x = *state;
	char cmd[128];

	/* a test that failed holding the reader: the HAL must be able to close */
	pthread_mutex_lock(&x->lock);
	x->hold = false;
	pthread_mutex_unlock(&x->lock);
	release_post(x);
	as9888_hal_close(x->h);
	for (int i = 0; i < 2; i++)
		if (x->fifo[i] >= 0)
			close(x->fifo[i]);
	shutdown(x->listen_fd, SHUT_RDWR);
	pthread_join(x->server, NULL);
	close(x->listen_fd);
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", x->dir);
	assert_int_equal(system(cmd), 0);
	fake_sysfs_teardown((void **)&x->f);
	free(x);
	return 0;
}

static void open_hal(struct fixture *x)
{
	char err[512];

	if (as9888_hal_open(&x->cfg, post, x, &x->h, err, sizeof(err)))
		fail_msg("as9888_hal_open: %s", err);
}

static void activate(struct fixture *x, int handle, int64_t period_ns, int64_t latency_ns)
{
	char err[512];
	int dev = handle == AS9888_HANDLE_ACCEL ? 0 : 1;

	assert_int_equal(as9888_hal_batch(x->h, handle, period_ns, latency_ns), 0);
	if (as9888_hal_activate(x->h, handle, true)) {
		as9888_hal_error(x->h, err, sizeof(err));
		fail_msg("activate %d: %s", handle, err);
	}
	if (x->fifo[dev] < 0) {
		char path[128];

		snprintf(path, sizeof(path), "%s/iio:device%d", x->dir, dev);
		x->fifo[dev] = open(path, O_WRONLY | O_NONBLOCK | O_CLOEXEC);
		assert_true(x->fifo[dev] >= 0);
	}
}

/* One sample of as9888-accel (x, y, z, temp, ts: 16 bytes) */
static void put_accel(struct fixture *x, int16_t ax, int16_t ay, int16_t az, int64_t ts)
{
	uint8_t s[16] = { 0 };
	int16_t v[4] = { ax, ay, az, 100 };

	memcpy(s, v, sizeof(v));
	memcpy(s + 8, &ts, 8);
	assert_int_equal(write(x->fifo[0], s, sizeof(s)), (ssize_t)sizeof(s));
}

/* One sample of as9888-magn (x, y, z, ts: 16 bytes) */
static void put_magn(struct fixture *x, int16_t mx, int16_t my, int16_t mz, int64_t ts)
{
	uint8_t s[16] = { 0 };
	int16_t v[3] = { mx, my, mz };

	memcpy(s, v, sizeof(v));
	memcpy(s + 8, &ts, 8);
	assert_int_equal(write(x->fifo[1], s, sizeof(s)), (ssize_t)sizeof(s));
}

static void assert_attr(const char *dir, const char *name, const char *want)
{
	char got[128];

	fake_get(dir, name, got, sizeof(got));
	got[strcspn(got, "\n")] = '\0';
	if (strcmp(got, want))
		fail_msg("%s is \"%s\", not \"%s\"", name, got, want);
}

static void sensor_list(void **state)
{
	struct fixture *x = *state;
	const struct as9888_sensor_info *s;

	open_hal(x);
	assert_int_equal(as9888_hal_sensors(x->h, &s), 3);
	assert_int_equal(s[0].type, AS9888_TYPE_ACCELEROMETER);
	/* from sampling_frequency_available: 400 Hz and 1 Hz; 100 Hz */
	assert_int_equal(s[0].min_delay_us, 2500);
	assert_int_equal(s[0].max_delay_us, 1000000);
	assert_int_equal(s[1].type, AS9888_TYPE_MAGNETIC_FIELD);
	assert_int_equal(s[1].min_delay_us, 10000);
	assert_float_equal(s[1].resolution, 0.3, 1e-6);
	assert_int_equal(s[2].type, AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED);
	assert_string_equal(s[2].type_name, "android.sensor.magnetic_field_uncalibrated");
	for (int i = 0; i < 3; i++)
		assert_int_equal(s[i].handle, i + 1);
	assert_int_equal(as9888_hal_activate(x->h, 0, true), -EINVAL);
	assert_int_equal(as9888_hal_activate(x->h, 4, true), -EINVAL);
	assert_int_equal(as9888_hal_batch(x->h, 1, -1, 0), -EINVAL);
}

/* m/s^2, the mount matrix, the timestamp, the attributes set and unset */
static void accelerometer(void **state)
{
	struct fixture *x = *state;
	const double g = 1024 * TREE_ACCEL_SCALE;

	fake_put(x->f->dev, "in_accel_mount_matrix", "0, 1, 0; -1, 0, 0; 0, 0, -1\n");
	open_hal(x);
	activate(x, AS9888_HANDLE_ACCEL, 10000000, 0);
	assert_attr(x->f->dev, "buffer/enable", "1");
	assert_attr(x->f->dev, "scan_elements/in_accel_x_en", "1");
	assert_attr(x->f->dev, "scan_elements/in_accel_z_en", "1");
	assert_attr(x->f->dev, "scan_elements/in_timestamp_en", "1");
	assert_attr(x->f->dev, "scan_elements/in_temp_en", "0");
	assert_attr(x->f->dev, "current_timestamp_clock", "boottime");
	assert_attr(x->f->dev, "trigger/current_trigger", "as9888-dev0");
	assert_attr(x->f->dev, "sampling_frequency", "100");
	assert_attr(x->f->dev, "buffer/watermark", "1");
	/* the magnetometer untouched */
	assert_attr(x->f->magn, "buffer/enable", "0");

	put_accel(x, 1024, -512, 256, INT64_C(5000000000));
	put_accel(x, 32767, 0, 0, INT64_C(5010000000));
	wait_events(x, 2);
	assert_int_equal(x->ev[0].handle, AS9888_HANDLE_ACCEL);
	assert_int_equal(x->ev[0].type, AS9888_TYPE_ACCELEROMETER);
	assert_true(x->ev[0].timestamp_ns == INT64_C(5000000000));
	assert_true(x->ev[1].timestamp_ns == INT64_C(5010000000));
	/* 1 g is 9.80665 m/s^2 */
	assert_float_equal(g, 9.80665, 1e-5);
	/* device = M * sensor: (y, -x, -z) */
	assert_float_equal(x->ev[0].v[0], -0.5 * g, 1e-4);
	assert_float_equal(x->ev[0].v[1], -g, 1e-4);
	assert_float_equal(x->ev[0].v[2], -0.25 * g, 1e-4);
	assert_int_equal(x->ev[0].status, AS9888_STATUS_ACCURACY_HIGH);
	/* the saturation mark: unreliable */
	assert_int_equal(x->ev[1].status, AS9888_STATUS_UNRELIABLE);

	/* a new rate while running */
	assert_int_equal(as9888_hal_batch(x->h, AS9888_HANDLE_ACCEL, 40000000, 0), 0);
	assert_attr(x->f->dev, "sampling_frequency", "25");
	/* a rate between those offered: the next faster */
	assert_int_equal(as9888_hal_batch(x->h, AS9888_HANDLE_ACCEL, 33333333, 0), 0);
	assert_attr(x->f->dev, "sampling_frequency", "50");
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_ACCEL, false), 0);
	assert_attr(x->f->dev, "buffer/enable", "0");
}

static void write_record(struct fixture *x)
{
	struct calib_record rec = {
		.dac = { 0x0d, 0x8f, 0x8c },
		.level_mean_q16 = { 0, 0, 256 << 16 },
		.t_level_mdegc = 25000,
		.gravity = { 0, 0, -1 },
		.samples = 16,
		.created = 1795305600,
		.magn = magn_example,
	};
	char buf[RECORD_MAX_SIZE];
	int len;
	FILE *f;

	memcpy(rec.eeprom, fake_example_eeprom, sizeof(rec.eeprom));
	len = record_format(&rec, buf, sizeof(buf));
	assert_true(len > 0);
	f = fopen(x->cfg.record, "w");
	assert_non_null(f);
	assert_int_equal(fwrite(buf, 1, (size_t)len, f), (size_t)len);
	fclose(f);
}

/* uT, the residual soft iron R, the bias: uncalibrated - bias = calibrated */
static void magnetometer(void **state)
{
	struct fixture *x = *state;
	struct as9888_magn_calibration cal;
	double y[3] = { 100 * TREE_MAGN_SCALE_X * 100, -200 * TREE_MAGN_SCALE_Y * 100,
			300 * TREE_MAGN_SCALE_Z * 100 };
	double f[3], b[3];
	char err[256];
	const struct as9888_event *c = NULL, *u = NULL;

	write_record(x);
	assert_int_equal(as9888_magn_load(x->cfg.record, &cal, err, sizeof(err)), 0);
	as9888_magn_correct(&cal, y, f);
	as9888_magn_hal_bias(&cal, b);
	/* R is not the identity here: the HAL must apply it */
	assert_true(fabs(f[0] - y[0]) > 0.1);
	fake_put(x->f->magn, "in_magn_mount_matrix", "0, -1, 0; 1, 0, 0; 0, 0, 1\n");
	open_hal(x);
	activate(x, AS9888_HANDLE_MAGN, 100000000, 0);
	activate(x, AS9888_HANDLE_MAGN_UNCAL, 100000000, 0);
	assert_attr(x->f->magn, "sampling_frequency", "10");
	assert_attr(x->f->magn, "scan_elements/in_magn_y_en", "1");
	put_magn(x, 100, -200, 300, INT64_C(7000000000));
	wait_events(x, 2);
	for (int i = 0; i < 2; i++) {
		if (x->ev[i].handle == AS9888_HANDLE_MAGN)
			c = &x->ev[i];
		if (x->ev[i].handle == AS9888_HANDLE_MAGN_UNCAL)
			u = &x->ev[i];
	}
	assert_non_null(c);
	assert_non_null(u);
	assert_int_equal(c->type, AS9888_TYPE_MAGNETIC_FIELD);
	assert_int_equal(u->type, AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED);
	assert_true(c->timestamp_ns == INT64_C(7000000000));
	assert_int_equal(c->status, AS9888_STATUS_ACCURACY_HIGH);
	/* device = M * (R y - e): (-f_y, f_x, f_z) */
	assert_float_equal(c->v[0], -f[1], 1e-3);
	assert_float_equal(c->v[1], f[0], 1e-3);
	assert_float_equal(c->v[2], f[2], 1e-3);
	assert_float_equal(u->v[3], -b[1], 1e-3);
	assert_float_equal(u->v[4], b[0], 1e-3);
	for (int i = 0; i < 3; i++)
		assert_float_equal(u->v[i] - u->v[3 + i], c->v[i], 1e-3);

	/* the daemon fed: the driver's output in uT, the accelerometer's from sysfs */
	pthread_mutex_lock(&x->lock);
	while (!x->feeds) {
		struct timespec until;

		clock_gettime(CLOCK_REALTIME, &until);
		until.tv_sec += STALL_S;
		if (pthread_cond_timedwait(&x->cond, &x->lock, &until) == ETIMEDOUT && !x->feeds) {
			pthread_mutex_unlock(&x->lock);
			fail_msg("no magn-feed reached the daemon");
		}
	}
	assert_string_equal(x->feed_line, "magn-feed 30.000 -61.172 88.242 0 0 1024\n");
	pthread_mutex_unlock(&x->lock);

	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_MAGN, false), 0);
	assert_attr(x->f->magn, "buffer/enable", "1");
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_MAGN_UNCAL, false), 0);
	assert_attr(x->f->magn, "buffer/enable", "0");
}

/* Without a record: the driver's output, low accuracy, bias 0 */
static void magnetometer_without_record(void **state)
{
	struct fixture *x = *state;

	open_hal(x);
	activate(x, AS9888_HANDLE_MAGN_UNCAL, 100000000, 0);
	put_magn(x, 100, 0, 0, 1000);
	wait_events(x, 1);
	assert_float_equal(x->ev[0].v[0], 30.0, 1e-4);
	assert_float_equal(x->ev[0].v[3], 0, 1e-9);
	assert_int_equal(x->ev[0].status, AS9888_STATUS_ACCURACY_LOW);
}

/* Two sensors of one device at unequal rates: each gets its own */
static void unequal_rates(void **state)
{
	struct fixture *x = *state;

	open_hal(x);
	activate(x, AS9888_HANDLE_MAGN, 50000000, 0);		/* 20 Hz */
	activate(x, AS9888_HANDLE_MAGN_UNCAL, 100000000, 0);	/* 10 Hz */
	assert_attr(x->f->magn, "sampling_frequency", "20");
	for (int i = 0; i < 40; i++)
		put_magn(x, 1, 2, 3, INT64_C(1000000000) + i * INT64_C(50000000));
	wait_events(x, 60);
	assert_int_equal(count_of(x, AS9888_HANDLE_MAGN), 40);
	assert_int_equal(count_of(x, AS9888_HANDLE_MAGN_UNCAL), 20);
}

/* Max report latency: held back until it runs out or a flush */
static void batching_and_flush(void **state)
{
	struct fixture *x = *state;
	struct timespec pause = { 0, 300000000 };

	open_hal(x);
	assert_int_equal(as9888_hal_flush(x->h, AS9888_HANDLE_ACCEL), -EINVAL);
	activate(x, AS9888_HANDLE_ACCEL, 10000000, INT64_C(60000000000));
	for (int i = 0; i < 5; i++)
		put_accel(x, 0, 0, 1024, 1000 + i * 10000000);
	nanosleep(&pause, NULL);
	/* a minute's latency: nothing yet (a late event cannot come early) */
	pthread_mutex_lock(&x->lock);
	assert_int_equal(x->nev, 0);
	pthread_mutex_unlock(&x->lock);
	assert_int_equal(as9888_hal_flush(x->h, AS9888_HANDLE_ACCEL), 0);
	wait_events(x, 6);
	for (int i = 0; i < 5; i++) {
		assert_int_equal(x->ev[i].type, AS9888_TYPE_ACCELEROMETER);
		assert_true(x->ev[i].timestamp_ns == 1000 + i * 10000000);
	}
	/* flush complete, after the queued events */
	assert_int_equal(x->ev[5].type, AS9888_TYPE_META_DATA);
	assert_int_equal(x->ev[5].handle, AS9888_HANDLE_ACCEL);
	/* a short latency: delivered when it runs out, without a flush */
	assert_int_equal(as9888_hal_batch(x->h, AS9888_HANDLE_ACCEL, 10000000, 200000000), 0);
	for (int i = 0; i < 3; i++)
		put_accel(x, 0, 0, 1024, INT64_C(2000000000) + i * 10000000);
	wait_events(x, 9);
	assert_true(x->ev[8].timestamp_ns == INT64_C(2020000000));
	/* a flush with nothing queued: the flush-complete alone */
	assert_int_equal(as9888_hal_flush(x->h, AS9888_HANDLE_ACCEL), 0);
	wait_events(x, 10);
	assert_int_equal(x->ev[9].type, AS9888_TYPE_META_DATA);
}

/* The magnetometer's activate on its own thread (it blocks in its set-up) */
struct activation {
	struct fixture *x;
	pthread_t thread;
	int ret;
	bool returned;
};

static void *activate_magn(void *arg)
{
	struct activation *a = arg;
	int ret = as9888_hal_activate(a->x->h, AS9888_HANDLE_MAGN, true);

	pthread_mutex_lock(&a->x->lock);
	a->ret = ret;
	a->returned = true;
	pthread_mutex_unlock(&a->x->lock);
	return NULL;
}

/*
 * A sensor activated while another runs: the running device's events keep
 * coming while the new one's buffer is set up. The magnetometer's
 * in_magn_x_type is a FIFO, so its set-up waits in that read until the
 * test writes the type; meanwhile an accelerometer sample must arrive
 * (a HAL that sets buffers up on its reader thread delivers nothing until
 * the set-up ends: a stall). Then both run, each event once; deactivated,
 * each buffer is off.
 */
static void running_stream_flows_during_setup(void **state)
{
	struct fixture *x = *state;
	struct activation a = { .x = x };
	char type[300];
	int fd = -1, tries;
	bool came, returned;

	open_hal(x);
	activate(x, AS9888_HANDLE_ACCEL, 10000000, 0);
	put_accel(x, 0, 0, 1024, 1000);
	wait_events(x, 1);
	snprintf(type, sizeof(type), "%s/scan_elements/in_magn_x_type", x->f->magn);
	assert_int_equal(unlink(type), 0);
	assert_int_equal(mkfifo(type, 0600), 0);
	assert_int_equal(as9888_hal_batch(x->h, AS9888_HANDLE_MAGN, 100000000, 0), 0);
	assert_int_equal(pthread_create(&a.thread, NULL, activate_magn, &a), 0);
	/* the set-up has opened the type to read it: a writer can open it */
	for (tries = 0; fd < 0 && tries < STALL_S * 100; tries++) {
		struct timespec pause = { 0, 10000000 };

		fd = open(type, O_WRONLY | O_NONBLOCK | O_CLOEXEC);
		if (fd < 0 && errno == ENXIO)
			nanosleep(&pause, NULL);
		else
			assert_true(fd >= 0);
	}
	assert_true(fd >= 0);
	put_accel(x, 0, 0, 1024, 11001000);
	came = events_came(x, 2);
	pthread_mutex_lock(&x->lock);
	returned = a.returned;
	pthread_mutex_unlock(&x->lock);
	/* the set-up goes on either way, so that a failure does not hang */
	assert_int_equal(write(fd, "le:s13/16>>0\n", 13), 13);
	close(fd);
	assert_int_equal(pthread_join(a.thread, NULL), 0);
	if (!came)
		fail_msg("no accelerometer event in %d s while the magnetometer was set up",
			 STALL_S);
	assert_false(returned);
	assert_int_equal(a.ret, 0);
	assert_attr(x->f->magn, "buffer/enable", "1");
	assert_attr(x->f->dev, "buffer/enable", "1");
	/* both run, every sample once */
	snprintf(type, sizeof(type), "%s/iio:device1", x->dir);
	x->fifo[1] = open(type, O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	assert_true(x->fifo[1] >= 0);
	put_magn(x, 1, 2, 3, 20000000);
	put_accel(x, 0, 0, 1024, 21001000);
	wait_events(x, 4);
	assert_int_equal(count_of(x, AS9888_HANDLE_ACCEL), 3);
	assert_int_equal(count_of(x, AS9888_HANDLE_MAGN), 1);
	/* the magnetometer off: its buffer off, the accelerometer's flowing */
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_MAGN, false), 0);
	assert_attr(x->f->magn, "buffer/enable", "0");
	put_accel(x, 0, 0, 1024, 31001000);
	wait_events(x, 5);
	assert_int_equal(count_of(x, AS9888_HANDLE_ACCEL), 4);
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_ACCEL, false), 0);
	assert_attr(x->f->dev, "buffer/enable", "0");
}

/* The descriptor of this process open for reading on @path; -1: none */
static int reader_fd_on(const char *path)
{
	char link[64], target[PATH_MAX];
	struct dirent *e;
	DIR *d = opendir("/proc/self/fd");
	int fd = -1;

	assert_non_null(d);
	while (fd < 0 && (e = readdir(d))) {
		int n = atoi(e->d_name);
		ssize_t len;

		snprintf(link, sizeof(link), "/proc/self/fd/%d", n);
		len = readlink(link, target, sizeof(target) - 1);
		if (len < 0 || n == dirfd(d))
			continue;
		target[len] = '\0';
		if (!strcmp(target, path) && (fcntl(n, F_GETFL) & O_ACCMODE) == O_RDONLY)
			fd = n;
	}
	closedir(d);
	return fd;
}

/*
 * A stream stopped and started again while the reader is out of the lock
 * (in a post, between a poll() and its handling of the second device)
 * gets the descriptor number the old one had; what that poll() said of
 * the old one (POLLHUP: its writer gone, as a device gone away says
 * POLLERR) must not stop the new one. The reader is held in its posts:
 * the first with the magnetometer's writer closed and more accelerometer
 * samples written than one post carries, so that the next poll() reports
 * both and the accelerometer's reading posts before the magnetometer's
 * turn; in that post the magnetometer is stopped and started.
 */
static void restarted_stream_not_stopped_by_old_poll(void **state)
{
	struct fixture *x = *state;
	char node[128];
	int fd, i;

	/* no feed thread: nothing else opens a descriptor meanwhile */
	x->cfg.socket[0] = '\0';
	open_hal(x);
	activate(x, AS9888_HANDLE_ACCEL, 10000000, 0);
	activate(x, AS9888_HANDLE_MAGN, 100000000, 0);
	snprintf(node, sizeof(node), "%s/iio:device1", x->dir);
	fd = reader_fd_on(node);
	assert_true(fd >= 0);
	hold_next_post(x);
	put_accel(x, 0, 0, 1024, 1000);
	wait_held(x);
	for (i = 1; i <= 300; i++)
		put_accel(x, 0, 0, 1024, 1000 + i * INT64_C(10000000));
	close(x->fifo[1]);
	x->fifo[1] = -1;
	hold_next_post(x);
	release_post(x);
	wait_held(x);
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_MAGN, false), 0);
	activate(x, AS9888_HANDLE_MAGN, 100000000, 0);
	/* the premise: the new stream has the old one's number */
	assert_int_equal(reader_fd_on(node), fd);
	release_post(x);
	wait_events(x, 301);
	assert_int_equal(count_of(x, AS9888_HANDLE_ACCEL), 301);
	assert_attr(x->f->magn, "buffer/enable", "1");
	put_magn(x, 1, 2, 3, 20000000);
	wait_events(x, 302);
	assert_int_equal(count_of(x, AS9888_HANDLE_MAGN), 1);
}

/* A bad attribute: activate fails, says which, leaves the buffer off */
static void bad_attribute(void **state)
{
	struct fixture *x = *state;
	char err[512];

	fake_put(x->f->magn, "scan_elements/in_magn_x_type", "le:s13\n");
	open_hal(x);
	assert_int_equal(as9888_hal_activate(x->h, AS9888_HANDLE_MAGN, true), -EINVAL);
	as9888_hal_error(x->h, err, sizeof(err));
	assert_non_null(strstr(err, "in_magn_x_type"));
	assert_attr(x->f->magn, "buffer/enable", "0");
	assert_int_equal(as9888_hal_flush(x->h, AS9888_HANDLE_MAGN), -EINVAL);
	/* mended, it starts */
	fake_put(x->f->magn, "scan_elements/in_magn_x_type", "le:s13/16>>0\n");
	activate(x, AS9888_HANDLE_MAGN, 100000000, 0);
	assert_attr(x->f->magn, "buffer/enable", "1");
}

static void open_errors(void **state)
{
	struct fixture *x = *state;
	char err[512];

	fake_put(x->f->dev, "sampling_frequency_available", "1 2 fast\n");
	assert_int_equal(as9888_hal_open(&x->cfg, post, x, &x->h, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "sampling_frequency_available"));
	x->h = NULL;
	snprintf(x->cfg.parent, sizeof(x->cfg.parent), "spi0.0");
	assert_int_equal(as9888_hal_open(&x->cfg, post, x, &x->h, err, sizeof(err)), -ENODEV);
	assert_non_null(strstr(err, "spi0.0"));
	x->h = NULL;
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(sensor_list, setup, teardown),
		cmocka_unit_test_setup_teardown(accelerometer, setup, teardown),
		cmocka_unit_test_setup_teardown(magnetometer, setup, teardown),
		cmocka_unit_test_setup_teardown(magnetometer_without_record, setup, teardown),
		cmocka_unit_test_setup_teardown(unequal_rates, setup, teardown),
		cmocka_unit_test_setup_teardown(batching_and_flush, setup, teardown),
		cmocka_unit_test_setup_teardown(running_stream_flows_during_setup, setup, teardown),
		cmocka_unit_test_setup_teardown(restarted_stream_not_stopped_by_old_poll, setup,
						teardown),
		cmocka_unit_test_setup_teardown(bad_attribute, setup, teardown),
		cmocka_unit_test_setup_teardown(open_errors, setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
