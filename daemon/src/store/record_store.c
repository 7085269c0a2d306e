// SPDX-License-Identifier: GPL-2.0
/*
 * The record store (record_store.h): the record and <record>.magn locked,
 * recovered, loaded, trusted, replaced and rolled back, each once.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "store/atomic_file.h"
#include "store/lock_file.h"
#include "store/record_pair.h"
#include "store/record_store.h"
#include "common/remedy.h"
#include "store/storage_trust.h"

/*
 * Who may have written the record's files (storage_trust.h): the one
 * policy of the process, set from its command line before any command.
 */
static struct storage_trust trust;

int record_store_trust_setup(const char *state_group, char *err, size_t errlen)
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

/* Every name of the store's files, from the record's @path */
static int build_paths(struct record_paths *p, const char *path)
{
	/* the journals: the previous file's name and RECORD_PAIR_JOURNAL_SUFFIX */
	size_t room = sizeof(p->record) - sizeof(RECORD_PREVIOUS_SUFFIX) -
		      sizeof(RECORD_MAGN_SUFFIX) - sizeof(RECORD_PAIR_JOURNAL_SUFFIX);

	if (strlen(path) > room) {
		fprintf(stderr, "as9888-calibd: record path %s is too long\n", path);
		return -ENAMETOOLONG;
	}
	snprintf(p->record, sizeof(p->record), "%s", path);
	snprintf(p->previous, sizeof(p->previous), "%s%s", path,
		 RECORD_PREVIOUS_SUFFIX);
	snprintf(p->magn, sizeof(p->magn), "%s%s", path, RECORD_MAGN_SUFFIX);
	snprintf(p->magn_previous, sizeof(p->magn_previous), "%s%s%s", path,
		 RECORD_MAGN_SUFFIX, RECORD_PREVIOUS_SUFFIX);
	snprintf(p->lock, sizeof(p->lock), "%s%s", path,
		 RECORD_STORE_LOCK_SUFFIX);
	snprintf(p->record_journal, sizeof(p->record_journal), "%s%s%s", path,
		 RECORD_PREVIOUS_SUFFIX, RECORD_PAIR_JOURNAL_SUFFIX);
	snprintf(p->magn_journal, sizeof(p->magn_journal), "%s%s%s%s", path,
		 RECORD_MAGN_SUFFIX, RECORD_PREVIOUS_SUFFIX,
		 RECORD_PAIR_JOURNAL_SUFFIX);

	return 0;
}

static struct record_pair record_pair_of(const struct record_paths *p)
{
	return (struct record_pair){ p->record, p->previous, p->record_journal,
				     RECORD_PAIR_RECORD };
}

static struct record_pair magn_pair_of(const struct record_paths *p)
{
	return (struct record_pair){ p->magn, p->magn_previous, p->magn_journal,
				     RECORD_PAIR_MAGN };
}

/*
 * One record file (the record or its previous one) into @buf: believed,
 * valid. Its length, or -errno said on stderr.
 */
static long read_record(const char *path, struct calib_record *rec, char *buf)
{
	char err[RECORD_STORE_ERR_LEN];
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

/*
 * The one reader of a magnetometer file (<record>.magn or its previous
 * one) beside the record @rec: read into @buf, believed, and judged
 * against @rec (record_magn_of(): valid, the chip's, the generation's),
 * its calibration in @m. Its length, or -errno with why in @err (-ENOENT
 * when there is none).
 */
static long read_magn(const char *file, const struct calib_record *rec,
		      char *buf, struct calib_magn *m, char *err, size_t errlen)
{
	char why[RECORD_STORE_ERR_LEN];
	struct stat st;
	long len;
	int ret;

	len = read_file_nofollow_stat(file, buf, RECORD_MAX_SIZE, &st, err,
				      errlen);
	if (len < 0)
		return len;
	if (storage_trust_file(&trust, file, &st, err, errlen))
		return -EPERM;
	ret = record_magn_of(rec, buf, (size_t)len, m, why, sizeof(why));
	if (ret) {
		snprintf(err, errlen, "%.256s is %.200s", file, why);
		return ret;
	}

	return len;
}

/*
 * <record>.magn into @s->rec.magn when it is there and of the record;
 * else the record's own (a format 2 record's section, or none). 0, or
 * -errno said on stderr, with a remedy (@s->rec.magn then holds none).
 */
static int load_magn(struct record_store *s)
{
	char buf[RECORD_MAX_SIZE], err[RECORD_STORE_ERR_LEN];
	char why[RECORD_STORE_ERR_LEN];
	struct calib_magn m;
	long len;

	len = read_magn(s->p.magn, &s->rec, buf, &m, err, sizeof(err));
	if (len == -ESTALE && s->lock_fd < 0 &&
	    read_magn(s->p.magn_previous, &s->rec, buf, &m, why,
		      sizeof(why)) >= 0) {
		/*
		 * A change of both cut between the pairs, read without the
		 * lock (restore at boot): what recovery makes of it, read-only
		 */
		fprintf(stderr, "as9888-calibd: %s is a change away from %s (an interrupted change of both): %s, the record's, is used; the next command that locks the record puts the pair in step\n",
			s->p.magn, s->p.record, s->p.magn_previous);
		len = 0;
	}
	if (len >= 0)
		s->rec.magn = m;
	if (len >= 0 || len == -ENOENT)
		return 0;
	s->rec.magn.present = false;
	if (len == -EXDEV)
		fprintf(stderr, "as9888-calibd: %s: its magnetometer calibration is not used: remove it, then run magn-calibrate on this unit\n",
			err);
	else if (len == -ESTALE)
		fprintf(stderr, "as9888-calibd: %s: its magnetometer calibration is not used with %s (a change of both was cut short, or the record was replaced); both files are kept: as9888-calibd magn-calibrate stores one for this record\n",
			err, s->p.record);
	else if (len == -EINVAL || len == -EPERM)
		fprintf(stderr, "as9888-calibd: %s\n", err);
	else
		print_with_remedy(err, (int)-len);

	return (int)len;
}

static int load(struct record_store *s, unsigned int flags)
{
	s->len = read_record(s->p.record, &s->rec, s->text);
	if (s->len < 0)
		return (int)s->len;
	s->magn_err = load_magn(s);

	return flags & RECORD_STORE_MAGN_OPTIONAL ? 0 : s->magn_err;
}

/*
 * A change of one pair (the record's or the magnetometer's) that was cut
 * short: finished or undone, said
 */
static int recover_pair(const struct record_pair *pair)
{
	enum record_pair_recovery what;
	char err[RECORD_STORE_ERR_LEN];
	int ret;

	ret = record_pair_recover(pair, &trust, &what, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);
	else if (what == RECORD_PAIR_UNDONE)
		fprintf(stderr, "as9888-calibd: %s: an interrupted change was undone; %s is as before it\n",
			pair->path, pair->prev);
	else if (what == RECORD_PAIR_FINISHED)
		fprintf(stderr, "as9888-calibd: %s: an interrupted change was finished; %s now holds the file it replaced\n",
			pair->path, pair->prev);

	return ret;
}

/*
 * The two pairs a change apart (a crash between the magnetometer's pair
 * and the record's: a save's first half, or a rollback's first half):
 * <record>.magn is of another generation than the record while
 * <record>.magn.previous is the record's. Swapping the magnetometer's pair
 * puts it in step and keeps both files. Anything else is left as it is
 * (the load says that a .magn is not used). 0 or -errno (said).
 */
static int recover_generation(const struct record_paths *p)
{
	char text[RECORD_MAX_SIZE], cur[RECORD_MAX_SIZE], prev[RECORD_MAX_SIZE];
	char err[RECORD_STORE_ERR_LEN];
	struct record_pair magn = magn_pair_of(p);
	struct calib_record rec;
	struct calib_magn m;
	long len, cur_len, prev_len;
	struct stat st;
	int ret;

	len = read_file_nofollow_stat(p->record, text, sizeof(text), &st, err,
				      sizeof(err));
	/* no record to be in step with, or not believed: the load says */
	if (len < 0 || storage_trust_file(&trust, p->record, &st, err, sizeof(err)) ||
	    record_parse(text, (size_t)len, &rec, NULL, 0))
		return 0;
	cur_len = read_magn(p->magn, &rec, cur, &m, err, sizeof(err));
	if (cur_len != -ESTALE)
		return 0;
	prev_len = read_magn(p->magn_previous, &rec, prev, &m, err, sizeof(err));
	if (prev_len < 0)
		return 0;
	/* it was believed and valid, of another generation: its text */
	cur_len = read_file_nofollow(p->magn, cur, sizeof(cur), err, sizeof(err));
	if (cur_len < 0)
		return 0;
	ret = record_pair_replace(&magn, prev, (size_t)prev_len, cur,
				  (size_t)cur_len, RECORD_MODE, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s is a change away from %s and could not be put in step: %s\n",
			p->magn, p->record, err);
	else
		fprintf(stderr, "as9888-calibd: %s was a change away from %s (an interrupted change of both): swapped with %s, which was the record's; both kept\n",
			p->magn, p->record, p->magn_previous);

	return ret;
}

/* Both pairs, the record's first, then the two in step */
static int recover(const struct record_paths *p)
{
	struct record_pair rec = record_pair_of(p), magn = magn_pair_of(p);
	int ret = recover_pair(&rec);

	if (!ret)
		ret = recover_pair(&magn);

	return ret ? ret : recover_generation(p);
}

/*
 * Before anything is measured or written: the record's path can hold a
 * record (a regular file or nothing yet) in a directory that exists or can
 * be made, is not a symbolic link, and nobody else could have written.
 */
static int check_record_path(const char *path, char *err, size_t errlen)
{
	struct stat st;
	int ret;

	if (!lstat(path, &st) && !S_ISREG(st.st_mode)) {
		snprintf(err, errlen, "%.300s is %s, not a record: give --record a path for a regular file",
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

/* Open the lock, checked and trusted; the fd or -errno (said) */
static int open_lock(const struct record_paths *p)
{
	char err[RECORD_STORE_ERR_LEN];
	int fd, ret;

	ret = check_record_path(p->record, err, sizeof(err));
	fd = ret ? ret : lock_file_open(p->lock, LOCK_MODE, true, err, sizeof(err));
	if (fd >= 0 && (ret = check_lock(p->lock, fd, err, sizeof(err)))) {
		close(fd);
		fd = ret;
	}
	if (fd < 0)
		print_with_remedy(err, -fd);

	return fd;
}

/*
 * The lock taken (waiting up to @timeout_s with @wait, saying so) and an
 * interrupted change recovered: the fd, -EWOULDBLOCK (silent) when another
 * holds it and we do not @wait, or -errno (said)
 */
static int take_lock(const struct record_paths *p, bool wait,
		     unsigned int timeout_s)
{
	unsigned int tries = 0;
	int fd, ret;

again:
	fd = open_lock(p);
	if (fd < 0)
		return fd;
	ret = lock_file_try(fd);
	if (ret == -EWOULDBLOCK && wait) {
		if (timeout_s)
			fprintf(stderr, "as9888-calibd: %s is held by another command; waiting up to %u s\n",
				p->lock, timeout_s);
		ret = lock_file_wait(fd, timeout_s * 1000);
	}
	if (ret == -ETIMEDOUT)
		fprintf(stderr, "as9888-calibd: %s is still held after %u s: another as9888-calibd command is running, or some process holds it (fuser -v %s shows which); nothing done\n",
			p->lock, timeout_s, p->lock);
	else if (ret && ret != -EWOULDBLOCK)
		fprintf(stderr, "as9888-calibd: cannot lock %s: %s\n", p->lock,
			strerror(-ret));
	/* the file was replaced (a loose lock made private) while we waited */
	if (!ret && !lock_file_current(fd, p->lock)) {
		close(fd);
		if (++tries < LOCK_REOPEN_TRIES)
			goto again;
		fprintf(stderr, "as9888-calibd: %s keeps being replaced while it is locked: remove it\n",
			p->lock);
		return -EBUSY;
	}
	if (!ret)
		ret = recover(p);
	if (ret) {
		close(fd);
		return ret;
	}

	return fd;
}

int record_store_open(struct record_store *s, const char *path,
		      unsigned int flags, unsigned int timeout_s)
{
	int ret;

	s->lock_fd = -1;
	s->len = 0;
	s->magn_err = 0;
	memset(&s->rec, 0, sizeof(s->rec));
	ret = build_paths(&s->p, path);
	if (ret)
		return ret;
	if (flags & RECORD_STORE_LOCK) {
		s->lock_fd = take_lock(&s->p, true, timeout_s);
		if (s->lock_fd < 0)
			return s->lock_fd;
	}
	ret = flags & RECORD_STORE_LOAD ? load(s, flags) : 0;
	if (ret)
		record_store_close(s);

	return ret;
}

void record_store_close(struct record_store *s)
{
	if (s->lock_fd >= 0)
		close(s->lock_fd);
	s->lock_fd = -1;
}

int record_store_recover_now(const char *path)
{
	struct record_paths p;
	int fd = build_paths(&p, path);

	/*
	 * Nothing interrupted: nothing made (not even the lock). A change of
	 * both cut between the pairs leaves no journal, only both of the
	 * magnetometer's files (recover_generation())
	 */
	if (!fd && access(p.record_journal, F_OK) && access(p.magn_journal, F_OK) &&
	    (access(p.magn, F_OK) || access(p.magn_previous, F_OK)))
		return 0;
	if (!fd)
		fd = take_lock(&p, false, 0);
	if (fd == -EWOULDBLOCK)
		return 0;	/* its holder has recovered */
	if (fd >= 0)
		close(fd);

	return fd < 0 ? fd : 0;
}

/*
 * The magnetometer's pair as it was before a change (@had: <record>.magn
 * existed; @prev_len -ENOENT: no previous one), to put back when the
 * record's own change fails
 */
struct magn_undo {
	bool had;
	char cur[RECORD_MAX_SIZE];
	long cur_len;
	char prev[RECORD_MAX_SIZE];
	long prev_len;
};

/*
 * What <record>.magn.previous becomes: <record>.magn as it is when it is
 * the record's being replaced (@old, @old_len), else what that record
 * held (a format 2 record's section, or none), stamped with its created.
 * Its length in @prev, or -errno.
 */
static long previous_magn(const struct magn_undo *u, const char *old,
			  size_t old_len, const struct calib_record *rec,
			  char *prev)
{
	struct calib_record before;
	struct calib_magn m;

	if (record_parse(old, old_len, &before, NULL, 0)) {
		memset(&before, 0, sizeof(before));
		before.created = rec->created;
	}
	if (u->had && !record_magn_of(&before, u->cur, (size_t)u->cur_len, &m,
				      NULL, 0)) {
		memcpy(prev, u->cur, (size_t)u->cur_len);
		return u->cur_len;
	}

	return record_magn_format(&before.magn, rec->eeprom, before.created,
				  prev, RECORD_MAX_SIZE);
}

/*
 * The magnetometer's file and its previous one: the new (@rec's
 * calibration) and the one it replaces (previous_magn()). Nothing is
 * written when there was none and there is none now. 1 when written (the
 * pair before in @u), 0 when not, or -errno with why in @err (the pair as
 * record_pair_replace() leaves it).
 */
static int save_magn(const struct record_paths *p, const struct calib_record *rec,
		     const char *old, size_t old_len, struct magn_undo *u,
		     char *err, size_t errlen)
{
	struct record_pair pair = magn_pair_of(p);
	char cur[RECORD_MAX_SIZE], prev[RECORD_MAX_SIZE];
	long prev_len;
	int len, ret;

	u->cur_len = read_file_nofollow(p->magn, u->cur, sizeof(u->cur), err,
					errlen);
	u->had = u->cur_len >= 0;
	if (u->cur_len < 0 && u->cur_len != -ENOENT)
		return (int)u->cur_len;
	if (!u->had && !rec->magn.present)
		return 0;
	u->prev_len = read_file_nofollow(p->magn_previous, u->prev,
					 sizeof(u->prev), err, errlen);
	if (u->prev_len < 0 && u->prev_len != -ENOENT)
		return (int)u->prev_len;
	prev_len = previous_magn(u, old, old_len, rec, prev);
	len = record_magn_format(&rec->magn, rec->eeprom, rec->created, cur,
				 sizeof(cur));
	if (len < 0 || prev_len < 0) {
		snprintf(err, errlen, "cannot format the magnetometer calibration: %s",
			 strerror(len < 0 ? -len : (int)-prev_len));
		return len < 0 ? len : (int)prev_len;
	}

	ret = record_pair_replace(&pair, cur, (size_t)len, prev, (size_t)prev_len,
				  RECORD_MODE, err, errlen);

	return ret ? ret : 1;
}

/* The magnetometer's pair put back as @u had it; 0 or -errno, why in @err */
static int undo_magn(const struct record_paths *p, const struct magn_undo *u,
		     char *err, size_t errlen)
{
	struct record_pair pair = magn_pair_of(p);
	int ret;

	if (u->had && u->prev_len >= 0)
		return record_pair_replace(&pair, u->cur, (size_t)u->cur_len,
					   u->prev, (size_t)u->prev_len,
					   RECORD_MODE, err, errlen);
	ret = u->had ? atomic_write_file(p->magn, u->cur, (size_t)u->cur_len,
					 RECORD_MODE, err, errlen) :
		       durable_unlink(p->magn, err, errlen);
	if (ret && ret != -ENOENT)
		return ret;
	/* the previous one as it was: there before (its text), or not */
	ret = u->prev_len >= 0 ?
	      atomic_write_file(p->magn_previous, u->prev, (size_t)u->prev_len,
				RECORD_MODE, err, errlen) :
	      durable_unlink(p->magn_previous, err, errlen);

	return ret == -ENOENT ? 0 : ret;
}

/*
 * A new record without a previous one (factory-test): a magnetometer
 * calibration beside it is the one of the record it replaces, removed
 * with its previous one
 */
static int forget_magn(const struct record_paths *p, char *err, size_t errlen)
{
	struct stat st;
	int ret = 0;

	if (!lstat(p->magn, &st))
		ret = durable_unlink(p->magn, err, errlen);
	if ((!ret || ret == -ENOENT) && !lstat(p->magn_previous, &st))
		ret = durable_unlink(p->magn_previous, err, errlen);

	return ret == -ENOENT ? 0 : ret;
}

/* 9999-12-31T23:59:59Z: the record's "created" has four digits for the year */
#define LAST_RECORD_TIME	253402300799LL

int record_store_replace(struct record_store *s, struct calib_record *rec,
			 bool keep_previous, char *err, size_t errlen)
{
	char buf[RECORD_MAX_SIZE], old[RECORD_MAX_SIZE];
	struct record_pair pair = record_pair_of(&s->p);
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
	ret = ensure_parent_dir(s->p.record, STATE_DIR_MODE, err, errlen);
	if (ret)
		return ret;

	if (!keep_previous) {
		ret = atomic_write_file(s->p.record, buf, (size_t)len, RECORD_MODE,
					err, errlen);
		if (ret)
			return ret;
		/* the record stands: a file left of the one it replaced is of
		 * another generation, never used with it (said, not a failure) */
		if (forget_magn(&s->p, why, sizeof(why)))
			fprintf(stderr, "as9888-calibd: the record is written; the magnetometer's files of the record it replaced could not be removed (%s): they are not used with the new record\n",
				why);
		return 0;
	}
	old_len = read_file_nofollow(s->p.record, old, sizeof(old), err, errlen);
	if (old_len < 0)
		return (int)old_len;

	magn = save_magn(&s->p, rec, old, (size_t)old_len, &undo, err, errlen);
	if (magn < 0)
		return magn;
	ret = record_pair_replace(&pair, buf, (size_t)len, old, (size_t)old_len,
				  RECORD_MODE, err, errlen);
	/*
	 * The record's pair stays the old one (its journal known to be
	 * gone): so does the magnetometer's. With its journal left, or not
	 * known to be gone, the record may be either; recovery settles it,
	 * then puts the magnetometer's pair in step.
	 */
	if (ret && magn && access(s->p.record_journal, F_OK) &&
	    errno == ENOENT && undo_magn(&s->p, &undo, why, sizeof(why))) {
		size_t n = strlen(err);

		snprintf(err + n, errlen - n, "; %s could not be put back (%s): as9888-calibd rollback",
			 s->p.magn, why);
	}

	return ret;
}

/*
 * The magnetometer's pair for a rollback: swapped when <record>.magn.previous
 * is the previous record's generation (and <record>.magn is valid and
 * believed), left when there is none or it is another generation's (said).
 * 0, or -errno said (nothing changed).
 */
static int rollback_check_magn(struct record_store *s, struct record_rollback *r)
{
	char err[RECORD_STORE_ERR_LEN];
	struct calib_magn m;
	long len;

	r->magn = false;
	r->magn_prev_len = read_magn(s->p.magn_previous, &r->before, r->magn_prev,
				     &m, err, sizeof(err));
	if (r->magn_prev_len == -ENOENT)
		return 0;
	if (r->magn_prev_len == -ESTALE) {
		fprintf(stderr, "as9888-calibd: rollback: %s: the magnetometer's pair is left as it is\n",
			err);
		return 0;
	}
	if (r->magn_prev_len < 0)
		goto refused;
	/* the current one of any generation: it becomes the previous one */
	len = read_magn(s->p.magn, &s->rec, r->magn_cur, &m, err, sizeof(err));
	if (len == -ENOENT)
		return 0;
	if (len < 0 && len != -ESTALE)
		goto refused;
	r->magn_cur_len = read_file_nofollow(s->p.magn, r->magn_cur,
					     sizeof(r->magn_cur), err, sizeof(err));
	if (r->magn_cur_len < 0)
		goto refused;
	r->magn = true;

	return 0;

refused:
	fprintf(stderr, "as9888-calibd: rollback: %s; nothing changed\n", err);
	return -EINVAL;
}

int record_store_rollback_check(struct record_store *s,
				struct record_rollback *r)
{
	if (access(s->p.previous, F_OK) && errno == ENOENT) {
		fprintf(stderr, "as9888-calibd: rollback: there is no %s: nothing to roll back (only recalibrate keeps a previous record)\n",
			s->p.previous);
		return -ENOENT;
	}
	r->prev_len = read_record(s->p.previous, &r->before, r->prev);
	if (r->prev_len < 0)
		return (int)r->prev_len;
	if (memcmp(s->rec.eeprom, r->before.eeprom, AS9888_EEPROM_LEN)) {
		fprintf(stderr, "as9888-calibd: rollback: %s belongs to another chip; nothing changed\n",
			s->p.previous);
		return -EXDEV;
	}

	return rollback_check_magn(s, r);
}

/* One pair made (@cur, @prev) of @r and @s's texts, forth or @back */
static int swap_pair(const struct record_pair *p, const char *a, long a_len,
		     const char *b, long b_len, bool back, char *err,
		     size_t errlen)
{
	return back ? record_pair_replace(p, a, (size_t)a_len, b, (size_t)b_len,
					  RECORD_MODE, err, errlen) :
		      record_pair_replace(p, b, (size_t)b_len, a, (size_t)a_len,
					  RECORD_MODE, err, errlen);
}

int record_store_rollback(struct record_store *s,
			  const struct record_rollback *r, bool back,
			  char *err, size_t errlen)
{
	struct record_pair rec = record_pair_of(&s->p), magn = magn_pair_of(&s->p);
	char why[RECORD_STORE_ERR_LEN];
	size_t n;
	int ret;

	ret = swap_pair(&rec, s->text, s->len, r->prev, r->prev_len, back, err,
			errlen);
	if (ret || !r->magn)
		return ret;
	ret = swap_pair(&magn, r->magn_cur, r->magn_cur_len, r->magn_prev,
			r->magn_prev_len, back, err, errlen);
	if (!ret)
		return 0;
	/* the two pairs are one change: the record's is put back too */
	n = strlen(err);
	if (swap_pair(&rec, s->text, s->len, r->prev, r->prev_len, !back, why,
		      sizeof(why)))
		snprintf(err + n, errlen - n, "; %s is changed and %s is not, and %s could not be put back (%s): run as9888-calibd rollback again",
			 s->p.record, s->p.magn, s->p.record, why);
	else
		snprintf(err + n, errlen - n, "; %s is put back as it was",
			 s->p.record);

	return ret;
}
