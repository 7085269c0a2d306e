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

/* <@path>.magn into @file (PATH_MAX); 0 or -ENAMETOOLONG with why in @err */
static int magn_file(const char *path, char *file, char *err, size_t errlen)
{
	if (snprintf(file, PATH_MAX, "%s%s", path, RECORD_MAGN_SUFFIX) < PATH_MAX)
		return 0;
	snprintf(err, errlen, "record path %s is too long", path);
	return -ENAMETOOLONG;
}

/*
 * The magnetometer's file beside the record (<@path>.magn): when it is
 * there, @rec->magn is what it holds (believed as the record is, valid,
 * and of the record's chip); else the record's own (a format 2 record's
 * section, or none). 0 or -errno, said on stderr.
 */
static int read_magn_file(const char *path, struct calib_record *rec)
{
	char file[PATH_MAX], buf[RECORD_MAX_SIZE], err[SESSION_ERR_LEN];
	struct calib_magn m;
	struct stat st;
	uint64_t chip;
	long len;

	if (magn_file(path, file, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return -ENAMETOOLONG;
	}
	len = read_file_nofollow_stat(file, buf, RECORD_MAX_SIZE, &st, err,
				      sizeof(err));
	if (len == -ENOENT)
		return 0;
	if (len < 0) {
		print_with_remedy(err, (int)-len);
		return (int)len;
	}
	if (storage_trust_file(&trust, file, &st, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return -EPERM;
	}
	if (record_magn_parse(buf, (size_t)len, &m, &chip, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s: not a valid magnetometer calibration: %s\n",
			file, err);
		return -EINVAL;
	}
	if (chip != record_fingerprint(rec->eeprom)) {
		fprintf(stderr, "as9888-calibd: %s belongs to chip %016llx, %s to chip %016llx: remove it, then run magn-calibrate on this unit\n",
			file, (unsigned long long)chip, path,
			(unsigned long long)record_fingerprint(rec->eeprom));
		return -EINVAL;
	}
	rec->magn = m;

	return 0;
}

int session_load_record(const char *path, struct calib_record *rec)
{
	char buf[RECORD_MAX_SIZE];
	long len = session_read_record(path, rec, buf);

	return len < 0 ? (int)len : read_magn_file(path, rec);
}

/*
 * The magnetometer's pair as it was before a change (@had: <record>.magn
 * existed; @prev_len -ENOENT: no previous one), to put back when the
 * record's own change fails
 */
struct magn_undo {
	char file[PATH_MAX];
	bool had;
	char cur[RECORD_MAX_SIZE];
	long cur_len;
	char prev[RECORD_MAX_SIZE];
	long prev_len;
};

/*
 * The magnetometer's file and its previous one: the new (@rec's
 * calibration) and the one it replaces: <@path>.magn as it is, or, when
 * there is none yet, what the record before (@old, a format 2 record's
 * section) held, or none. Nothing is written when there was none and
 * there is none now. 1 when written (the pair before in @u), 0 when not,
 * or -errno with why in @err (the pair as record_pair_replace() leaves
 * it).
 */
static int save_magn_file(const char *path, const struct calib_record *rec,
			  const char *old, size_t old_len, struct magn_undo *u,
			  char *err, size_t errlen)
{
	char prev_path[PATH_MAX + sizeof(RECORD_PAIR_PREVIOUS)];
	char cur[RECORD_MAX_SIZE], prev[RECORD_MAX_SIZE];
	struct calib_record before;
	long prev_len;
	int len, ret;

	ret = magn_file(path, u->file, err, errlen);
	if (ret)
		return ret;
	u->cur_len = read_file_nofollow(u->file, u->cur, sizeof(u->cur), err,
					errlen);
	u->had = u->cur_len >= 0;
	if (u->cur_len < 0 && u->cur_len != -ENOENT)
		return (int)u->cur_len;
	if (!u->had && !rec->magn.present)
		return 0;
	snprintf(prev_path, sizeof(prev_path), "%s%s", u->file,
		 RECORD_PAIR_PREVIOUS);
	u->prev_len = read_file_nofollow(prev_path, u->prev, sizeof(u->prev),
					 err, errlen);
	if (u->prev_len < 0 && u->prev_len != -ENOENT)
		return (int)u->prev_len;
	if (u->had) {
		memcpy(prev, u->cur, (size_t)u->cur_len);
		prev_len = u->cur_len;
	} else {
		if (record_parse(old, old_len, &before, NULL, 0)) {
			memset(&before, 0, sizeof(before));
			before.created = rec->created;
		}
		prev_len = record_magn_format(&before.magn, rec->eeprom,
					      before.created, prev, sizeof(prev));
	}
	len = record_magn_format(&rec->magn, rec->eeprom, rec->created, cur,
				 sizeof(cur));
	if (len < 0 || prev_len < 0) {
		snprintf(err, errlen, "cannot format the magnetometer calibration: %s",
			 strerror(len < 0 ? -len : (int)-prev_len));
		return len < 0 ? len : (int)prev_len;
	}

	ret = record_pair_replace(u->file, cur, (size_t)len, prev, (size_t)prev_len,
				  RECORD_MODE, err, errlen);

	return ret ? ret : 1;
}

/* The magnetometer's pair put back as @u had it; 0 or -errno, why in @err */
static int undo_magn_file(const struct magn_undo *u, char *err, size_t errlen)
{
	char prev[PATH_MAX + sizeof(RECORD_PAIR_PREVIOUS)];
	int ret;

	snprintf(prev, sizeof(prev), "%s%s", u->file, RECORD_PAIR_PREVIOUS);
	if (u->had && u->prev_len >= 0)
		return record_pair_replace(u->file, u->cur, (size_t)u->cur_len,
					   u->prev, (size_t)u->prev_len,
					   RECORD_MODE, err, errlen);
	ret = u->had ? atomic_write_file(u->file, u->cur, (size_t)u->cur_len,
					 RECORD_MODE, err, errlen) :
		       durable_unlink(u->file, err, errlen);
	if (!ret || ret == -ENOENT)
		ret = durable_unlink(prev, err, errlen);

	return ret == -ENOENT ? 0 : ret;
}

/*
 * One magnetometer file of the record at @path read into @buf: believed,
 * valid and of the chip @eeprom. Its length, or -errno with why in @err
 * (-ENOENT when there is none)
 */
static long read_magn_text(const char *file, const uint8_t *eeprom, char *buf,
			   char *err, size_t errlen)
{
	struct calib_magn m;
	char why[256];
	struct stat st;
	uint64_t chip;
	long len;

	len = read_file_nofollow_stat(file, buf, RECORD_MAX_SIZE, &st, err,
				      errlen);
	if (len < 0)
		return len;
	if (storage_trust_file(&trust, file, &st, err, errlen))
		return -EPERM;
	if (record_magn_parse(buf, (size_t)len, &m, &chip, why, sizeof(why))) {
		snprintf(err, errlen, "%s is not a valid magnetometer calibration: %s",
			 file, why);
		return -EINVAL;
	}
	if (chip != record_fingerprint(eeprom)) {
		snprintf(err, errlen, "%s belongs to another chip", file);
		return -EINVAL;
	}

	return len;
}

int session_magn_rollback(const char *path, const struct calib_record *rec,
			  bool swap, char *err, size_t errlen)
{
	char file[PATH_MAX], prev[PATH_MAX + sizeof(RECORD_PAIR_PREVIOUS)];
	char cur_text[RECORD_MAX_SIZE], prev_text[RECORD_MAX_SIZE];
	long cur_len, prev_len;
	int ret;

	ret = magn_file(path, file, err, errlen);
	if (ret)
		return ret;
	snprintf(prev, sizeof(prev), "%s%s", file, RECORD_PAIR_PREVIOUS);
	prev_len = read_magn_text(prev, rec->eeprom, prev_text, err, errlen);
	cur_len = prev_len < 0 ? prev_len :
		  read_magn_text(file, rec->eeprom, cur_text, err, errlen);
	if (prev_len == -ENOENT || cur_len == -ENOENT)
		return 0;
	if (cur_len < 0)
		return (int)cur_len;
	if (!swap)
		return 1;
	ret = record_pair_replace(file, prev_text, (size_t)prev_len, cur_text,
				  (size_t)cur_len, RECORD_MODE, err, errlen);

	return ret ? ret : 1;
}

/*
 * A new record without a previous one (factory-test): a magnetometer
 * calibration beside it is the one of the record it replaces, removed
 * with its previous one
 */
static int forget_magn_files(const char *path, char *err, size_t errlen)
{
	char file[PATH_MAX], prev[PATH_MAX + sizeof(RECORD_PAIR_PREVIOUS)];
	struct stat st;
	int ret;

	ret = magn_file(path, file, err, errlen);
	if (ret)
		return ret;
	snprintf(prev, sizeof(prev), "%s%s", file, RECORD_PAIR_PREVIOUS);
	if (!lstat(file, &st))
		ret = durable_unlink(file, err, errlen);
	if ((!ret || ret == -ENOENT) && !lstat(prev, &st))
		ret = durable_unlink(prev, err, errlen);

	return ret == -ENOENT ? 0 : ret;
}

/* 9999-12-31T23:59:59Z: the record's "created" has four digits for the year */
#define LAST_RECORD_TIME	253402300799LL

/*
 * Write @rec (stamped now) to @path crash-safely: the accelerometer's
 * record as format 1 (which every build reads), the magnetometer's
 * calibration in <path>.magn. With @keep_previous, the record at @path is
 * first saved as <path>.previous, and <path>.magn as <path>.magn.previous,
 * so that a bad recalibration can be rolled back: the magnetometer's pair
 * first, then the record's, each a crash-safe change of its own; when the
 * record's fails, the magnetometer's is put back as it was.
 */
int session_save_record(const char *path, struct calib_record *rec,
			bool keep_previous, char *err, size_t errlen)
{
	char buf[RECORD_MAX_SIZE], old[RECORD_MAX_SIZE];
	struct calib_record check, accel;
	struct magn_undo undo;
	char why[256];
	long old_len;
	int len, ret, magn;

	rec->created = (int64_t)time(NULL);
	accel = *rec;
	accel.magn.present = false;
	len = record_format(&accel, buf, sizeof(buf));
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

	if (!keep_previous) {
		ret = atomic_write_file(path, buf, (size_t)len, RECORD_MODE, err,
					errlen);
		return ret ? ret : forget_magn_files(path, err, errlen);
	}
	old_len = read_file_nofollow(path, old, sizeof(old), err, errlen);
	if (old_len < 0)
		return (int)old_len;

	magn = save_magn_file(path, rec, old, (size_t)old_len, &undo, err,
			      errlen);
	if (magn < 0)
		return magn;
	ret = record_pair_replace(path, buf, (size_t)len, old, (size_t)old_len,
				  RECORD_MODE, err, errlen);
	/* the record's pair stays the old one: so does the magnetometer's */
	if (ret && magn && undo_magn_file(&undo, why, sizeof(why))) {
		size_t n = strlen(err);

		snprintf(err + n, errlen - n, "; %s%s could not be put back (%s): as9888-calibd rollback",
			 path, RECORD_MAGN_SUFFIX, why);
	}

	return ret;
}

/*
 * A change of the record at @path and its previous one that was cut
 * short (or of the magnetometer's file and its previous one): finished
 * or undone
 */
static int recover_pair(const char *path)
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

/* Both pairs: the record's, then the magnetometer's file's */
static int recover(const char *path)
{
	char file[PATH_MAX], err[SESSION_ERR_LEN];
	int ret = recover_pair(path);

	if (!ret && magn_file(path, file, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		ret = -ENAMETOOLONG;
	}

	return ret ? ret : recover_pair(file);
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
