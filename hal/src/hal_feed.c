// SPDX-License-Identifier: GPL-2.0
/* The calibration daemon's field mode, fed (hal_feed.h) */
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "as9888_magn.h"
#include "hal_attr.h"
#include "hal_feed.h"
#include "hal_layout.h"

struct hal_feed {
	char socket[108];
	char accel_dir[256];
	int64_t interval_ns;
	pthread_t thread;
	pthread_mutex_t lock;
	pthread_cond_t cond;
	bool stop;
	bool waiting;
	bool have_accel;
	double y[3];
	double accel[3];
	int64_t last_taken_ns;
	unsigned long fed;
	unsigned long failed;
	char last_err[256];
};

/* The accelerometer's raw reading from sysfs (its buffer is off) */
static int read_accel(const char *dir, double a[3], char *err, size_t errlen)
{
	char name[32];
	int i, ret;

	for (i = 0; i < 3; i++) {
		snprintf(name, sizeof(name), "in_accel_%s_raw", hal_axis_names[i]);
		ret = hal_attr_double(dir, name, &a[i], err, errlen);
		if (ret)
			return ret;
	}
	return 0;
}

static void *feed_thread(void *arg)
{
	struct hal_feed *f = arg;
	double y[3], a[3];
	char err[256];
	bool have_accel;
	int ret;

	pthread_mutex_lock(&f->lock);
	for (;;) {
		while (!f->stop && !f->waiting)
			pthread_cond_wait(&f->cond, &f->lock);
		if (f->stop)
			break;
		memcpy(y, f->y, sizeof(y));
		memcpy(a, f->accel, sizeof(a));
		have_accel = f->have_accel;
		f->waiting = false;
		pthread_mutex_unlock(&f->lock);

		ret = have_accel ? 0 : read_accel(f->accel_dir, a, err, sizeof(err));
		if (!ret)
			ret = as9888_magn_feed(f->socket, y, a, err, sizeof(err));

		pthread_mutex_lock(&f->lock);
		if (ret) {
			f->failed++;
			snprintf(f->last_err, sizeof(f->last_err), "%s", err);
		} else {
			f->fed++;
		}
	}
	pthread_mutex_unlock(&f->lock);
	return NULL;
}

int hal_feed_start(const char *socket, const char *accel_dir,
		   unsigned int interval_ms, struct hal_feed **out,
		   char *err, size_t errlen)
{
	struct hal_feed *f = calloc(1, sizeof(*f));
	int ret;

	if (!f) {
		snprintf(err, errlen, "magn-feed: out of memory");
		return -ENOMEM;
	}
	snprintf(f->socket, sizeof(f->socket), "%s", socket);
	snprintf(f->accel_dir, sizeof(f->accel_dir), "%s", accel_dir);
	f->interval_ns = (int64_t)interval_ms * 1000000;
	f->last_taken_ns = INT64_MIN;
	pthread_mutex_init(&f->lock, NULL);
	pthread_cond_init(&f->cond, NULL);
	ret = -pthread_create(&f->thread, NULL, feed_thread, f);
	if (ret) {
		snprintf(err, errlen, "magn-feed: cannot start its thread: %s",
			 strerror(-ret));
		pthread_cond_destroy(&f->cond);
		pthread_mutex_destroy(&f->lock);
		free(f);
		return ret;
	}
	*out = f;
	return 0;
}

void hal_feed_offer(struct hal_feed *f, const double y[3], const int32_t *accel,
		    int64_t now_ns)
{
	int i;

	if (!f)
		return;
	pthread_mutex_lock(&f->lock);
	if (f->last_taken_ns == INT64_MIN || now_ns - f->last_taken_ns >= f->interval_ns) {
		f->last_taken_ns = now_ns;
		memcpy(f->y, y, sizeof(f->y));
		f->have_accel = accel != NULL;
		for (i = 0; accel && i < 3; i++)
			f->accel[i] = accel[i];
		f->waiting = true;
		pthread_cond_signal(&f->cond);
	}
	pthread_mutex_unlock(&f->lock);
}

void hal_feed_stats(struct hal_feed *f, unsigned long *fed, unsigned long *failed,
		    char *last_err, size_t len)
{
	pthread_mutex_lock(&f->lock);
	*fed = f->fed;
	*failed = f->failed;
	snprintf(last_err, len, "%s", f->last_err);
	pthread_mutex_unlock(&f->lock);
}

void hal_feed_stop(struct hal_feed *f)
{
	if (!f)
		return;
	pthread_mutex_lock(&f->lock);
	f->stop = true;
	pthread_cond_signal(&f->cond);
	pthread_mutex_unlock(&f->lock);
	pthread_join(f->thread, NULL);
	pthread_cond_destroy(&f->cond);
	pthread_mutex_destroy(&f->lock);
	free(f);
}
