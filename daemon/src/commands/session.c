// SPDX-License-Identifier: GPL-2.0
/*
 * What every command needs besides the record store (record_store.h): the
 * backend the command line names, the factory test run on it, and a
 * record applied to the chip.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "chip/backend_raw.h"
#include "chip/backend_sim.h"
#include "ftest/ftest.h"
#include "chip/iio_cal.h"
#include "common/remedy.h"
#include "commands/session.h"

int session_open_backend(const struct cli_opts *o, struct transport **t)
{
	struct backend_sim_opts sim = {
		.unit_path = o->unit_path,
		.virtual_clock = o->virtual_clock,
	};
	char err[SESSION_ERR_LEN];
	int ret;

	if (o->backend == CLI_BACKEND_NONE) {
		fprintf(stderr, "as9888-calibd: %s\n", o->backend_why);
		return -ENODEV;
	}
	if (o->backend == CLI_BACKEND_IIO) {
		snprintf(err, sizeof(err),
			 "--backend iio has no register access: use sim or raw");
		ret = -EOPNOTSUPP;
	} else if (o->backend == CLI_BACKEND_RAW)
		ret = backend_raw_open(&o->raw, t, err, sizeof(err));
	else
		ret = backend_sim_open(&sim, t, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);

	return ret;
}

/*
 * Apply @rec to the chip behind the command's backend: step 1 of the
 * application note with the record's DAC values loaded as trims, refused
 * before anything is written when the chip's EEPROM is not the record's.
 * The read-back of step 1 (D10) checks the DAC values too.
 */
int session_apply_record(const struct cli_opts *o, const struct calib_record *rec)
{
	struct ftest_result res = { 0 };
	const struct judgment *j;
	struct transport *t;
	struct ftest_opts f;
	int ret;

	if (session_open_backend(o, &t))
		return -ENODEV;
	ftest_opts_default(&f);
	f.expect_eeprom = rec->eeprom;
	f.apply_dac = rec->dac;
	ret = ftest_step1(t, &f, &res);
	transport_destroy(t);

	j = report_first_failure(&res.report);
	if (ret == -ENODEV && res.have_eeprom)
		fprintf(stderr, "as9888-calibd: %s belongs to chip %016llx, this chip is %016llx; nothing applied: " REMEDY_OTHER_CHIP "\n",
			o->record_path,
			(unsigned long long)record_fingerprint(rec->eeprom),
			(unsigned long long)record_fingerprint(res.ee.raw));
	else if (ret || j)
		fprintf(stderr, "as9888-calibd: cannot apply the record: step %s (%s: %s); nothing applied\n",
			j ? j->step : "1", j ? j->name : "initialisation",
			j ? j->measured : strerror(-ret));
	ftest_result_free(&res);

	return ret ? ret : j ? -EIO : 0;
}

static int find_iio_device(const char *what, char *dir, size_t size)
{
	if (iio_find_device(NULL, dir, size)) {
		fprintf(stderr, "as9888-calibd: %s: no %s IIO device: " REMEDY_NO_DRIVER "\n",
			what, IIO_ACCEL_NAME);
		return -ENODEV;
	}

	return 0;
}

/*
 * Run the test on the command's backend: register access (sim, raw) or the
 * driver (iio).
 */
int session_run_test(const struct cli_opts *o, const struct ftest_opts *f,
		     struct ftest_result *res)
{
	char dir[IIO_PATH_MAX];
	struct transport *t;
	int ret;

	if (o->backend == CLI_BACKEND_IIO) {
		ret = find_iio_device("test", dir, sizeof(dir));
		res->backend = cli_backend_name(o->backend);
		if (!ret)
			ftest_run_iio(dir, f, res);
		return ret;
	}

	ret = session_open_backend(o, &t);
	if (ret)
		return ret;
	res->backend = cli_backend_name(o->backend);
	ftest_run(t, f, res);
	transport_destroy(t);
	/* a simulated chip's calibration is marked so: restore refuses it */
	res->rec.simulated = o->backend == CLI_BACKEND_SIM;

	return 0;
}

/*
 * A new record in effect: the register engine leaves its DAC values in the
 * chip, the driver gets the record written into its attributes.
 */
static int session_activate_record(const struct cli_opts *o,
				   const struct calib_record *rec)
{
	char dir[IIO_PATH_MAX];
	int ret;

	if (o->backend != CLI_BACKEND_IIO)
		return 0;
	ret = find_iio_device("apply", dir, sizeof(dir));

	return ret ? ret : iio_apply_record(dir, rec);
}

/* Step 4-1: store the record crash-safely, and put it in effect */
bool session_store_result(const struct cli_opts *o, struct record_store *s,
			  struct ftest_result *res, bool keep_previous)
{
	char err[SESSION_ERR_LEN];
	int ret;

	ret = record_store_replace(s, &res->rec, keep_previous, err, sizeof(err));
	if (!ret && session_activate_record(o, &res->rec)) {
		snprintf(err, sizeof(err),
			 "%s written but not applied to the device",
			 o->record_path);
		ret = -EIO;
	}
	report_add(&res->report, "4-1", "store calibration record",
		   ret ? JUDGMENT_FAIL : JUDGMENT_PASS, NULL, "%s",
		   ret ? err : o->record_path);

	return ret == 0;
}

/* Is @dir the accelerometer's IIO device? */
static bool is_accel(const char *dir)
{
	char name[IIO_ATTR_MAX];

	return iio_read_attr(dir, "name", name, sizeof(name)) >= 0 &&
	       !strcmp(name, IIO_ACCEL_NAME);
}

int session_restore_iio(const struct record_store *s, const char *dir,
			bool one_device)
{
	const char *what = s->p.record;
	int ret;

	if (!s->magn_err)
		return one_device ? iio_apply_device(dir, &s->rec, what) :
				    iio_apply_checked(dir, &s->rec, what);
	/* the accelerometer's part alone: the magnetometer is left as it is */
	if (one_device && !is_accel(dir)) {
		fprintf(stderr, "as9888-calibd: %s cannot be used (above): nothing applied to %s\n",
			s->p.magn, dir);
		return s->magn_err;
	}
	ret = iio_apply_device(dir, &s->rec, what);
	if (ret || one_device)
		return ret;
	fprintf(stderr, "as9888-calibd: the accelerometer's calibration is applied to %s; the magnetometer's is not (%s cannot be used, above): the magnetometer is left as it was\n",
		dir, s->p.magn);

	return s->magn_err;
}

/*
 * The command layer's restore through the driver: load the record at
 * @record_path and apply it to the device at @dir. Here, not in iio.c, so
 * that the driver's sysfs layer does not depend on the record store.
 */
static int restore(const char *record_path, const char *dir,
		   bool allow_simulated, bool one_device)
{
	struct record_store s;

	if (record_store_open(&s, record_path,
			      RECORD_STORE_LOAD | RECORD_STORE_MAGN_OPTIONAL, 0))
		return -EINVAL;
	if (s.rec.simulated && !allow_simulated) {
		fprintf(stderr, "as9888-calibd: %s was written by a factory test on the simulator (source = simulator), not on this chip: a simulated calibration is never applied to a real one. Run factory-test on this unit; nothing applied\n",
			record_path);
		return -EPERM;
	}

	return session_restore_iio(&s, dir, one_device);
}

int iio_restore(const char *record_path, const char *dir,
		bool allow_simulated)
{
	return restore(record_path, dir, allow_simulated, false);
}

int iio_restore_device(const char *record_path, const char *dir)
{
	return restore(record_path, dir, false, true);
}
