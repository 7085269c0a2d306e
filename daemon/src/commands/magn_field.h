/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The daemon's field mode for the magnetometer: the calibration refined
 * from the samples magnetometer consumers read anyway, which they hand to
 * the daemon ("magn-feed" on its socket; as9888_magn_feed() in
 * libas9888magn). The daemon itself never reads, enables or wakes the
 * magnetometer for it: with no consumer it sleeps as before (0 wake-ups).
 *
 * The samples (uncalibrated, uT) are kept in a file on a tmpfs (the
 * runtime directory), at most MAGN_FIELD_KEEP of them, kept by direction
 * as magn-calibrate's are (magcal's store: a long time in one posture
 * does not push out the directions covered before); every
 * MAGN_FIELD_FIT_EVERY new ones the fit library solves them, and the
 * record is rewritten only when the fit is good, it differs meaningfully
 * from the record's calibration (MAGN_FIELD_BIAS_STEP_NT,
 * MAGN_FIELD_W_STEP_MICRO, for W and the turn) and the record's calibration is at least
 * MAGN_FIELD_MIN_AGE_S old (docs/DECISIONS.md: the flash wear).
 */
#ifndef AS9888_MAGN_FIELD_H
#define AS9888_MAGN_FIELD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "magcal.h"
#include "common/record.h"

#define MAGN_FIELD_KEEP			300
#define MAGN_FIELD_FIT_EVERY		50
/* A calibration is replaced at most once per 6 hours: 4 rewrites a day */
#define MAGN_FIELD_MIN_AGE_S		(6 * 3600)
/*
 * Meaningful: the hard iron moved by 1 uT on an axis, or a term of W or
 * of the turn Rrot by 0.01 (a turn of about 0.57 deg)
 */
#define MAGN_FIELD_BIAS_STEP_NT		1000
#define MAGN_FIELD_W_STEP_MICRO		10000
/* The samples file: in $RUNTIME_DIRECTORY, else beside the socket */
#define MAGN_FIELD_SAMPLES_NAME		"magn-samples"

/*
 * A W whose det^(1/3) is this far from 1 was scaled to the site's field
 * (magn-calibrate --earth-field): det 1 is the fit's own, to the record's
 * micro units
 */
#define MAGN_FIELD_SCALED_TOL		1e-4

/*
 * The site's field (uT) the calibration @m was scaled to by
 * magn-calibrate --earth-field, for the field mode's fits to keep; 0 when
 * it was not (its W has det 1) or there is none
 */
double magn_field_reference_ut(const struct calib_magn *m);

/*
 * Whether the calibration @next should replace @cur (present or not) at
 * @now: it is meaningfully different and @cur is old enough
 */
bool magn_field_should_replace(const struct calib_magn *cur,
			       const struct calib_magn *next, int64_t now);

/*
 * Add the sample @m (uT, uncalibrated), @a (the accelerometer's reading)
 * to the samples file @path (locked; created 0600, refused unless ours and
 * writable by us alone): the file's samples and this one go through
 * @fit's store, an empty session, and what it keeps is written back,
 * oldest first. 1 when MAGN_FIELD_FIT_EVERY samples came since the last
 * fit (@fit then holds the store: solve it), 0 when not yet, -errno with
 * why in @err.
 */
int magn_field_store_sample(const char *path, const double m[AS9888_AXES],
			    const double a[AS9888_AXES],
			    struct magcal_session *fit, char *err, size_t errlen);

#endif
