// SPDX-License-Identifier: GPL-2.0
/*
 * The commands of the factory line and of boot: factory-test, restore and
 * show.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "store/atomic_file.h"
#include "commands/commands.h"
#include "ftest/ftest_print.h"
#include "chip/iio.h"
#include "common/remedy.h"
#include "commands/session.h"
#include "commands/show.h"

/* The mode of a JUnit report: it holds nothing secret */
#define JUNIT_MODE	0644
/* What a file must start with to be taken as an older report and replaced */
#define JUNIT_MAGIC	"<?xml"

/*
 * --junit FILE, checked and begun before the test, so that a bad path
 * costs no unit: written as the record is (atomic_file.h: never through a
 * symbolic link, a temporary file renamed over it), and an existing FILE
 * is replaced only when it is a regular file with one link that starts as
 * an XML document does (an older report), never some other file a script
 * named by mistake. 0, or -errno said on stderr.
 */
static int begin_junit(const char *path, struct atomic_pending *p)
{
	char head[sizeof(JUNIT_MAGIC) - 1], err[512];
	struct stat st = { 0 };
	ssize_t n = 0;
	int fd, ret = 0;

	fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
	if (fd < 0 && errno == ELOOP) {
		snprintf(err, sizeof(err), "%s is a symbolic link: not followed; give the report's own path",
			 path);
		ret = -ELOOP;
	} else if (fd < 0 && errno != ENOENT) {
		snprintf(err, sizeof(err), "cannot open %s: %s", path, strerror(errno));
		ret = -errno;
	} else if (fd >= 0) {
		if (!fstat(fd, &st) && S_ISREG(st.st_mode))
			n = read(fd, head, sizeof(head));
		if (fstat(fd, &st) || !S_ISREG(st.st_mode) || st.st_nlink != 1 ||
		    n != (ssize_t)sizeof(head) || memcmp(head, JUNIT_MAGIC, sizeof(head))) {
			snprintf(err, sizeof(err), "%s exists and is not a JUnit report (%s): not replaced; remove it or give another path",
				 path, !S_ISREG(st.st_mode) ? "not a regular file" :
				 st.st_nlink != 1 ? "it has other hard links" :
				 "it does not start with " JUNIT_MAGIC);
			ret = -EEXIST;
		}
		close(fd);
	}
	if (!ret)
		ret = atomic_begin(p, path, JUNIT_MODE, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: cannot write the JUnit report: %s; nothing done\n",
			err);

	return ret;
}

/* The JUnit report into @p; false (said) when it could not be written */
static bool write_junit(struct atomic_pending *p, const char *path,
			const struct ftest_result *res)
{
	char *buf = NULL, err[512];
	size_t len = 0;
	FILE *f;
	bool ok;

	f = open_memstream(&buf, &len);
	if (f) {
		ftest_print_junit(f, res);
		ok = !ferror(f);
		ok = !fclose(f) && ok;
	} else {
		ok = false;
	}
	if (!ok) {
		snprintf(err, sizeof(err), "out of memory");
		atomic_abort(p);
	} else {
		ok = !atomic_commit(p, buf, len, err, sizeof(err));
	}
	if (!ok)
		fprintf(stderr, "as9888-calibd: cannot write %s: %s\n", path, err);
	free(buf);

	return ok;
}

int cmd_factory_test(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	bool stored = false, junit_ok = true;
	struct atomic_pending junit;
	struct record_store s;
	int ret;

	if (o->junit_path && begin_junit(o->junit_path, &junit))
		return EXIT_FAILURE;
	if (record_store_open(&s, o->record_path, RECORD_STORE_LOCK,
			      o->lock_timeout_s) ||
	    session_run_test(o, &o->ftest, &res)) {
		if (o->junit_path)
			atomic_abort(&junit);
		return EXIT_FAILURE;
	}

	if (res.have_calibration && !report_first_failure(&res.report))
		stored = session_store_result(o, &s, &res, false);
	record_store_close(&s);

	if (o->junit_path)
		junit_ok = write_junit(&junit, o->junit_path, &res);
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
static int restore_iio(const struct cli_opts *o, const struct record_store *s)
{
	char dir[IIO_PATH_MAX];

	if (o->device) {
		if (session_restore_iio(s, o->device, true))
			return EXIT_FAILURE;
		if (o->verbose)
			printf("restored %s to %s\n", o->record_path, o->device);
		return EXIT_SUCCESS;
	}
	if (iio_find_device(NULL, dir, sizeof(dir))) {
		fprintf(stderr, "as9888-calibd: restore: no %s IIO device; nothing applied: " REMEDY_NO_DRIVER "\n",
			IIO_ACCEL_NAME);
		return EXIT_FAILURE;
	}
	if (session_restore_iio(s, dir, false))
		return EXIT_FAILURE;
	if (o->verbose)
		printf("restored %s to %s\n", o->record_path, dir);

	return EXIT_SUCCESS;
}

int cmd_restore(const struct cli_opts *o)
{
	struct record_store s;
	const struct calib_record *rec = &s.rec;

	if (o->backend == CLI_BACKEND_NONE) {
		fprintf(stderr, "as9888-calibd: restore: %s\n", o->backend_why);
		return EXIT_FAILURE;
	}
	/* a .magn that cannot be used (said) stops only the magnetometer's part */
	if (record_store_open(&s, o->record_path,
			      RECORD_STORE_LOAD | RECORD_STORE_MAGN_OPTIONAL, 0))
		return EXIT_FAILURE;
	if (rec->simulated && o->backend != CLI_BACKEND_SIM) {
		fprintf(stderr, "as9888-calibd: restore: %s was written by a factory test on the simulator (source = simulator), not on this chip: a simulated calibration is never applied to a real one (--backend %s). Run factory-test on this unit; nothing applied\n",
			o->record_path, cli_backend_name(o->backend));
		return EXIT_FAILURE;
	}
	if (o->backend == CLI_BACKEND_IIO)
		return restore_iio(o, &s);
	/* the chip's registers take the accelerometer's part alone */
	if (session_apply_record(o, rec))
		return EXIT_FAILURE;
	if (o->verbose)
		printf("restored DAC 0x%02x 0x%02x 0x%02x on chip %016llx\n",
		       rec->dac[0], rec->dac[1], rec->dac[2],
		       (unsigned long long)record_fingerprint(rec->eeprom));

	return EXIT_SUCCESS;
}

int cmd_show(const struct cli_opts *o)
{
	struct record_store st;
	const struct calib_record *rec = &st.rec;
	struct show_result s;
	char err[SESSION_ERR_LEN];

	if (record_store_open(&st, o->record_path, RECORD_STORE_LOAD, 0))
		return EXIT_FAILURE;
	if (show_compute(rec, o->temperature_given, o->temperature_mdegc, &s,
			 err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: show: %s\n", err);
		return EXIT_FAILURE;
	}
	if (o->json)
		show_print_json(stdout, rec, &s);
	else
		show_print_text(stdout, rec, &s);

	return EXIT_SUCCESS;
}

