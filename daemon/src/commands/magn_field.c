// SPDX-License-Identifier: GPL-2.0
/* The daemon's magnetometer field mode (magn_field.h). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "commands/commands.h"
#include "chip/iio_cal.h"
#include "store/lock_file.h"
#include "magcal.h"
#include "common/magn_cal.h"
#include "commands/magn_field.h"
#include "chip/magn_iio.h"
#include "magn/magn_session.h"
#include "common/request.h"
#include "store/record_store.h"

#define MICRO		1000000.0
/* "m1 m2 m3 a1 a2 a3\n" with %.3f fields */
#define LINE_LEN	160
#define FILE_MAX	((MAGN_FIELD_KEEP + 2) * LINE_LEN)
/* magcal_export() keeps the newest samples only when the file holds all */
_Static_assert(MAGN_FIELD_KEEP >= MAGCAL_MAX_SAMPLES,
	       "the field mode's file must hold magcal's whole store");

double magn_field_reference_ut(const struct calib_magn *m)
{
	double w[AS9888_AXES][AS9888_AXES], det;
	int i, j;

	if (!m->present)
		return 0;
	for (i = 0; i < AS9888_AXES; i++)
		for (j = 0; j < AS9888_AXES; j++)
			w[i][j] = m->soft_iron_micro[i][j] / MICRO;
	det = w[0][0] * (w[1][1] * w[2][2] - w[1][2] * w[2][1]) -
	      w[0][1] * (w[1][0] * w[2][2] - w[1][2] * w[2][0]) +
	      w[0][2] * (w[1][0] * w[2][1] - w[1][1] * w[2][0]);
	if (!(det > 0) || fabs(cbrt(det) - 1) <= MAGN_FIELD_SCALED_TOL)
		return 0;
	return m->field_nt / 1000.0;
}

/* Rrot's term @i,@j in micro units: the identity's without a turn */
static int32_t rotation_micro(const struct calib_magn *m, int i, int j)
{
	return m->has_rotation ? m->rotation_micro[i][j] : (i == j) * 1000000;
}

bool magn_field_should_replace(const struct calib_magn *cur,
			       const struct calib_magn *next, int64_t now)
{
	int i, j;

	if (!cur->present)
		return true;
	if (now - cur->learned < MAGN_FIELD_MIN_AGE_S)
		return false;
	for (i = 0; i < AS9888_AXES; i++) {
		if (abs(next->hard_iron_nt[i] - cur->hard_iron_nt[i]) >=
		    MAGN_FIELD_BIAS_STEP_NT)
			return true;
		for (j = 0; j < AS9888_AXES; j++)
			if (abs(next->soft_iron_micro[i][j] -
				cur->soft_iron_micro[i][j]) >=
			    MAGN_FIELD_W_STEP_MICRO ||
			    abs(rotation_micro(next, i, j) -
				rotation_micro(cur, i, j)) >=
			    MAGN_FIELD_W_STEP_MICRO)
				return true;
	}

	return false;
}

/* What the driver's attributes hold now (defaults without a driver or them) */
static void driver_state(const struct calib_record *rec,
			 struct magn_driver_cal *d, char *accel, size_t size)
{
	char magn[IIO_PATH_MAX], err[IIO_ERR_LEN];

	magn_driver_identity(d);
	accel[0] = '\0';
	if (iio_find_device(NULL, accel, size)) {
		accel[0] = '\0';
		return;
	}
	if (!iio_find_magn(accel, magn, sizeof(magn), NULL, 0) &&
	    magn_iio_has_calibration(magn) &&
	    magn_iio_read(magn, d, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: magn-feed: %s\n", err);
		magn_driver_identity(d);
	}
}

static void samples_path(const struct cli_opts *o, char *path, size_t size)
{
	const char *dir = getenv("RUNTIME_DIRECTORY");

	if (dir && *dir && !strchr(dir, ':'))
		snprintf(path, size, "%s/%s", dir, MAGN_FIELD_SAMPLES_NAME);
	else
		snprintf(path, size, "%s.%s", o->socket_path,
			 MAGN_FIELD_SAMPLES_NAME);
}

/*
 * The longest wait for the samples file's lock, held by the feed of
 * another client: a holder that never lets go costs this sample only
 */
#define MAGN_FIELD_LOCK_MS	5000

/* A regular file owned by us, with one name, that no other user can write */
static bool samples_file_trusted(int fd)
{
	struct stat st;

	return !fstat(fd, &st) && S_ISREG(st.st_mode) && st.st_nlink == 1 &&
	       st.st_uid == geteuid() && !(st.st_mode & (S_IWGRP | S_IWOTH));
}

/* Offer the file's samples (after its first line) to @fit, in their order */
static void replay(char *p, struct magcal_session *fit)
{
	char *nl;

	for (; *p && (nl = strchr(p, '\n')); p = nl + 1) {
		double v[6];

		*nl = '\0';
		if (sscanf(p, "%lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2],
			   &v[3], &v[4], &v[5]) == 6)
			magcal_add(fit, v, v + 3);
	}
}

/* The store exported: each sample's reading and gravity */
struct kept {
	double m[MAGN_FIELD_KEEP][3];
	double g[MAGN_FIELD_KEEP][3];
};

/*
 * The file's contents: the count since the last fit, then @fit's store;
 * -ENOMEM leaves the file as it was; a failed write (a full disk) is an
 * error, never a store silently cut short
 */
static int write_store(int fd, unsigned int fresh,
		       const struct magcal_session *fit)
{
	struct kept *k = malloc(sizeof(*k));
	unsigned int n, i;
	int ret = 0;
	FILE *out;

	if (!k) {
		close(fd);
		return -ENOMEM;
	}
	n = magcal_export(fit, k->m, k->g, MAGN_FIELD_KEEP);
	out = fdopen(fd, "w");
	if (!out) {
		ret = -errno;
		close(fd);
		free(k);
		return ret;
	}
	if (ftruncate(fd, 0) || lseek(fd, 0, SEEK_SET)) {
		ret = -errno;
	} else {
		fprintf(out, "#%u\n", fresh);
		for (i = 0; i < n; i++)
			fprintf(out, "%.3f %.3f %.3f %.0f %.0f %.0f\n",
				k->m[i][0], k->m[i][1], k->m[i][2], k->g[i][0],
				k->g[i][1], k->g[i][2]);
		if (ferror(out))
			ret = -EIO;
	}
	if (fclose(out) && !ret)	/* and the lock */
		ret = -EIO;
	free(k);

	return ret;
}

int magn_field_store_sample(const char *path, const double m[3],
			    const double a[3], struct magcal_session *fit,
			    char *err, size_t errlen)
{
	char *text = malloc(FILE_MAX + 1), *p;
	unsigned int fresh = 0;
	int fd, ret = 0;
	ssize_t len;

	if (!text) {
		snprintf(err, errlen, "out of memory");
		return -ENOMEM;
	}
	/* never through a link, never blocking on a FIFO put there */
	/* the samples are data: a loose file of ours is tightened, never replaced */
	fd = lock_file_open(path, 0600, false, err, errlen);
	if (fd < 0) {
		free(text);
		return fd;
	}
	/*
	 * Only a file of our own that nobody else may write: next to a
	 * socket in a shared directory another user could have planted it
	 * to steer the fit or have us write into their file.
	 */
	if (!samples_file_trusted(fd)) {
		snprintf(err, errlen, "%.300s: not a regular file of ours, mode 0600: refused, nothing stored",
			 path);
		close(fd);
		free(text);
		return -EPERM;
	}
	ret = lock_file_wait(fd, MAGN_FIELD_LOCK_MS);
	if (ret) {
		snprintf(err, errlen, "%.300s: not locked within %u ms: %s; this sample is not stored",
			 path, MAGN_FIELD_LOCK_MS, strerror(-ret));
		close(fd);
		free(text);
		return ret;
	}
	len = read(fd, text, FILE_MAX);
	if (len < 0)
		len = 0;
	text[len] = '\0';
	/* the first line counts the samples since the last fit */
	p = text;
	if (*p == '#') {
		fresh = (unsigned int)strtoul(p + 1, NULL, 10);
		p = strchr(p, '\n');
		p = p ? p + 1 : text + len;
	}
	/*
	 * The store as it was, then the new sample: kept by direction
	 * (magcal's store), so a long time in one posture replaces samples
	 * of that posture, not the directions covered before
	 */
	replay(p, fit);
	magcal_add(fit, m, a);
	if (++fresh >= MAGN_FIELD_FIT_EVERY) {
		fresh = 0;
		ret = 1;
	}
	free(text);
	fd = write_store(fd, fresh, fit);
	if (fd) {
		snprintf(err, errlen, "%.300s: cannot be rewritten: %s; the stored samples may be lost",
			 path, strerror(-fd));
		return fd;
	}

	return ret;
}

/* A good fit that changes the record enough: stored and applied */
static int maybe_store(const struct cli_opts *o, struct calib_record *rec,
		       const struct magcal_result *r, const char *accel)
{
	char err[RECORD_STORE_ERR_LEN];
	struct calib_magn next;
	struct record_store s;
	int64_t now = (int64_t)time(NULL);
	int ret;

	/* a consumer's samples: one measurement each */
	if (!magn_session_done(r, false) ||
	    magn_session_to_record(r, now, &next, err, sizeof(err)) ||
	    !magn_field_should_replace(&rec->magn, &next, now))
		return 0;
	/* someone else changing the record now: the next fit tries again */
	if (record_store_open(&s, o->record_path,
			      RECORD_STORE_LOCK | RECORD_STORE_LOAD, 0))
		return 0;
	*rec = s.rec;
	if (!magn_field_should_replace(&rec->magn, &next, now)) {
		record_store_close(&s);
		return 0;
	}
	rec->magn = next;
	ret = record_store_replace(&s, rec, true, err, sizeof(err));
	record_store_close(&s);
	if (ret) {
		fprintf(stderr, "as9888-calibd: field mode: cannot store the magnetometer calibration: %s\n",
			err);
		return ret;
	}
	/* the daemon's log (the journal), and the client */
	dprintf(o->log_fd >= 0 ? o->log_fd : STDERR_FILENO,
		"as9888-calibd: field mode: magnetometer calibration refined (hard iron %.3f %.3f %.3f uT, residual %.3f uT) and stored in %s (the sample that completed the fit from %s)\n",
		next.hard_iron_nt[0] / 1000.0, next.hard_iron_nt[1] / 1000.0,
		next.hard_iron_nt[2] / 1000.0, next.residual_nt / 1000.0,
		o->record_path, o->requester ? o->requester : "this command");
	printf("stored in %s\n", o->record_path);

	/* the magnetometer's part, on this chip: the accelerometer's is as it was */
	return *accel ? iio_apply_magn_checked(accel, rec, o->record_path) : 0;
}

int cmd_magn_feed(const struct cli_opts *o)
{
	char path[PATH_MAX], accel[IIO_PATH_MAX], err[RECORD_STORE_ERR_LEN];
	double s[AS9888_AXES], m[AS9888_AXES];
	struct magcal_session *fit;
	struct magn_driver_cal d;
	struct magcal_config cfg;
	struct magcal_result r;
	struct record_store st;
	struct calib_record rec;
	int i, ret;

	if (!o->magn_feed)
		return EXIT_FAILURE;
	if (record_store_open(&st, o->record_path, RECORD_STORE_LOAD, 0))
		return EXIT_FAILURE;
	rec = st.rec;
	driver_state(&rec, &d, accel, sizeof(accel));
	magn_scale_ut(rec.eeprom, s);
	for (i = 0; i < AS9888_AXES; i++)
		m[i] = magn_uncorrect_driver(&d, i, o->magn_feed[i], s[i]);
	/* a calibration given the site's field keeps it through refinements */
	magcal_config_default(&cfg);
	cfg.reference_field_ut = magn_field_reference_ut(&rec.magn);
	fit = magcal_new(&cfg);
	if (!fit && cfg.reference_field_ut) {
		cfg.reference_field_ut = 0;
		fit = magcal_new(&cfg);
	}
	if (!fit) {
		fprintf(stderr, "as9888-calibd: magn-feed: out of memory\n");
		return EXIT_FAILURE;
	}
	samples_path(o, path, sizeof(path));
	ret = magn_field_store_sample(path, m, o->magn_feed + AS9888_AXES, fit,
				      err, sizeof(err));
	if (ret < 0)
		fprintf(stderr, "as9888-calibd: magn-feed: %s\n", err);
	if (ret == 1 && !magcal_solve(fit, &r)) {
		printf("fit: %s, coverage %.0f%%, residual %.3f uT\n",
		       magcal_status_str(r.status), 100 * r.coverage,
		       r.residual_ut);
		ret = maybe_store(o, &rec, &r, accel);
	}
	magcal_free(fit);

	return ret < 0 ? EXIT_FAILURE : EXIT_SUCCESS;
}
