// SPDX-License-Identifier: GPL-2.0
/*
 * The factory on-board function test: steps 1 to 3 of the application note
 * (section 5) with the decisions of the datasheet (section 7). Every
 * judgment lands in the report under its step number.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "as9888_regs.h"
#include "ftest/ftest_internal.h"

/* Pause before retrying a level run whose temperature moved */
#define FTEST_STABLE_RETRY_MS	200

const char *const ftest_axis_name = "XYZ";

/* Where each judgment of a level run finds its step (pass1_steps[]) */
enum level_step {
	LEVEL_ST1 = 0,
	LEVEL_TMPS = 1,
	LEVEL_EMPT = 2,
	LEVEL_ST2 = 3,
	LEVEL_MAX = 4,		/* max X Y Z, then min X Y Z */
	LEVEL_FLUCT = 10,	/* X Y Z */
	LEVEL_SAMPLES = 13,	/* every sample X low, X high, Y..., Z... */
};

bool ftest_judge(struct ftest_ctx *x, const char *step, const char *name,
		 bool ok, const char *limits, const char *fmt, ...)
{
	char measured[JUDGMENT_TEXT_LEN];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(measured, sizeof(measured), fmt, ap);
	va_end(ap);
	report_add(&x->res->report, step, name,
		   ok ? JUDGMENT_PASS : JUDGMENT_FAIL, limits, "%s", measured);
	if (!ok && !x->o->keep_going)
		x->stop = true;

	return ok;
}

void ftest_skip(struct ftest_ctx *x, const char *step, const char *name,
		const char *why)
{
	report_add(&x->res->report, step, name, JUDGMENT_SKIP, NULL, "%s", why);
}

void ftest_value(struct ftest_ctx *x, double v, double lo, double hi,
		 const char *unit)
{
	report_set_value(&x->res->report, v, lo, hi, unit);
}

int ftest_io_failed(struct ftest_ctx *x, const char *step, const char *what,
		    int err)
{
	report_add(&x->res->report, step, what, JUDGMENT_FAIL, NULL,
		   "bus transfer failed: %s", strerror(-err));
	x->stop = true;

	return err;
}

int ftest_check_eeprom(struct ftest_ctx *x,
		       const uint8_t raw[AS9888_EEPROM_LEN])
{
	struct ftest_result *res = x->res;
	uint32_t bits;
	int ret;

	ret = as9888_eeprom_decode(raw, &res->ee);
	res->have_eeprom = ret == 0;
	res->warnings = res->ee.warnings;
	if (ret) {
		char why[JUDGMENT_TEXT_LEN] = "";

		for (bits = res->ee.errors; bits; bits &= bits - 1) {
			size_t len = strlen(why);

			snprintf(why + len, sizeof(why) - len, "%s%s",
				 len ? "; " : "",
				 as9888_ee_error_str(bits & -bits));
		}
		ftest_judge(x, "1-27", "EEPROM contents", false,
			    "gain 7..43, DAC 0..67/128..195, not blank", "%s", why);
		/* without factory data nothing below can be judged */
		x->stop = true;
		return -ENODATA;
	}
	ftest_judge(x, "1-27", "EEPROM contents", true,
		    "gain 7..43, DAC 0..67/128..195, not blank",
		    "fingerprint %016llx",
		    (unsigned long long)record_fingerprint(raw));
	if (x->o->expect_eeprom &&
	    !ftest_judge(x, "1-27.match", "chip matches the calibration record",
			 !memcmp(raw, x->o->expect_eeprom, AS9888_EEPROM_LEN),
			 "EEPROM equals the record's",
			 "chip %016llx, record %016llx",
			 (unsigned long long)record_fingerprint(raw),
			 (unsigned long long)record_fingerprint(x->o->expect_eeprom))) {
		/* never touch another chip's calibration */
		x->stop = true;
		return -ENODEV;
	}

	for (bits = res->ee.warnings; bits; bits &= bits - 1)
		report_add(&res->report, "1-27.warning", "EEPROM warning", JUDGMENT_PASS,
			   NULL, "warning: %s",
			   as9888_ee_warning_str(bits & -bits));

	return 0;
}

static const char *const selftest_steps[AS9888_AXES] = { "2-17", "2-19", "2-21" };
#define SELFTEST_NAME_LEN	40

static void selftest_axis_name(int axis, char name[SELFTEST_NAME_LEN])
{
	snprintf(name, SELFTEST_NAME_LEN, "self-test %c after adjustment",
		 ftest_axis_name[axis]);
}

bool ftest_judge_selftest_axis(struct ftest_ctx *x, int axis, bool ok,
			       int32_t adj_q8, const char *note)
{
	char name[SELFTEST_NAME_LEN];

	selftest_axis_name(axis, name);
	ftest_judge(x, selftest_steps[axis], name, ok,
		    axis == 2 ? "300..1000" : "-100..100", "%.2f%s",
		    adj_q8 / 256.0, note);
	ftest_value(x, adj_q8 / 256.0, axis == 2 ? 300 : -100,
		    axis == 2 ? 1000 : 100, "LSB");

	return ok;
}

void ftest_skip_selftest_axis(struct ftest_ctx *x, int axis, const char *why)
{
	char name[SELFTEST_NAME_LEN];

	selftest_axis_name(axis, name);
	ftest_skip(x, selftest_steps[axis], name, why);
}

void level_run_init(struct level_run *r)
{
	int axis;

	memset(r, 0, sizeof(*r));
	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->min[axis] = INT16_MAX;
		r->max[axis] = INT16_MIN;
	}
	r->tmps_min = UINT8_MAX;
	r->bad_st1 = r->bad_tmps = r->bad_empt = r->bad_st2 = -1;
	for (axis = 0; axis < AS9888_AXES; axis++)
		r->bad_acc[axis][0] = r->bad_acc[axis][1] = -1;
}

void level_run_add(struct level_run *r, const struct chip_sample *s)
{
	int axis, i = (int)r->n;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->sum[axis] += s->acc[axis];
		r->sq_sum[axis] += (int64_t)s->acc[axis] * s->acc[axis];
		if (s->acc[axis] < r->min[axis])
			r->min[axis] = s->acc[axis];
		if (s->acc[axis] > r->max[axis])
			r->max[axis] = s->acc[axis];
		if (as9888_acc_saturated(s->acc[axis])) {
			int end = s->acc[axis] > 0;

			if (!r->saturated[axis][end]++)
				r->bad_acc[axis][end] = i;
		}
	}
	r->tmps_sum += s->tmps;
	if (s->tmps < r->tmps_min)
		r->tmps_min = s->tmps;
	if (s->tmps > r->tmps_max)
		r->tmps_max = s->tmps;
	if (r->bad_tmps < 0 && !as9888_tmps_valid(s->tmps)) {
		r->bad_tmps = i;
		r->bad_tmps_val = s->tmps;
	}
	if (r->status_by_driver) {
		r->n++;
		return;
	}
	if (r->bad_st1 < 0 && s->st1 != AS9888_ST1_DRDY_MSK) {
		r->bad_st1 = i;
		r->bad_st1_val = s->st1;
	}
	if (r->bad_empt < 0 && s->empt != 0) {
		r->bad_empt = i;
		r->bad_empt_val = s->empt;
	}
	if (r->bad_st2 < 0 && s->st2 != AS9888_ST2_HST_MSK) {
		r->bad_st2 = i;
		r->bad_st2_val = s->st2;
	}
	r->n++;
}

/* Append @m's samples to @r's, as if one run had taken them all */
static void level_run_merge(struct level_run *r, const struct level_run *m)
{
	int axis, end;

#define MERGE_BAD(f)						\
	do {							\
		if (r->bad_##f < 0 && m->bad_##f >= 0) {	\
			r->bad_##f = (int)r->n + m->bad_##f;	\
			r->bad_##f##_val = m->bad_##f##_val;	\
		}						\
	} while (0)
	MERGE_BAD(st1);
	MERGE_BAD(tmps);
	MERGE_BAD(empt);
	MERGE_BAD(st2);
#undef MERGE_BAD
	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->sum[axis] += m->sum[axis];
		r->sq_sum[axis] += m->sq_sum[axis];
		if (m->min[axis] < r->min[axis])
			r->min[axis] = m->min[axis];
		if (m->max[axis] > r->max[axis])
			r->max[axis] = m->max[axis];
		for (end = 0; end < 2; end++) {
			if (!r->saturated[axis][end] && m->saturated[axis][end])
				r->bad_acc[axis][end] = (int)r->n + m->bad_acc[axis][end];
			r->saturated[axis][end] += m->saturated[axis][end];
		}
	}
	r->tmps_sum += m->tmps_sum;
	if (m->tmps_min < r->tmps_min)
		r->tmps_min = m->tmps_min;
	if (m->tmps_max > r->tmps_max)
		r->tmps_max = m->tmps_max;
	r->n += m->n;
}

/*
 * Collect N samples at a stable temperature (Note 2, Note 4b): a run whose
 * TMPS codes spread more than FTEST_TMPS_SPREAD_MAX is taken again, until
 * the stability timeout. @pre (may be NULL): samples already taken in the
 * same posture with the same DAC (the pilot of Note 2), which the first try
 * starts with; it takes max(N, pre->n) samples.
 */
static int level_collect_stable(struct ftest_ctx *x, uint32_t n,
				const char *step, const struct level_run *pre,
				struct level_run *r)
{
	uint64_t give_up = x->ops->now_ns(x) +
			   x->o->stable_timeout_ms * NS_PER_MS;
	struct level_run more;
	int ret;

	for (;;) {
		if (pre) {
			*r = *pre;
			ret = n > pre->n ?
			      x->ops->level_collect(x, n - pre->n, step, &more) : 0;
			if (!ret && n > pre->n)
				level_run_merge(r, &more);
			pre = NULL;	/* a retry starts afresh */
		} else {
			ret = x->ops->level_collect(x, n, step, r);
		}
		if (ret)
			return ret;
		if (r->tmps_max - r->tmps_min <= FTEST_TMPS_SPREAD_MAX ||
		    r->bad_tmps >= 0 || x->ops->now_ns(x) >= give_up)
			break;
		x->ops->sleep_ns(x, FTEST_STABLE_RETRY_MS * NS_PER_MS);
	}

	return 0;
}

/* The ID @step.@what, for a second judgment of one step */
static const char *sub_id(char buf[JUDGMENT_ID_LEN], const char *step,
			  const char *what)
{
	snprintf(buf, JUDGMENT_ID_LEN, "%s.%s", step, what);
	return buf;
}

/*
 * A status register on every sample: @bad the first offending sample (-1:
 * none), @bad_val its value, @want the value the step requires
 */
static bool judge_every_sample(struct ftest_ctx *x, const struct level_run *r,
			       const char *step, const char *name, int bad,
			       uint8_t bad_val, uint8_t want)
{
	char limits[8];

	/*
	 * Through the driver the register is not seen: the driver checks it
	 * on every sample and delivers none that fails (a run short of
	 * samples fails as not delivered). Not judged here, and said so.
	 */
	if (r->status_by_driver) {
		ftest_skip(x, step, name,
			   "not visible through the driver, which checks it on every sample and delivers none that fails");
		return !x->stop;
	}
	snprintf(limits, sizeof(limits), "0x%02x", want);
	ftest_judge(x, step, name, bad < 0, limits,
		    bad < 0 ? "all 0x%02x" : "sample %d: 0x%02x",
		    bad < 0 ? want : bad, bad_val);
	ftest_value(x, bad < 0 ? want : bad_val, want, want, "code");

	return !x->stop;
}

/*
 * 3-7..3-12 (3-32..3-37): every sample of each axis within
 * -2048 < A < 2047. The application note reads A1xL and A1xH in two rows
 * under one two-sided limit; the lower half is judged under the L row's
 * step (3-7, 3-9, 3-11), the upper half under the H row's (3-8, 3-10,
 * 3-12).
 */
static bool judge_samples_in_range(struct ftest_ctx *x,
				   const struct level_run *r,
				   const char *const steps[])
{
	int axis, end;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		for (end = 0; end < 2; end++) {
			uint32_t bad = r->saturated[axis][end];
			char name[48];

			snprintf(name, sizeof(name), "%c %s on every sample",
				 ftest_axis_name[axis], end ? "below 2047" : "above -2048");
			ftest_judge(x, steps[LEVEL_SAMPLES + 2 * axis + end], name,
				    !bad, end ? "A < 2047" : "A > -2048",
				    !bad ? "all %u samples" : "%u samples at %d, the first sample %d",
				    !bad ? r->n : bad, end ? 2047 : -2048,
				    r->bad_acc[axis][end]);
			ftest_value(x, bad, 0, 0, "samples");
			if (x->stop)
				return false;
		}
	}

	return true;
}

/* 3-14..3-22: saturation and fluctuation */
static void level_judge_values(struct ftest_ctx *x, const struct level_run *r,
			       const char *const steps[])
{
	int axis, i;

	/* 3-14..3-19: the maxima, then the minima, must not saturate */
	for (i = 0; i < 2 * AS9888_AXES; i++) {
		const int16_t *v = i < AS9888_AXES ? r->max : r->min;
		char name[48];

		axis = i % AS9888_AXES;
		snprintf(name, sizeof(name), "%s of %c",
			 i < AS9888_AXES ? "maximum" : "minimum", ftest_axis_name[axis]);
		ftest_judge(x, steps[LEVEL_MAX + i], name,
			    !as9888_acc_saturated(v[axis]), "-2048 < A < 2047",
			    "%d", v[axis]);
		ftest_value(x, v[axis], -2047, 2046, "LSB");
		if (x->stop)
			return;
	}
	for (axis = 0; axis < AS9888_AXES; axis++) {
		bool ok = as9888_fluctuation_ok(r->min[axis], r->max[axis],
						x->o->fluctuation);
		char name[48], limits[24];

		snprintf(name, sizeof(name), "fluctuation of %c", ftest_axis_name[axis]);
		snprintf(limits, sizeof(limits), "max - min <= %u",
			 x->o->fluctuation);
		ftest_judge(x, steps[LEVEL_FLUCT + axis], name, ok, limits, "%d%s",
			    r->max[axis] - r->min[axis],
			    !ok && x->o->user_mode ?
			    ": the device moved; keep it still and flat, then try again" :
			    "");
		ftest_value(x, r->max[axis] - r->min[axis], 0, x->o->fluctuation,
			    "LSB");
		if (x->stop)
			return;
	}
}

/* The per-sample and min/max/fluctuation judgments of one level run */
static void level_judge(struct ftest_ctx *x, const struct level_run *r,
			const char *const steps[])
{
	char id[JUDGMENT_ID_LEN];
	int spread = r->tmps_max - r->tmps_min;

	if (!judge_every_sample(x, r, steps[LEVEL_ST1], "ST1 data ready (every sample)",
				r->bad_st1, r->bad_st1_val, AS9888_ST1_DRDY_MSK))
		return;
	ftest_judge(x, steps[LEVEL_TMPS], "TMPS within specification",
		    r->bad_tmps < 0, "0x28..0xe0",
		    r->bad_tmps < 0 ? "0x%02x..0x%02x" : "sample %d: 0x%02x",
		    r->bad_tmps < 0 ? r->tmps_min : r->bad_tmps,
		    r->bad_tmps < 0 ? r->tmps_max : r->bad_tmps_val);
	/* the sample farthest from the middle of the range, or the bad one */
	ftest_value(x, r->bad_tmps >= 0 ? r->bad_tmps_val :
		    0x84 - r->tmps_min > r->tmps_max - 0x84 ? r->tmps_min :
		    r->tmps_max, 0x28, 0xe0, "code");
	if (x->stop)
		return;
	ftest_judge(x, sub_id(id, steps[LEVEL_TMPS], "stable"),
		    "temperature stable during averaging (Note 4b)",
		    spread <= FTEST_TMPS_SPREAD_MAX,
		    "TMPS spread <= 1 code (0.625 degC)", "TMPS 0x%02x..0x%02x",
		    r->tmps_min, r->tmps_max);
	ftest_value(x, spread, 0, FTEST_TMPS_SPREAD_MAX, "code");
	if (x->stop)
		return;
	if (!judge_every_sample(x, r, steps[LEVEL_EMPT], "EMPT (every sample)",
				r->bad_empt, r->bad_empt_val, 0) ||
	    !judge_samples_in_range(x, r, steps))
		return;
	if (r->status_by_driver)
		ftest_skip(x, steps[LEVEL_ST2], "ST2 normal end, magnetometer off (HST)",
			   "ST2 is not visible through the driver");
	else if (!judge_every_sample(x, r, steps[LEVEL_ST2],
				     "ST2 normal end, magnetometer off (HST)",
				     r->bad_st2, r->bad_st2_val, AS9888_ST2_HST_MSK))
		return;

	level_judge_values(x, r, steps);
}

/* The steps of one level run, indexed by enum level_step */
static const char *const pass1_steps[] = {
	"3-4", "3-5", "3-6", "3-13",
	"3-14", "3-15", "3-16", "3-17", "3-18", "3-19",
	"3-20", "3-21", "3-22",
	"3-7", "3-8", "3-9", "3-10", "3-11", "3-12",
};

static const char *const pass2_steps[] = {
	"3-29", "3-30", "3-31", "3-38",
	"3-39", "3-40", "3-41", "3-42", "3-43", "3-44",
	"3-45", "3-46", "3-47",
	"3-32", "3-33", "3-34", "3-35", "3-36", "3-37",
};

double ftest_two_sided_z(double p)
{
	double lo = 0.0, hi = 40.0;
	int i;

	/* P(|Z| <= z) = erf(z / sqrt(2)), increasing in z: bisection */
	for (i = 0; i < 100; i++) {
		double mid = (lo + hi) / 2;

		if (erf(mid / M_SQRT2) < p)
			lo = mid;
		else
			hi = mid;
	}

	return (lo + hi) / 2;
}

/*
 * Note 2: N >= n * (sigma / Sigma)^2, with sigma measured on a pilot run of
 * single samples (n = 1), the noisiest axis deciding. The pilot's sigma-hat
 * is an estimate: N is taken for its one-sided 95 % upper confidence bound,
 * sigma-hat * sqrt((m - 1) / chi2_0.05(m - 1)) for m pilot samples, so that
 * the level mean's standard error sigma / sqrt(N) is within E in at least
 * 95 % of runs: a one-sigma bound. With --confidence P the bound scales by
 * z = z_(1+P)/2, so that |mean - true value| <= z sigma / sqrt(N) <= E with
 * probability P per axis (docs/DECISIONS.md). @pilot keeps the samples for
 * the first level run, which starts with them.
 */
static int choose_samples(struct ftest_ctx *x, uint32_t *n,
			  struct level_run *pilot)
{
	double worst = 0.0, upper, scaled;
	char limits[64], bound[48] = "";
	bool ok;
	int axis, ret;

	x->res->bound_z = 1.0;
	if (!x->o->permissible_error_q16) {
		*n = x->o->samples;
		return 0;
	}

	ret = x->ops->level_collect(x, FTEST_PILOT_SAMPLES, "3-3", pilot);
	if (ret || x->stop)
		return ret;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		double mean = (double)pilot->sum[axis] / pilot->n;
		double var = ((double)pilot->sq_sum[axis] - mean * pilot->sum[axis]) /
			     (pilot->n - 1);

		if (var > worst)
			worst = var;
	}
	worst = sqrt(worst);
	upper = worst * sqrt((FTEST_PILOT_SAMPLES - 1) / FTEST_PILOT_CHI2_05);
	if (x->o->confidence_1e4) {
		x->res->bound_z = ftest_two_sided_z(x->o->confidence_1e4 / 1e4);
		snprintf(bound, sizeof(bound), ", |error| <= E with P %.4g (z %.3f)",
			 x->o->confidence_1e4 / 1e4, x->res->bound_z);
	}
	x->res->pilot_sigma = worst;
	x->res->pilot_sigma_upper = upper;
	scaled = upper * x->res->bound_z * AS9888_Q16_ONE;
	*n = scaled < UINT32_MAX ?
	     as9888_samples_needed(1, (uint32_t)lround(scaled),
				   x->o->permissible_error_q16) :
	     AS9888_SAMPLES_MAX + 1;
	if (*n < x->o->samples)
		*n = x->o->samples;
	ok = *n <= AS9888_SAMPLES_MAX;
	snprintf(limits, sizeof(limits), "N <= %d", AS9888_SAMPLES_MAX);
	ftest_judge(x, "3-3.N", "averaging count from Note 2", ok, limits,
		    "sigma %.3f LSB (95 %% upper bound %.3f), E %.3f LSB%s: N %u%s",
		    worst, upper,
		    (double)x->o->permissible_error_q16 / AS9888_Q16_ONE, bound, *n,
		    ok ? "" : " (environment too noisy)");
	ftest_value(x, *n, x->o->samples, AS9888_SAMPLES_MAX, "samples");

	return ok ? 0 : -ERANGE;
}

static void means(const struct level_run *r, int32_t mean_q16[AS9888_AXES])
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++)
		as9888_mean_q16(r->sum[axis], r->n, &mean_q16[axis]);
}

/* The standard error of each axis' mean from the run's own samples */
static void standard_errors(const struct level_run *r, double se[AS9888_AXES])
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		double mean = (double)r->sum[axis] / r->n;
		double var = r->n > 1 ?
			     ((double)r->sq_sum[axis] - mean * r->sum[axis]) / (r->n - 1) : 0;

		se[axis] = sqrt(var > 0 ? var : 0) / sqrt(r->n);
	}
}

/*
 * A product user's recalibration also wants the device flat, not merely
 * level in the sense of D8: the angle between the vertical axis and the
 * reading, offsets included, must stay within FTEST_USER_TILT_DEG.
 */
static int user_flat(struct ftest_ctx *x, const int32_t mean_q16[AS9888_AXES],
		     const int8_t g[AS9888_AXES])
{
	double h2 = 0.0, v = 0.0, tilt;
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		double a = mean_q16[axis] / 65536.0;

		if (g[axis])
			v = fabs(a);
		else
			h2 += a * a;
	}
	tilt = atan2(sqrt(h2), v) * 180.0 / M_PI;
	ftest_judge(x, "3-23.flat", "device flat", tilt <= FTEST_USER_TILT_DEG,
		    "tilt <= 10 degrees",
		    tilt <= FTEST_USER_TILT_DEG ? "tilt about %.1f degrees" :
		    "the device is not flat (tilted about %.1f degrees): lay it flat on a level surface and try again",
		    tilt);
	ftest_value(x, tilt, 0, FTEST_USER_TILT_DEG, "degree");
	if (tilt > FTEST_USER_TILT_DEG)
		return -EINVAL;

	return 0;
}

/* D8: posture, from the data or as given */
static int posture(struct ftest_ctx *x, const int32_t mean_q16[AS9888_AXES],
		   const int32_t st_q16[AS9888_AXES], int8_t g[AS9888_AXES])
{
	static const char *const why[] = {
		[AS9888_POSTURE_OK] = "level",
		[AS9888_POSTURE_NOT_LEVEL] = "not level: a horizontal axis reads more than St/2",
		[AS9888_POSTURE_NOT_VERTICAL] = "not level: the vertical axis reads less than St/2",
		[AS9888_POSTURE_WRONG_SIGN] = "not level: gravity points the other way than given",
		[AS9888_POSTURE_BAD_G] = "invalid gravity direction",
	};
	enum as9888_posture_error err;

	if (x->o->gravity_given)
		memcpy(g, x->o->gravity, AS9888_AXES);
	else
		as9888_posture_detect(mean_q16, g);

	err = as9888_posture_check(mean_q16, st_q16, g);
	ftest_judge(x, "3-23.posture", "level posture (D8)", err == AS9888_POSTURE_OK,
		    "horizontal |A| <= St/2, vertical |A| >= St/2",
		    "%s; A = %.2f %.2f %.2f, G = %d %d %d%s", why[err],
		    mean_q16[0] / 65536.0, mean_q16[1] / 65536.0,
		    mean_q16[2] / 65536.0, g[0], g[1], g[2],
		    x->o->gravity_given ? " (given)" : " (detected)");

	if (err != AS9888_POSTURE_OK)
		return -EINVAL;

	return x->o->user_mode ? user_flat(x, mean_q16, g) : 0;
}

static int level_temperature(const struct level_run *r, int32_t *t_mdegc)
{
	return as9888_tmps_mean_to_mdegc(r->tmps_sum, r->n, t_mdegc);
}

static int sensitivities(const struct as9888_eeprom *ee, int32_t t_mdegc,
			 int32_t st_q16[AS9888_AXES])
{
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = as9888_sensitivity_q16(&ee->axis[axis], ee->t_rt_mdegc,
					     t_mdegc, &st_q16[axis]);
		if (ret)
			return ret;
	}

	return 0;
}

/* Step 3-23: DACopt from the first level run; D6 */
static int dac_optimum(struct ftest_ctx *x, const int32_t mean_q16[AS9888_AXES],
		       const int32_t st_q16[AS9888_AXES],
		       const int8_t g[AS9888_AXES], uint8_t dac[AS9888_AXES])
{
	const struct as9888_eeprom *ee = &x->res->ee;
	bool clamped = false;
	int32_t ot_l[AS9888_AXES];
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		const struct as9888_axis_trim *trim = &ee->axis[axis];

		ret = as9888_offset_level_q16(mean_q16[axis], st_q16[axis],
					      g[axis], &ot_l[axis]);
		if (ret)
			return ret;
		if (as9888_dac_opt(trim->ga, x->dac[axis], trim->gain, ot_l[axis],
				   &dac[axis]) == -ERANGE)
			clamped = true;
	}

	ftest_judge(x, "3-23.dacopt", "optimal DAC (6.6)", !clamped,
		    "linear code within -67..67",
		    "Ot_L %.2f %.2f %.2f LSB -> DAC 0x%02x 0x%02x 0x%02x%s",
		    ot_l[0] / 65536.0, ot_l[1] / 65536.0, ot_l[2] / 65536.0,
		    dac[0], dac[1], dac[2],
		    clamped ? ": offset beyond DAC range (D6)" : "");

	return clamped ? -ERANGE : 0;
}

static void store_level(struct ftest_result *res,
			const int32_t mean[AS9888_AXES], int32_t t_mdegc,
			const int8_t g[AS9888_AXES])
{
	memcpy(res->level_mean_q16, mean, sizeof(res->level_mean_q16));
	memcpy(res->level_g, g, sizeof(res->level_g));
	res->level_t_mdegc = t_mdegc;
	res->have_level = true;
}

/*
 * One level run with its judgments: N samples at a stable temperature, then
 * their mean, temperature and the sensitivity there.
 */
static int level_pass(struct ftest_ctx *x, uint32_t n, const char *step,
		      const struct level_run *pre,
		      const char *const steps[], int32_t mean[AS9888_AXES],
		      int32_t *t_l, int32_t st[AS9888_AXES])
{
	char id[JUDGMENT_ID_LEN];
	struct level_run run;
	int ret;

	ret = level_collect_stable(x, n, step, pre, &run);
	if (ret || x->stop)
		return ret;
	level_judge(x, &run, steps);
	if (x->stop)
		return 0;

	means(&run, mean);
	standard_errors(&run, x->res->level_se);
	ret = level_temperature(&run, t_l);
	if (!ret)
		ret = sensitivities(&x->res->ee, *t_l, st);
	if (ret)
		ftest_judge(x, sub_id(id, steps[LEVEL_TMPS], "temperature"),
			    "level temperature", false, "-30..85 degC",
			    "cannot use the level temperature");

	return ret;
}

/* Step 3: accelerometer function test and level data */
static int step3(struct ftest_ctx *x)
{
	struct ftest_result *res = x->res;
	const struct as9888_eeprom *ee = &res->ee;
	int32_t mean[AS9888_AXES], st[AS9888_AXES], t_l;
	int8_t g[AS9888_AXES];
	uint8_t dac[AS9888_AXES];
	struct level_run pilot;
	uint32_t n;
	int axis, ret;

	ret = x->ops->level_setup(x);
	if (ret || x->stop)
		return ret;

	ret = choose_samples(x, &n, &pilot);
	if (ret || x->stop)
		return ret;

	/* the pilot was taken in this posture with these DAC values: reused */
	ret = level_pass(x, n, "3-3", x->o->permissible_error_q16 ? &pilot : NULL,
			 pass1_steps, mean, &t_l, st);
	if (ret || x->stop)
		return ret;
	ret = posture(x, mean, st, g);
	if (ret && x->stop)
		return 0;
	store_level(res, mean, t_l, g);
	if (x->o->measure_only)
		return 0;
	ret = dac_optimum(x, mean, st, g, dac);
	if (ret && x->stop)
		return 0;

	ret = x->ops->write_dac(x, dac);
	if (ret || x->stop)
		return ret;

	/* 3-27..3-47: again with DACopt */
	ret = level_pass(x, n, "3-28", NULL, pass2_steps, mean, &t_l, st);
	if (ret || x->stop)
		return ret;

	store_level(res, mean, t_l, g);
	memcpy(res->rec.eeprom, ee->raw, AS9888_EEPROM_LEN);
	memcpy(res->rec.dac, dac, AS9888_AXES);
	memcpy(res->rec.level_mean_q16, mean, sizeof(mean));
	memcpy(res->rec.gravity, g, AS9888_AXES);
	res->rec.t_level_mdegc = t_l;
	res->rec.samples = n;
	res->rec.lpf = x->o->lpf;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = as9888_offset_level_q16(mean[axis], st[axis], g[axis],
					      &res->offset_q16[axis]);
		if (ret)
			return ret;
	}
	res->have_calibration = true;

	return 0;
}

void ftest_opts_default(struct ftest_opts *o)
{
	memset(o, 0, sizeof(*o));
	o->samples = AS9888_SAMPLES_MIN;
	o->fluctuation = AS9888_FLUCTUATION_DEFAULT;
	o->stable_timeout_ms = FTEST_STABLE_TIMEOUT_MS_DEFAULT;
	o->busy_timeout_ms = FTEST_BUSY_TIMEOUT_MS_DEFAULT;
}

int ftest_engine_run(struct ftest_ctx *x)
{
	uint64_t start = x->ops->now_ns(x);
	int ret;

	x->res->opts = *x->o;
	x->res->started = (int64_t)time(NULL);

	ret = x->ops->step1(x);
	if (!ret && !x->stop && !x->o->level_only)
		ret = x->ops->step2(x);
	if (!ret && !x->stop)
		ret = step3(x);

	x->ops->finish(x);
	x->res->duration_ns = x->ops->now_ns(x) - start;

	return ret;
}

void ftest_result_free(struct ftest_result *res)
{
	report_free(&res->report);
}
