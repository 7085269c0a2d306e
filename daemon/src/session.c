// SPDX-License-Identifier: GPL-2.0
/*
 * What every command needs: the backend the command line names, and the
 * calibration record read and written safely.
 */
#include <errno.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "atomic_file.h"
#include "backend_raw.h"
#include "backend_sim.h"
#include "ftest.h"
#include "session.h"

int session_open_backend(const struct cli_opts *o, struct transport **t)
{
	struct backend_sim_opts sim = {
		.unit_path = o->unit_path,
		.virtual_clock = o->virtual_clock,
	};
	char err[SESSION_ERR_LEN];
	int ret;

	if (o->backend == CLI_BACKEND_IIO) {
		snprintf(err, sizeof(err),
			 "the test engine needs register access: --backend sim or raw (the driver-backed engine is not written yet)");
		ret = -EOPNOTSUPP;
	} else if (o->backend == CLI_BACKEND_RAW)
		ret = backend_raw_open(&o->raw, t, err, sizeof(err));
	else
		ret = backend_sim_open(&sim, t, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);

	return ret;
}

int session_load_record(const char *path, struct calib_record *rec)
{
	char buf[RECORD_MAX_SIZE + 1], err[SESSION_ERR_LEN];
	long len;

	len = read_file_nofollow(path, buf, RECORD_MAX_SIZE, err, sizeof(err));
	if (len < 0) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return (int)len;
	}
	if (record_parse(buf, (size_t)len, rec, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s: not a valid record: %s\n", path,
			err);
		return -EINVAL;
	}

	return 0;
}

/*
 * Write @rec (stamped now) to @path crash-safely. With @keep_previous, the
 * record at @path is first saved as <path>.previous, so that a bad
 * recalibration can be rolled back.
 */
int session_save_record(const char *path, struct calib_record *rec,
			bool keep_previous, char *err, size_t errlen)
{
	char buf[RECORD_MAX_SIZE], old[RECORD_MAX_SIZE], prev[PATH_MAX];
	long old_len;
	int len, ret;

	rec->created = (int64_t)time(NULL);
	len = record_format(rec, buf, sizeof(buf));
	if (len < 0) {
		snprintf(err, errlen, "cannot format the record: %s", strerror(-len));
		return len;
	}
	ret = ensure_parent_dir(path, STATE_DIR_MODE, err, errlen);
	if (ret)
		return ret;

	if (keep_previous) {
		old_len = read_file_nofollow(path, old, sizeof(old), err, errlen);
		if (old_len < 0)
			return (int)old_len;
		if (snprintf(prev, sizeof(prev), "%s%s", path,
			     SESSION_PREVIOUS_SUFFIX) >= (int)sizeof(prev)) {
			snprintf(err, errlen, "record path too long");
			return -ENAMETOOLONG;
		}
		ret = atomic_write_file(prev, old, (size_t)old_len, RECORD_MODE,
					err, errlen);
		if (ret)
			return ret;
	}

	return atomic_write_file(path, buf, (size_t)len, RECORD_MODE, err, errlen);
}

/*
 * Commands that change the record take <path>.lock exclusively, so two of
 * them (a factory run and a recalibration, two recalibrations) never
 * interleave their writes; the second waits for the first.
 */
int session_lock(const char *path)
{
	char lock[PATH_MAX], err[SESSION_ERR_LEN];
	int fd, ret;

	ret = ensure_parent_dir(path, STATE_DIR_MODE, err, sizeof(err));
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return ret;
	}
	snprintf(lock, sizeof(lock), "%s.lock", path);
	fd = open(lock, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, RECORD_MODE);
	if (fd < 0 || flock(fd, LOCK_EX)) {
		ret = -errno;
		fprintf(stderr, "as9888-calibd: cannot lock %s: %s\n", lock,
			strerror(errno));
		if (fd >= 0)
			close(fd);
		return ret;
	}

	return fd;
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
		fprintf(stderr, "as9888-calibd: %s belongs to chip %016llx, this chip is %016llx; nothing applied\n",
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
