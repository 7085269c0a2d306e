/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The record store: the calibration record, the magnetometer's file beside
 * it (<record>.magn) and the previous one of each, behind one API that a
 * command calls once per phase:
 *
 *   record_store_open()      lock (waiting at most a timeout), finish or
 *                            undo an interrupted change of either pair,
 *                            load and trust the record and its .magn
 *   record_store_replace()   both files stored crash-safely (keeping the
 *                            ones they replace as .previous, or not)
 *   record_store_rollback_check(), record_store_rollback()
 *                            both pairs read and checked first, then
 *                            swapped (and swapped back)
 *   record_store_close()     the lock released
 *
 * Every path (.previous, .magn, .magn.previous, .lock) is built once, in
 * record_store_open(). The files' own machinery is below it: atomic_file.h
 * (one file), record_pair.h (a file and its previous one), lock_file.h,
 * storage_trust.h (whose files are believed). Applying a record to the
 * chip is not the store's (session.h).
 *
 * The two files are one generation: <record>.magn is used only when its
 * "created" is the record's (record_magn_of()). A crash between the two
 * pairs' changes leaves them a change apart; record_store_open() with the
 * lock puts the magnetometer's pair back in step when its previous file is
 * the record's generation (daemon/RECORD.md), and otherwise leaves both
 * as they are and says that the .magn is not used: nothing is deleted.
 */
#ifndef AS9888_RECORD_STORE_H
#define AS9888_RECORD_STORE_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>

#include "common/record.h"

#define RECORD_MODE		0644
/* Nobody else may open the lock: flock() needs only read access (lock_file.h) */
#define LOCK_MODE		0600
#define STATE_DIR_MODE		0755
#define RECORD_STORE_ERR_LEN	512
#define RECORD_STORE_LOCK_SUFFIX ".lock"

/* The store's files, named once */
struct record_paths {
	char record[PATH_MAX];
	char previous[PATH_MAX];
	char magn[PATH_MAX];
	char magn_previous[PATH_MAX];
	char lock[PATH_MAX];
	char record_journal[PATH_MAX];	/* record_pair.h's journals */
	char magn_journal[PATH_MAX];
};

/* record_store_open()'s @flags */
#define RECORD_STORE_LOCK	0x1u	/* lock (and recover) before loading */
#define RECORD_STORE_LOAD	0x2u	/* the record must be there: loaded */
/* a .magn that cannot be used is said, not fatal: @magn_err tells */
#define RECORD_STORE_MAGN_OPTIONAL 0x4u

/**
 * struct record_store - one command's view of the record's files
 * @p:		their paths
 * @lock_fd:	the lock's descriptor, -1 when not locked
 * @rec:	the record loaded, its magnetometer calibration from
 *		<record>.magn when that is there and of this record
 * @text:	the record's text as read, @len bytes (0: not read yet;
 *		-errno: it could not be)
 * @magn_err:	0, or -errno when <record>.magn is there but not used
 *		(said on stderr; @rec.magn then holds none)
 */
struct record_store {
	struct record_paths p;
	int lock_fd;
	struct calib_record rec;
	char text[RECORD_MAX_SIZE];
	long len;
	int magn_err;
};

/*
 * Whose record files are believed when run as root: root's, which the
 * group @state_group (NULL: none) may write too (storage_trust.h). Called
 * once, before any record is read or written. 0 or -errno, why in @err.
 */
int record_store_trust_setup(const char *state_group, char *err,
			     size_t errlen);

/*
 * Open the record at @path. With RECORD_STORE_LOCK: its directory checked
 * (made when missing), <path>.lock taken exclusively (waiting up to
 * @timeout_s for another holder, saying so) and an interrupted change of
 * either pair finished or undone. With RECORD_STORE_LOAD: the record
 * read, believed and parsed, and <record>.magn with it (a .magn that
 * cannot be used fails the open, unless RECORD_STORE_MAGN_OPTIONAL).
 * 0, or -errno said on stderr (nothing held then).
 */
int record_store_open(struct record_store *s, const char *path,
		      unsigned int flags, unsigned int timeout_s);

/*
 * Store @rec (stamped now) crash-safely: the accelerometer's record as
 * format 1 (which every build reads), the magnetometer's calibration in
 * <record>.magn, each pair one crash-safe change, the magnetometer's
 * first; when the record's fails, the magnetometer's is put back. With
 * @keep_previous the files replaced are kept as .previous; without, a new
 * record starts without a magnetometer file. The store must be locked.
 * 0, or -errno with why in @err (the old pairs stand, or as @err says).
 */
int record_store_replace(struct record_store *s, struct calib_record *rec,
			 bool keep_previous, char *err, size_t errlen);

/**
 * struct record_rollback - both pairs, read and checked before a rollback
 * @before:	the previous record (<record>.previous), of the same chip
 * @prev:	its text, @prev_len bytes
 * @magn:	the magnetometer's pair is swapped with the record's
 * @magn_cur:	<record>.magn's text, @magn_cur_len bytes (with @magn)
 * @magn_prev:	<record>.magn.previous's, @magn_prev_len bytes
 */
struct record_rollback {
	struct calib_record before;
	char prev[RECORD_MAX_SIZE];
	long prev_len;
	bool magn;
	char magn_cur[RECORD_MAX_SIZE];
	long magn_cur_len;
	char magn_prev[RECORD_MAX_SIZE];
	long magn_prev_len;
};

/*
 * Before a rollback changes anything (store opened locked and loaded):
 * <record>.previous there, believed, valid and of the record's chip; the
 * magnetometer's pair believed and valid, swapped with the record's only
 * when <record>.magn.previous is the previous record's generation (else it
 * is left and said). 0, or -errno said on stderr (nothing changed).
 */
int record_store_rollback_check(struct record_store *s,
				struct record_rollback *r);

/*
 * Swap both pairs as @r read them: the record's, then the magnetometer's
 * (with @r->magn); with @back, put them back as they were. When the
 * magnetometer's pair fails, the record's is put back. 0, or -errno with
 * why in @err (the pairs as they were, or as @err says).
 */
int record_store_rollback(struct record_store *s,
			  const struct record_rollback *r, bool back,
			  char *err, size_t errlen);

/* The lock released (a store not locked: nothing to do) */
void record_store_close(struct record_store *s);

/*
 * The recovery of record_store_open() without waiting, when a journal
 * says a change was interrupted: done now when nobody holds the lock;
 * when a command holds it, that command has done it. 0 or -errno (said).
 */
int record_store_recover_now(const char *path);

#endif
