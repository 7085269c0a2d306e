// SPDX-License-Identifier: GPL-2.0
/*
 * What every command needs: the backend the command line names, and the
 * calibration record read and written safely.
 */
#include <errno.h>
#include <fcntl.h>
#include <unistd.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "atomic_file.h"
#include "backend_raw.h"
#include "backend_sim.h"
#include "ftest.h"
#include "iio_cal.h"
#include "lock_file.h"
#include "record_pair.h"
#include "remedy.h"
#include "session.h"
#include "storage_trust.h"

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
 * Who may have written the record's files (storage_trust.h): the one
 * policy of the process, set from its command line before any command.
 */
static struct storage_trust trust;

int session_trust_setup(const char *state_group, char *err, size_t errlen)
{
	return storage_trust_init(&trust, state_group, err, errlen);
}

/*
 * "as9888-calibd: @err", followed by what to do about @errnum met on the
 * record's files, if there is a remedy for it
 */
static void print_with_remedy(const char *err, int errnum)
{
	const char *remedy = remedy_record(errnum);

	fprintf(stderr, "as9888-calibd: %s%s%s\n", err, remedy ? ": " : "",
		remedy ? remedy : "");
}

long session_read_record(const char *path, struct calib_record *rec, char *buf)
{
	char err[SESSION_ERR_LEN];
	struct stat st;
	long len;

	len = read_file_nofollow_stat(path, buf, RECORD_MAX_SIZE, &st, err,
				      sizeof(err));
	if (len == -ENOENT) {
		fprintf(stderr, "as9888-calibd: %s: %s\n", err, REMEDY_NO_RECORD);
		return len;
	}
	if (len < 0) {
		print_with_remedy(err, (int)-len);
		return len;
	}
	if (storage_trust_parent(&trust, path, err, sizeof(err)) ||
	    storage_trust_file(&trust, path, &st, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return -EPERM;
	}
	if (record_parse(buf, (size_t)len, rec, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s: not a valid record: %s\n", path,
			err);
		return -EINVAL;
	}

	return len;
}

int session_load_record(const char *path, struct calib_record *rec)
{
	char buf[RECORD_MAX_SIZE];
	long len = session_read_record(path, rec, buf);

	return len < 0 ? (int)len : 0;
}

/* 9999-12-31T23:59:59Z: the record's "created" has four digits for the year */
#define LAST_RECORD_TIME	253402300799LL

/*
 * Write @rec (stamped now) to @path crash-safely. With @keep_previous, the
 * record at @path is first saved as <path>.previous, so that a bad
 * recalibration can be rolled back.
 */
int session_save_record(const char *path, struct calib_record *rec,
			bool keep_previous, char *err, size_t errlen)
{
	char buf[RECORD_MAX_SIZE], old[RECORD_MAX_SIZE];
	long old_len;
	int len, ret;

	struct calib_record check;
	char why[256];

	rec->created = (int64_t)time(NULL);
	len = record_format(rec, buf, sizeof(buf));
	if (len < 0) {
		snprintf(err, errlen, "cannot format the record: %s", strerror(-len));
		return len;
	}
	/* what show, restore and rollback would refuse is never saved */
	if (record_parse(buf, (size_t)len, &check, why, sizeof(why))) {
		snprintf(err, errlen, "cannot make a valid record (%s)%s; nothing written",
			 why, rec->created < 0 || rec->created > LAST_RECORD_TIME ?
			 ": the system clock is outside 1970-9999, set it first" : "");
		return -EINVAL;
	}
	ret = ensure_parent_dir(path, STATE_DIR_MODE, err, errlen);
	if (ret)
		return ret;

	if (!keep_previous)
		return atomic_write_file(path, buf, (size_t)len, RECORD_MODE, err,
					 errlen);
	old_len = read_file_nofollow(path, old, sizeof(old), err, errlen);
	if (old_len < 0)
		return (int)old_len;

	return record_pair_replace(path, buf, (size_t)len, old, (size_t)old_len,
				   RECORD_MODE, err, errlen);
}

/* A change of the record and its previous one that was cut short: finished or undone */
static int recover(const char *path)
{
	enum record_pair_recovery what;
	char err[SESSION_ERR_LEN];
	int ret;

	ret = record_pair_recover(path, &trust, &what, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);
	else if (what == RECORD_PAIR_UNDONE)
		fprintf(stderr, "as9888-calibd: %s: an interrupted change was undone; %s%s is as before it\n",
			path, path, RECORD_PAIR_PREVIOUS);
	else if (what == RECORD_PAIR_FINISHED)
		fprintf(stderr, "as9888-calibd: %s: an interrupted change was finished; %s%s now holds the record it replaced\n",
			path, path, RECORD_PAIR_PREVIOUS);

	return ret;
}

/*
 * Before anything is measured or written: @path can hold a record (a
 * regular file or nothing yet) in a directory that exists or can be made,
 * is not a symbolic link, and nobody else could have written.
 */
static int check_record_path(const char *path, char *err, size_t errlen)
{
	struct stat st;
	int ret;

	if (!lstat(path, &st) && !S_ISREG(st.st_mode)) {
		snprintf(err, errlen, "%s is %s, not a record: give --record a path for a regular file",
			 path, S_ISLNK(st.st_mode) ? "a symbolic link" :
			 S_ISDIR(st.st_mode) ? "a directory" : "a device, FIFO or socket");
		return -EINVAL;
	}
	ret = ensure_parent_dir(path, STATE_DIR_MODE, err, errlen);
	if (!ret)
		ret = storage_trust_parent(&trust, path, err, errlen);

	return ret;
}

static int check_lock(const char *lock, int fd, char *err, size_t errlen)
{
	struct stat st;

	if (fstat(fd, &st)) {
		int ret = -errno;

		snprintf(err, errlen, "cannot examine lock %.256s: %s", lock,
			 strerror(-ret));
		return ret;
	}

	return storage_trust_file(&trust, lock, &st, err, errlen);
}

/* A lock found replaced after it was taken is opened again this often at most */
#define LOCK_REOPEN_TRIES	4

/* Open <@path>.lock, checked and trusted; the fd or -errno (said) */
static int open_lock(const char *path, char *lock, size_t size)
{
	char err[SESSION_ERR_LEN];
	int fd, ret;

	ret = check_record_path(path, err, sizeof(err));
	if (!ret && snprintf(lock, size, "%s%s", path, SESSION_LOCK_SUFFIX) >=
		    (int)size) {
		snprintf(err, sizeof(err), "record path %s is too long", path);
		ret = -ENAMETOOLONG;
	}
	fd = ret ? ret : lock_file_open(lock, LOCK_MODE, true, err, sizeof(err));
	if (fd >= 0 && (ret = check_lock(lock, fd, err, sizeof(err)))) {
		close(fd);
		fd = ret;
	}
	if (fd < 0)
		print_with_remedy(err, -fd);

	return fd;
}

/*
 * <@path>.lock taken (waiting up to @timeout_s with @wait, saying so) and
 * an interrupted change recovered: the fd, -EWOULDBLOCK (silent) when
 * another holds it and we do not @wait, or -errno (said)
 */
static int take_lock(const char *path, bool wait, unsigned int timeout_s)
{
	char lock[PATH_MAX];
	unsigned int tries = 0;
	int fd, ret;

again:
	fd = open_lock(path, lock, sizeof(lock));
	if (fd < 0)
		return fd;
	ret = lock_file_try(fd);
	if (ret == -EWOULDBLOCK && wait) {
		fprintf(stderr, "as9888-calibd: %s is held by another command; waiting up to %u s\n",
			lock, timeout_s);
		ret = lock_file_wait(fd, timeout_s * 1000);
	}
	if (ret == -ETIMEDOUT)
		fprintf(stderr, "as9888-calibd: %s is still held after %u s: another as9888-calibd command is running, or some process holds it (fuser -v %s shows which); nothing done\n",
			lock, timeout_s, lock);
	else if (ret && ret != -EWOULDBLOCK)
		fprintf(stderr, "as9888-calibd: cannot lock %s: %s\n", lock,
			strerror(-ret));
	/* the file was replaced (a loose lock made private) while we waited */
	if (!ret && !lock_file_current(fd, lock)) {
		close(fd);
		if (++tries < LOCK_REOPEN_TRIES)
			goto again;
		fprintf(stderr, "as9888-calibd: %s keeps being replaced while it is locked: remove it\n",
			lock);
		return -EBUSY;
	}
	if (!ret)
		ret = recover(path);
	if (ret) {
		close(fd);
		return ret;
	}

	return fd;
}

/*
 * Commands that change the record take <path>.lock exclusively, so two of
 * them (a factory run and a recalibration, two recalibrations) never
 * interleave their writes; the second waits for the first, up to
 * @timeout_s, saying that it waits.
 */
int session_lock(const char *path, unsigned int timeout_s)
{
	return take_lock(path, true, timeout_s);
}

int session_recover_now(const char *path)
{
	int fd = take_lock(path, false, 0);

	if (fd == -EWOULDBLOCK)
		return 0;	/* its holder has recovered */
	if (fd >= 0)
		close(fd);

	return fd < 0 ? fd : 0;
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
int session_activate_record(const struct cli_opts *o,
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
bool session_store_result(const struct cli_opts *o, struct ftest_result *res,
			  bool keep_previous)
{
	char err[SESSION_ERR_LEN];
	int ret;

	ret = session_save_record(o->record_path, &res->rec, keep_previous, err,
				  sizeof(err));
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

/*
 * The command layer's restore through the driver: load the record at
 * @record_path and apply it to the device at @dir (iio_apply_checked()).
 * Here, not in iio.c, so that the driver's sysfs layer does not depend on
 * the commands' record handling.
 */
static int restore(const char *record_path, const char *dir,
		   bool allow_simulated, bool one_device)
{
	struct calib_record rec;

	if (session_load_record(record_path, &rec))
		return -EINVAL;
	if (rec.simulated && !allow_simulated) {
		fprintf(stderr, "as9888-calibd: %s was written by a factory test on the simulator (source = simulator), not on this chip: a simulated calibration is never applied to a real one. Run factory-test on this unit; nothing applied\n",
			record_path);
		return -EPERM;
	}

	return one_device ? iio_apply_device(dir, &rec, record_path) :
			    iio_apply_checked(dir, &rec, record_path);
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
