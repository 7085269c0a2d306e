/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The record and the one it replaced (<path>.previous), changed together as
 * one crash-safe transaction, and an interrupted change finished or undone.
 *
 * A change writes the new previous record as <previous>.swap (the
 * journal: it exists exactly while a change is in progress), then replaces
 * <path>, then renames the journal over <path>.previous; every step is
 * durable before the next. After a crash, <path> tells how far it got: if
 * it still holds what the journal holds, <path> was not replaced yet and
 * the change is undone (the journal removed); otherwise it was, and the
 * change is finished (the journal renamed). <path> itself is never changed
 * by a recovery. So the pair is always the old pair or the new pair.
 */
#ifndef AS9888_RECORD_PAIR_H
#define AS9888_RECORD_PAIR_H

#include <stddef.h>

/* The journal's name: the previous file's, with this appended */
#define RECORD_PAIR_JOURNAL_SUFFIX	".swap"

/* What the pair's files hold: the record, or the magnetometer's file */
enum record_pair_kind {
	RECORD_PAIR_RECORD,
	RECORD_PAIR_MAGN,
};

/* One pair's files, named by the caller (record_store.h builds them) */
struct record_pair {
	const char *path;	/* the file */
	const char *prev;	/* the one it replaced */
	const char *journal;	/* the change's journal */
	enum record_pair_kind kind;
};

enum record_pair_recovery {
	RECORD_PAIR_CLEAN = 0,	/* no change was interrupted */
	RECORD_PAIR_UNDONE,	/* one was: the old pair stands */
	RECORD_PAIR_FINISHED,	/* one was: the new pair stands */
};

/*
 * Make (<path>, <path>.previous) hold (@cur, @prev). The file modes are
 * @mode. 0, or -errno with what failed in @err; a failure leaves the old
 * pair, or the new one when only the last step failed and could not be
 * finished (the next record_pair_recover() finishes it).
 */
int record_pair_replace(const struct record_pair *p, const char *cur,
			size_t cur_len, const char *prev, size_t prev_len,
			unsigned int mode, char *err, size_t errlen);

struct storage_trust;

/*
 * Finish or undo a change that was interrupted (call with the record's
 * lock held). The journal is acted on only when @trust believes it (its
 * owner and mode, storage_trust.h) and it is a valid file of @p's kind;
 * otherwise nothing is changed. The magnetometer's file's first change
 * (a journal beside no file) is undone; a record gone beside its journal
 * is left to the operator (the journal holds the only copy). 0 with what was done in @what, or -errno with the
 * reason and the fix in @err.
 */
int record_pair_recover(const struct record_pair *p,
			const struct storage_trust *trust,
			enum record_pair_recovery *what, char *err, size_t errlen);

#endif
