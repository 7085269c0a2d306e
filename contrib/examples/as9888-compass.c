// SPDX-License-Identifier: GPL-2.0
/*
 * as9888-compass: a worked example (issue 28, point 6) of what a HAL or an
 * application reads: the tilt-compensated compass heading from the two
 * IIO devices of the AS9888.
 *
 *   field = R * (in_magn_<axis>_raw * in_magn_<axis>_scale)   (gauss)
 *   up    = in_accel_<axis>_raw * in_accel_scale               (m/s^2)
 *   both turned into the device frame by the mount matrix, then
 *   heading = magcal_heading_deg(field, up, declination)
 *
 * The driver already applies the hard iron and the diagonal of the
 * soft-iron correction (calibbias, calibscale); R is the residual matrix
 * that only userspace can apply (the daemon's record and socket give it;
 * the identity when the soft iron has no cross terms). The heading is that
 * of the device's +Y axis, clockwise from north: magnetic north without a
 * declination, true north with the local declination (east positive).
 * The device must be still: the accelerometer stands for gravity.
 *
 * Usage: as9888-compass [--sysfs DIR] [--declination DEG]
 *                       [--residual "r11 r12 r13 r21 ... r33"]
 */

#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "magcal.h"

struct options {
	const char *sysfs;
	double declination;
	double resid[3][3];
};

/* One number from <dir>/<attr>; false if missing or malformed */
static bool read_number(const char *dir, const char *attr, double *v)
{
	char path[PATH_MAX];
	FILE *f;
	bool ok;

	if (snprintf(path, sizeof(path), "%s/%s", dir, attr) >= (int)sizeof(path))
		return false;
	f = fopen(path, "r");
	if (!f)
		return false;
	ok = fscanf(f, "%lf", v) == 1;
	fclose(f);
	return ok;
}

/* The IIO device directory whose "name" is @name */
static bool find_device(const char *sysfs, const char *name, char *dir,
			size_t len)
{
	char base[PATH_MAX], np[PATH_MAX + 8], buf[64];
	struct dirent *e;
	bool found = false;
	DIR *d;
	FILE *f;

	snprintf(base, sizeof(base), "%s/bus/iio/devices", sysfs);
	d = opendir(base);
	if (!d)
		return false;
	while (!found && (e = readdir(d))) {
		if (snprintf(dir, len, "%s/%s", base, e->d_name) >= (int)len ||
		    snprintf(np, sizeof(np), "%s/name", dir) >= (int)sizeof(np))
			continue;	/* a path too long is not ours */
		f = fopen(np, "r");
		if (!f)
			continue;
		if (fgets(buf, sizeof(buf), f)) {
			buf[strcspn(buf, "\n")] = '\0';
			found = !strcmp(buf, name);
		}
		fclose(f);
	}
	closedir(d);
	return found;
}

/*
 * <type>_<axis>_raw times the scale (per axis, or shared by the type), in
 * the sensor's frame corrected by @resid when given (the magnetometer's
 * residual soft iron, a sensor-frame matrix), then turned into the device
 * frame by <type>_mount_matrix when there is one.
 */
static bool read_vector(const char *dir, const char *type,
			const double (*resid)[3], double v[3])
{
	static const char axes[3] = { 'x', 'y', 'z' };
	double raw[3], s[3], scale;
	double m[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
	char attr[64], path[PATH_MAX];
	FILE *f;
	int i;

	for (i = 0; i < 3; i++) {
		snprintf(attr, sizeof(attr), "in_%s_%c_raw", type, axes[i]);
		if (!read_number(dir, attr, &raw[i]))
			return false;
		snprintf(attr, sizeof(attr), "in_%s_%c_scale", type, axes[i]);
		if (!read_number(dir, attr, &scale)) {
			snprintf(attr, sizeof(attr), "in_%s_scale", type);
			if (!read_number(dir, attr, &scale))
				return false;
		}
		raw[i] *= scale;
	}
	if (snprintf(path, sizeof(path), "%s/in_%s_mount_matrix", dir,
		     type) >= (int)sizeof(path))
		return false;
	f = fopen(path, "r");
	if (f) {
		if (fscanf(f, "%lf, %lf, %lf; %lf, %lf, %lf; %lf, %lf, %lf",
			   &m[0][0], &m[0][1], &m[0][2], &m[1][0], &m[1][1],
			   &m[1][2], &m[2][0], &m[2][1], &m[2][2]) != 9) {
			fclose(f);
			return false;
		}
		fclose(f);
	}
	for (i = 0; i < 3; i++)
		s[i] = resid ? resid[i][0] * raw[0] + resid[i][1] * raw[1] +
			       resid[i][2] * raw[2] : raw[i];
	for (i = 0; i < 3; i++)
		v[i] = m[i][0] * s[0] + m[i][1] * s[1] + m[i][2] * s[2];
	return true;
}

static int usage(void)
{
	fprintf(stderr, "usage: as9888-compass [--sysfs DIR] [--declination DEG] "
		"[--residual \"r11 r12 r13 r21 r22 r23 r31 r32 r33\"]\n");
	return 2;
}

static bool parse_args(int argc, char **argv, struct options *o)
{
	double *r = &o->resid[0][0];
	int i;

	for (i = 1; i + 1 < argc; i += 2) {
		if (!strcmp(argv[i], "--sysfs"))
			o->sysfs = argv[i + 1];
		else if (!strcmp(argv[i], "--declination"))
			o->declination = atof(argv[i + 1]);
		else if (!strcmp(argv[i], "--residual") &&
			 sscanf(argv[i + 1], "%lf %lf %lf %lf %lf %lf %lf %lf %lf",
				&r[0], &r[1], &r[2], &r[3], &r[4], &r[5], &r[6],
				&r[7], &r[8]) == 9)
			continue;
		else
			return false;
	}
	return i == argc;
}

int main(int argc, char **argv)
{
	struct options o = { "/sys", 0, { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } } };
	char accel[PATH_MAX], magn[PATH_MAX];
	double up[3], field[3], heading;

	if (!parse_args(argc, argv, &o))
		return usage();
	if (!find_device(o.sysfs, "as9888-accel", accel, sizeof(accel)) ||
	    !find_device(o.sysfs, "as9888-magn", magn, sizeof(magn))) {
		fprintf(stderr, "as9888-compass: no as9888-accel and as9888-magn "
			"IIO devices under %s\n", o.sysfs);
		return 1;
	}
	/* the userspace part of the soft-iron correction, before the mount */
	if (!read_vector(accel, "accel", NULL, up) ||
	    !read_vector(magn, "magn", (const double (*)[3])o.resid, field)) {
		fprintf(stderr, "as9888-compass: cannot read the raw values "
			"(%s)\n", strerror(errno));
		return 1;
	}
	if (magcal_heading_deg(field, up, o.declination, &heading)) {
		fprintf(stderr, "as9888-compass: no heading (the field is "
			"vertical, or +Y points up or down)\n");
		return 1;
	}
	printf("heading %.1f\n", heading);
	return 0;
}
