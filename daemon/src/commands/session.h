/* SPDX-License-Identifier: GPL-2.0 */
/* What every command needs besides the record store: its backend, the test, the chip applied. */
#ifndef AS9888_SESSION_H
#define AS9888_SESSION_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>

#include "commands/cli.h"
#include "ftest/ftest.h"
#include "common/record.h"
#include "store/record_store.h"
#include "chip/transport.h"

#define SESSION_ERR_LEN		RECORD_STORE_ERR_LEN

/* The command's backend; 0, or -errno said on stderr */
int session_open_backend(const struct cli_opts *o, struct transport **t);

/* Apply @rec to the chip (identity checked first); 0 or -errno, said on stderr */
int session_apply_record(const struct cli_opts *o, const struct calib_record *rec);

/*
 * Run the factory test with @f on the command's backend. 0 when it ran
 * (judgments in @res), -errno when it could not start (said on stderr).
 */
int session_run_test(const struct cli_opts *o, const struct ftest_opts *f,
		     struct ftest_result *res);

/*
 * Step 4-1: store @res's record crash-safely in @s (locked; keeping the
 * one it replaces as <path>.previous with @keep_previous) and put it in
 * effect; the outcome is judged in @res's report. True when both were done.
 */
bool session_store_result(const struct cli_opts *o, struct record_store *s,
			  struct ftest_result *res, bool keep_previous);

/*
 * Apply the record loaded in @s (record_store_open() with
 * RECORD_STORE_MAGN_OPTIONAL) to the AS9888 IIO device at @dir, both its
 * parts (iio_apply_checked()), or with @one_device that device's part
 * (iio_apply_device()). When <record>.magn could not be used (said by the
 * store), the accelerometer's part is applied and the magnetometer is left
 * as it was; that fails the call unless @dir is the accelerometer's device
 * alone. 0 or -errno, said on stderr.
 */
int session_restore_iio(const struct record_store *s, const char *dir,
			bool one_device);

/*
 * Apply the record at @record_path to the AS9888 IIO device at @dir: the
 * chip must be the record's (EEPROM), and a record made on the simulator
 * ("source = simulator") is refused unless @allow_simulated (the caller
 * itself runs on the simulator). A <record>.magn that cannot be used does
 * not stop the accelerometer's part: it is applied, and the restore still
 * fails (the magnetometer is left as it was). 0 or -errno, said on stderr.
 */
int iio_restore(const char *record_path, const char *dir,
		bool allow_simulated);

/*
 * The same for the one AS9888 IIO device at @dir, accelerometer or
 * magnetometer (iio_apply_device()): restore --device. The
 * accelerometer's device does not need <record>.magn.
 */
int iio_restore_device(const char *record_path, const char *dir);

#endif
