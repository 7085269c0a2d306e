// SPDX-License-Identifier: GPL-2.0
/*
 * The commands of the factory line and of boot: factory-test, restore and
 * show.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "ftest_print.h"
#include "iio.h"
#include "remedy.h"
#include "session.h"
#include "show.h"

/* --junit FILE: opened before the test, so that a bad path costs no unit */
static FILE *open_junit(const char *path)
{
	FILE *f = fopen(path, "we");

	if (!f)
		fprintf(stderr, "as9888-calibd: cannot write %s: %s; nothing done\n",
			path, strerror(errno));
	return f;
}

/* The JUnit report into @f, closed; false (said) when it could not be written */
static bool write_junit(FILE *f, const char *path, const struct ftest_result *res)
{
	bool ok;

	ftest_print_junit(f, res);
	ok = !ferror(f);
	ok = !fclose(f) && ok;
	if (!ok)
		fprintf(stderr, "as9888-calibd: cannot write %s\n", path);

	return ok;
}

int cmd_factory_test(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	bool stored = false, junit_ok = true;
	FILE *junit = NULL;
	int ret;

	if (o->junit_path && !(junit = open_junit(o->junit_path)))
		return EXIT_FAILURE;
	if (session_lock(o->record_path, o->lock_timeout_s) < 0 ||
	    session_run_test(o, &o->ftest, &res)) {
		if (junit)
			fclose(junit);
		return EXIT_FAILURE;
	}

	if (res.have_calibration && !report_first_failure(&res.report))
		stored = session_store_result(o, &res, false);

	if (junit)
		junit_ok = write_junit(junit, o->junit_path, &res);
	if (o->json) {
		ftest_print_json(stdout, &res, o->record_path, stored);
	} else {
		ftest_print_text(stdout, &res);
		if (stored)
			printf("Record written to %s\n", o->record_path);
	}
	ret = report_first_failure(&res.report) || res.report.oom || !junit_ok ?
	      EXIT_FAILURE : EXIT_SUCCESS;
	ftest_result_free(&res);

	return ret;
}

/* Through the driver: the record's DAC and calibration into its attributes */
static int restore_iio(const struct cli_opts *o)
{
	char dir[IIO_PATH_MAX];

	if (iio_find_device(NULL, dir, sizeof(dir))) {
		fprintf(stderr, "as9888-calibd: restore: no %s IIO device; nothing applied: " REMEDY_NO_DRIVER "\n",
			IIO_ACCEL_NAME);
		return EXIT_FAILURE;
	}
	if (iio_restore(o->record_path, dir, false))
		return EXIT_FAILURE;
	if (o->verbose)
		printf("restored %s to %s\n", o->record_path, dir);

	return EXIT_SUCCESS;
}

int cmd_restore(const struct cli_opts *o)
{
	struct calib_record rec;

	if (o->backend == CLI_BACKEND_NONE) {
		fprintf(stderr, "as9888-calibd: restore: %s\n", o->backend_why);
		return EXIT_FAILURE;
	}
	if (session_load_record(o->record_path, &rec))
		return EXIT_FAILURE;
	if (rec.simulated && o->backend != CLI_BACKEND_SIM) {
		fprintf(stderr, "as9888-calibd: restore: %s was written by a factory test on the simulator (source = simulator), not on this chip: a simulated calibration is never applied to a real one (--backend %s). Run factory-test on this unit; nothing applied\n",
			o->record_path, cli_backend_name(o->backend));
		return EXIT_FAILURE;
	}
	if (o->backend == CLI_BACKEND_IIO)
		return restore_iio(o);
	if (session_apply_record(o, &rec))
		return EXIT_FAILURE;
	if (o->verbose)
		printf("restored DAC 0x%02x 0x%02x 0x%02x on chip %016llx\n",
		       rec.dac[0], rec.dac[1], rec.dac[2],
		       (unsigned long long)record_fingerprint(rec.eeprom));

	return EXIT_SUCCESS;
}

int cmd_show(const struct cli_opts *o)
{
	struct calib_record rec;
	struct show_result s;
	char err[SESSION_ERR_LEN];

	if (session_load_record(o->record_path, &rec))
		return EXIT_FAILURE;
	if (show_compute(&rec, o->temperature_given, o->temperature_mdegc, &s,
			 err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: show: %s\n", err);
		return EXIT_FAILURE;
	}
	if (o->json)
		show_print_json(stdout, &rec, &s);
	else
		show_print_text(stdout, &rec, &s);

	return EXIT_SUCCESS;
}

