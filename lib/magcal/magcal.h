/* SPDX-License-Identifier: GPL-2.0 */
/*
 * magcal: magnetometer calibration (hard and soft iron) from the samples a
 * device produces while it moves, for the AS9888 calibration daemon.
 *
 * The model: the magnetometer reads m = S b_ext + h (+ noise), b_ext the
 * external field (the Earth's, constant in the world), h the hard iron, S
 * the soft iron. The samples of a turning device lie on an ellipsoid; the
 * fit finds its centre b (= h) and a symmetric W with |W (m - b)| = F for
 * every sample, F the field's magnitude. The calibrated field is then
 * c = W (m - b).
 *
 * A session keeps a bounded set of samples (at most MAGCAL_MAX_SAMPLES
 * distinct ones) that keeps coverage: the samples are binned by the
 * direction of the field in the sensor frame, and a full store replaces
 * the oldest sample of the most crowded cell, so a direction seen once
 * stays however long the user then turns elsewhere. It reports how much
 * of the sphere of directions they cover, and solves on request: a robust
 * fit (outliers such as a strong passing magnet are found and left out),
 * regularised toward a sphere where the motion left a direction
 * unobserved, with quality figures and a status. A fit must also be
 * consistent in time: a field whose magnitude or dip drifts along the
 * samples (a weak magnet passing slowly, which the fit would absorb into
 * a wrong hard iron) is refused (MAGCAL_INCONSISTENT).
 *
 * The scale of W is not observable (a sphere of radius kF reads the same
 * as one of F): W is normalised to det(W) = 1, so an isotropic gain of the
 * board's soft iron stays in the calibrated magnitude. Heading, which
 * uses directions only, does not depend on it. An integrator who knows
 * the site's field strength (the World Magnetic Model's, as Android's
 * GeomagneticField gives it) sets config reference_field_ut: W is then
 * scaled so the calibrated magnitude is that reference.
 *
 * Userspace C99, double arithmetic, no global state: sessions are
 * independent and may be used from different threads (one thread per
 * session). Units: uT for fields, degrees for angles.
 */
#ifndef MAGCAL_H
#define MAGCAL_H

#include <stdbool.h>
#include <stddef.h>

#define MAGCAL_MAX_SAMPLES	300

/**
 * enum magcal_status - the verdict of magcal_solve()
 * @MAGCAL_OK:			the fit meets every quality figure
 * @MAGCAL_NO_COVERAGE:		too few samples, or they cover too little of
 *				the sphere of directions, or they leave the
 *				fit uncertain (keep moving)
 * @MAGCAL_FIELD_IMPLAUSIBLE:	the fitted magnitude is outside the Earth's
 *				(config field_min_ut .. field_max_ut): a
 *				magnet, a wrong scale
 * @MAGCAL_RESIDUAL_HIGH:	the samples do not lie on one ellipsoid (a
 *				disturbance through the session, a changing
 *				hard iron): rms above config max_residual_ut
 * @MAGCAL_SINGULAR:		the fit did not converge (degenerate data)
 * @MAGCAL_INCONSISTENT:	the field changed along the session: the
 *				residuals (its magnitude) or the dip (its
 *				angle to gravity) drift in time beyond config
 *				max_drift_ut / max_dip_drift_deg (a magnet
 *				passing slowly, which a fit can absorb)
 */
enum magcal_status {
	MAGCAL_OK = 0,
	MAGCAL_NO_COVERAGE,
	MAGCAL_FIELD_IMPLAUSIBLE,
	MAGCAL_RESIDUAL_HIGH,
	MAGCAL_SINGULAR,
	MAGCAL_INCONSISTENT,
};

/**
 * struct magcal_config - thresholds (magcal_config_default() fills them)
 * @max_samples:	samples kept, 1..MAGCAL_MAX_SAMPLES
 * @min_samples:	fewer samples used than this: MAGCAL_NO_COVERAGE
 * @min_coverage:	coverage (0..1) below this: MAGCAL_NO_COVERAGE
 * @min_separation_ut:	a sample closer than this to a kept one replaces
 *			nothing and is not kept (a device lying still)
 * @field_min_ut:	plausible Earth field, lower bound (20)
 * @field_max_ut:	plausible Earth field, upper bound (70)
 * @max_residual_ut:	residual rms above this: MAGCAL_RESIDUAL_HIGH
 * @outlier_ut:		a sample whose residual exceeds the larger of this
 *			and 4 robust standard deviations is rejected
 * @max_uncertainty_deg: the fit's own uncertainty (see magcal_result)
 *			above this: MAGCAL_NO_COVERAGE
 * @reference_field_ut:	the site's field magnitude, uT, or 0 (the default):
 *			none. When set (within field_min_ut..field_max_ut),
 *			magcal_solve() scales W (after every check has
 *			judged the fit as made) so that the calibrated
 *			field's magnitude is this reference
 * @max_drift_ut:	slow drift of the residuals (magcal_result
 *			drift_ut) above this: MAGCAL_INCONSISTENT
 * @max_dip_drift_deg:	slow drift of the dip (magcal_result
 *			dip_drift_deg) above this: MAGCAL_INCONSISTENT
 * @max_turn_uncertainty_deg: the turn (magcal_result turn) is trusted
 *			(given in @rot) only when its uncertainty is at most
 *			this (0.3): orientations varied about one axis only
 *			leave the turn about that axis unobserved
 */
struct magcal_config {
	unsigned int max_samples;
	unsigned int min_samples;
	double min_coverage;
	double min_separation_ut;
	double field_min_ut;
	double field_max_ut;
	double max_residual_ut;
	double outlier_ut;
	double max_uncertainty_deg;
	double reference_field_ut;
	double max_drift_ut;
	double max_dip_drift_deg;
	double max_turn_uncertainty_deg;
};

/**
 * struct magcal_result - what magcal_solve() found
 * @status:	the verdict; the numbers below are filled whenever a fit was
 *		made (also with a status other than MAGCAL_OK) so that a
 *		caller can show why
 * @bias:	hard iron b, uT, sensor frame
 * @w:		soft-iron correction W, symmetric, det(W) = @scale^3
 * @field_ut:	the calibrated field's magnitude F, uT: the fitted one, or
 *		the reference when config reference_field_ut is set
 * @fitted_field_ut: the fitted field magnitude (det(W) = 1), uT: what the
 *		plausibility check (field_min_ut..field_max_ut) judged
 * @scale:	the factor W was scaled by: reference_field_ut /
 *		@fitted_field_ut with a reference, else 1
 * @residual_ut: rms of |W (m - b)| - F over the samples used, uT (in the
 *		calibrated field's scale: the quality check judged it
 *		before the scaling)
 * @coverage:	fraction of the sphere of directions covered, 0..1
 * @used:	samples the fit used
 * @rejected:	samples left out as outliers
 * @uncertainty_deg: how well the samples pin the fit down, as a
 *		direction error of the calibrated field (degrees, one standard
 *		deviation, from the parameters' covariance without the prior):
 *		large when the motion left a direction unobserved
 * @dip_deg:	field inclination seen against gravity (mean angle below
 *		the horizon), when gravity was given with the samples used;
 *		else 0
 * @has_dip:	@dip_deg is valid
 * @drift_ut:	the residuals' slow structure in time, uT: the largest
 *		mean over 12 successive samples used (in the order they were
 *		kept) away from their median, beyond what the noise seen
 *		between neighbours explains; 0 for a field that stayed put
 * @dip_drift_deg: the same of the dip, degrees (0 without gravity),
 *		after @turn_deg is taken out
 * @turn_deg:	the magnetometer's turn against the accelerometer that best
 *		makes the dip constant over the orientations (an asymmetric
 *		soft iron), degrees, at most 5 (0: none found, or none that
 *		small). Learned only from the samples whose gravity's
 *		magnitude is within 2 % of the median's (1 g: a hand's
 *		linear acceleration biases the dip), exact for turns of a few
 *		degrees (Gauss-Newton on the rotation)
 * @turn:	that turn as a rotation vector, degrees (its length is
 *		@turn_deg): the rotation by @turn of W (m - b) is the field
 *		in the accelerometer's frame
 * @turn_uncertainty_deg: the turn's standard deviation, degrees (the
 *		square root of the trace of its covariance; infinite when
 *		the samples do not determine it)
 * @turn_trusted: @turn_uncertainty_deg is within config
 *		max_turn_uncertainty_deg: the turn is measured, not guessed
 * @rot:	the rotation to store and apply after W: the rotation by @turn
 *		when @turn_trusted, else the identity. The full correction is
 *		then @rot W (m - b) (magcal_apply() applies W only)
 */
struct magcal_result {
	enum magcal_status status;
	double bias[3];
	double w[3][3];
	double field_ut;
	double fitted_field_ut;
	double scale;
	double residual_ut;
	double coverage;
	unsigned int used;
	unsigned int rejected;
	double uncertainty_deg;
	double dip_deg;
	bool has_dip;
	double drift_ut;
	double dip_drift_deg;
	double turn_deg;
	double turn[3];
	double turn_uncertainty_deg;
	bool turn_trusted;
	double rot[3][3];
};

struct magcal_session;

/* The default thresholds (see struct magcal_config). */
void magcal_config_default(struct magcal_config *cfg);

/*
 * A new, empty session with @cfg (NULL: the defaults). Returns NULL on
 * allocation failure or an invalid @cfg.
 */
struct magcal_session *magcal_new(const struct magcal_config *cfg);
void magcal_free(struct magcal_session *s);

/* Forget every sample (a new session with the same configuration). */
void magcal_reset(struct magcal_session *s);

/**
 * magcal_add() - offer one sample
 * @s:		the session
 * @m_ut:	the magnetometer's reading, uT, sensor frame (uncalibrated)
 * @gravity:	the accelerometer's reading at the same time (any scale,
 *		pointing up when the device is still), or NULL
 *
 * Return: 1 when the sample was kept, 0 when it was too close to a kept
 * one (not kept), -EINVAL for a reading that is not finite.
 */
int magcal_add(struct magcal_session *s, const double m_ut[3],
	       const double *gravity);

/* Samples kept now. */
unsigned int magcal_count(const struct magcal_session *s);

/*
 * The samples kept now, oldest first (the order they were kept in, which
 * the consistency gate judges): at most @max readings into @m and their
 * gravity into @g (zeros for a sample offered without; @g may be NULL).
 * Offered again in this order to an empty session of the same
 * configuration they are all kept, in the same order: a caller can keep
 * the store between runs (the daemon's field mode keeps it in a file).
 * Returns how many.
 */
unsigned int magcal_export(const struct magcal_session *s, double m[][3],
			   double g[][3], unsigned int max);

/*
 * Progress: the fraction (0..1) of the sphere of directions the kept
 * samples cover, seen from the current estimate of the centre.
 */
double magcal_progress(const struct magcal_session *s);

/**
 * magcal_guide() - which way to turn the device to cover more
 * @s:		the session
 * @m_ut:	the latest reading, uT, sensor frame
 * @axis:	out: the unit axis, sensor frame, to turn the device about
 *		(right-handed: a positive turn about it)
 * @deg:	out: by how much, degrees
 *
 * The field's direction in the sensor frame, seen from the current
 * estimate of the centre, is taken to the nearest of the coverage's cells
 * that no kept sample is in: turning the device by @deg about @axis turns
 * the field seen by the sensor by -@deg about it, onto that cell's centre.
 *
 * Return: 0; -ENOENT when every cell is covered; -EAGAIN when there is no
 * estimate of the centre yet (too few samples) or @m_ut is at it;
 * -EINVAL for NULL arguments.
 */
int magcal_guide(const struct magcal_session *s, const double m_ut[3],
		 double axis[3], double *deg);

/*
 * Fit the kept samples. Returns 0 with @r filled (r->status is the
 * verdict), or -EINVAL for NULL arguments. The session is unchanged.
 */
int magcal_solve(const struct magcal_session *s, struct magcal_result *r);

/* Human-readable name of a status ("ok", "not enough coverage", ...). */
const char *magcal_status_str(enum magcal_status st);

/* The full correction: out = W (m - b). @out may be @m. */
void magcal_apply(const struct magcal_result *r, const double m[3],
		  double out[3]);

/**
 * magcal_split() - split W for the driver and userspace
 * @r:		a result
 * @diag:	the diagonal D the driver applies (its calibscale per axis)
 * @resid:	R = W D^-1, what userspace applies to the driver's output
 *
 * W (m - b) = R D (m - b): the driver subtracts the bias and scales each
 * axis, userspace multiplies by R (the identity when W is diagonal).
 */
void magcal_split(const struct magcal_result *r, double diag[3],
		  double resid[3][3]);

/**
 * magcal_heading_deg() - tilt-compensated compass heading
 * @field:	calibrated field, sensor frame (any scale)
 * @up:		the accelerometer's reading of a still device (points up,
 *		any scale), sensor frame
 * @declination_deg: magnetic north's angle east of true north (0 for a
 *		magnetic heading)
 * @heading:	the heading of the sensor's +Y axis, clockwise from north,
 *		0 <= heading < 360
 *
 * Return: 0, or -EDOM when the field is parallel to up or +Y points
 * straight up or down (no heading).
 */
int magcal_heading_deg(const double field[3], const double up[3],
		       double declination_deg, double *heading);

#endif /* MAGCAL_H */
