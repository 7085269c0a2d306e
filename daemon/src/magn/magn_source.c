// SPDX-License-Identifier: GPL-2.0
/* Magnetometer samples from the chip's registers or the driver (magn_source.h). */
#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "as9888_regs.h"
#include "chip/chip.h"
#include "ftest/ftest.h"
#include "chip/iio.h"
#include "chip/iio_value.h"
#include "iio_mount.h"
#include "common/magn_cal.h"
#include "magn/magn_capture.h"
#include "chip/magn_iio.h"
#include "magn/magn_source.h"

#define NS_PER_US	1000ULL
#define NS_PER_S	1000000000ULL
/* The chip's output codes: -4096 and 4095 mean overflow (datasheet 5) */
#define MAGN_RAW_MAX	4096
#define ACCEL_RAW_MAX	2048
/* (count + calibbias) * calibscale: the driver's largest raw reading */
#define MAGN_RAW_RANGE_MAX	((MAGN_RAW_MAX + MAGN_CALIBBIAS_MAX) * 2)
#define MICRO		1000000.0

/**
 * struct magn_source - a sample source
 * @t:		the transport (register access), or NULL (the driver)
 * @chip:	the chip behind @t
 * @accel_dir:	the driver's accelerometer device
 * @magn_dir:	the driver's magnetometer device
 * @driver:	what the driver's calibration attributes held at open
 * @scale_ut:	uT per raw LSB of each magnetometer axis (the EEPROM's EHC)
 * @cap:	the driver's buffered capture of both devices, or NULL: sysfs
 * @log:	where the way the driver is read is said, or NULL
 * @mount:	the driver's mount matrix (device = mount * sensor)
 * @has_mount:	@mount was read: the device's frame is known
 */
struct magn_source {
	struct transport *t;
	struct chip chip;
	char accel_dir[IIO_PATH_MAX];
	char magn_dir[IIO_PATH_MAX];
	struct magn_driver_cal driver;
	double scale_ut[AS9888_AXES];
	struct magn_capture *cap;
	FILE *log;
	double mount[AS9888_AXES][AS9888_AXES];
	bool has_mount;
};

static int fail(char *err, size_t errlen, int ret, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static int fail(char *err, size_t errlen, int ret, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(err, errlen, fmt, ap);
	va_end(ap);

	return ret;
}

static int check_chip(const uint8_t got[AS9888_EEPROM_LEN],
		      const uint8_t want[AS9888_EEPROM_LEN], char *err,
		      size_t errlen)
{
	if (!memcmp(got, want, AS9888_EEPROM_LEN))
		return 0;

	return fail(err, errlen, -ENODEV,
		    "this chip is %016llx, the record's is %016llx: run factory-test on this unit first",
		    (unsigned long long)record_fingerprint(got),
		    (unsigned long long)record_fingerprint(want));
}

int magn_source_open_chip(struct transport *t, const struct calib_record *rec,
			  struct magn_source **out, char *err, size_t errlen)
{
	struct ftest_result res = { 0 };
	struct magn_source *s = calloc(1, sizeof(*s));
	const struct judgment *j;
	struct ftest_opts f;
	int ret;

	if (!s) {
		transport_destroy(t);
		return fail(err, errlen, -ENOMEM, "out of memory");
	}
	s->t = t;
	chip_init(&s->chip, t);
	/*
	 * Step 1 of the application note with the record's DAC values: the
	 * chip is the record's and measures as calibrated (as restore does)
	 */
	ftest_opts_default(&f);
	f.expect_eeprom = rec->eeprom;
	f.apply_dac = rec->dac;
	ret = ftest_step1(t, &f, &res);
	j = report_first_failure(&res.report);
	if (ret == -ENODEV && res.have_eeprom)
		ret = check_chip(res.ee.raw, rec->eeprom, err, errlen);
	else if (ret || j)
		ret = fail(err, errlen, ret ? ret : -EIO,
			   "cannot set the chip up: step %s (%s: %s)",
			   j ? j->step : "1", j ? j->name : "initialisation",
			   j ? j->measured : strerror(-ret));
	ftest_result_free(&res);
	/* a single measurement with MEN: the magnetometer and the accelerometer */
	if (!ret) {
		ret = transport_write_reg(t, AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
		if (ret)
			fail(err, errlen, ret, "cannot set SLCT2 over %s: %s",
			     t->name, strerror(-ret));
	}
	if (ret) {
		magn_source_close(s);
		return ret;
	}
	magn_scale_ut(rec->eeprom, s->scale_ut);
	*out = s;

	return 0;
}

/*
 * The device's frame from the magnetometer's in_magn_mount_matrix; a
 * driver without one (or one that is no mount matrix: said) leaves the
 * chip's axes, which only the hints of the progress lines use
 */
static void read_mount(struct magn_source *s)
{
	char val[IIO_MOUNT_TEXT_MAX];
	int ret;

	ret = iio_read_attr(s->magn_dir, "in_magn_mount_matrix", val,
			    sizeof(val));
	if (ret == -ENOENT)
		return;
	if (ret < 0) {
		if (s->log)
			fprintf(s->log, "samples: %s/in_magn_mount_matrix: %s: turns are named in the chip's axes\n",
				s->magn_dir, strerror(-ret));
		return;
	}
	if (iio_mount_parse(val, s->mount)) {
		if (s->log)
			fprintf(s->log, "samples: %s/in_magn_mount_matrix reads \"%s\", not a mount matrix: turns are named in the chip's axes\n",
				s->magn_dir, val);
		return;
	}
	s->has_mount = true;
}

/*
 * The buffered capture of both devices when it can be had; else say why
 * and read sysfs
 */
static void start_capture(struct magn_source *s)
{
	char why[IIO_ERR_LEN];

	if (!magn_capture_open(s->accel_dir, s->magn_dir, &s->cap, why,
			       sizeof(why))) {
		if (s->log)
			fprintf(s->log, "samples: both devices' buffers on %s at %d Hz, the field and the acceleration of each measurement paired, %d measurements averaged a sample\n",
				magn_capture_trigger(s->cap), MAGN_CAPTURE_RATE_HZ,
				MAGN_SOURCE_AVERAGE);
	} else if (s->log) {
		fprintf(s->log, "samples: no buffered capture (%s): sysfs reads, the field and the acceleration of a sample a few measurements apart (a fast turn can be refused as a changing field), one measurement a sample (noisier)\n",
			why);
	}
	if (s->log)
		fflush(s->log);
}

int magn_source_open_iio(const char *accel_dir, const char *magn_dir,
			 const uint8_t eeprom[AS9888_EEPROM_LEN], FILE *log,
			 struct magn_source **out, char *err, size_t errlen)
{
	uint8_t raw[AS9888_EEPROM_LEN];
	struct magn_source *s;
	int ret;

	ret = iio_read_eeprom(accel_dir, raw);
	if (ret)
		return fail(err, errlen, ret, "%s: cannot read the EEPROM: %s",
			    accel_dir, strerror(-ret));
	ret = check_chip(raw, eeprom, err, errlen);
	if (ret)
		return ret;
	s = calloc(1, sizeof(*s));
	if (!s)
		return fail(err, errlen, -ENOMEM, "out of memory");
	snprintf(s->accel_dir, sizeof(s->accel_dir), "%s", accel_dir);
	snprintf(s->magn_dir, sizeof(s->magn_dir), "%s", magn_dir);
	magn_driver_identity(&s->driver);
	if (magn_iio_has_calibration(magn_dir)) {
		ret = magn_iio_read(magn_dir, &s->driver, err, errlen);
		if (ret) {
			free(s);
			return ret;
		}
	}
	magn_scale_ut(raw, s->scale_ut);
	s->log = log;
	read_mount(s);
	start_capture(s);
	*out = s;

	return 0;
}

uint64_t magn_source_now_ns(struct magn_source *s)
{
	struct timespec ts;

	if (s->t)
		return transport_now_ns(s->t);
	clock_gettime(CLOCK_MONOTONIC, &ts);

	return (uint64_t)ts.tv_sec * NS_PER_S + (uint64_t)ts.tv_nsec;
}

static int read_chip(struct magn_source *s, struct magn_reading *r, char *err,
		     size_t errlen)
{
	struct chip_sample cs;
	enum chip_wait how;
	bool newer;
	int axis, ret;

	ret = chip_measure(&s->chip, AS9888_MS_SINGLE, AS9888_T_MAG_US, &how);
	if (!ret && how == CHIP_WAIT_TIMEOUT)
		ret = -ETIMEDOUT;
	if (!ret)
		ret = chip_read_overlapped(&s->chip, &cs, &newer);
	if (ret)
		return fail(err, errlen, ret, "magnetometer measurement over %s: %s",
			    s->t->name, strerror(-ret));
	if (cs.st2 & AS9888_ST2_HOFL_MSK)
		return -ERANGE;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->field_ut[axis] = cs.mag[axis] * s->scale_ut[axis];
		r->accel[axis] = cs.acc[axis];
	}
	r->t_ns = transport_now_ns(s->t);

	return 0;
}

static int read_raw(const char *dir, const char *name, long max, long *v,
		    char *err, size_t errlen)
{
	char val[IIO_ATTR_MAX];
	int ret = iio_read_attr(dir, name, val, sizeof(val));

	if (ret == -ERANGE)
		return ret;	/* the driver's overflow */
	if (ret == -EBUSY)
		return fail(err, errlen, ret, "%s/%s: busy: another program has the device's buffer enabled (a HAL, iio_readdev); stop it for the session",
			    dir, name);
	if (ret < 0)
		return fail(err, errlen, ret, "%s/%s: cannot read: %s", dir, name,
			    strerror(-ret));
	if (iio_int_parse(val, -max, max, v))
		return fail(err, errlen, -EINVAL, "%s/%s reads \"%s\", not a reading",
			    dir, name, val);

	return 0;
}

/* A reading of the driver's, (count + calibbias) * calibscale, as uT */
static double driver_ut(const struct magn_source *s, int axis, long v)
{
	return magn_uncorrect_driver(&s->driver, axis, v * s->scale_ut[axis],
				     s->scale_ut[axis]);
}

/*
 * A pair from the capture: 0, -ERANGE for an overflow, -EIO for a
 * saturated accelerometer; -EAGAIN when the capture stopped (said in the
 * log), the caller then reads sysfs
 */
static int read_capture(struct magn_source *s, struct magn_reading *r,
			char *err, size_t errlen)
{
	struct magn_capture_pair p;
	char why[IIO_ERR_LEN];
	bool overflow = false;
	int axis, ret;

	ret = magn_capture_next(s->cap, &p, why, sizeof(why));
	if (ret) {
		if (s->log) {
			fprintf(s->log, "samples: the buffered capture stopped (%s): sysfs reads from now on\n",
				why);
			fflush(s->log);
		}
		magn_capture_close(s->cap);
		s->cap = NULL;
		return -EAGAIN;
	}
	for (axis = 0; axis < AS9888_AXES; axis++) {
		/* the rails: an overflow or beyond the output range */
		overflow |= p.magn[axis] <= -MAGN_RAW_MAX ||
			    p.magn[axis] >= MAGN_RAW_MAX - 1;
		if (p.accel[axis] == INT16_MIN || p.accel[axis] == INT16_MAX)
			return fail(err, errlen, -EIO, "%s: in_accel_%c saturated in the buffer",
				    s->accel_dir, "xyz"[axis]);
		r->field_ut[axis] = driver_ut(s, axis, p.magn[axis]);
		r->accel[axis] = p.accel[axis];
	}
	r->t_ns = magn_source_now_ns(s);

	return overflow ? -ERANGE : 0;
}

static int read_iio(struct magn_source *s, struct magn_reading *r, char *err,
		    size_t errlen)
{
	static const char *const magn_raw[AS9888_AXES] = {
		"in_magn_x_raw", "in_magn_y_raw", "in_magn_z_raw",
	};
	static const char *const accel_raw[AS9888_AXES] = {
		"in_accel_x_raw", "in_accel_y_raw", "in_accel_z_raw",
	};
	long v;
	int axis, ret;

	if (s->cap) {
		ret = read_capture(s, r, err, errlen);
		if (ret != -EAGAIN)
			return ret;
	}
	/*
	 * Each read is a measurement of its own, and a device that turns
	 * moves between them: each axis of the field is read right before the
	 * same axis of the accelerometer, so that the two vectors are taken
	 * one measurement apart axis by axis (the angle between them, the dip
	 * the calibration's consistency gate watches, is then off by what the
	 * device turns in one measurement, not in three)
	 */
	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = read_raw(s->magn_dir, magn_raw[axis],
			       MAGN_RAW_RANGE_MAX, &v, err, errlen);
		if (ret)
			return ret;
		/* raw = (count + calibbias) * calibscale: the count back */
		r->field_ut[axis] = driver_ut(s, axis, v);
		ret = read_raw(s->accel_dir, accel_raw[axis], 8 * ACCEL_RAW_MAX,
			       &v, err, errlen);
		if (ret)
			return ret == -ERANGE ? fail(err, errlen, -EIO,
				"%s/%s: saturated", s->accel_dir, accel_raw[axis]) : ret;
		r->accel[axis] = v;
	}
	r->t_ns = magn_source_now_ns(s);

	return 0;
}

/* Measurements that come one after the other: the chip's, the capture's */
static bool averages(const struct magn_source *s)
{
	return s->t || s->cap;
}

int magn_source_read(struct magn_source *s, struct magn_reading *r,
		     char *err, size_t errlen)
{
	struct magn_reading one;
	unsigned int n = 0;
	int axis, ret;

	memset(r, 0, sizeof(*r));
	/*
	 * a capture that stops half way ends the sample with what it has
	 * and the one sysfs read that follows
	 */
	do {
		ret = s->t ? read_chip(s, &one, err, errlen) :
			     read_iio(s, &one, err, errlen);
		if (ret)
			return ret;
		for (axis = 0; axis < AS9888_AXES; axis++) {
			r->field_ut[axis] += one.field_ut[axis];
			r->accel[axis] += one.accel[axis];
		}
		n++;
	} while (n < MAGN_SOURCE_AVERAGE && averages(s));
	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->field_ut[axis] /= n;
		r->accel[axis] /= n;
	}
	r->t_ns = one.t_ns;
	r->measurements = n;

	return 0;
}

bool magn_source_mount(const struct magn_source *s,
		       double m[AS9888_AXES][AS9888_AXES])
{
	if (s->has_mount)
		memcpy(m, s->mount, sizeof(s->mount));
	return s->has_mount;
}

void magn_source_sleep(struct magn_source *s, uint64_t ns)
{
	struct timespec ts = {
		.tv_sec = (time_t)(ns / NS_PER_S),
		.tv_nsec = (long)(ns % NS_PER_S),
	};

	if (s->t) {
		transport_sleep_ns(s->t, ns);
		return;
	}
	/* the capture's rate paces the samples: its next pair is waited for */
	if (s->cap)
		return;
	while (nanosleep(&ts, &ts) && errno == EINTR)
		;
}

void magn_source_close(struct magn_source *s)
{
	if (!s)
		return;
	if (s->t) {
		chip_set_mode(&s->chip, AS9888_MS_POWER_DOWN);
		transport_destroy(s->t);
	}
	magn_capture_close(s->cap);
	free(s);
}
