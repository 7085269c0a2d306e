/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The explicit calibration session of magn-calibrate: samples from a
 * source (magn_source.h) fed to the fit library (lib/magcal) while the
 * user turns the device, progress shown, until the fit's quality is
 * reached or the time is up.
 */
#ifndef AS9888_MAGN_SESSION_H
#define AS9888_MAGN_SESSION_H

#include <stdint.h>
#include <stdio.h>

#include "magcal.h"
#include "magn/magn_source.h"
#include "common/record.h"

/*
 * One sample every 50 ms: 20 Hz, a turning hand moves a few degrees; each
 * the mean of MAGN_SOURCE_AVERAGE measurements (magn_source.h)
 */
#define MAGN_SESSION_INTERVAL_NS	50000000ULL
/* A fit is tried after every this many newly kept samples */
#define MAGN_SESSION_SOLVE_EVERY	10
/*
 * The session goes on past magcal's own minimum (its MAGCAL_OK) until the
 * samples cover this much of the sphere: more directions, a better fit,
 * and part of the disturbance gate's margin. What is enough depends on
 * the samples' noise: samples that are the mean of MAGN_SOURCE_AVERAGE
 * measurements need MAGN_SESSION_COVERAGE, samples of one measurement
 * (sysfs reads; the field mode's, one from a consumer each)
 * MAGN_SESSION_COVERAGE_SINGLE (the sweep in docs/DECISIONS.md, "Compass
 * v3: five measurements a sample"). The fit at the timeout is held to it
 * too (magn_session_done()).
 */
#define MAGN_SESSION_COVERAGE		0.55
#define MAGN_SESSION_COVERAGE_SINGLE	0.6
/*
 * The consistency gate's limit on the field strength's drift along a
 * session (magcal_config max_drift_ut), uT: a session lasts two minutes
 * at most, in which nothing but a moving magnet or steel changes the
 * field's strength by this much beyond the noise (undisturbed runs of the
 * sweeps drift by 0.00; a slow magnet that a motion visiting each
 * direction once let through, 0.17..0.37). The field mode, whose samples
 * span hours of temperature, keeps magcal's default (0.4).
 */
#define MAGN_SESSION_MAX_DRIFT_UT	0.1
/*
 * A fit whose magnetometer is turned by this much against the
 * accelerometer (magcal_result turn_deg: an asymmetric soft iron, which
 * the record cannot hold) is stored with a note saying so
 */
#define MAGN_SESSION_TURN_NOTE_DEG	0.5
/*
 * Progress is printed after every this many newly kept samples, and at
 * the latest after this many samples (2 s): a user turning through what
 * is covered keeps no sample, and is told where to turn next
 */
#define MAGN_SESSION_PROGRESS_EVERY	20
#define MAGN_SESSION_PROGRESS_SAMPLES	40

/**
 * struct magn_hint - a turn of the device that covers more directions
 * @axis:	the axis to turn the device about (0 X, 1 Y, 2 Z)
 * @sign:	+1: right-handed about it (X turns +Y toward +Z, Y turns
 *		+Z toward +X, Z turns +X toward +Y); -1: the other way
 * @deg:	about how far
 * @device:	@axis is the device's (the driver's mount matrix applied),
 *		not the chip's
 */
struct magn_hint {
	int axis;
	int sign;
	double deg;
	bool device;
};

/**
 * struct magn_session_result - how a session ended
 * @fit:	the last fit (valid when @solved)
 * @solved:	a fit was made at all
 * @samples:	samples taken (each the mean of a source's measurements)
 * @overflows:	samples the magnetometer overflowed in (skipped)
 * @coverage:	the coverage when it ended
 * @elapsed_ns:	how long it ran, on the source's clock
 * @averaged:	every sample was the mean of MAGN_SOURCE_AVERAGE
 *		measurements (the coverage it needs: magn_session_done())
 */
struct magn_session_result {
	struct magcal_result fit;
	bool solved;
	bool averaged;
	unsigned int samples;
	unsigned int overflows;
	double coverage;
	uint64_t elapsed_ns;
};

/* The coverage a stored fit needs: its samples @averaged or of one measurement */
double magn_session_coverage(bool averaged);

/*
 * A fit that is stored: magcal's MAGCAL_OK and magn_session_coverage(),
 * @averaged when each of its samples was the mean of MAGN_SOURCE_AVERAGE
 * measurements
 */
bool magn_session_done(const struct magcal_result *fit, bool averaged);

/*
 * Where to turn the device from the reading @m_ut to cover the nearest
 * directions not covered yet (magcal_guide()), as a turn about the
 * device's axis nearest to the exact one when @mount (device = mount *
 * sensor) is given, else the chip's: 0, or magcal_guide()'s -errno
 */
int magn_session_hint(const struct magcal_session *fit, const double m_ut[3],
		      const double (*mount)[AS9888_AXES], struct magn_hint *h);

/* magn_hint_text()'s longest text and its end */
#define MAGN_HINT_TEXT_MAX	96

/* @h in words: "turn it about the device's X axis, +Y toward +Z, ..." */
void magn_hint_text(const struct magn_hint *h, char *buf, size_t size);

/*
 * Run a session on @src for at most @timeout_ns, progress lines to
 * @progress (NULL: none). @earth_ut: the site's field strength, uT, the
 * calibrated magnitude (magcal's reference_field_ut), or 0: none. 0 when the fit's quality was reached (@res->fit
 * with status MAGCAL_OK), -ETIMEDOUT when the time ran out first (@res
 * says how far it got), other -errno when the source failed (why in
 * @err).
 */
int magn_session_run(struct magn_source *src, uint64_t timeout_ns,
		     double earth_ut, FILE *progress, struct magn_session_result *res,
		     char *err, size_t errlen);

/*
 * Why a session that ran out of time failed, for the user, with what to
 * do about it
 */
void magn_session_why(const struct magn_session_result *res, char *buf,
		      size_t size);

/*
 * The record's form of a successful fit, learned at @now. 0, or -ERANGE
 * with why in @err when it is beyond what a record keeps (the driver's
 * calibscale range 0.5..2, a hard iron beyond +-1000 uT).
 */
int magn_session_to_record(const struct magcal_result *fit, int64_t now,
			   struct calib_magn *m, char *err, size_t errlen);

#endif
