/* SPDX-License-Identifier: GPL-2.0 */
/* What every command needs: its backend, and the record read and written. */
#ifndef AS9888_SESSION_H
#define AS9888_SESSION_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>

#include "cli.h"
#include "ftest.h"
#include "record.h"
#include "record_pair.h"
#include "transport.h"

#define RECORD_MODE		0644
/* Nobody else may open the lock: flock() needs only read access (lock_file.h) */
#define LOCK_MODE		0600
#define STATE_DIR_MODE		0755
#define SESSION_ERR_LEN		512
#define SESSION_PREVIOUS_SUFFIX	RECORD_PAIR_PREVIOUS
#define SESSION_LOCK_SUFFIX	".lock"

/*
 * Whose record files are believed when run as root: root's, which the
 * group @state_group (NULL: none) may write too (storage_trust.h). Called
 * once, before any record is read or written. 0 or -errno, why in @err.
 */
int session_trust_setup(const char *state_group, char *err, size_t errlen);

/* Both print the reason to stderr and return -errno on failure */
int session_open_backend(const struct cli_opts *o, struct transport **t);
int session_load_record(const char *path, struct calib_record *rec);
/* The same, keeping the text in @buf (RECORD_MAX_SIZE): its length or -errno */
long session_read_record(const char *path, struct calib_record *rec, char *buf);
int session_save_record(const char *path, struct calib_record *rec,
			bool keep_previous, char *err, size_t errlen);

/*
 * Rollback's second half: <@path>.magn and <@path>.magn.previous swapped
 * (both believed, valid and of @rec's chip), or with !@swap only checked
 * (before the record's pair is swapped, so that files that cannot be read
 * stop a rollback before it changes anything). 1 when swapped (or it
 * can be), 0 when there is no pair to swap, or -errno with why in @err
 * (nothing changed, or the pair settled as record_pair_replace() says)
 */
int session_magn_rollback(const char *path, const struct calib_record *rec,
			  bool swap, char *err, size_t errlen);

/* Apply @rec to the chip (identity checked first); 0 or -errno, said on stderr */
int session_apply_record(const struct cli_opts *o, const struct calib_record *rec);

/*
 * Run the factory test with @f on the command's backend. 0 when it ran
 * (judgments in @res), -errno when it could not start (said on stderr).
 */
int session_run_test(const struct cli_opts *o, const struct ftest_opts *f,
		     struct ftest_result *res);

/*
 * Step 4-1: store @res's record crash-safely (keeping the one it replaces
 * as <path>.previous with @keep_previous) and put it in effect; the
 * outcome is judged in @res's report. True when both were done.
 */
bool session_store_result(const struct cli_opts *o, struct ftest_result *res,
			  bool keep_previous);

/* Put a newly stored record in effect on the device; 0 or -errno (said) */
int session_activate_record(const struct cli_opts *o,
			    const struct calib_record *rec);

/*
 * Lock @path's record for writing, waiting at most @timeout_s for another
 * holder, and finish or undo a change of the record and its previous one
 * that was interrupted (record_pair.h). The lock's fd (held until exit),
 * or -errno (said on stderr).
 */
int session_lock(const char *path, unsigned int timeout_s);

/*
 * The same recovery without waiting: done now when nobody holds the lock;
 * when a command holds it, that command has done it. 0 or -errno (said).
 */
int session_recover_now(const char *path);

/*
 * Apply the record at @record_path to the AS9888 IIO device at @dir: the
 * chip must be the record's (EEPROM), and a record made on the simulator
 * ("source = simulator") is refused unless @allow_simulated (the caller
 * itself runs on the simulator). 0 or -errno, said on stderr.
 */
int iio_restore(const char *record_path, const char *dir,
		bool allow_simulated);

/*
 * The same for the one AS9888 IIO device at @dir, accelerometer or
 * magnetometer (iio_apply_device()): restore --device.
 */
int iio_restore_device(const char *record_path, const char *dir);

#endif
