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

#include "as9888_regs.h"
#include "chip.h"
#include "ftest.h"

#define NS_PER_US	1000ULL
#define NS_PER_MS	1000000ULL

/* Pause before retrying a level run whose temperature moved */
#define FTEST_STABLE_RETRY_MS	200

static const char *const axis_name = "XYZ";

/* Judgment helpers: a failed judgment stops the test unless keep_going */
struct ftest_ctx {
	struct chip chip;
	const struct ftest_opts *o;
	struct ftest_result *res;
	bool stop;
	uint8_t dac[AS9888_AXES];	/* the DAC values in the chip */
};

static bool judge(struct ftest_ctx *x, const char *step, const char *name,
		  bool ok, const char *limits, const char *fmt, ...)
	__attribute__((format(printf, 6, 7)));

static bool judge(struct ftest_ctx *x, const char *step, const char *name,
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

static void skip(struct ftest_ctx *x, const char *step, const char *name,
		 const char *why)
{
	report_add(&x->res->report, step, name, JUDGMENT_SKIP, NULL, "%s", why);
}

/* A bus error ends the test: nothing after it can be trusted */
static int bus_failed(struct ftest_ctx *x, const char *step, const char *what,
		      int err)
{
	report_add(&x->res->report, step, what, JUDGMENT_FAIL, NULL,
		   "bus transfer failed: %s", strerror(-err));
	x->stop = true;

	return err;
}

/* Step 1 and D11's RSTN check */
static int step1_identify(struct ftest_ctx *x)
{
	struct transport *t = x->chip.t;
	uint8_t wia, val;
	int ret;

	ret = chip_reset(&x->chip);
	if (ret == -EOPNOTSUPP) {
		skip(x, "1-2", "reset pulse (RSTN)", "backend has no reset line");
		ret = 0;
	} else if (ret) {
		return bus_failed(x, "1-2", "reset pulse (RSTN)", ret);
	}

	ret = transport_read_reg(t, AS9888_REG_WIA, &wia);
	if (ret)
		return bus_failed(x, "1-4", "device ID (WIA)", ret);
	if (!judge(x, "1-4", "device ID (WIA)", wia == AS9888_WIA_VAL, "0x48",
		   "0x%02x", wia))
		return x->stop ? -ENODEV : 0;

	/* D11: a written R/W register must read 0x00 after a reset pulse */
	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = chip_reset(&x->chip);
	if (ret == -EOPNOTSUPP) {
		skip(x, "1-2", "RSTN pin check (D11)", "RSTN not controlled");
		return 0;
	}
	if (!ret)
		ret = transport_read_reg(t, AS9888_REG_INT1EN, &val);
	if (ret)
		return bus_failed(x, "1-2", "RSTN pin check (D11)", ret);
	judge(x, "1-2", "RSTN pin check (D11)", val == 0,
	      "INT1EN reads 0x00 after reset", "INT1EN 0x%02x", val);

	return 0;
}

static int step1_eeprom(struct ftest_ctx *x)
{
	struct ftest_result *res = x->res;
	struct transport *t = x->chip.t;
	uint8_t raw[AS9888_EEPROM_LEN];
	uint32_t bits;
	int ret;

	ret = chip_set_mode(&x->chip, AS9888_MS_EEPROM);
	if (ret)
		return bus_failed(x, "1-5", "EEPROM access mode", ret);
	transport_sleep_ns(t, AS9888_T_EEP_US * NS_PER_US);
	ret = transport_read(t, AS9888_REG_EEPROM, raw, sizeof(raw));
	if (ret)
		return bus_failed(x, "1-7", "EEPROM read", ret);

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
		judge(x, "1-27", "EEPROM contents", false,
		      "gain 7..43, DAC 0..67/128..195, not blank", "%s", why);
		/* without factory data nothing below can be judged */
		x->stop = true;
		return -ENODATA;
	}
	judge(x, "1-27", "EEPROM contents", true,
	      "gain 7..43, DAC 0..67/128..195, not blank",
	      "fingerprint %016llx",
	      (unsigned long long)record_fingerprint(raw));
	if (x->o->expect_eeprom &&
	    !judge(x, "1-27", "chip matches the calibration record",
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
		report_add(&res->report, "1-27", "EEPROM warning", JUDGMENT_PASS,
			   NULL, "warning: %s",
			   as9888_ee_warning_str(bits & -bits));

	return 0;
}

/* Steps 1-28..1-39 and the read-back check of D10 */
static int step1_trims(struct ftest_ctx *x)
{
	const struct as9888_eeprom *ee = &x->res->ee;
	struct transport *t = x->chip.t;
	uint8_t trim[AS9888_TRIM_LEN], back[AS9888_TRIM_LEN];
	int axis, i, ret;

	ret = chip_set_mode(&x->chip, AS9888_MS_POWER_DOWN);
	if (ret)
		return bus_failed(x, "1-28", "power-down mode", ret);
	/* 1-29: the trim registers take writes t_PD after power-down */
	transport_sleep_ns(t, AS9888_T_PD_US * NS_PER_US);

	trim[AS9888_REG_REF1 - AS9888_REG_REF1] = ee->ref1;
	trim[AS9888_REG_REF2 - AS9888_REG_REF1] = ee->ref2;
	trim[AS9888_REG_REF3 - AS9888_REG_REF1] = ee->ref3;
	trim[AS9888_REG_OSC - AS9888_REG_REF1] = ee->osc;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		trim[AS9888_REG_AGA(axis) - AS9888_REG_REF1] = ee->axis[axis].ga;
		trim[AS9888_REG_ADA(axis) - AS9888_REG_REF1] =
			x->o->apply_dac ? x->o->apply_dac[axis] : ee->axis[axis].da;
	}
	ret = transport_write(t, AS9888_REG_REF1, trim, sizeof(trim));
	if (ret)
		return bus_failed(x, "1-30", "trim load", ret);
	memcpy(x->dac, &trim[AS9888_REG_AXDA - AS9888_REG_REF1], AS9888_AXES);
	ret = transport_read(t, AS9888_REG_REF1, back, sizeof(back));
	if (ret)
		return bus_failed(x, "1-39", "register R/W check (D10)", ret);

	for (i = 0; i < AS9888_TRIM_LEN; i++)
		if (back[i] != trim[i])
			break;
	if (i < AS9888_TRIM_LEN)
		judge(x, "1-39", "register R/W check (D10)", false,
		      "read-back equals written",
		      "register 0x%02x wrote 0x%02x read 0x%02x",
		      AS9888_REG_REF1 + i, trim[i], back[i]);
	else
		judge(x, "1-39", "register R/W check (D10)", true,
		      "read-back equals written", "10 trim registers match");

	return 0;
}

int ftest_step1(struct transport *t, const struct ftest_opts *o,
		     struct ftest_result *res)
{
	struct ftest_ctx x = { .res = res, .o = o };
	int ret;

	chip_init(&x.chip, t);
	ret = step1_identify(&x);
	if (!ret && !x.stop)
		ret = step1_eeprom(&x);
	if (!ret && !x.stop)
		ret = step1_trims(&x);
	if (ret)
		return ret;

	return x.stop ? -EIO : 0;
}

/*
 * Start a measurement and wait for it. Reports the INT1 pin check (D11)
 * the first time @int_step is given; with INT1 dead and keep_going, the
 * rest of the test polls DRDY.
 */
static int measure(struct ftest_ctx *x, uint8_t ms, bool men,
		   const char *step, bool check_pins, struct chip_sample *s)
{
	struct transport *t = x->chip.t;
	uint64_t us = chip_measure_time_us(men, x->o->lpf);
	bool int1 = x->chip.use_int1;
	enum chip_wait how;
	int ret;

	ret = chip_measure(&x->chip, ms, us, &how);
	if (ret)
		return bus_failed(x, step, "measurement", ret);

	if (check_pins && int1)
		judge(x, step, "INT1 pin check (D11)", how == CHIP_WAIT_INT1,
		      "rises within the measurement time + 5 ms",
		      how == CHIP_WAIT_INT1 ? "rose" : "stayed low");
	else if (check_pins)
		skip(x, step, "INT1 pin check (D11)", "INT1 not monitored");

	if (check_pins && t->ops->pin_monitored(t, TRANSPORT_INT2)) {
		/* INT2 is driven at the same instant as INT1 */
		ret = how == CHIP_WAIT_TIMEOUT ? 0 :
		      t->ops->wait_pin(t, TRANSPORT_INT2, 0);
		if (ret < 0)
			return bus_failed(x, step, "INT2 pin check (D11)", ret);
		judge(x, step, "INT2 pin check (D11)", ret > 0,
		      "rises within the measurement time + 5 ms",
		      ret > 0 ? "rose" : "stayed low");
	} else if (check_pins) {
		skip(x, step, "INT2 pin check (D11)", "INT2 not monitored");
	}

	if (how == CHIP_WAIT_TIMEOUT) {
		judge(x, step, "measurement completes", false,
		      "DRDY within the measurement time + 5 ms",
		      "no data ready after %llu us",
		      (unsigned long long)us + 5000);
		x->stop = true;
		return -ETIMEDOUT;
	}
	if (int1 && how == CHIP_WAIT_DRDY)
		x->chip.use_int1 = false;

	ret = chip_read_sample(&x->chip, s);
	if (ret)
		return bus_failed(x, step, "sample read", ret);

	return 0;
}

/* Step 2: magnetometer, normal measurement then self-test */
static int step2(struct ftest_ctx *x)
{
	static const char *const ovf_step[] = { "2-7", "2-9", "2-11" };
	static const char *const st_step[] = { "2-17", "2-19", "2-21" };
	const struct as9888_eeprom *ee = &x->res->ee;
	struct transport *t = x->chip.t;
	struct chip_sample s;
	uint8_t int1st;
	int axis, ret;

	/* 2-1: DR1EN, and DR2EN so that INT2 can be checked too (D11) */
	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_INT2EN,
					  AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_SLCT2,
					  AS9888_SLCT2_MEN_MSK);
	if (ret)
		return bus_failed(x, "2-1", "interrupt and MEN set-up", ret);

	ret = measure(x, AS9888_MS_SINGLE, true, "2-4", true, &s);
	if (ret || x->stop)
		return ret;

	ret = transport_read_reg(t, AS9888_REG_INT1ST, &int1st);
	if (ret)
		return bus_failed(x, "2-5", "INT1ST", ret);
	if (!judge(x, "2-5", "INT1ST reflects INT1", int1st == 0x01, "0x01",
		   "0x%02x", int1st) && x->stop)
		return 0;
	if (!judge(x, "2-6", "ST1 data ready", s.st1 == AS9888_ST1_DRDY_MSK,
		   "0x01", "0x%02x", s.st1) && x->stop)
		return 0;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		char name[32];

		snprintf(name, sizeof(name), "magnetometer %c no overflow",
			 axis_name[axis]);
		if (!judge(x, ovf_step[axis], name,
			   !as9888_mag_overflow(s.mag[axis]), "-4096 < H < 4095",
			   "%d", s.mag[axis]) && x->stop)
			return 0;
	}
	if (!judge(x, "2-13", "ST2 normal end", s.st2 == 0, "0x00", "0x%02x",
		   s.st2) && x->stop)
		return 0;

	ret = measure(x, AS9888_MS_SELF_TEST, true, "2-15", false, &s);
	if (ret || x->stop)
		return ret;
	if (!judge(x, "2-16", "ST1 data ready (self-test)",
		   s.st1 == AS9888_ST1_DRDY_MSK, "0x01", "0x%02x", s.st1) &&
	    x->stop)
		return 0;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		int32_t adj = as9888_mag_adjust_q8(s.mag[axis], ee->axis[axis].ehc);
		char name[40];

		snprintf(name, sizeof(name), "self-test %c after adjustment",
			 axis_name[axis]);
		if (!judge(x, st_step[axis], name,
			   as9888_selftest_ok(axis, s.mag[axis], ee->axis[axis].ehc),
			   axis == 2 ? "300..1000" : "-100..100",
			   "%.2f (raw %d)", adj / 256.0, s.mag[axis]) && x->stop)
			return 0;
	}
	judge(x, "2-23", "ST2 normal end (self-test)", s.st2 == 0, "0x00",
	      "0x%02x", s.st2);

	return 0;
}

/* The statistics of one level run of N samples */
struct level_run {
	uint32_t n;
	int64_t sum[AS9888_AXES];
	int16_t min[AS9888_AXES];
	int16_t max[AS9888_AXES];
	int64_t tmps_sum;
	uint8_t tmps_min;
	uint8_t tmps_max;
	/* first offending sample of each per-sample check, or -1 */
	int bad_st1, bad_tmps, bad_empt, bad_st2;
	uint8_t bad_st1_val, bad_tmps_val, bad_empt_val, bad_st2_val;
	int64_t sq_sum[AS9888_AXES];
};

static void level_run_init(struct level_run *r)
{
	int axis;

	memset(r, 0, sizeof(*r));
	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->min[axis] = INT16_MAX;
		r->max[axis] = INT16_MIN;
	}
	r->tmps_min = UINT8_MAX;
	r->bad_st1 = r->bad_tmps = r->bad_empt = r->bad_st2 = -1;
}

static void level_run_add(struct level_run *r, const struct chip_sample *s)
{
	int axis, i = (int)r->n;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		r->sum[axis] += s->acc[axis];
		r->sq_sum[axis] += (int64_t)s->acc[axis] * s->acc[axis];
		if (s->acc[axis] < r->min[axis])
			r->min[axis] = s->acc[axis];
		if (s->acc[axis] > r->max[axis])
			r->max[axis] = s->acc[axis];
	}
	r->tmps_sum += s->tmps;
	if (s->tmps < r->tmps_min)
		r->tmps_min = s->tmps;
	if (s->tmps > r->tmps_max)
		r->tmps_max = s->tmps;
	if (r->bad_st1 < 0 && s->st1 != AS9888_ST1_DRDY_MSK) {
		r->bad_st1 = i;
		r->bad_st1_val = s->st1;
	}
	if (r->bad_tmps < 0 && !as9888_tmps_valid(s->tmps)) {
		r->bad_tmps = i;
		r->bad_tmps_val = s->tmps;
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

/* Take N accelerometer-only samples (steps 3-2..3-13 or 3-27..3-38) */
static int level_collect(struct ftest_ctx *x, uint32_t n, const char *step,
			 struct level_run *r)
{
	struct chip_sample s;
	uint32_t i;
	int ret;

	level_run_init(r);
	for (i = 0; i < n; i++) {
		ret = measure(x, AS9888_MS_SINGLE, false, step, false, &s);
		if (ret)
			return ret;
		level_run_add(r, &s);
	}

	return 0;
}

/*
 * Collect N samples at a stable temperature (Note 2, Note 4b): a run whose
 * TMPS codes spread more than FTEST_TMPS_SPREAD_MAX is taken again, until
 * the stability timeout.
 */
static int level_collect_stable(struct ftest_ctx *x, uint32_t n,
				const char *step, struct level_run *r)
{
	struct transport *t = x->chip.t;
	uint64_t give_up = transport_now_ns(t) +
			   x->o->stable_timeout_ms * NS_PER_MS;
	int ret;

	for (;;) {
		ret = level_collect(x, n, step, r);
		if (ret)
			return ret;
		if (r->tmps_max - r->tmps_min <= FTEST_TMPS_SPREAD_MAX ||
		    r->bad_tmps >= 0 || transport_now_ns(t) >= give_up)
			break;
		transport_sleep_ns(t, FTEST_STABLE_RETRY_MS * NS_PER_MS);
	}

	return 0;
}

/* The per-sample and min/max/fluctuation judgments of one level run */
static void level_judge(struct ftest_ctx *x, const struct level_run *r,
			const char *const steps[])
{
	/* steps: ST1, TMPS, EMPT, ST2, max X Y Z, min X Y Z, fluct X Y Z */
	int axis, i;

	judge(x, steps[0], "ST1 data ready (every sample)", r->bad_st1 < 0,
	      "0x01", r->bad_st1 < 0 ? "all 0x01" : "sample %d: 0x%02x",
	      r->bad_st1, r->bad_st1_val);
	if (x->stop)
		return;
	judge(x, steps[1], "TMPS within specification",
	      r->bad_tmps < 0, "0x28..0xe0",
	      r->bad_tmps < 0 ? "0x%02x..0x%02x" : "sample %d: 0x%02x",
	      r->bad_tmps < 0 ? r->tmps_min : r->bad_tmps,
	      r->bad_tmps < 0 ? r->tmps_max : r->bad_tmps_val);
	if (x->stop)
		return;
	judge(x, steps[1], "temperature stable during averaging (Note 4b)",
	      r->tmps_max - r->tmps_min <= FTEST_TMPS_SPREAD_MAX,
	      "TMPS spread <= 1 code (0.625 degC)", "TMPS 0x%02x..0x%02x",
	      r->tmps_min, r->tmps_max);
	if (x->stop)
		return;
	judge(x, steps[2], "EMPT (every sample)", r->bad_empt < 0, "0x00",
	      r->bad_empt < 0 ? "all 0x00" : "sample %d: 0x%02x",
	      r->bad_empt, r->bad_empt_val);
	if (x->stop)
		return;
	judge(x, steps[3], "ST2 normal end, magnetometer off (HST)",
	      r->bad_st2 < 0, "0x02",
	      r->bad_st2 < 0 ? "all 0x02" : "sample %d: 0x%02x",
	      r->bad_st2, r->bad_st2_val);
	if (x->stop)
		return;

	/* 3-14..3-19: the maxima, then the minima, must not saturate */
	for (i = 0; i < 2 * AS9888_AXES; i++) {
		const int16_t *v = i < AS9888_AXES ? r->max : r->min;
		char name[48];

		axis = i % AS9888_AXES;
		snprintf(name, sizeof(name), "%s of %c",
			 i < AS9888_AXES ? "maximum" : "minimum", axis_name[axis]);
		if (!judge(x, steps[4 + i], name, !as9888_acc_saturated(v[axis]),
			   "-2048 < A < 2047", "%d", v[axis]) && x->stop)
			return;
	}
	for (axis = 0; axis < AS9888_AXES; axis++) {
		bool ok = as9888_fluctuation_ok(r->min[axis], r->max[axis],
						x->o->fluctuation);
		char name[48], limits[24];

		snprintf(name, sizeof(name), "fluctuation of %c", axis_name[axis]);
		snprintf(limits, sizeof(limits), "max - min <= %u",
			 x->o->fluctuation);
		if (!judge(x, steps[10 + axis], name, ok, limits, "%d%s",
			   r->max[axis] - r->min[axis],
			   !ok && x->o->user_mode ?
			   ": the device moved; keep it still and flat, then try again" :
			   "") && x->stop)
			return;
	}
}

static const char *const pass1_steps[] = {
	"3-4", "3-5", "3-6", "3-13",
	"3-14", "3-15", "3-16", "3-17", "3-18", "3-19",
	"3-20", "3-21", "3-22",
};

static const char *const pass2_steps[] = {
	"3-29", "3-30", "3-31", "3-38",
	"3-39", "3-40", "3-41", "3-42", "3-43", "3-44",
	"3-45", "3-46", "3-47",
};

/*
 * Note 2: N >= n * (sigma / Sigma)^2, with sigma measured on a pilot run of
 * single samples (n = 1), the noisiest axis deciding.
 */
static int choose_samples(struct ftest_ctx *x, uint32_t *n)
{
	struct level_run pilot;
	double worst = 0.0;
	char limits[64];
	int axis, ret;

	if (!x->o->permissible_error_q16) {
		*n = x->o->samples;
		return 0;
	}

	ret = level_collect(x, FTEST_PILOT_SAMPLES, "3-3", &pilot);
	if (ret)
		return ret;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		double mean = (double)pilot.sum[axis] / pilot.n;
		double var = ((double)pilot.sq_sum[axis] - mean * pilot.sum[axis]) /
			     (pilot.n - 1);

		if (var > worst)
			worst = var;
	}
	worst = sqrt(worst);
	*n = as9888_samples_needed(1, (uint32_t)lround(worst * AS9888_Q16_ONE),
				   x->o->permissible_error_q16);
	snprintf(limits, sizeof(limits), "N <= %d", AS9888_SAMPLES_MAX);
	if (!judge(x, "3-7", "averaging count from Note 2", *n <= AS9888_SAMPLES_MAX,
		   limits, "sigma %.3f LSB, Sigma %.3f LSB: N %u%s", worst,
		   (double)x->o->permissible_error_q16 / AS9888_Q16_ONE, *n,
		   *n > AS9888_SAMPLES_MAX ? " (environment too noisy)" : ""))
		return -ERANGE;
	if (*n < x->o->samples)
		*n = x->o->samples;

	return 0;
}

static void means(const struct level_run *r, int32_t mean_q16[AS9888_AXES])
{
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++)
		as9888_mean_q16(r->sum[axis], r->n, &mean_q16[axis]);
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
	if (!judge(x, "3-23", "device flat", tilt <= FTEST_USER_TILT_DEG,
		   "tilt <= 10 degrees",
		   tilt <= FTEST_USER_TILT_DEG ? "tilt about %.1f degrees" :
		   "the device is not flat (tilted about %.1f degrees): lay it flat on a level surface and try again",
		   tilt))
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
	judge(x, "3-23", "level posture (D8)", err == AS9888_POSTURE_OK,
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

	judge(x, "3-23", "optimal DAC (6.6)", !clamped,
	      "linear code within -67..67",
	      "Ot_L %.2f %.2f %.2f LSB -> DAC 0x%02x 0x%02x 0x%02x%s",
	      ot_l[0] / 65536.0, ot_l[1] / 65536.0, ot_l[2] / 65536.0,
	      dac[0], dac[1], dac[2],
	      clamped ? ": offset beyond DAC range (D6)" : "");

	return clamped ? -ERANGE : 0;
}

static int write_dac(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES])
{
	struct transport *t = x->chip.t;
	uint8_t back[AS9888_AXES];
	int ret;

	/* the chip is in power-down after a single measurement */
	ret = transport_write(t, AS9888_REG_AXDA, dac, AS9888_AXES);
	if (ret)
		return bus_failed(x, "3-24", "DAC write", ret);
	ret = transport_read(t, AS9888_REG_AXDA, back, AS9888_AXES);
	if (ret)
		return bus_failed(x, "3-26", "DAC read-back", ret);
	memcpy(x->dac, back, AS9888_AXES);
	judge(x, "3-26", "DAC written (3-24..3-26, D2)",
	      !memcmp(back, dac, AS9888_AXES), "read-back equals DACopt",
	      "0x%02x 0x%02x 0x%02x", back[0], back[1], back[2]);

	return 0;
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
		      const char *const steps[], int32_t mean[AS9888_AXES],
		      int32_t *t_l, int32_t st[AS9888_AXES])
{
	struct level_run run;
	int ret;

	ret = level_collect_stable(x, n, step, &run);
	if (ret || x->stop)
		return ret;
	level_judge(x, &run, steps);
	if (x->stop)
		return 0;

	means(&run, mean);
	ret = level_temperature(&run, t_l);
	if (!ret)
		ret = sensitivities(&x->res->ee, *t_l, st);
	if (ret)
		judge(x, steps[1], "level temperature", false, "-30..85 degC",
		      "cannot use the level temperature");

	return ret;
}

/* Step 3: accelerometer function test and level data */
static int step3(struct ftest_ctx *x)
{
	struct ftest_result *res = x->res;
	const struct as9888_eeprom *ee = &res->ee;
	struct transport *t = x->chip.t;
	int32_t mean[AS9888_AXES], st[AS9888_AXES], t_l;
	int8_t g[AS9888_AXES];
	uint8_t dac[AS9888_AXES];
	uint32_t n;
	int axis, ret;

	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_SLCT2,
					  x->o->lpf ? AS9888_SLCT2_ALPF_MSK : 0);
	if (ret)
		return bus_failed(x, "3-1", "SLCT2 set-up", ret);

	ret = choose_samples(x, &n);
	if (ret || x->stop)
		return ret;

	ret = level_pass(x, n, "3-3", pass1_steps, mean, &t_l, st);
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

	ret = write_dac(x, dac);
	if (ret || x->stop)
		return ret;

	/* 3-27..3-47: again with DACopt */
	ret = level_pass(x, n, "3-28", pass2_steps, mean, &t_l, st);
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
}

int ftest_run(struct transport *t, const struct ftest_opts *o,
	      struct ftest_result *res)
{
	struct ftest_ctx x = { .o = o, .res = res };
	uint64_t start = transport_now_ns(t);
	int ret;

	chip_init(&x.chip, t);

	ret = step1_identify(&x);
	if (!ret && !x.stop)
		ret = step1_eeprom(&x);
	if (!ret && !x.stop)
		ret = step1_trims(&x);
	if (!ret && !x.stop && !o->level_only)
		ret = step2(&x);
	if (!ret && !x.stop)
		ret = step3(&x);

	/* leave the chip idle whatever happened; a failure here changes nothing */
	chip_set_mode(&x.chip, AS9888_MS_POWER_DOWN);
	res->duration_ns = transport_now_ns(t) - start;

	return ret;
}

void ftest_result_free(struct ftest_result *res)
{
	report_free(&res->report);
}
