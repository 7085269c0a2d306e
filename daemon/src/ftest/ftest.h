/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The factory on-board function test: steps 1 to 3 of the application note
 * with the datasheet's decisions, over a register-level transport. Step 4
 * (storing the record) belongs to the caller, which knows where.
 */
#ifndef AS9888_FTEST_H
#define AS9888_FTEST_H

#include <stdbool.h>
#include <stdint.h>

#include "as9888_calib.h"
#include "common/record.h"
#include "ftest/report.h"
#include "chip/transport.h"

/* Pilot samples taken to measure the noise for --permissible-error */
#define FTEST_PILOT_SAMPLES		32
/*
 * The 5 % quantile of the chi-square distribution with
 * FTEST_PILOT_SAMPLES - 1 = 31 degrees of freedom: (m - 1) s^2 / sigma^2
 * is below it with probability 0.05, so sigma <= s * sqrt(31 / 19.281)
 * = 1.268 s with probability 0.95
 */
#define FTEST_PILOT_CHI2_05		19.281
/* --confidence: P from 0.5 to 0.9999 (in units of 1e-4) */
#define FTEST_CONFIDENCE_MIN_1E4	5000
#define FTEST_CONFIDENCE_MAX_1E4	9999
/* Largest TMPS spread (codes) within one averaging run: 0.625 degC */
#define FTEST_TMPS_SPREAD_MAX		1
#define FTEST_STABLE_TIMEOUT_MS_DEFAULT	10000
/* How long the test through the driver waits for another program's capture */
#define FTEST_BUSY_TIMEOUT_MS_DEFAULT	30000
#define FTEST_BUSY_TIMEOUT_S_MAX	3600
/* Field recalibration: stricter than the factory */
#define FTEST_USER_FLUCTUATION		8
#define FTEST_USER_TILT_DEG		10

/**
 * struct ftest_opts - how to run the test
 * @samples:		N, samples averaged per level measurement (0: D7's 10)
 * @permissible_error_q16: Sigma of Note 2 in LSB Q16 (0: use @samples)
 * @confidence_1e4:	with a permissible error, 0: Note 2's rule, a
 *			one-sigma bound (the standard error of each stored
 *			mean <= E); else P x 10000: |stored mean - true
 *			value| <= E with probability P per axis (N scaled by
 *			the normal quantile z_(1+P)/2 squared)
 * @fluctuation:	max - min limit per axis, LSB (Note 3)
 * @lpf:		accelerometer low-pass filter on (SLCT2 ALPF)
 * @gravity_given:	@gravity was given (else D8 detects it)
 * @gravity:		direction of gravity in the sensor frame
 * @keep_going:		go on after a failed judgment
 * @stable_timeout_ms:	how long to wait for a stable temperature
 * @busy_timeout_ms:	how long to wait for another program to stop
 *			capturing from the IIO device (--backend iio)
 * @level_only:		skip step 2 (field recalibration and checks)
 * @user_mode:		a product user runs it: stricter conditions (still,
 *			flat within FTEST_USER_TILT_DEG) and plain messages
 * @measure_only:	stop after the first level run: no DAC change
 * @expect_eeprom:	refuse a chip whose EEPROM differs (NULL: any chip)
 * @apply_dac:		DAC values to load after the trims (NULL: EEPROM's)
 * @note_order:		the application note's literal order on the register
 *			backends: every register of a sample read before the
 *			next MS write, t_PD before the trims, the project's
 *			read-backs at once (default: the datasheet's order,
 *			the bus working while the chip converts; the same
 *			judgments)
 */
struct ftest_opts {
	uint32_t samples;
	uint32_t permissible_error_q16;
	uint32_t confidence_1e4;
	uint32_t fluctuation;
	bool lpf;
	bool gravity_given;
	int8_t gravity[AS9888_AXES];
	bool keep_going;
	uint32_t stable_timeout_ms;
	uint32_t busy_timeout_ms;
	bool level_only;
	bool user_mode;
	bool measure_only;
	const uint8_t *expect_eeprom;
	const uint8_t *apply_dac;
	bool note_order;
};

void ftest_opts_default(struct ftest_opts *o);

/* The normal quantile z with P(|Z| <= z) = @p, for 0 < @p < 1 */
double ftest_two_sided_z(double p);

/**
 * struct ftest_result - what the test found
 * @report:	every judgment
 * @warnings:	EEPROM warnings (D4, D9), as enum as9888_ee_warning bits
 * @ee:		the decoded EEPROM (valid when @have_eeprom)
 * @have_eeprom: step 1 read and decoded the EEPROM
 * @have_calibration: step 3 completed and @rec holds the calibration
 * @rec:	the calibration record (without timestamp)
 * @offset_q16:	Ot_L per axis with the new DAC values
 * @duration_ns: how long steps 1..3 took on the backend's clock
 * @have_level:	a level run completed (@level_* valid), also with
 *		@measure_only
 * @level_mean_q16: its mean per axis
 * @level_t_mdegc: its temperature
 * @level_g:	its gravity direction
 * @backend:	the backend the test ran on ("sim", "raw", "iio"), set by the
 *		caller (NULL: not said)
 * @pilot_sigma: with a permissible error: the pilot's sigma-hat of the
 *		noisiest axis, LSB
 * @pilot_sigma_upper: its 95 % upper confidence bound, which chose N
 * @bound_z:	the normal quantile N was chosen for (1: one-sigma bound)
 * @level_se:	the standard error each stored level mean achieved, from
 *		its own run's samples: s / sqrt(N), LSB
 * @overlap_lost: measurements lost because a stall let the next
 *		measurement end before the last sample was read (datasheet's
 *		order only; the run then took more)
 * @opts:	the options the test ran with
 * @started:	when it started, seconds since the epoch (UTC)
 */
struct ftest_result {
	struct report report;
	uint32_t warnings;
	struct as9888_eeprom ee;
	bool have_eeprom;
	bool have_calibration;
	struct calib_record rec;
	int32_t offset_q16[AS9888_AXES];
	uint64_t duration_ns;
	bool have_level;
	int32_t level_mean_q16[AS9888_AXES];
	int32_t level_t_mdegc;
	int8_t level_g[AS9888_AXES];
	const char *backend;
	double pilot_sigma;
	double pilot_sigma_upper;
	double bound_z;
	double level_se[AS9888_AXES];
	uint32_t overlap_lost;
	struct ftest_opts opts;
	int64_t started;
};

/*
 * Run steps 1..3. Returns 0 when the test ran to its end (judgments may
 * still have failed: see report_first_failure()), -errno when it could not
 * go on (the failing judgment is in the report).
 */
int ftest_run(struct transport *t, const struct ftest_opts *o,
	      struct ftest_result *res);
void ftest_result_free(struct ftest_result *res);

/*
 * The same test through the AS9888 IIO driver bound to the chip, whose
 * sysfs directory is @dir (iio_find_device()): see ftest_iio.c for how each
 * step maps onto the driver's interfaces. The device's attributes are left
 * as they were found.
 */
int ftest_run_iio(const char *dir, const struct ftest_opts *o,
		  struct ftest_result *res);

/*
 * Step 1 only: reset, identify, read the EEPROM (refused when it is not
 * @o->expect_eeprom), load the trims (@o->apply_dac as the DAC values) and
 * read them back. Used to apply a record.
 */
int ftest_step1(struct transport *t, const struct ftest_opts *o,
		     struct ftest_result *res);

#endif
