// SPDX-License-Identifier: GPL-2.0
/* The record and the one it replaced, changed together crash-safely. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "atomic_file.h"
#include "record.h"
#include "record_pair.h"

struct pair_paths {
	char prev[PATH_MAX];
	char journal[PATH_MAX];
};

static int pair_paths(const char *path, struct pair_paths *p, char *err,
		      size_t errlen)
{
	if (snprintf(p->prev, sizeof(p->prev), "%s%s", path,
		     RECORD_PAIR_PREVIOUS) >= (int)sizeof(p->prev) ||
	    snprintf(p->journal, sizeof(p->journal), "%s%s", path,
		     RECORD_PAIR_JOURNAL) >= (int)sizeof(p->journal)) {
		snprintf(err, errlen, "record path %s is too long", path);
		return -ENAMETOOLONG;
	}

	return 0;
}

int record_pair_recover(const char *path, enum record_pair_recovery *what,
			char *err, size_t errlen)
{
	char journal[RECORD_MAX_SIZE], cur[RECORD_MAX_SIZE], why[256];
	struct pair_paths p;
	long jlen, clen;
	int ret;

	*what = RECORD_PAIR_CLEAN;
	ret = pair_paths(path, &p, err, errlen);
	if (ret)
		return ret;
	if (access(p.journal, F_OK) && errno == ENOENT)
		return 0;

	jlen = read_file_nofollow(p.journal, journal, sizeof(journal), why, sizeof(why));
	clen = jlen < 0 ? jlen :
	       read_file_nofollow(path, cur, sizeof(cur), why, sizeof(why));
	if (jlen < 0 || clen < 0) {
		snprintf(err, errlen, "an interrupted change of %s cannot be finished: %s; move %s aside by hand",
			 path, why, p.journal);
		return jlen < 0 ? (int)jlen : (int)clen;
	}
	if (jlen == clen && !memcmp(journal, cur, (size_t)clen)) {
		ret = durable_unlink(p.journal, err, errlen);
		*what = RECORD_PAIR_UNDONE;
	} else {
		ret = durable_rename(p.journal, p.prev, err, errlen);
		*what = RECORD_PAIR_FINISHED;
	}

	return ret;
}

int record_pair_replace(const char *path, const char *cur, size_t cur_len,
			const char *prev, size_t prev_len, unsigned int mode,
			char *err, size_t errlen)
{
	enum record_pair_recovery what;
	struct pair_paths p;
	char ignored[256];
	int ret;

	ret = pair_paths(path, &p, err, errlen);
	if (!ret)
		ret = atomic_write_file(p.journal, prev, prev_len, mode, err, errlen);
	if (ret)
		return ret;	/* nothing changed: the journal never appeared */
	ret = atomic_write_file(path, cur, cur_len, mode, err, errlen);
	if (!ret)
		ret = durable_rename(p.journal, p.prev, err, errlen);
	/* a failed step: back to the old pair, or on to the new one */
	if (ret)
		record_pair_recover(path, &what, ignored, sizeof(ignored));

	return ret;
}
