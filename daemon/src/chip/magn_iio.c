// SPDX-License-Identifier: GPL-2.0
/* The magnetometer's calibration in the driver (magn_iio.h). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "chip/iio.h"
#include "chip/iio_value.h"
#include "chip/magn_iio.h"

#define MICRO	1000000

const char *const magn_calibbias_attr[AS9888_AXES] = {
	"in_magn_x_calibbias", "in_magn_y_calibbias", "in_magn_z_calibbias",
};

const char *const magn_calibscale_attr[AS9888_AXES] = {
	"in_magn_x_calibscale", "in_magn_y_calibscale", "in_magn_z_calibscale",
};

bool magn_iio_has_calibration(const char *magn_dir)
{
	char path[IIO_PATH_MAX];
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		snprintf(path, sizeof(path), "%s/%s", magn_dir,
			 magn_calibbias_attr[axis]);
		if (access(path, F_OK))
			return false;
		snprintf(path, sizeof(path), "%s/%s", magn_dir,
			 magn_calibscale_attr[axis]);
		if (access(path, F_OK))
			return false;
	}

	return true;
}

/*
 * IIO_VAL_INT_PLUS_MICRO as sysfs prints it ("1.020000", "0.987654"):
 * in 1e-6, 0 or -EINVAL
 */
static int parse_micro(const char *s, int32_t *out)
{
	long whole, frac = 0;
	const char *dot = strchr(s, '.');
	char head[32];
	size_t n, digits;

	n = dot ? (size_t)(dot - s) : strlen(s);
	if (n == 0 || n >= sizeof(head) || s[0] == '-')
		return -EINVAL;
	memcpy(head, s, n);
	head[n] = '\0';
	if (iio_int_parse(head, 0, 2, &whole))
		return -EINVAL;
	if (dot) {
		digits = strlen(dot + 1);
		if (digits == 0 || digits > 6 || dot[1] == '-' || dot[1] == '+' ||
		    iio_int_parse(dot + 1, 0, MICRO - 1, &frac))
			return -EINVAL;
		while (digits++ < 6)
			frac *= 10;
	}
	*out = (int32_t)(whole * MICRO + frac);

	return 0;
}

int magn_iio_read(const char *magn_dir, struct magn_driver_cal *d,
		  char *err, size_t errlen)
{
	char val[IIO_ATTR_MAX];
	long v;
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = iio_read_attr(magn_dir, magn_calibbias_attr[axis], val,
				    sizeof(val));
		if (ret < 0) {
			snprintf(err, errlen, "%s/%s: cannot read: %s", magn_dir,
				 magn_calibbias_attr[axis], strerror(-ret));
			return ret;
		}
		ret = iio_int_parse(val, -MAGN_CALIBBIAS_MAX, MAGN_CALIBBIAS_MAX,
				    &v);
		if (ret) {
			snprintf(err, errlen, "%s/%s reads \"%s\": %s (%d..%d)",
				 magn_dir, magn_calibbias_attr[axis], val,
				 iio_value_strerror(ret), -MAGN_CALIBBIAS_MAX,
				 MAGN_CALIBBIAS_MAX);
			return -EINVAL;
		}
		d->calibbias[axis] = (int32_t)v;
		ret = iio_read_attr(magn_dir, magn_calibscale_attr[axis], val,
				    sizeof(val));
		if (ret < 0) {
			snprintf(err, errlen, "%s/%s: cannot read: %s", magn_dir,
				 magn_calibscale_attr[axis], strerror(-ret));
			return ret;
		}
		/* the driver's range: a scale outside it (0) is no reading */
		if (parse_micro(val, &d->calibscale_micro[axis]) ||
		    d->calibscale_micro[axis] < AS9888_MAGN_CALIBSCALE_MIN ||
		    d->calibscale_micro[axis] > AS9888_MAGN_CALIBSCALE_MAX) {
			snprintf(err, errlen, "%s/%s reads \"%s\", not a scale like 1.000000 (0.500000..2.000000)",
				 magn_dir, magn_calibscale_attr[axis], val);
			return -EINVAL;
		}
	}

	return 0;
}

int magn_iio_write(const char *magn_dir, const struct magn_driver_cal *d,
		   char *err, size_t errlen)
{
	struct magn_driver_cal got;
	char val[IIO_ATTR_MAX];
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		const char *names[2] = { magn_calibbias_attr[axis],
					 magn_calibscale_attr[axis] };
		int i;

		for (i = 0; i < 2; i++) {
			if (i == 0)
				snprintf(val, sizeof(val), "%d", d->calibbias[axis]);
			else
				snprintf(val, sizeof(val), "%d.%06d",
					 d->calibscale_micro[axis] / MICRO,
					 d->calibscale_micro[axis] % MICRO);
			ret = iio_write_attr(magn_dir, names[i], val);
			if (ret) {
				snprintf(err, errlen, "%s/%s: cannot write \"%s\": %s",
					 magn_dir, names[i], val, strerror(-ret));
				return ret;
			}
		}
	}
	ret = magn_iio_read(magn_dir, &got, err, errlen);
	if (ret)
		return ret;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		if (got.calibbias[axis] != d->calibbias[axis]) {
			snprintf(err, errlen, "%s/%s: wrote %d, reads back %d",
				 magn_dir, magn_calibbias_attr[axis],
				 d->calibbias[axis], got.calibbias[axis]);
			return -EIO;
		}
		if (got.calibscale_micro[axis] != d->calibscale_micro[axis]) {
			snprintf(err, errlen, "%s/%s: wrote %d.%06d, reads back %d.%06d",
				 magn_dir, magn_calibscale_attr[axis],
				 d->calibscale_micro[axis] / MICRO,
				 d->calibscale_micro[axis] % MICRO,
				 got.calibscale_micro[axis] / MICRO,
				 got.calibscale_micro[axis] % MICRO);
			return -EIO;
		}
	}

	return 0;
}

/*
 * The magnetometer device beside @accel_dir. The driver registers it just
 * after the accelerometer's, whose appearance started this restore: when
 * a calibration waits for it, it is given MAGN_APPEAR_TRIES looks
 * MAGN_APPEAR_WAIT_NS apart (only at a device's appearance, never idle)
 */
#define MAGN_APPEAR_TRIES	10
#define MAGN_APPEAR_WAIT_NS	100000000L

static int find_magn(const char *accel_dir, bool wait, char *magn, size_t size)
{
	struct timespec ts = { .tv_nsec = MAGN_APPEAR_WAIT_NS };
	int i, ret = -ENOENT;

	for (i = 0; i < (wait ? MAGN_APPEAR_TRIES : 1); i++) {
		if (i)
			nanosleep(&ts, NULL);
		ret = iio_find_magn(accel_dir, magn, size, NULL, 0);
		if (ret != -ENOENT)
			break;
	}

	return ret;
}

int magn_iio_apply(const char *accel_dir, const struct calib_record *rec)
{
	char magn[IIO_PATH_MAX];

	if (find_magn(accel_dir, rec->magn.present, magn, sizeof(magn))) {
		if (rec->magn.present)
			fprintf(stderr, "as9888-calibd: warning: no %s IIO device beside %s: the magnetometer calibration is not applied (the accelerometer's is)\n",
				IIO_MAGN_NAME, accel_dir);
		return 0;
	}

	return magn_iio_apply_dev(magn, rec);
}

int magn_iio_apply_dev(const char *magn, const struct calib_record *rec)
{
	char err[IIO_ERR_LEN];
	struct magn_driver_cal d;
	int ret;

	if (!magn_iio_has_calibration(magn)) {
		if (rec->magn.present)
			fprintf(stderr, "as9888-calibd: warning: %s has no in_magn_{x,y,z}_calib{bias,scale}: the driver is older than the magnetometer calibration, which is not applied (the accelerometer's is); update the driver\n",
				magn);
		return 0;
	}
	if (!rec->magn.present) {
		struct magn_driver_cal now;

		/*
		 * A record without a magnetometer section asks for the
		 * driver's defaults. A device just bound already holds them:
		 * then nothing is written.
		 */
		magn_driver_identity(&d);
		if (!magn_iio_read(magn, &now, err, sizeof(err)) &&
		    !memcmp(&now, &d, sizeof(d)))
			return 0;
	} else if (magn_driver_split(&rec->magn, rec->eeprom, &d)) {
		fprintf(stderr, "as9888-calibd: the record's magnetometer hard iron is beyond what %s can cancel (calibbias +-%d); nothing applied to it\n",
			magn, MAGN_CALIBBIAS_MAX);
		return -ERANGE;
	}
	ret = magn_iio_write(magn, &d, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);

	return ret;
}
