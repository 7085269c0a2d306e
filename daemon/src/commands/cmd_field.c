// SPDX-License-Identifier: GPL-2.0
/*
 * Field repair (application note, section 3: a strong shock can shift the
 * accelerometer offset): recalibrate on top of the factory record, roll a
 * recalibration back, and check whether one is advisable.
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands/commands.h"
#include "ftest/ftest_print.h"
#include "chip/iio.h"
#include "common/json.h"
#include "commands/session.h"

static void field_opts(const struct cli_opts *o, const struct calib_record *rec,
		       struct ftest_opts *f)
{
	*f = o->ftest;
	f->level_only = true;
	f->user_mode = true;
	f->expect_eeprom = rec->eeprom;
	f->apply_dac = rec->dac;
	if (!o->fluctuation_given)
		f->fluctuation = FTEST_USER_FLUCTUATION;
}

int cmd_recalibrate(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	struct record_store s;
	struct ftest_opts f;
	bool stored = false;
	int ret;

	if (record_store_open(&s, o->record_path,
			      RECORD_STORE_LOCK | RECORD_STORE_LOAD,
			      o->lock_timeout_s)) {
		if (s.len < 0)	/* the lock was taken: the record is what failed */
			fprintf(stderr, "as9888-calibd: recalibrate needs the factory record; run factory-test first\n");
		return EXIT_FAILURE;
	}
	field_opts(o, &s.rec, &f);
	if (session_run_test(o, &f, &res))
		return EXIT_FAILURE;

	/* the accelerometer is recalibrated; the magnetometer's calibration stays */
	res.rec.magn = s.rec.magn;
	if (res.have_calibration && !report_first_failure(&res.report))
		stored = session_store_result(o, &s, &res, true);
	record_store_close(&s);
	if (o->json) {
		ftest_print_json(stdout, &res, o->record_path, stored);
	} else {
		ftest_print_text(stdout, &res);
		if (stored)
			printf("Recalibrated; the previous calibration is kept as %s (as9888-calibd rollback)\n",
			       s.p.previous);
	}
	ret = report_first_failure(&res.report) ? EXIT_FAILURE : EXIT_SUCCESS;
	ftest_result_free(&res);

	return ret;
}

/*
 * Through the driver, after both pairs were swapped: the rolled-back
 * record applied, or the swaps undone (the pairs as they were) when the
 * device takes none or only part of it, and the record of before applied
 * again (a part taken is put back). 0 or -1, said on stderr.
 */
static int rollback_apply_iio(const struct cli_opts *o, struct record_store *s,
			      const struct record_rollback *r)
{
	char dir[IIO_PATH_MAX], err[SESSION_ERR_LEN];
	bool found = !iio_find_device(NULL, dir, sizeof(dir));

	if (found && !iio_restore(o->record_path, dir, false))
		return 0;
	if (record_store_rollback(s, r, true, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: rollback: the record is rolled back but not applied to the device, and could not be put back: %s\n",
			err);
		return -1;
	}
	if (found && session_restore_iio(s, dir, false))
		fprintf(stderr, "as9888-calibd: rollback: the device did not take %s; the record's files are as they were, and applying them again failed too (above)\n",
			s->p.previous);
	else
		fprintf(stderr, "as9888-calibd: rollback: the device did not take %s; nothing changed\n",
			s->p.previous);
	return -1;
}

/*
 * current := previous, previous := current, as one crash-safe change
 * (record_pair.h): never losing either; then the magnetometer's file
 * <path>.magn and its previous one the same way, when that is the
 * previous record's (record_store.h). On the raw and simulated chips the
 * previous record is applied first, so a chip it does not belong to leaves
 * the pair as it was; through the driver the restore reads the record
 * file, so the pair is swapped first and swapped back when the device
 * refuses it.
 */
int cmd_rollback(const struct cli_opts *o)
{
	static struct record_rollback r;
	char err[SESSION_ERR_LEN];
	struct record_store s;
	bool iio = o->backend == CLI_BACKEND_IIO;

	/* the magnetometer's pair is judged by the check */
	if (record_store_open(&s, o->record_path, RECORD_STORE_LOCK |
			      RECORD_STORE_LOAD | RECORD_STORE_MAGN_OPTIONAL,
			      o->lock_timeout_s) ||
	    record_store_rollback_check(&s, &r))
		return EXIT_FAILURE;
	/* its own message says "nothing applied"; the pair is untouched */
	if (!iio && session_apply_record(o, &r.before))
		return EXIT_FAILURE;
	if (record_store_rollback(&s, &r, false, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: rollback: %s\n", err);
		if (!iio && !session_apply_record(o, &s.rec))
			fprintf(stderr, "as9888-calibd: rollback: the chip runs %s again\n",
				o->record_path);
		return EXIT_FAILURE;
	}
	if (iio && rollback_apply_iio(o, &s, &r))
		return EXIT_FAILURE;
	record_store_close(&s);
	printf("Rolled back: %s holds the calibration from before the last recalibration\n",
	       o->record_path);
	if (r.magn)
		printf("Rolled back: %s holds the magnetometer's calibration from before the last change\n",
		       s.p.magn);
	return EXIT_SUCCESS;
}

/* Below this, a difference from the prediction is noise (Note 4b: 10 LSB ~ 2.2 degrees) */
#define CHECK_THRESHOLD_LSB	10.0

int cmd_check(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	struct as9888_eeprom ee;
	struct record_store s;
	struct calib_record rec;
	struct ftest_opts f;
	const struct judgment *j;
	int32_t ot_l[AS9888_AXES];
	double diff[AS9888_AXES], deg[AS9888_AXES], worst = 0.0;
	int axis, ret;

	if (record_store_open(&s, o->record_path, RECORD_STORE_LOAD, 0))
		return EXIT_FAILURE;
	rec = s.rec;
	field_opts(o, &rec, &f);
	f.measure_only = true;
	if (session_run_test(o, &f, &res))
		return EXIT_FAILURE;

	j = report_first_failure(&res.report);
	if (j || !res.have_level) {
		fprintf(stderr, "as9888-calibd: check: cannot measure: step %s (%s: %s)\n",
			j ? j->step : "3", j ? j->name : "level run",
			j ? j->measured : "no level data");
		ftest_result_free(&res);
		return EXIT_FAILURE;
	}

	as9888_eeprom_decode(rec.eeprom, &ee);
	ret = record_level_offsets(&rec, &ee, ot_l);
	for (axis = 0; !ret && axis < AS9888_AXES; axis++) {
		const struct as9888_axis_trim *trim = &ee.axis[axis];
		int32_t st, ot, predicted;

		ret = as9888_sensitivity_q16(trim, ee.t_rt_mdegc, res.level_t_mdegc, &st);
		if (!ret)
			ret = as9888_offset_q16(trim, ot_l[axis], rec.t_level_mdegc,
						res.level_t_mdegc, &ot);
		/* Ot = A + St G, so a level reading should be Ot - St G */
		if (!ret)
			ret = as9888_offset_level_q16(ot, st, -res.level_g[axis],
						      &predicted);
		if (ret)
			break;
		diff[axis] = ((int64_t)res.level_mean_q16[axis] - predicted) / 65536.0;
		deg[axis] = asin(fmin(1.0, fabs(diff[axis]) / (st / 65536.0))) *
			    180.0 / M_PI;
		if (fabs(diff[axis]) > worst)
			worst = fabs(diff[axis]);
	}
	ftest_result_free(&res);
	if (ret) {
		fprintf(stderr, "as9888-calibd: check: %s\n", strerror(-ret));
		return EXIT_FAILURE;
	}

	if (o->json) {
		printf("{\n  \"temperature\": %.3f,\n  \"advisable\": %s,\n  \"threshold\": %.1f,\n  \"axes\": {",
		       res.level_t_mdegc / 1000.0, worst > CHECK_THRESHOLD_LSB ? "true" : "false",
		       CHECK_THRESHOLD_LSB);
		for (axis = 0; axis < AS9888_AXES; axis++)
			printf("%s\n    \"%c\": {\"difference\": %.3f, \"degrees\": %.2f}",
			       axis ? "," : "", "xyz"[axis], diff[axis], deg[axis]);
		printf("\n  }\n}\n");
	} else {
		printf("At %.3f degC the level reading differs from the calibration by\n",
		       res.level_t_mdegc / 1000.0);
		for (axis = 0; axis < AS9888_AXES; axis++)
			printf("  %c  %+8.2f LSB  (%.2f degrees)\n", "XYZ"[axis],
			       diff[axis], deg[axis]);
		printf(worst > CHECK_THRESHOLD_LSB ?
		       "A recalibration is advisable (more than %.0f LSB): lay the device flat and run as9888-calibd recalibrate.\n" :
		       "No recalibration needed (within %.0f LSB).\n", CHECK_THRESHOLD_LSB);
	}

	return EXIT_SUCCESS;
}
