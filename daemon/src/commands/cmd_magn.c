// SPDX-License-Identifier: GPL-2.0
/*
 * The magnetometer's calibration: learned in an explicit session
 * (magn-calibrate) and shown (the daemon's "magn" request).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "commands/commands.h"
#include "chip/iio_cal.h"
#include "magn/magn_session.h"
#include "magn/magn_show.h"
#include "magn/magn_source.h"
#include "common/remedy.h"
#include "commands/session.h"

int cmd_magn_show(const struct cli_opts *o)
{
	struct record_store s;
	const struct calib_record *rec = &s.rec;

	if (record_store_open(&s, o->record_path, RECORD_STORE_LOAD, 0))
		return EXIT_FAILURE;
	if (!rec->magn.present) {
		fprintf(stderr, "as9888-calibd: %s has no magnetometer calibration (no %s with one, nor a format 2 record): run as9888-calibd magn-calibrate\n",
			o->record_path, s.p.magn);
		return EXIT_FAILURE;
	}
	if (o->json) {
		magn_show_json(stdout, rec, 0);
		fputc('\n', stdout);
	} else {
		magn_show_text(stdout, rec);
	}

	return EXIT_SUCCESS;
}

/* The command's sample source: the chip's registers, or the driver */
static int open_source(const struct cli_opts *o, const struct calib_record *rec,
		       struct magn_source **src, bool *driver, char *accel,
		       size_t accel_size)
{
	char magn[IIO_PATH_MAX], err[IIO_ERR_LEN];
	struct transport *t;
	int ret;

	*driver = o->backend == CLI_BACKEND_IIO;
	if (!*driver) {
		ret = session_open_backend(o, &t);
		if (ret)
			return ret;
		ret = magn_source_open_chip(t, rec, src, err, sizeof(err));
	} else if (iio_find_device(NULL, accel, accel_size)) {
		snprintf(err, sizeof(err), "no %s IIO device: " REMEDY_NO_DRIVER,
			 IIO_ACCEL_NAME);
		ret = -ENODEV;
	} else if (iio_find_magn(accel, magn, sizeof(magn), NULL, 0)) {
		snprintf(err, sizeof(err), "no %s IIO device beside %s: the driver registers none",
			 IIO_MAGN_NAME, accel);
		ret = -ENODEV;
	} else {
		ret = magn_source_open_iio(accel, magn, rec->eeprom, stdout,
					   src, err, sizeof(err));
	}
	if (ret)
		fprintf(stderr, "as9888-calibd: magn-calibrate: %s\n", err);

	return ret;
}

static void print_fit(const struct calib_magn *m, const struct magn_session_result *res)
{
	int i;

	printf("Magnetometer calibrated in %.1f s: %u samples used, %u rejected, coverage %.0f%%\n",
	       res->elapsed_ns / 1e9, res->fit.used, res->fit.rejected,
	       100 * res->fit.coverage);
	printf("  field %.3f uT, residual %.3f uT rms\n", m->field_nt / 1000.0,
	       m->residual_nt / 1000.0);
	if (res->fit.scale != 1)
		printf("  the site's field: the fit saw %.3f uT, W scaled by %.6f\n",
		       res->fit.fitted_field_ut, res->fit.scale);
	printf("  hard iron [uT] %.3f %.3f %.3f\n", m->hard_iron_nt[0] / 1000.0,
	       m->hard_iron_nt[1] / 1000.0, m->hard_iron_nt[2] / 1000.0);
	for (i = 0; i < AS9888_AXES; i++)
		printf("  %s %.6f %.6f %.6f\n", i ? "              " : "soft iron W  ",
		       m->soft_iron_micro[i][0] / 1e6, m->soft_iron_micro[i][1] / 1e6,
		       m->soft_iron_micro[i][2] / 1e6);
	/* the soft iron's turn against the accelerometer (magcal's judgment) */
	if (res->fit.turn_trusted)
		printf("  turn against the accelerometer %.2f deg (+-%.2f), stored: about (%.3f %.3f %.3f) deg\n",
		       res->fit.turn_deg, res->fit.turn_uncertainty_deg,
		       res->fit.turn[0], res->fit.turn[1], res->fit.turn[2]);
	else
		printf("  turn against the accelerometer not stored (identity): the motion does not determine it (uncertain by %.2f deg, more than 0.3: turned about one axis only?)\n",
		       res->fit.turn_uncertainty_deg);
}

int cmd_magn_calibrate(const struct cli_opts *o)
{
	struct magn_session_result res;
	char accel[IIO_PATH_MAX], err[SESSION_ERR_LEN];
	struct magn_source *src;
	struct record_store s;
	struct calib_record rec;
	bool driver;
	int ret;

	/* a .magn that cannot be used (said) is what this replaces */
	if (record_store_open(&s, o->record_path, RECORD_STORE_LOCK |
			      RECORD_STORE_LOAD | RECORD_STORE_MAGN_OPTIONAL,
			      o->lock_timeout_s)) {
		if (s.len < 0)	/* the lock was taken: the record is what failed */
			fprintf(stderr, "as9888-calibd: magn-calibrate adds to the record of factory-test (the chip's identity): run factory-test first\n");
		return EXIT_FAILURE;
	}
	rec = s.rec;
	if (rec.simulated && o->backend != CLI_BACKEND_SIM) {
		fprintf(stderr, "as9888-calibd: %s was written by a factory test on the simulator (source = simulator), not on this chip: run factory-test on this unit; nothing measured\n",
			o->record_path);
		return EXIT_FAILURE;
	}
	if (open_source(o, &rec, &src, &driver, accel, sizeof(accel)))
		return EXIT_FAILURE;
	printf("Turn the device slowly through every direction (a figure eight, then over on every side); at most %u s\n",
	       o->magn_timeout_s);
	fflush(stdout);
	ret = magn_session_run(src, (uint64_t)o->magn_timeout_s * 1000000000ULL,
			       o->magn_earth_nt / 1000.0, stdout, &res, err, sizeof(err));
	magn_source_close(src);
	if (ret == -ETIMEDOUT) {
		magn_session_why(&res, err, sizeof(err));
		fprintf(stderr, "as9888-calibd: magn-calibrate failed: %s; the record is unchanged\n",
			err);
		return EXIT_FAILURE;
	}
	if (ret) {
		fprintf(stderr, "as9888-calibd: magn-calibrate: %s; the record is unchanged\n",
			err);
		return EXIT_FAILURE;
	}
	if (magn_session_to_record(&res.fit, (int64_t)time(NULL), &rec.magn, err,
				   sizeof(err))) {
		fprintf(stderr, "as9888-calibd: magn-calibrate: the fit cannot be kept: %s; the record is unchanged\n",
			err);
		return EXIT_FAILURE;
	}
	print_fit(&rec.magn, &res);
	ret = record_store_replace(&s, &rec, true, err, sizeof(err));
	record_store_close(&s);
	if (ret) {
		fprintf(stderr, "as9888-calibd: magn-calibrate: cannot store the record: %s\n",
			err);
		return EXIT_FAILURE;
	}
	printf("Stored in %s; the previous record is kept as %s (as9888-calibd rollback)\n",
	       o->record_path, s.p.previous);
	/* through the driver: in effect now, as restore puts it at boot */
	if (driver && iio_apply_magn_checked(accel, &rec, o->record_path))
		return EXIT_FAILURE;
	if (driver)
		printf("Applied to the driver (in_magn_*_calibbias, in_magn_*_calibscale)\n");

	return EXIT_SUCCESS;
}
