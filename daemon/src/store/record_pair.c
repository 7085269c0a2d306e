// SPDX-License-Identifier: GPL-2.0
/* The record and the one it replaced, changed together crash-safely. */
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "store/atomic_file.h"
#include "common/record.h"
#include "store/record_pair.h"
#include "store/storage_trust.h"

/*
 * The journal at @journal into @buf: believed (@trust, NULL when we just
 * wrote it ourselves) and a valid record (a valid magnetometer file with
 * @magn), or -errno with why in @why
 */
static long read_journal(const char *journal, bool magn,
			 const struct storage_trust *trust, char *buf,
			 size_t size, char *why, size_t whylen)
{
	struct calib_record rec;
	char reason[256];
	struct stat st;
	uint64_t chip;
	long len;
	int bad;

	len = read_file_nofollow_stat(journal, buf, size, &st, why, whylen);
	if (len < 0)
		return len;
	if (trust && storage_trust_file(trust, journal, &st, why, whylen))
		return -EPERM;
	bad = magn ? record_magn_parse(buf, (size_t)len, &rec.magn, &chip,
				       reason, sizeof(reason)) :
		     record_parse(buf, (size_t)len, &rec, reason, sizeof(reason));
	if (bad) {
		snprintf(why, whylen, "%.256s is not a valid record: %.200s", journal,
			 reason);
		return -EINVAL;
	}

	return len;
}

int record_pair_recover(const struct record_pair *p,
			const struct storage_trust *trust,
			enum record_pair_recovery *what, char *err, size_t errlen)
{
	char journal[RECORD_MAX_SIZE], cur[RECORD_MAX_SIZE], why[512];
	bool magn = p->kind == RECORD_PAIR_MAGN;
	long jlen, clen;
	int ret;

	*what = RECORD_PAIR_CLEAN;
	if (access(p->journal, F_OK) && errno == ENOENT)
		return 0;

	/* nothing is renamed or removed on the word of a journal not believed */
	jlen = read_journal(p->journal, magn, trust, journal, sizeof(journal),
			    why, sizeof(why));
	clen = jlen < 0 ? jlen :
	       read_file_nofollow(p->path, cur, sizeof(cur), why, sizeof(why));
	/*
	 * <record>.magn's first change (no file before it): not made yet. A
	 * record's journal holds the only copy of the record it replaces, so
	 * a record gone beside its journal is left to the operator (below).
	 */
	if (magn && clen == -ENOENT) {
		*what = RECORD_PAIR_UNDONE;
		return durable_unlink(p->journal, err, errlen);
	}
	if (jlen < 0 || clen < 0) {
		snprintf(err, errlen, "an interrupted change of %s cannot be finished: %s; nothing changed: move %s aside by hand",
			 p->path, why, p->journal);
		return jlen < 0 ? (int)jlen : (int)clen;
	}
	if (jlen == clen && !memcmp(journal, cur, (size_t)clen)) {
		ret = durable_unlink(p->journal, err, errlen);
		*what = RECORD_PAIR_UNDONE;
	} else {
		ret = durable_rename(p->journal, p->prev, err, errlen);
		*what = RECORD_PAIR_FINISHED;
	}

	return ret;
}

/* Does the file at @path hold exactly @data? */
static bool holds(const char *path, const char *data, size_t len)
{
	char buf[RECORD_MAX_SIZE], why[256];
	long n = read_file_nofollow(path, buf, sizeof(buf), why, sizeof(why));

	return n == (long)len && !memcmp(buf, data, len);
}

/*
 * A step of a change failed with @ret: settle the pair (recover, which
 * undoes it or finishes it, and flush the directory) and tell which pair
 * stands. 0 when the change took effect after all: the new record is in
 * @path, no journal is left and the directory is flushed; else @ret, with
 * the old pair, or with a journal left when even settling failed (the next
 * command's recovery decides then, and @err says so).
 */
static int settle(const struct record_pair *p, const char *cur, size_t cur_len,
		  int ret, char *err, size_t errlen)
{
	enum record_pair_recovery what;
	char why[256];
	int rec;

	rec = record_pair_recover(p, NULL, &what, why, sizeof(why));
	if (!rec && what == RECORD_PAIR_CLEAN)
		rec = durable_sync_dir(p->path, why, sizeof(why));
	if (rec) {
		size_t n = strlen(err);

		snprintf(err + n, errlen - n, "; the change is left unfinished (%s): the next command that takes %s.lock finishes or undoes it",
			 why, p->path);
		return ret;
	}
	if (what != RECORD_PAIR_UNDONE && holds(p->path, cur, cur_len) &&
	    access(p->journal, F_OK) && errno == ENOENT)
		return 0;

	return ret;
}

/* Anything but a regular file (or nothing) at @prev stops a change before it starts */
static int check_previous(const char *prev, char *err, size_t errlen)
{
	struct stat st;

	if (lstat(prev, &st)) {
		if (errno == ENOENT)
			return 0;
		snprintf(err, errlen, "cannot examine %s: %s", prev, strerror(errno));
		return -errno;
	}
	if (S_ISREG(st.st_mode))
		return 0;
	snprintf(err, errlen, "%s is %s, not a record: nothing changed; remove it",
		 prev, S_ISLNK(st.st_mode) ? "a symbolic link" :
		 S_ISDIR(st.st_mode) ? "a directory" : "a device, FIFO or socket");

	return S_ISDIR(st.st_mode) ? -EISDIR : -EINVAL;
}

int record_pair_replace(const struct record_pair *p, const char *cur,
			size_t cur_len, const char *prev, size_t prev_len,
			unsigned int mode, char *err, size_t errlen)
{
	int ret;

	ret = check_previous(p->prev, err, errlen);
	if (ret)
		return ret;
	ret = atomic_write_file(p->journal, prev, prev_len, mode, err, errlen);
	if (!ret)
		ret = atomic_write_file(p->path, cur, cur_len, mode, err, errlen);
	if (!ret)
		ret = durable_rename(p->journal, p->prev, err, errlen);

	/* a failed step: back to the old pair, or on to the new one */
	return ret ? settle(p, cur, cur_len, ret, err, errlen) : 0;
}
