// SPDX-License-Identifier: GPL-2.0
/* The accelerometer's calibration through the driver, and a record applied (iio_cal.h). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "chip/iio_cal.h"
#include "chip/iio_value.h"
#include "chip/magn_iio.h"
#include "common/record.h"
#include "common/remedy.h"

const char *const iio_calibbias_attr[AS9888_AXES] = {
	"in_accel_x_calibbias", "in_accel_y_calibbias", "in_accel_z_calibbias",
};

/* The device at @dir is on the chip @rec was made on (its EEPROM) */
static int check_chip(const char *dir, const struct calib_record *rec,
		      const char *what)
{
	uint8_t eeprom[AS9888_EEPROM_LEN];
	int ret;

	ret = iio_read_eeprom(dir, eeprom);
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s: cannot read the EEPROM: %s\n",
			dir, strerror(-ret));
		return ret;
	}
	if (memcmp(eeprom, rec->eeprom, AS9888_EEPROM_LEN)) {
		fprintf(stderr, "as9888-calibd: %s belongs to chip %016llx, %s is chip %016llx; nothing applied: " REMEDY_OTHER_CHIP "\n",
			what, (unsigned long long)record_fingerprint(rec->eeprom),
			dir, (unsigned long long)record_fingerprint(eeprom));
		return -ENODEV;
	}

	return 0;
}

int iio_apply_checked(const char *dir, const struct calib_record *rec,
		      const char *what)
{
	int ret = check_chip(dir, rec, what);

	return ret ? ret : iio_apply_record(dir, rec);
}

int iio_apply_magn_checked(const char *accel_dir,
			   const struct calib_record *rec, const char *what)
{
	int ret;

	if (rec->simulated) {
		fprintf(stderr, "as9888-calibd: %s was written on the simulator (source = simulator): its magnetometer calibration is not applied to %s\n",
			what, accel_dir);
		return -EPERM;
	}
	ret = check_chip(accel_dir, rec, what);

	return ret ? ret : magn_iio_apply(accel_dir, rec);
}

int iio_apply_device(const char *dir, const struct calib_record *rec,
		     const char *what)
{
	char name[IIO_ATTR_MAX];
	int ret;

	ret = iio_read_attr(dir, "name", name, sizeof(name));
	if (ret < 0) {
		fprintf(stderr, "as9888-calibd: %s is not an IIO device (no name: %s); nothing applied\n",
			dir, strerror(-ret));
		return ret;
	}
	if (strcmp(name, IIO_ACCEL_NAME) && strcmp(name, IIO_MAGN_NAME)) {
		fprintf(stderr, "as9888-calibd: %s is IIO device \"%s\", not an AS9888 one (%s or %s); nothing applied\n",
			dir, name, IIO_ACCEL_NAME, IIO_MAGN_NAME);
		return -ENODEV;
	}
	ret = check_chip(dir, rec, what);
	if (ret)
		return ret;

	return strcmp(name, IIO_ACCEL_NAME) ? magn_iio_apply_dev(dir, rec) :
					      iio_apply_accel(dir, rec);
}

/*
 * The helpers below reach @name below @dir through @dfd, @dir opened
 * (iio_dir_open()), or by its path when @dfd < 0; @dir names it in
 * messages
 */

/*
 * Where the calibration's attributes are: below @dir, opened as @dfd
 * (-1: by path), or kept open in @files (the factory test's)
 */
struct cal_where {
	const char *dir;
	int dfd;
	const struct iio_attr *files;
};

/*
 * Calibbias of @axis as text into @buf: 0, or -errno with the attribute
 * and the reason in @err
 */
static int read_text(const struct cal_where *w, int axis, char *buf,
		     size_t size, char *err, size_t errlen)
{
	const char *name = iio_calibbias_attr[axis];
	int ret;

	if (w->files)
		ret = iio_attr_read(&w->files[axis], buf, size);
	else if (w->dfd < 0)
		ret = iio_read_attr(w->dir, name, buf, size);
	else
		ret = iio_read_attr_at(w->dfd, name, buf, size);
	if (ret < 0)
		snprintf(err, errlen, "%s/%s: cannot read: %s", w->dir, name,
			 strerror(-ret));

	return ret < 0 ? ret : 0;
}

static int write_text(const struct cal_where *w, int axis, const char *val,
		      char *err, size_t errlen)
{
	const char *name = iio_calibbias_attr[axis];
	int ret;

	if (w->files)
		ret = iio_attr_write(&w->files[axis], val);
	else if (w->dfd < 0)
		ret = iio_write_attr(w->dir, name, val);
	else
		ret = iio_write_attr_at(w->dfd, name, val);
	if (ret)
		snprintf(err, errlen, "%s/%s: cannot write \"%s\": %s", w->dir,
			 name, val, strerror(-ret));

	return ret;
}

static int read_cal(const struct cal_where *w, struct as9888_accel_cal *cal,
		    char *err, size_t errlen)
{
	struct as9888_accel_cal c;
	char val[IIO_ATTR_MAX];
	long v;
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = read_text(w, axis, val, sizeof(val), err, errlen);
		if (ret)
			return ret;
		ret = iio_int_parse(val, -AS9888_CALIBBIAS_MAX,
				    AS9888_CALIBBIAS_MAX, &v);
		if (ret) {
			snprintf(err, errlen, "%s/%s reads \"%s\": %s (%d..%d)",
				 w->dir, iio_calibbias_attr[axis], val,
				 iio_value_strerror(ret), -AS9888_CALIBBIAS_MAX,
				 AS9888_CALIBBIAS_MAX);
			return ret;
		}
		c.bias[axis] = (int32_t)v;
	}
	*cal = c;

	return 0;
}

/* Write @cal and read it back into @back */
static int write_cal(const struct cal_where *w,
		     const struct as9888_accel_cal *cal,
		     struct as9888_accel_cal *back, char *err, size_t errlen)
{
	char val[IIO_ATTR_MAX];
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		snprintf(val, sizeof(val), "%d", cal->bias[axis]);
		ret = write_text(w, axis, val, err, errlen);
		if (ret)
			return ret;
	}

	return read_cal(w, back, err, errlen);
}

/*
 * @dir opened for the calibration's attributes, read or written in a row,
 * each resolving the attribute's name alone; by path (dfd -1) when it
 * cannot be
 */
static void cal_open(struct cal_where *w, const char *dir)
{
	w->dir = dir;
	w->dfd = iio_dir_open(dir);
	if (w->dfd < 0)
		w->dfd = -1;
	w->files = NULL;
}

static void cal_close(struct cal_where *w)
{
	if (w->dfd >= 0)
		close(w->dfd);
}

int iio_read_accel_cal(const char *dir, struct as9888_accel_cal *cal,
		       char *err, size_t errlen)
{
	struct cal_where w;
	int ret;

	cal_open(&w, dir);
	ret = read_cal(&w, cal, err, errlen);
	cal_close(&w);

	return ret;
}

int iio_write_accel_cal(const char *dir, const struct as9888_accel_cal *cal,
			char *err, size_t errlen)
{
	struct as9888_accel_cal old, got;
	char why[IIO_ERR_LEN];
	struct cal_where w;
	int axis, ret;

	/*
	 * All or nothing: when a value fails (a bus error in the driver's
	 * write), the ones written before it go back to what was in effect,
	 * so that the device never runs on part of a calibration
	 */
	cal_open(&w, dir);
	ret = read_cal(&w, &old, err, errlen);
	if (ret)
		goto out;
	ret = write_cal(&w, cal, &got, err, errlen);
	for (axis = 0; !ret && axis < AS9888_AXES; axis++)
		if (got.bias[axis] != cal->bias[axis]) {
			snprintf(err, errlen, "%s/%s: wrote %d, reads back %d",
				 dir, iio_calibbias_attr[axis], cal->bias[axis],
				 got.bias[axis]);
			ret = -EIO;
		}
	if (ret && write_cal(&w, &old, &got, why, sizeof(why))) {
		size_t len = strlen(err);

		snprintf(err + len, errlen - len,
			 "; the calibration in effect before could not be put back: %s",
			 why);
	}
out:
	cal_close(&w);

	return ret;
}

int iio_write_dac(const char *dir, const struct iio_attr *files,
		  const struct as9888_eeprom *ee,
		  const uint8_t da[AS9888_AXES], uint8_t got[AS9888_AXES],
		  struct as9888_accel_cal *now, char *err, size_t errlen)
{
	struct as9888_accel_cal cal, back;
	struct cal_where w = { .dir = dir, .dfd = -1, .files = files };
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = as9888_dac_bias(&ee->axis[axis], da[axis], &cal.bias[axis]);
		if (ret) {
			snprintf(err, errlen,
				 "%s/%s: no calibbias gives DAC 0x%02x: %s",
				 dir, iio_calibbias_attr[axis], da[axis],
				 strerror(-ret));
			return ret;
		}
	}
	if (!files)
		cal_open(&w, dir);
	ret = write_cal(&w, &cal, &back, err, errlen);
	if (!files)
		cal_close(&w);
	if (ret)
		return ret;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		uint8_t ga = ee->axis[axis].ga;

		as9888_bias_dac(&ee->axis[axis], back.bias[axis], &got[axis]);
		/* 0x00 and 0x80 are both DAC 0 */
		if (as9888_dac2lin(ga, got[axis]) == as9888_dac2lin(ga, da[axis]))
			got[axis] = da[axis];
	}
	*now = back;

	return 0;
}

int iio_apply_accel(const char *dir, const struct calib_record *rec)
{
	struct as9888_accel_cal cal;
	struct as9888_eeprom ee;
	char err[IIO_ERR_LEN];
	int ret;

	ret = as9888_eeprom_decode(rec->eeprom, &ee);
	if (!ret)
		ret = as9888_accel_cal_from_level(&ee, rec->level_mean_q16,
						  rec->t_level_mdegc,
						  rec->gravity, rec->dac, &cal);
	if (ret) {
		fprintf(stderr, "as9888-calibd: the record's level test gives no calibration: %s; nothing applied to %s\n",
			strerror(-ret), dir);
		return ret;
	}

	ret = iio_write_accel_cal(dir, &cal, err, sizeof(err));
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return ret;
	}

	return 0;
}

int iio_apply_record(const char *dir, const struct calib_record *rec)
{
	int ret = iio_apply_accel(dir, rec);

	return ret ? ret : magn_iio_apply(dir, rec);
}
