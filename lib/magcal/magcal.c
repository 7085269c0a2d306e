// SPDX-License-Identifier: GPL-2.0
/*
 * magcal: the ellipsoid fit of magcal.h.
 *
 * Method (docs/DECISIONS.md, "Magnetometer calibration: the fit"):
 *  1. A linear sphere fit (|m|^2 = 2 b.m + k, least squares) gives a centre
 *     c0 and a radius F0; the samples are normalised to (m - c0) / F0.
 *  2. Levenberg-Marquardt on the geometric residual |L (m' - b')| - 1 over
 *     nine parameters (b', the symmetric L), with three plus three prior
 *     rows that pull L toward a multiple of the identity: weak where the
 *     motion observed a direction, decisive where it did not (partial
 *     coverage), so an unobserved axis stays a sphere's instead of
 *     running away.
 *  0. Robust start: a RANSAC sphere (exact spheres through 4 samples, the
 *     one with the most samples within 15 % of its radius wins: a soft
 *     iron of +-10 % stays inside, a passing magnet of a few uT and more
 *     falls outside; only radii near a plausible Earth field compete, or a
 *     huge sphere would hold everything) chooses the samples of the first
 *     fit.
 *  3. Robustness: rounds that keep every sample whose residual is within
 *     max(outlier_ut, 4 robust sigma) of the last fit, until the set is
 *     stable.
 *  4. W = L / det(L)^(1/3), b = c0 + F0 b', F = F0 / det(L)^(1/3).
 *  5. With a reference field R (config reference_field_ut), after the
 *     verdict: W *= R / F, F = R (docs/DECISIONS.md, "Magnetometer
 *     magnitude: the site's field as a reference").
 *  6. Consistency in time (before the verdict): the residuals and the dip
 *     of the samples used, in the order they were kept, must not drift
 *     (means over DRIFT_WINDOW successive samples against the median,
 *     beyond the noise between neighbours): docs/DECISIONS.md, "Compass
 *     v2: the store and the gate".
 * The store (magcal_add): see store_victim().
 */

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "magcal.h"

#define NPARAM			9	/* b'(3), L00 L11 L22 L01 L02 L12 */
#define LM_MAX_ITER		60
#define LM_TOL			1e-12
#define RANSAC_TRIES		80
#define RANSAC_TOL		0.15	/* of the radius */
/* candidate radii: the plausible field, widened by the soft iron */
#define RANSAC_RADIUS_SLACK	0.7
#define ROBUST_ROUNDS		8
#define ROBUST_SIGMAS		4.0
#define MAD_TO_SIGMA		1.4826
/* prior: expected size of the anisotropic part of L (row weight) */
#define PRIOR_WEIGHT		0.1
/* coverage: cube faces split in 3 x 3 equal-angle cells */
#define FACE_SPLIT		0.2679491924311228	/* tan(15 deg) */
/* a cell's centre on its face: the middle of 15..45 deg, tan(30 deg) */
#define FACE_CENTRE		0.5773502691896257
/* two directions closer than this (the sine between them) are parallel */
#define PARALLEL_SIN		1e-9
#define COVER_BINS		54
#define DEG_PER_RAD		(180.0 / M_PI)
/* consistency in time: means over this many successive samples */
#define DRIFT_WINDOW		12
#define DRIFT_SIGMAS		4.0
/* the largest turn of the magnetometer against gravity taken out, deg */
#define MAX_TURN_DEG		5.0
/* the turn learned from samples whose |g| is within 2 % of 1 g only */
#define TURN_G_TOLERANCE	0.02
/* Gauss-Newton steps of the turn at most (two make 5 deg exact) */
#define TURN_STEPS		4

/* the store's cells: cube faces split in 4 x 4 equal-angle cells */
#define STORE_SPLIT		4
#define STORE_BINS		(6 * STORE_SPLIT * STORE_SPLIT)

struct sample {
	double m[3];
	double g[3];
	bool has_g;
	unsigned long long seq;	/* the order samples were kept in */
};

struct magcal_session {
	struct magcal_config cfg;
	unsigned int n;		/* samples kept */
	unsigned long long seq;	/* samples kept so far, ever */
	struct sample s[MAGCAL_MAX_SAMPLES];
};

/* A fit in progress: normalisation and the nine parameters */
struct fit {
	double c0[3];
	double f0;
	double x[NPARAM];
};

void magcal_config_default(struct magcal_config *cfg)
{
	cfg->max_samples = MAGCAL_MAX_SAMPLES;
	cfg->min_samples = 40;
	cfg->min_coverage = 0.4;
	cfg->min_separation_ut = 2.0;
	cfg->field_min_ut = 20.0;
	cfg->field_max_ut = 70.0;
	cfg->max_residual_ut = 1.5;
	cfg->outlier_ut = 2.0;
	cfg->max_uncertainty_deg = 0.6;
	cfg->reference_field_ut = 0;
	cfg->max_drift_ut = 0.4;
	cfg->max_dip_drift_deg = 0.6;
	cfg->max_turn_uncertainty_deg = 0.3;
}

static bool config_ok(const struct magcal_config *c)
{
	return c->max_samples >= 1 && c->max_samples <= MAGCAL_MAX_SAMPLES &&
	       c->min_coverage >= 0 && c->min_coverage <= 1 &&
	       c->min_separation_ut >= 0 && c->field_min_ut >= 0 &&
	       c->field_max_ut > c->field_min_ut && c->max_residual_ut > 0 &&
	       c->outlier_ut > 0 && c->max_uncertainty_deg > 0 &&
	       c->max_drift_ut > 0 && c->max_dip_drift_deg > 0 &&
	       c->max_turn_uncertainty_deg > 0 &&
	       (c->reference_field_ut == 0 ||
		(c->reference_field_ut >= c->field_min_ut &&
		 c->reference_field_ut <= c->field_max_ut));
}

struct magcal_session *magcal_new(const struct magcal_config *cfg)
{
	struct magcal_session *s;
	struct magcal_config def;

	if (!cfg) {
		magcal_config_default(&def);
		cfg = &def;
	}
	if (!config_ok(cfg))
		return NULL;
	s = calloc(1, sizeof(*s));
	if (s)
		s->cfg = *cfg;
	return s;
}

void magcal_free(struct magcal_session *s)
{
	free(s);
}

void magcal_reset(struct magcal_session *s)
{
	s->n = 0;
	s->seq = 0;
}

unsigned int magcal_count(const struct magcal_session *s)
{
	return s->n;
}

unsigned int magcal_export(const struct magcal_session *s, double m[][3],
			   double g[][3], unsigned int max)
{
	unsigned int order[MAGCAL_MAX_SAMPLES], i, j, n;

	if (!s || !m)
		return 0;
	/* insertion sort by the order kept (C99 has no qsort with a context) */
	for (i = 0; i < s->n; i++) {
		for (j = i; j > 0 && s->s[order[j - 1]].seq > s->s[i].seq; j--)
			order[j] = order[j - 1];
		order[j] = i;
	}
	n = s->n < max ? s->n : max;
	for (i = 0; i < n; i++) {
		const struct sample *k = &s->s[order[i]];

		memcpy(m[i], k->m, sizeof(m[i]));
		if (g && k->has_g)
			memcpy(g[i], k->g, sizeof(g[i]));
		else if (g)
			memset(g[i], 0, sizeof(g[i]));
	}
	return n;
}

static double dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) +
		    (a[1] - b[1]) * (a[1] - b[1]) +
		    (a[2] - b[2]) * (a[2] - b[2]));
}

static double norm3(const double a[3])
{
	return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

static bool finite3(const double a[3])
{
	return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

static unsigned int store_victim(const struct magcal_session *s,
				 const double m[3]);

int magcal_add(struct magcal_session *s, const double m_ut[3],
	       const double *gravity)
{
	struct sample *dst;
	unsigned int i;

	if (!s || !m_ut || !finite3(m_ut) || (gravity && !finite3(gravity)))
		return -EINVAL;
	for (i = 0; i < s->n; i++)
		if (dist3(s->s[i].m, m_ut) < s->cfg.min_separation_ut)
			return 0;
	if (s->n < s->cfg.max_samples)
		dst = &s->s[s->n++];
	else
		dst = &s->s[store_victim(s, m_ut)];
	memcpy(dst->m, m_ut, sizeof(dst->m));
	dst->has_g = gravity != NULL;
	if (gravity)
		memcpy(dst->g, gravity, sizeof(dst->g));
	dst->seq = s->seq++;
	return 1;
}

/* ---- linear algebra ---- */

static void cross3(const double a[3], const double b[3], double out[3])
{
	out[0] = a[1] * b[2] - a[2] * b[1];
	out[1] = a[2] * b[0] - a[0] * b[2];
	out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Solve a x = b (n <= NPARAM) by Gaussian elimination; false if singular */
static bool solve(int n, double a[NPARAM][NPARAM], double b[NPARAM],
		  double x[NPARAM])
{
	int i, j, k, p;

	for (k = 0; k < n; k++) {
		p = k;
		for (i = k + 1; i < n; i++)
			if (fabs(a[i][k]) > fabs(a[p][k]))
				p = i;
		if (fabs(a[p][k]) < 1e-300)
			return false;
		for (j = 0; j < n; j++) {
			double t = a[k][j];

			a[k][j] = a[p][j];
			a[p][j] = t;
		}
		{
			double t = b[k];

			b[k] = b[p];
			b[p] = t;
		}
		for (i = k + 1; i < n; i++) {
			double f = a[i][k] / a[k][k];

			for (j = k; j < n; j++)
				a[i][j] -= f * a[k][j];
			b[i] -= f * b[k];
		}
	}
	for (i = n - 1; i >= 0; i--) {
		double t = b[i];

		for (j = i + 1; j < n; j++)
			t -= a[i][j] * x[j];
		x[i] = t / a[i][i];
	}
	for (i = 0; i < n; i++)
		if (!isfinite(x[i]))
			return false;
	return true;
}

static double det3(const double m[3][3])
{
	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
	       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
	       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* ---- the sphere fit (start values, progress) ---- */

/* |m|^2 = 2 b.m + k over the flagged samples; false if degenerate */
static bool sphere_fit(const struct magcal_session *s, const bool *use,
		       double c[3], double *r)
{
	double a[NPARAM][NPARAM] = { { 0 } }, rhs[NPARAM] = { 0 };
	double x[NPARAM], r2;
	unsigned int i, cnt = 0;
	int j, k;

	for (i = 0; i < s->n; i++) {
		const double *m = s->s[i].m;
		double row[4] = { 2 * m[0], 2 * m[1], 2 * m[2], 1 };
		double y = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];

		if (use && !use[i])
			continue;
		cnt++;
		for (j = 0; j < 4; j++) {
			for (k = 0; k < 4; k++)
				a[j][k] += row[j] * row[k];
			rhs[j] += row[j] * y;
		}
	}
	if (cnt < 4 || !solve(4, a, rhs, x))
		return false;
	r2 = x[3] + x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
	if (!(r2 > 0))
		return false;
	memcpy(c, x, 3 * sizeof(double));
	*r = sqrt(r2);
	return true;
}

/* ---- coverage ---- */

/* The cell (0..COVER_BINS-1) of a direction: cube face, then 3 x 3 */
static int cover_bin(const double v[3])
{
	double a[3] = { fabs(v[0]), fabs(v[1]), fabs(v[2]) };
	int face = a[0] >= a[1] && a[0] >= a[2] ? 0 : a[1] >= a[2] ? 1 : 2;
	double u = v[(face + 1) % 3] / a[face];
	double w = v[(face + 2) % 3] / a[face];
	int iu = u < -FACE_SPLIT ? 0 : u > FACE_SPLIT ? 2 : 1;
	int iw = w < -FACE_SPLIT ? 0 : w > FACE_SPLIT ? 2 : 1;

	face = 2 * face + (v[face] < 0);
	return face * 9 + iu * 3 + iw;
}

/* The cells hit by the directions of (m - c), transformed by @w */
static void cover_hits(const struct magcal_session *s, const bool *use,
		       const double c[3], const double w[3][3],
		       bool hit[COVER_BINS])
{
	unsigned int i;
	int j;

	memset(hit, 0, COVER_BINS * sizeof(*hit));
	for (i = 0; i < s->n; i++) {
		double d[3], v[3];

		if (use && !use[i])
			continue;
		for (j = 0; j < 3; j++)
			d[j] = s->s[i].m[j] - c[j];
		for (j = 0; j < 3; j++)
			v[j] = w ? w[j][0] * d[0] + w[j][1] * d[1] +
				   w[j][2] * d[2] : d[j];
		if (norm3(v) > 0)
			hit[cover_bin(v)] = true;
	}
}

/* Fraction of cells hit by the directions of (m - c), transformed by @w */
static double coverage(const struct magcal_session *s, const bool *use,
		       const double c[3], const double w[3][3])
{
	bool hit[COVER_BINS];
	unsigned int cnt = 0;
	int j;

	cover_hits(s, use, c, w, hit);
	for (j = 0; j < COVER_BINS; j++)
		cnt += hit[j];
	return (double)cnt / COVER_BINS;
}

/* The store's cell (0..STORE_BINS-1) of a direction: cube face, then cells */
static int store_bin(const double v[3])
{
	double a[3] = { fabs(v[0]), fabs(v[1]), fabs(v[2]) };
	int face = a[0] >= a[1] && a[0] >= a[2] ? 0 : a[1] >= a[2] ? 1 : 2;
	/* equal angles: atan of the face coordinate, -pi/4..pi/4 */
	double u = atan(v[(face + 1) % 3] / a[face]) / M_PI_2 + 0.5;
	double w = atan(v[(face + 2) % 3] / a[face]) / M_PI_2 + 0.5;
	int iu = (int)fmin(STORE_SPLIT - 1, fmax(0, u * STORE_SPLIT));
	int iw = (int)fmin(STORE_SPLIT - 1, fmax(0, w * STORE_SPLIT));

	face = 2 * face + (v[face] < 0);
	return (face * STORE_SPLIT + iu) * STORE_SPLIT + iw;
}

/* The store's cell of reading @m seen from the centre @c */
static int store_bin_of(const double m[3], const double c[3])
{
	double d[3] = { m[0] - c[0], m[1] - c[1], m[2] - c[2] };

	return norm3(d) > 0 ? store_bin(d) : 0;
}

/*
 * The sample a new reading @m replaces in a full store: the oldest of the
 * most crowded cell of directions (the field's, in the sensor frame, seen
 * from the centre of the samples kept), the new reading counted in its
 * own cell, which wins a tie. A direction seen once stays kept however
 * long the user then turns elsewhere; where the samples crowd, the newest
 * replace the oldest.
 */
static unsigned int store_victim(const struct magcal_session *s,
				 const double m[3])
{
	unsigned int count[STORE_BINS] = { 0 }, oldest[STORE_BINS] = { 0 };
	double c[3] = { 0 }, r;
	int own, best = -1, b;
	unsigned int i, k;

	if (!sphere_fit(s, NULL, c, &r))
		memcpy(c, s->s[0].m, sizeof(c));
	for (i = 0; i < s->n; i++) {
		b = store_bin_of(s->s[i].m, c);
		if (!count[b]++ || s->s[i].seq < s->s[oldest[b]].seq)
			oldest[b] = i;
	}
	own = store_bin_of(m, c);
	for (b = 0; b < STORE_BINS; b++) {
		if (!count[b])
			continue;
		k = count[b] + (b == own);
		if (best < 0 || k > count[best] + (best == own) ||
		    (k == count[best] + (best == own) && b == own))
			best = b;
	}
	return oldest[best];
}

double magcal_progress(const struct magcal_session *s)
{
	double c[3], r;

	if (!s || !sphere_fit(s, NULL, c, &r))
		return 0;
	return coverage(s, NULL, c, NULL);
}

/* The centre direction (unit) of coverage cell @bin: cover_bin()'s inverse */
static void cover_centre(int bin, double v[3])
{
	static const double face_coord[3] = { -FACE_CENTRE, 0, FACE_CENTRE };
	int face = bin / 9, k = face / 2;
	double n;

	v[k] = face % 2 ? -1 : 1;
	v[(k + 1) % 3] = face_coord[bin % 9 / 3];
	v[(k + 2) % 3] = face_coord[bin % 3];
	n = norm3(v);
	v[0] /= n;
	v[1] /= n;
	v[2] /= n;
}

/*
 * The centre of the cell no sample hit nearest to the unit direction
 * @f, into @target: false when every cell is hit
 */
static bool nearest_open_cell(const bool hit[COVER_BINS], const double f[3],
			      double target[3])
{
	double best_dot = 0;
	bool found = false;
	int j;

	for (j = 0; j < COVER_BINS; j++) {
		double v[3], dot;

		if (hit[j])
			continue;
		cover_centre(j, v);
		dot = v[0] * f[0] + v[1] * f[1] + v[2] * f[2];
		if (!found || dot > best_dot) {
			best_dot = dot;
			memcpy(target, v, 3 * sizeof(*v));
			found = true;
		}
	}
	return found;
}

/*
 * The turn of the device that takes the field it sees from the unit
 * direction @f to the unit direction @target: the axis target x f (a turn
 * of the device by t about an axis of its own turns the field it sees by
 * -t), any axis across @f when the two are parallel
 */
static void device_turn(const double f[3], const double target[3],
			double axis[3], double *deg)
{
	double n, dot = f[0] * target[0] + f[1] * target[1] + f[2] * target[2];
	int j;

	cross3(target, f, axis);
	n = norm3(axis);
	if (n < PARALLEL_SIN) {
		/* a helper axis away from f, crossed with it */
		double e[3] = { fabs(f[0]) < M_SQRT1_2, fabs(f[0]) >= M_SQRT1_2,
				0 };

		cross3(e, f, axis);
		n = norm3(axis);
	}
	for (j = 0; j < 3; j++)
		axis[j] /= n;
	*deg = acos(fmax(-1, fmin(1, dot))) * DEG_PER_RAD;
}

int magcal_guide(const struct magcal_session *s, const double m_ut[3],
		 double axis[3], double *deg)
{
	double c[3], r, f[3], target[3], n;
	bool hit[COVER_BINS];
	int j;

	if (!s || !m_ut || !axis || !deg)
		return -EINVAL;
	if (!sphere_fit(s, NULL, c, &r))
		return -EAGAIN;
	for (j = 0; j < 3; j++)
		f[j] = m_ut[j] - c[j];
	n = norm3(f);
	if (!(n > 0))
		return -EAGAIN;
	for (j = 0; j < 3; j++)
		f[j] /= n;
	cover_hits(s, NULL, c, NULL, hit);
	if (!nearest_open_cell(hit, f, target))
		return -ENOENT;
	device_turn(f, target, axis, deg);

	return 0;
}

/* ---- Levenberg-Marquardt on the geometric residual ---- */

static void param_matrix(const double x[NPARAM], double l[3][3])
{
	l[0][0] = x[3];
	l[1][1] = x[4];
	l[2][2] = x[5];
	l[0][1] = l[1][0] = x[6];
	l[0][2] = l[2][0] = x[7];
	l[1][2] = l[2][1] = x[8];
}

/* Residual of one normalised sample and, if @jac, its gradient */
static double residual(const double x[NPARAM], const double mn[3],
		       double jac[NPARAM])
{
	double l[3][3], d[3], u[3], n;
	int j;

	param_matrix(x, l);
	for (j = 0; j < 3; j++)
		d[j] = mn[j] - x[j];
	for (j = 0; j < 3; j++)
		u[j] = l[j][0] * d[0] + l[j][1] * d[1] + l[j][2] * d[2];
	n = norm3(u);
	if (!jac)
		return n - 1;
	if (n < 1e-12)
		n = 1e-12;
	for (j = 0; j < 3; j++) {
		jac[j] = -(l[0][j] * u[0] + l[1][j] * u[1] + l[2][j] * u[2]) / n;
		jac[3 + j] = u[j] * d[j] / n;
	}
	jac[6] = (u[0] * d[1] + u[1] * d[0]) / n;
	jac[7] = (u[0] * d[2] + u[2] * d[0]) / n;
	jac[8] = (u[1] * d[2] + u[2] * d[1]) / n;
	return n - 1;
}

/* The prior rows: off-diagonal and anisotropic diagonal of L toward 0 */
static int prior_rows(const double x[NPARAM], double r[6],
		      double jac[6][NPARAM])
{
	double mean = (x[3] + x[4] + x[5]) / 3;
	int i, j;

	memset(jac, 0, 6 * sizeof(jac[0]));
	for (i = 0; i < 3; i++) {
		r[i] = PRIOR_WEIGHT * (x[3 + i] - mean);
		for (j = 0; j < 3; j++)
			jac[i][3 + j] = PRIOR_WEIGHT * ((i == j) - 1.0 / 3);
		r[3 + i] = PRIOR_WEIGHT * x[6 + i];
		jac[3 + i][6 + i] = PRIOR_WEIGHT;
	}
	return 6;
}

static void normalise(const struct fit *f, const double m[3], double mn[3])
{
	int j;

	for (j = 0; j < 3; j++)
		mn[j] = (m[j] - f->c0[j]) / f->f0;
}

/* Sum of squares at @x; with @jtj/@jtr the normal equations too */
static double accumulate(const struct magcal_session *s, const bool *use,
			 const struct fit *f, const double x[NPARAM],
			 double jtj[NPARAM][NPARAM], double jtr[NPARAM])
{
	double jac[NPARAM], pr[6], pj[6][NPARAM], mn[3], cost = 0, r;
	unsigned int i;
	int j, k, np;

	if (jtj) {
		memset(jtj, 0, sizeof(double) * NPARAM * NPARAM);
		memset(jtr, 0, sizeof(double) * NPARAM);
	}
	for (i = 0; i < s->n; i++) {
		if (!use[i])
			continue;
		normalise(f, s->s[i].m, mn);
		r = residual(x, mn, jtj ? jac : NULL);
		cost += r * r;
		for (j = 0; jtj && j < NPARAM; j++) {
			for (k = 0; k < NPARAM; k++)
				jtj[j][k] += jac[j] * jac[k];
			jtr[j] += jac[j] * r;
		}
	}
	np = prior_rows(x, pr, pj);
	for (i = 0; i < (unsigned int)np; i++) {
		cost += pr[i] * pr[i];
		for (j = 0; jtj && j < NPARAM; j++) {
			for (k = 0; k < NPARAM; k++)
				jtj[j][k] += pj[i][j] * pj[i][k];
			jtr[j] += pj[i][j] * pr[i];
		}
	}
	return cost;
}

/* One damped step from @x; true if it lowered the cost */
static bool lm_step(const struct magcal_session *s, const bool *use,
		    const struct fit *f, double x[NPARAM], double *cost,
		    double *mu)
{
	double jtj[NPARAM][NPARAM], jtr[NPARAM], a[NPARAM][NPARAM];
	double b[NPARAM], dx[NPARAM], xn[NPARAM], c;
	int j, k;

	accumulate(s, use, f, x, jtj, jtr);
	for (j = 0; j < NPARAM; j++) {
		for (k = 0; k < NPARAM; k++)
			a[j][k] = jtj[j][k];
		a[j][j] += *mu * (jtj[j][j] + 1e-9);
		b[j] = -jtr[j];
	}
	if (!solve(NPARAM, a, b, dx)) {
		*mu *= 4;
		return false;
	}
	for (j = 0; j < NPARAM; j++)
		xn[j] = x[j] + dx[j];
	c = accumulate(s, use, f, xn, NULL, NULL);
	if (!(c < *cost)) {
		*mu *= 4;
		return false;
	}
	memcpy(x, xn, sizeof(xn));
	*cost = c;
	*mu = fmax(*mu / 3, 1e-12);
	return true;
}

/* Fit the flagged samples from a sphere start; false if it failed */
static bool fit_used(const struct magcal_session *s, const bool *use,
		     struct fit *f)
{
	double cost, prev, mu = 1e-3;
	int it;

	if (!sphere_fit(s, use, f->c0, &f->f0))
		return false;
	memset(f->x, 0, sizeof(f->x));
	f->x[3] = f->x[4] = f->x[5] = 1;
	cost = accumulate(s, use, f, f->x, NULL, NULL);
	for (it = 0; it < LM_MAX_ITER && mu < 1e12; it++) {
		prev = cost;
		if (lm_step(s, use, f, f->x, &cost, &mu) &&
		    prev - cost <= LM_TOL * (prev + LM_TOL))
			break;
	}
	return isfinite(cost);
}

/* ---- the result ---- */

/* W, b and F from a fit; false when L is not positive definite */
static bool fit_result(const struct fit *f, struct magcal_result *r)
{
	double l[3][3], det, k;
	int i, j;

	param_matrix(f->x, l);
	det = det3(l);
	if (!(det > 0) || l[0][0] <= 0 || l[1][1] <= 0 || l[2][2] <= 0)
		return false;
	k = cbrt(det);
	for (i = 0; i < 3; i++) {
		for (j = 0; j < 3; j++)
			r->w[i][j] = l[i][j] / k;
		r->bias[i] = f->c0[i] + f->f0 * f->x[i];
	}
	r->field_ut = f->f0 / k;
	r->fitted_field_ut = r->field_ut;
	return true;
}

void magcal_apply(const struct magcal_result *r, const double m[3],
		  double out[3])
{
	double d[3];
	int i;

	for (i = 0; i < 3; i++)
		d[i] = m[i] - r->bias[i];
	for (i = 0; i < 3; i++)
		out[i] = r->w[i][0] * d[0] + r->w[i][1] * d[1] +
			 r->w[i][2] * d[2];
}

/* |W (m - b)| - F of sample @i, uT */
static double residual_ut(const struct magcal_session *s, unsigned int i,
			  const struct magcal_result *r)
{
	double c[3];

	magcal_apply(r, s->s[i].m, c);
	return norm3(c) - r->field_ut;
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* The @q quantile (0..1) of |residual| over the flagged samples */
static double abs_quantile(const struct magcal_session *s, const bool *use,
			   const struct magcal_result *r, double q)
{
	double v[MAGCAL_MAX_SAMPLES];
	unsigned int i, n = 0;

	for (i = 0; i < s->n; i++)
		if (!use || use[i])
			v[n++] = fabs(residual_ut(s, i, r));
	if (!n)
		return 0;
	qsort(v, n, sizeof(v[0]), cmp_double);
	return v[(unsigned int)(q * (n - 1) + 0.5)];
}

/* Flag the samples within @limit uT; returns whether the set changed */
static bool select_within(const struct magcal_session *s,
			  const struct magcal_result *r, double limit,
			  bool *use)
{
	bool changed = false;
	unsigned int i;

	for (i = 0; i < s->n; i++) {
		bool in = fabs(residual_ut(s, i, r)) <= limit;

		changed |= in != use[i];
		use[i] = in;
	}
	return changed;
}

/* xorshift64: the RANSAC draws, seeded per solve (no global state) */
static unsigned int draw(unsigned long long *state, unsigned int n)
{
	*state ^= *state << 13;
	*state ^= *state >> 7;
	*state ^= *state << 17;
	return (unsigned int)(*state % n);
}

/* Flag the samples within RANSAC_TOL of the sphere (c, r); count them */
static unsigned int sphere_inliers(const struct magcal_session *s,
				   const double c[3], double r, bool *use)
{
	unsigned int i, cnt = 0;

	for (i = 0; i < s->n; i++) {
		bool in = fabs(dist3(s->s[i].m, c) - r) <= RANSAC_TOL * r;

		if (use)
			use[i] = in;
		cnt += in;
	}
	return cnt;
}

/* The first sample set: the inliers of the best of RANSAC_TRIES spheres */
static void ransac_start(const struct magcal_session *s, bool *use)
{
	unsigned long long state = 0x9e3779b97f4a7c15ULL ^ s->n;
	bool pick[MAGCAL_MAX_SAMPLES];
	double c[3], r, best_c[3] = { 0 }, best_r = 0;
	unsigned int t, k, best = 0, cnt;

	for (t = 0; t < RANSAC_TRIES; t++) {
		memset(pick, 0, s->n * sizeof(pick[0]));
		for (k = 0; k < 4; k++)
			pick[draw(&state, s->n)] = true;
		if (!sphere_fit(s, pick, c, &r) ||
		    r < RANSAC_RADIUS_SLACK * s->cfg.field_min_ut ||
		    r > s->cfg.field_max_ut / RANSAC_RADIUS_SLACK)
			continue;
		cnt = sphere_inliers(s, c, r, NULL);
		if (cnt > best) {
			best = cnt;
			memcpy(best_c, c, sizeof(c));
			best_r = r;
		}
	}
	if (best >= 10) {
		sphere_inliers(s, best_c, best_r, use);
		return;
	}
	/* no plausible sphere: fit them all, the verdict will say why */
	for (t = 0; t < s->n; t++)
		use[t] = true;
}

/* Rounds of fit and selection; false when a fit failed */
static bool robust_fit(const struct magcal_session *s, bool *use,
		       struct fit *f, struct magcal_result *r)
{
	double limit;
	int round;

	ransac_start(s, use);
	for (round = 0; round < ROBUST_ROUNDS; round++) {
		if (!fit_used(s, use, f) || !fit_result(f, r))
			return false;
		limit = MAD_TO_SIGMA * ROBUST_SIGMAS *
			abs_quantile(s, use, r, 0.5);
		limit = fmax(limit, s->cfg.outlier_ut);
		if (!select_within(s, r, limit, use))
			return true;
	}
	return fit_used(s, use, f) && fit_result(f, r);
}

/*
 * How well the samples pin the fit down: the standard deviations of the
 * nine parameters from the data alone (sigma^2 (J^T J)^-1, no prior), as
 * a direction error of the calibrated field in degrees: the bias' share
 * (its largest std over F) and the shape's (the largest std of L, which
 * is relative), combined. A direction the motion did not observe has a
 * huge std: the fit there is the prior's guess, not a measurement.
 */
static double uncertainty_deg(const struct magcal_session *s, const bool *use,
			      const struct fit *f,
			      const struct magcal_result *r)
{
	double jtj[NPARAM][NPARAM] = { { 0 } }, jac[NPARAM], mn[3];
	double a[NPARAM][NPARAM], e[NPARAM], col[NPARAM], var[NPARAM];
	double sq = 0, sigma2, eb = 0, el = 0, res;
	unsigned int i, n = 0;
	int j, k;

	for (i = 0; i < s->n; i++) {
		if (!use[i])
			continue;
		normalise(f, s->s[i].m, mn);
		res = residual(f->x, mn, jac);
		sq += res * res;
		n++;
		for (j = 0; j < NPARAM; j++)
			for (k = 0; k < NPARAM; k++)
				jtj[j][k] += jac[j] * jac[k];
	}
	if (n <= NPARAM)
		return INFINITY;
	/*
	 * The noise seen, but no more than the residual allowed: samples off
	 * the ellipsoid are the residual's verdict, this one is geometry's
	 */
	sigma2 = fmin(sq / (n - NPARAM),
		      pow(s->cfg.max_residual_ut / r->field_ut, 2));
	for (j = 0; j < NPARAM; j++) {
		memcpy(a, jtj, sizeof(a));
		for (k = 0; k < NPARAM; k++) {
			a[k][k] += 1e-12;
			e[k] = k == j;
		}
		if (!solve(NPARAM, a, e, col))
			return INFINITY;
		var[j] = sigma2 * col[j];
	}
	for (j = 0; j < 3; j++) {
		eb = fmax(eb, sqrt(fmax(0, var[j])) * f->f0 / r->field_ut);
		el = fmax(el, sqrt(fmax(0, var[3 + j])));
		el = fmax(el, sqrt(fmax(0, var[6 + j])));
	}
	return hypot(eb, el) * DEG_PER_RAD;
}

/* ---- consistency in time ---- */

/* A sample's index and what is judged of it, in the order they were kept */
struct timed {
	unsigned long long seq;
	double v;
};

static int cmp_timed(const void *a, const void *b)
{
	const struct timed *x = a, *y = b;

	return x->seq < y->seq ? -1 : x->seq > y->seq;
}

/*
 * Slow structure of @v (in the order the samples were kept): the largest
 * deviation of a mean over DRIFT_WINDOW (and 3 x DRIFT_WINDOW: a slower,
 * smaller drift) successive values from the median of all, less what
 * white noise of the size seen between neighbours gives such a mean
 * (DRIFT_SIGMAS of its standard deviation). A field that
 * changed for a while (a magnet passing slowly) moves the means of the
 * samples of that while together; noise averages out.
 */
static double drift(struct timed *t, unsigned int n)
{
	static const unsigned int windows[] = { DRIFT_WINDOW, 3 * DRIFT_WINDOW };
	double d[MAGCAL_MAX_SAMPLES], med, sigma, sum, worst = 0, dev;
	unsigned int i, k, w;

	if (n < 2 * DRIFT_WINDOW)
		return 0;
	qsort(t, n, sizeof(t[0]), cmp_timed);
	for (i = 0; i + 1 < n; i++)
		d[i] = fabs(t[i + 1].v - t[i].v);
	qsort(d, n - 1, sizeof(d[0]), cmp_double);
	/* |a - b| of two N(0, s): median 0.6745 sqrt(2) s */
	sigma = d[(n - 1) / 2] / (0.6745 * M_SQRT2);
	for (i = 0; i < n; i++)
		d[i] = t[i].v;
	qsort(d, n, sizeof(d[0]), cmp_double);
	med = d[n / 2];
	for (k = 0; k < sizeof(windows) / sizeof(windows[0]); k++) {
		w = windows[k];
		if (2 * w > n)
			break;
		for (i = 0, sum = 0; i < n; i++) {
			sum += t[i].v - med;
			if (i >= w)
				sum -= t[i - w].v - med;
			if (i + 1 < w)
				continue;
			dev = fabs(sum) / w - DRIFT_SIGMAS * sigma / sqrt(w);
			worst = fmax(worst, dev);
		}
	}
	return worst;
}

/* The angle (deg) of the calibrated field @c below the horizon of up @g */
static double dip_of(const double c[3], const double g[3])
{
	double cosang = (c[0] * g[0] + c[1] * g[1] + c[2] * g[2]) /
			(norm3(c) * norm3(g));

	return asin(fmax(-1, fmin(1, -cosang))) * DEG_PER_RAD;
}

/* @r = the rotation by the rotation vector @v (radians): Rodrigues */
static void rot_from_vector(const double v[3], double r[3][3])
{
	double a = norm3(v), k[3], sa, ca;
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			r[i][j] = i == j;
	if (!(a > 0))
		return;
	for (i = 0; i < 3; i++)
		k[i] = v[i] / a;
	sa = sin(a);
	ca = 1 - cos(a);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			r[i][j] = (i == j ? 1 : 0) + ca * (k[i] * k[j] - (i == j));
	r[2][1] += sa * k[0];
	r[1][2] -= sa * k[0];
	r[0][2] += sa * k[1];
	r[2][0] -= sa * k[1];
	r[1][0] += sa * k[2];
	r[0][1] -= sa * k[2];
}

/* The rotation vector (radians) of the rotation @r (an angle below 180 deg) */
static void rot_to_vector(const double r[3][3], double v[3])
{
	double c = (r[0][0] + r[1][1] + r[2][2] - 1) / 2, a, f;

	a = acos(fmax(-1, fmin(1, c)));
	f = a > 1e-12 ? a / (2 * sin(a)) : 0.5;
	v[0] = f * (r[2][1] - r[1][2]);
	v[1] = f * (r[0][2] - r[2][0]);
	v[2] = f * (r[1][0] - r[0][1]);
}

static void mat_vec(const double m[3][3], const double v[3], double out[3])
{
	int i;

	for (i = 0; i < 3; i++)
		out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

/*
 * The samples the turn is learned from: unit field @c and unit up @u of
 * each sample whose gravity's magnitude is within TURN_G_TOLERANCE of the
 * median's (1 g: a hand's linear acceleration tilts the accelerometer's
 * reading away from up, and that would bias the dip). Returns how many.
 */
static unsigned int turn_samples(const struct magcal_session *s,
				 const bool *use, const struct magcal_result *r,
				 double c[][3], double u[][3])
{
	double mag[MAGCAL_MAX_SAMPLES], sorted[MAGCAL_MAX_SAMPLES], g1, nc;
	unsigned int i, n = 0, k = 0;
	int j;

	for (i = 0; i < s->n; i++)
		mag[i] = use[i] && s->s[i].has_g ? norm3(s->s[i].g) : 0;
	for (i = 0; i < s->n; i++)
		if (mag[i] > 0)
			sorted[k++] = mag[i];
	if (!k)
		return 0;
	qsort(sorted, k, sizeof(sorted[0]), cmp_double);
	g1 = sorted[k / 2];
	for (i = 0; i < s->n; i++) {
		if (!(mag[i] > 0) || fabs(mag[i] / g1 - 1) > TURN_G_TOLERANCE)
			continue;
		magcal_apply(r, s->s[i].m, c[n]);
		nc = norm3(c[n]);
		if (!(nc > 0))
			continue;
		for (j = 0; j < 3; j++) {
			c[n][j] /= nc;
			u[n][j] = s->s[i].g[j] / mag[i];
		}
		n++;
	}
	return n;
}

/*
 * The turn @rot of the magnetometer against the accelerometer that makes
 * the dip constant: u . (rot c) = sin of the angle to up, the same for
 * every sample. Gauss-Newton on the rotation (the first step is the
 * linear least squares in (constant, omega); a few steps make a turn of
 * a few degrees exact, not linearised). Returns the standard deviation of
 * the turn found (radians, sqrt of the trace of omega's covariance), or
 * INFINITY when it is not determined.
 */
static double learn_turn(double c[][3], double u[][3], unsigned int n,
			 double rot[3][3])
{
	double a[NPARAM][NPARAM], inv[NPARAM][NPARAM], rhs[NPARAM], x[NPARAM];
	double cr[3], cg[3], row[4], rt[3][3], step[3][3], sq, var = 0;
	unsigned int i, it;
	int j, k, l;

	for (j = 0; j < 3; j++)
		for (k = 0; k < 3; k++)
			rot[j][k] = j == k;
	if (n < 2 * DRIFT_WINDOW)
		return INFINITY;
	for (it = 0; it < TURN_STEPS; it++) {
		memset(a, 0, sizeof(a));
		memset(rhs, 0, sizeof(rhs));
		for (i = 0; i < n; i++) {
			mat_vec(rot, c[i], cr);
			cross3(cr, u[i], cg);
			row[0] = 1;
			for (j = 0; j < 3; j++)
				row[1 + j] = -cg[j];
			for (j = 0; j < 4; j++) {
				for (k = 0; k < 4; k++)
					a[j][k] += row[j] * row[k];
				rhs[j] += row[j] * (cr[0] * u[i][0] +
						    cr[1] * u[i][1] +
						    cr[2] * u[i][2]);
			}
		}
		memcpy(inv, a, sizeof(inv));
		if (!solve(4, inv, rhs, x))
			return INFINITY;
		rot_from_vector(x + 1, step);
		for (j = 0; j < 3; j++)
			for (k = 0; k < 3; k++)
				for (l = 0, rt[j][k] = 0; l < 3; l++)
					rt[j][k] += step[j][l] * rot[l][k];
		memcpy(rot, rt, sizeof(rt));
		if (norm3(x + 1) < 1e-10)
			break;
	}
	/* the noise left about the constant dip, and omega's covariance */
	for (i = 0, sq = 0; i < n; i++) {
		mat_vec(rot, c[i], cr);
		sq += pow(cr[0] * u[i][0] + cr[1] * u[i][1] + cr[2] * u[i][2] -
			  x[0], 2);
	}
	for (j = 1; j < 4; j++) {
		double e[NPARAM] = { 0 }, col[NPARAM];

		memcpy(inv, a, sizeof(inv));
		e[j] = 1;
		if (!solve(4, inv, e, col))
			return INFINITY;
		var += col[j];
	}
	return sqrt(fmax(0, var * sq / (n - 4)));
}

/*
 * The fit's consistency in time: the slow structure of the residuals
 * (the field's magnitude) and of the dip (its angle to gravity) along the
 * samples used. Both are constant while only the device turns; the
 * magnetometer turned against the accelerometer (an asymmetric soft
 * iron, which a magnitude fit cannot see) makes the dip depend on the
 * orientation, so that turn is learned first and taken out, unless it is
 * beyond any board's (MAX_TURN_DEG). It is trusted (@rot, what a caller
 * stores) only when the samples pin it down.
 */
static void consistency(const struct magcal_session *s, const bool *use,
			const struct magcal_config *cfg,
			struct magcal_result *r)
{
	double c[MAGCAL_MAX_SAMPLES][3], u[MAGCAL_MAX_SAMPLES][3];
	struct timed e[MAGCAL_MAX_SAMPLES], dip[MAGCAL_MAX_SAMPLES];
	double rot[3][3], theta[3], cm[3], cr[3], sd;
	unsigned int i, ne = 0, nd = 0;
	int j;

	sd = learn_turn(c, u, turn_samples(s, use, r, c, u), rot);
	rot_to_vector(rot, theta);
	r->turn_uncertainty_deg = sd * DEG_PER_RAD;
	r->turn_trusted = r->turn_uncertainty_deg <=
			  cfg->max_turn_uncertainty_deg;
	if (!(norm3(theta) * DEG_PER_RAD <= MAX_TURN_DEG)) {
		rot_from_vector((double[3]){ 0, 0, 0 }, rot);
		rot_to_vector(rot, theta);
		r->turn_trusted = false;
	}
	r->turn_deg = norm3(theta) * DEG_PER_RAD;
	for (j = 0; j < 3; j++)
		r->turn[j] = theta[j] * DEG_PER_RAD;
	memcpy(r->rot, rot, sizeof(rot));
	if (!r->turn_trusted)
		rot_from_vector((double[3]){ 0, 0, 0 }, r->rot);

	for (i = 0; i < s->n; i++) {
		if (!use[i])
			continue;
		e[ne].seq = s->s[i].seq;
		e[ne++].v = residual_ut(s, i, r);
		if (!s->s[i].has_g || !(norm3(s->s[i].g) > 0))
			continue;
		magcal_apply(r, s->s[i].m, cm);
		mat_vec(rot, cm, cr);
		if (!(norm3(cr) > 0))
			continue;
		dip[nd].seq = s->s[i].seq;
		dip[nd++].v = dip_of(cr, s->s[i].g);
	}
	r->drift_ut = drift(e, ne);
	r->dip_drift_deg = drift(dip, nd);
}

static void quality(const struct magcal_session *s, const bool *use,
		    struct magcal_result *r)
{
	double sq = 0, dip = 0, c[3];
	unsigned int i, ndip = 0;

	r->used = r->rejected = 0;
	for (i = 0; i < s->n; i++) {
		double e;

		if (!use[i]) {
			r->rejected++;
			continue;
		}
		r->used++;
		e = residual_ut(s, i, r);
		sq += e * e;
		magcal_apply(r, s->s[i].m, c);
		if (s->s[i].has_g && norm3(s->s[i].g) > 0 && norm3(c) > 0) {
			dip += dip_of(c, s->s[i].g);
			ndip++;
		}
	}
	r->residual_ut = r->used ? sqrt(sq / r->used) : 0;
	r->coverage = coverage(s, use, r->bias, r->w);
	r->has_dip = ndip > 0;
	r->dip_deg = ndip ? dip / ndip : 0;
}

static enum magcal_status verdict(const struct magcal_config *cfg,
				  const struct magcal_result *r)
{
	if (r->used < cfg->min_samples || r->coverage < cfg->min_coverage ||
	    !(r->uncertainty_deg <= cfg->max_uncertainty_deg))
		return MAGCAL_NO_COVERAGE;
	if (r->field_ut < cfg->field_min_ut || r->field_ut > cfg->field_max_ut)
		return MAGCAL_FIELD_IMPLAUSIBLE;
	if (r->residual_ut > cfg->max_residual_ut)
		return MAGCAL_RESIDUAL_HIGH;
	if (r->drift_ut > cfg->max_drift_ut ||
	    r->dip_drift_deg > cfg->max_dip_drift_deg)
		return MAGCAL_INCONSISTENT;
	return MAGCAL_OK;
}

/* The site's field as the calibrated magnitude: W, F and the residual scale */
static void apply_reference(const struct magcal_config *cfg,
			    struct magcal_result *r)
{
	int i, j;

	r->scale = cfg->reference_field_ut / r->fitted_field_ut;
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			r->w[i][j] *= r->scale;
	r->field_ut = cfg->reference_field_ut;
	r->residual_ut *= r->scale;
}

int magcal_solve(const struct magcal_session *s, struct magcal_result *r)
{
	bool use[MAGCAL_MAX_SAMPLES];
	struct fit f;
	unsigned int i;

	if (!s || !r)
		return -EINVAL;
	memset(r, 0, sizeof(*r));
	r->w[0][0] = r->w[1][1] = r->w[2][2] = 1;
	r->rot[0][0] = r->rot[1][1] = r->rot[2][2] = 1;
	r->turn_uncertainty_deg = INFINITY;
	r->scale = 1;
	for (i = 0; i < s->n; i++)
		use[i] = true;
	if (s->n < 10) {
		r->used = s->n;
		r->status = MAGCAL_NO_COVERAGE;
		return 0;
	}
	if (!robust_fit(s, use, &f, r)) {
		r->status = MAGCAL_SINGULAR;
		return 0;
	}
	quality(s, use, r);
	consistency(s, use, &s->cfg, r);
	r->uncertainty_deg = uncertainty_deg(s, use, &f, r);
	r->status = verdict(&s->cfg, r);
	if (s->cfg.reference_field_ut > 0 && r->fitted_field_ut > 0)
		apply_reference(&s->cfg, r);
	return 0;
}

const char *magcal_status_str(enum magcal_status st)
{
	switch (st) {
	case MAGCAL_OK:
		return "ok";
	case MAGCAL_NO_COVERAGE:
		return "not enough coverage";
	case MAGCAL_FIELD_IMPLAUSIBLE:
		return "field implausible for Earth";
	case MAGCAL_RESIDUAL_HIGH:
		return "residual too high";
	case MAGCAL_SINGULAR:
		return "fit did not converge";
	case MAGCAL_INCONSISTENT:
		return "field changed during the session";
	}
	return "unknown";
}

void magcal_split(const struct magcal_result *r, double diag[3],
		  double resid[3][3])
{
	int i, j;

	for (i = 0; i < 3; i++)
		diag[i] = r->w[i][i];
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			resid[i][j] = r->w[i][j] / diag[j];
}

int magcal_heading_deg(const double field[3], const double up[3],
		       double declination_deg, double *heading)
{
	double e[3], n[3], u[3], ne, nu, h;
	int i;

	nu = norm3(up);
	if (!(nu > 0))
		return -EDOM;
	for (i = 0; i < 3; i++)
		u[i] = up[i] / nu;
	cross3(field, u, e);		/* east: field x up */
	ne = norm3(e);
	if (!(ne > 1e-9 * norm3(field)) || !(ne > 0))
		return -EDOM;
	for (i = 0; i < 3; i++)
		e[i] /= ne;
	cross3(u, e, n);		/* north: up x east */
	if (hypot(e[1], n[1]) < 1e-6)
		return -EDOM;		/* +Y points straight up or down */
	h = atan2(e[1], n[1]) * DEG_PER_RAD + declination_deg;
	h = fmod(h, 360);
	if (h < 0)
		h += 360;
	*heading = h >= 360 ? 0 : h;
	return 0;
}
