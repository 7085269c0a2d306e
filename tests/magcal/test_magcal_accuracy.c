// SPDX-License-Identifier: GPL-2.0
/*
 * Issue 28, point 5: the magnetometer calibration judged against the
 * truth. For a seeded set of boards (hard iron up to +-200 uT, soft-iron
 * gains 0.9..1.1 with cross terms up to +-0.05, 0.4 uT rms noise, an Earth
 * field of their own) at three temperatures, the chip model (through the
 * userspace simulator, as the daemon sees it) runs a session of 300
 * samples of natural motion (the seeded tumble), lib/magcal fits them, and
 * over 200 orientations the calibrated field is compared with the truth:
 *  - magnitude error rms <= 1 uT, against F * g, g = det(S)^(1/3) the
 *    board's isotropic soft-iron gain that no self-calibration can observe
 *    (magcal.h: det(W) = 1); the error against F alone is printed too;
 *  - with the site's field (config reference_field_ut: the integrator
 *    gives the World Magnetic Model's field strength for the site), the
 *    magnitude error rms <= 1 uT against F itself. The reference is the
 *    board's true F off by a WMM error drawn per board, uniform within
 *    +-WMM_ERROR (0.5 %, some 250 nT: the model's own total-intensity
 *    uncertainty, about 145 nT 1 sigma, plus a local crustal anomaly);
 *  - tilt-compensated heading (magcal_heading_deg() from the calibrated
 *    field and the driver's compensated accelerometer, after the daemon's
 *    level calibration) against the true heading of the model's
 *    orientation and declination: rms <= 2 deg, worst <= 5 deg.
 * Each orientation averages 16 samples (a compass display's smoothing;
 * one sample's 0.4 uT noise alone is about 1 deg of heading). Orientations
 * keep the sensor's +Y within 60 deg of the horizon (a heading of +Y).
 *
 * The full correction is the deployed stack: the driver's calibbias and
 * calibscale (hard iron and the diagonal D, quantised as the driver
 * takes them) and userspace's residual matrix R = W D^-1. The driver-only
 * column applies the driver's part alone. An uncalibrated board and a
 * naive fit of a session with a passing magnet must fail the judgment.
 */

#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "as9888_calib.h"
#include "as9888_sim.h"
#include "magcal.h"

#define DEG			(M_PI / 180.0)
#define BOARDS			8
#define SESSION_SAMPLES		300
#define ORIENTATIONS		200
#define AVERAGE			16
#define NOISE_NT		400
#define TUMBLE_MDEG		6000
#define MAX_PITCH_DEG		60.0
#define LIMIT_MAG_RMS_UT	1.0
#define LIMIT_HEAD_RMS_DEG	2.0
#define LIMIT_HEAD_WORST_DEG	5.0
#define CALIBBIAS_MAX		4096
#define LEVEL_SAMPLES		32
/* the site's field from the WMM: relative error, uniform within +- */
#define WMM_ERROR		0.005

static const s32 temperatures_mdegc[] = { -10000, 25000, 60000 };

static uint64_t rng_state;

/* splitmix64: neighbouring seeds give unrelated sequences */
static double uniform(void)
{
	uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	z ^= z >> 31;
	return (z >> 11) * (1.0 / 9007199254740992.0);
}

static double between(double lo, double hi)
{
	return lo + (hi - lo) * uniform();
}

/* ---- the board and the chip ---- */

/* A board: its iron, its place on Earth */
static void board_unit(unsigned int board, s32 t_mdegc, struct as9888_unit *u)
{
	int i, j;

	rng_state = 0x5eed0000ULL + board;
	as9888_unit_default(u);
	u->temperature_mdegc = t_mdegc;
	u->seed = 1000 + board * 7 + (u64)(t_mdegc + 50000);
	u->world = AS9888_UNIT_WORLD_EARTH | AS9888_UNIT_WORLD_ORIENTATION;
	u->earth_nt = (s32)between(30000, 60000);
	u->incl_mdeg = (s32)between(-65000, 65000);
	u->decl_mdeg = (s32)between(-15000, 15000);
	for (i = 0; i < 3; i++) {
		u->hard_nt[i] = (s32)between(-200000, 200000);
		u->soft_ppm[i * 4] = (s32)between(900000, 1100000);
		for (j = i + 1; j < 3; j++)
			u->soft_ppm[i * 3 + j] = u->soft_ppm[j * 3 + i] =
				(s32)between(-50000, 50000);
	}
	u->magn_noise_nt = NOISE_NT;
	for (i = 0; i < 4; i++)
		u->orientation[i] = (s32)between(-1000000, 1000000);
}

struct chip {
	struct as9888_sim *sim;
	struct as9888_eeprom ee;
	struct as9888_accel_cal cal;	/* the accelerometer's, level test */
	double scale_ut[3];	/* uT per count: in_magn_scale */
};

static void chip_write(struct chip *c, u8 reg, u8 v)
{
	assert_int_equal(as9888_sim_write_reg(c->sim, reg, v), 0);
}

struct reading {
	s16 count[3];		/* magnetometer, chip counts */
	s16 raw_accel[3];
	u8 tmps;
	double accel_g[3];	/* compensated as the driver does */
};

static void measure(struct chip *c, struct reading *r);

/*
 * The accelerometer's calibration, as the daemon's level test makes it
 * (lib/calib): the model's offsets are given at 25 degC, the EEPROM's
 * reference is t_RT, so the factory state alone leaves some 0.05 g.
 */
static void level_calibrate(struct chip *c)
{
	static const s32 level[3] = { 0, 0, 1000000 };
	static const s8 g[3] = { 0, 0, -1 };
	s64 sum[3] = { 0 };
	s32 mean_q16[3];
	u8 da[3];
	struct reading r;
	int n, i;

	as9888_model_set_up(as9888_sim_model(c->sim),
			    as9888_sim_now_ns(c->sim), level);
	for (n = 0; n < LEVEL_SAMPLES; n++) {
		measure(c, &r);
		for (i = 0; i < 3; i++)
			sum[i] += r.raw_accel[i];
	}
	for (i = 0; i < 3; i++) {
		mean_q16[i] = (s32)(sum[i] * AS9888_Q16_ONE / LEVEL_SAMPLES);
		da[i] = c->ee.axis[i].da;
	}
	assert_int_equal(as9888_accel_cal_from_level(&c->ee, mean_q16,
			 as9888_tmps_to_mdegc(r.tmps), g, da, &c->cal), 0);
}

/* Power on, read the EEPROM, load the trim (the driver's probe) */
static void chip_open(struct chip *c, const struct as9888_unit *u)
{
	struct as9888_sim_opts opts = { .clock = AS9888_SIM_CLOCK_VIRTUAL };
	u8 raw[AS9888_EEPROM_LEN], trim[AS9888_TRIM_LEN];
	int i;

	c->sim = as9888_sim_new(u, &opts);
	assert_non_null(c->sim);
	as9888_sim_sleep_ns(c->sim, AS9888_T_BOOT_US * 1000ULL);
	chip_write(c, AS9888_REG_MS, AS9888_MS_EEPROM);
	as9888_sim_sleep_ns(c->sim, AS9888_T_EEP_US * 1000ULL);
	assert_int_equal(as9888_sim_read(c->sim, AS9888_REG_EEPROM, raw,
					 sizeof(raw)), 0);
	chip_write(c, AS9888_REG_MS, AS9888_MS_POWER_DOWN);
	as9888_sim_sleep_ns(c->sim, AS9888_T_PD_US * 1000ULL);
	assert_int_equal(as9888_eeprom_decode(raw, &c->ee), 0);
	trim[0] = c->ee.ref1;
	trim[1] = c->ee.ref2;
	trim[2] = c->ee.ref3;
	trim[3] = c->ee.osc;
	for (i = 0; i < 3; i++) {
		trim[4 + i] = c->ee.axis[i].ga;
		trim[7 + i] = c->ee.axis[i].da;
		c->scale_ut[i] = 0.3 * (c->ee.axis[i].ehc + 128) / 256;
	}
	assert_int_equal(as9888_sim_write(c->sim, AS9888_REG_REF1, trim,
					  sizeof(trim)), 0);
	chip_write(c, AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	memset(&c->cal, 0, sizeof(c->cal));
	level_calibrate(c);
	as9888_model_set_orientation(as9888_sim_model(c->sim),
				     as9888_sim_now_ns(c->sim), u->orientation);
}


static void measure(struct chip *c, struct reading *r)
{
	u8 b[AS9888_SAMPLE_LEN];
	s32 ot, st, t;
	s16 out;
	int i;

	as9888_sim_sleep_ns(c->sim, AS9888_T_PD_US * 1000ULL);
	chip_write(c, AS9888_REG_MS, AS9888_MS_SINGLE);
	as9888_sim_sleep_ns(c->sim, AS9888_T_MAG_US * 1000ULL);
	assert_int_equal(as9888_sim_read(c->sim, AS9888_REG_ST1, b,
					 sizeof(b)), 0);
	t = as9888_tmps_to_mdegc(b[7]);
	for (i = 0; i < 3; i++) {
		s16 acc = (s16)(b[9 + 2 * i] | b[10 + 2 * i] << 8);

		r->count[i] = (s16)(b[1 + 2 * i] | b[2 + 2 * i] << 8);
		r->raw_accel[i] = acc;
		r->tmps = b[7];
		assert_int_equal(as9888_accel_correction(&c->ee, &c->cal, i,
							 c->ee.axis[i].da, t,
							 &ot, &st), 0);
		assert_int_equal(as9888_accel_compensate(acc, ot, st, &out), 0);
		r->accel_g[i] = (double)out / AS9888_ACC_OUT_PER_G;
	}
}

/* ---- the corrections under test ---- */

/* CORR_SITE: the full correction of the fit given the site's field */
enum correction { CORR_FULL, CORR_SITE, CORR_DRIVER, CORR_NONE, CORR_COUNT };

static const char *const corr_names[CORR_COUNT] = {
	"full", "full, site's F", "driver only", "uncalibrated",
};

/* Which magnitude a correction is judged against */
static const char *const corr_judged[CORR_COUNT] = {
	"g*F", "F", "g*F", "g*F",
};

/* What the driver is given (calibbias, calibscale) and R for userspace */
struct stack {
	int calibbias[3];
	double calibscale[3];
	double resid[3][3];
};

/* False when the driver cannot take the fit (its ranges) */
static bool stack_from(const struct chip *c, const struct magcal_result *r,
		       struct stack *st)
{
	double diag[3], bias;
	int i;

	magcal_split(r, diag, st->resid);
	for (i = 0; i < 3; i++) {
		bias = -r->bias[i] / c->scale_ut[i];
		if (!(fabs(bias) <= CALIBBIAS_MAX) || !(diag[i] >= 0.5) ||
		    !(diag[i] <= 2))
			return false;
		st->calibbias[i] = (int)lrint(bias);
		/* IIO_VAL_INT_PLUS_MICRO */
		st->calibscale[i] = round(diag[i] * 1e6) / 1e6;
	}
	return true;
}

/* The field a consumer gets, uT, with correction @k */
static void corrected(const struct chip *c, const struct stack *st,
		      enum correction k, const double count[3], double out[3])
{
	double drv[3];
	int i;

	for (i = 0; i < 3; i++) {
		/* in_magn_raw = round((count + calibbias) * calibscale) */
		drv[i] = round((count[i] + st->calibbias[i]) *
			       st->calibscale[i]) * c->scale_ut[i];
		if (k == CORR_NONE)
			out[i] = count[i] * c->scale_ut[i];
	}
	if (k == CORR_NONE)
		return;
	for (i = 0; i < 3; i++)
		out[i] = k == CORR_DRIVER ? drv[i] :
			 st->resid[i][0] * drv[0] + st->resid[i][1] * drv[1] +
			 st->resid[i][2] * drv[2];
}

/* ---- the session ---- */

/* @s and @site (the same fit given the site's field) get every sample */
static void run_session(struct chip *c, struct magcal_session *s,
			struct magcal_session *site, const s32 *dist_nt,
			u32 dist_n)
{
	struct as9888_model *m = as9888_sim_model(c->sim);
	struct reading r;
	double mut[3];
	int n, i;

	as9888_model_set_tumble(m, as9888_sim_now_ns(c->sim), TUMBLE_MDEG);
	for (n = 0; n < SESSION_SAMPLES; n++) {
		if (dist_nt && n == SESSION_SAMPLES / 3)
			as9888_model_set_disturbance(m, as9888_sim_now_ns(c->sim),
						     dist_nt, dist_n);
		measure(c, &r);
		for (i = 0; i < 3; i++)
			mut[i] = r.count[i] * c->scale_ut[i];
		assert_true(magcal_add(s, mut, r.accel_g) >= 0);
		assert_true(magcal_add(site, mut, r.accel_g) >= 0);
	}
	as9888_model_set_tumble(m, as9888_sim_now_ns(c->sim), 0);
}

/* ---- judged against the truth ---- */

struct score {
	double mag_rms;		/* vs F * g */
	double mag_abs_rms;	/* vs F */
	double mag_judged;	/* the one of the two corr_judged[] names */
	double head_rms;
	double head_worst;
};

/* A random orientation whose +Y is within MAX_PITCH_DEG of the horizon */
static void pick_orientation(s32 q[4])
{
	double w, x, y, z, n, yz;

	do {
		w = between(-1, 1);
		x = between(-1, 1);
		y = between(-1, 1);
		z = between(-1, 1);
		n = sqrt(w * w + x * x + y * y + z * z);
		w /= n;
		x /= n;
		y /= n;
		z /= n;
		/* up component of R(q) (0, 1, 0) */
		yz = 2 * (y * z + w * x);
	} while (n > 1 || n < 0.1 || fabs(yz) > sin(MAX_PITCH_DEG * DEG));
	q[0] = (s32)lrint(w * 1e6);
	q[1] = (s32)lrint(x * 1e6);
	q[2] = (s32)lrint(y * 1e6);
	q[3] = (s32)lrint(z * 1e6);
}

/* True heading of +Y for the model's orientation now */
static double true_heading(struct as9888_model *m)
{
	double w, x, y, z, e, n, h;
	s32 q[4];

	as9888_model_orientation(m, q);
	w = q[0] / 1073741824.0;
	x = q[1] / 1073741824.0;
	y = q[2] / 1073741824.0;
	z = q[3] / 1073741824.0;
	e = 2 * (x * y - w * z);
	n = 1 - 2 * (x * x + z * z);
	h = atan2(e, n) / DEG;
	return h < 0 ? h + 360 : h;
}

static double angle_diff(double a, double b)
{
	double d = fmod(a - b, 360);

	if (d > 180)
		d -= 360;
	if (d < -180)
		d += 360;
	return d;
}

static void judge(struct chip *c, const struct as9888_unit *u,
		  const struct stack *st, const struct stack *site,
		  struct score sc[CORR_COUNT])
{
	struct as9888_model *m = as9888_sim_model(c->sim);
	double g = cbrt(fabs(
		(u->soft_ppm[0] * ((double)u->soft_ppm[4] * u->soft_ppm[8] -
				   (double)u->soft_ppm[5] * u->soft_ppm[7]) -
		 u->soft_ppm[1] * ((double)u->soft_ppm[3] * u->soft_ppm[8] -
				   (double)u->soft_ppm[5] * u->soft_ppm[6]) +
		 u->soft_ppm[2] * ((double)u->soft_ppm[3] * u->soft_ppm[7] -
				   (double)u->soft_ppm[4] * u->soft_ppm[6])))) /
		1e6;
	double f = u->earth_nt / 1000.0, decl = u->decl_mdeg / 1000.0;
	double sq[CORR_COUNT][3] = { { 0 } };
	int o, k, i, j;

	memset(sc, 0, CORR_COUNT * sizeof(*sc));
	for (o = 0; o < ORIENTATIONS; o++) {
		double cnt[3] = { 0 }, acc[3] = { 0 }, fld[3], h, truth, e;
		struct reading r;
		s32 q[4];

		pick_orientation(q);
		as9888_model_set_orientation(m, as9888_sim_now_ns(c->sim), q);
		for (j = 0; j < AVERAGE; j++) {
			measure(c, &r);
			for (i = 0; i < 3; i++) {
				cnt[i] += (double)r.count[i] / AVERAGE;
				acc[i] += r.accel_g[i] / AVERAGE;
			}
		}
		truth = true_heading(m);
		for (k = 0; k < CORR_COUNT; k++) {
			if (k == CORR_SITE)
				corrected(c, site, CORR_FULL, cnt, fld);
			else
				corrected(c, st, k, cnt, fld);
			e = sqrt(fld[0] * fld[0] + fld[1] * fld[1] +
				 fld[2] * fld[2]);
			sq[k][0] += (e - f * g) * (e - f * g);
			sq[k][1] += (e - f) * (e - f);
			if (magcal_heading_deg(fld, acc, decl, &h))
				h = truth + 180;	/* no heading: worst */
			e = fabs(angle_diff(h, truth));
			sq[k][2] += e * e;
			sc[k].head_worst = fmax(sc[k].head_worst, e);
		}
	}
	for (k = 0; k < CORR_COUNT; k++) {
		sc[k].mag_rms = sqrt(sq[k][0] / ORIENTATIONS);
		sc[k].mag_abs_rms = sqrt(sq[k][1] / ORIENTATIONS);
		sc[k].head_rms = sqrt(sq[k][2] / ORIENTATIONS);
		sc[k].mag_judged = k == CORR_SITE ? sc[k].mag_abs_rms :
						    sc[k].mag_rms;
	}
}

static bool passes(const struct score *sc)
{
	return sc->mag_judged <= LIMIT_MAG_RMS_UT &&
	       sc->head_rms <= LIMIT_HEAD_RMS_DEG &&
	       sc->head_worst <= LIMIT_HEAD_WORST_DEG;
}

/* One board at one temperature: session, fit, judgment */
struct outcome {
	struct magcal_result fit;
	struct magcal_result site_fit;	/* given the site's field */
	double wmm_error;		/* its relative error */
	struct score sc[CORR_COUNT];
	double bias_err;
};

/*
 * The WMM's error at board @board's site, relative, seeded per board (its
 * own sequence: the boards and orientations stay those without it)
 */
static double wmm_error(unsigned int board)
{
	uint64_t saved = rng_state;
	double e;

	rng_state = 0x3a3a0000ULL + board;
	e = between(-WMM_ERROR, WMM_ERROR);
	rng_state = saved;
	return e;
}

static void evaluate(unsigned int board, s32 t_mdegc,
		     const struct magcal_config *cfg, const s32 *dist_nt,
		     u32 dist_n, struct outcome *out)
{
	struct magcal_config site_cfg;
	struct magcal_session *s = magcal_new(cfg), *site;
	struct as9888_unit u;
	struct stack st, site_st;
	struct chip c;
	int i;

	assert_non_null(s);
	board_unit(board, t_mdegc, &u);
	if (cfg)
		site_cfg = *cfg;
	else
		magcal_config_default(&site_cfg);
	out->wmm_error = wmm_error(board);
	site_cfg.reference_field_ut = u.earth_nt / 1e3 * (1 + out->wmm_error);
	site = magcal_new(&site_cfg);
	assert_non_null(site);
	chip_open(&c, &u);
	run_session(&c, s, site, dist_nt, dist_n);
	assert_int_equal(magcal_solve(s, &out->fit), 0);
	assert_int_equal(magcal_solve(site, &out->site_fit), 0);
	/* the reference changes the scale, never the verdict */
	assert_int_equal(out->site_fit.status, out->fit.status);
	out->bias_err = 0;
	for (i = 0; i < 3; i++)
		out->bias_err = fmax(out->bias_err,
				     fabs(out->fit.bias[i] - u.hard_nt[i] / 1e3));
	if (stack_from(&c, &out->fit, &st) &&
	    stack_from(&c, &out->site_fit, &site_st)) {
		judge(&c, &u, &st, &site_st, out->sc);
	} else {
		/* beyond the driver's ranges: no consumer gets a field */
		for (i = 0; i < CORR_COUNT; i++)
			out->sc[i] = (struct score){ INFINITY, INFINITY,
						     INFINITY, INFINITY,
						     INFINITY };
	}
	as9888_sim_free(c.sim);
	magcal_free(site);
	magcal_free(s);
}

static void print_header(void)
{
	printf("%-5s %5s %-6s %7s %5s %5s %6s %6s | %-26s | %-32s | %-26s | %s\n",
	       "board", "degC", "status", "used/rj", "cover", "unc", "F",
	       "b err",
	       "full: |B| rms abs  hd rms/worst",
	       "site's F (wmm%): |B| abs hd rms",
	       "driver only: |B|  hd rms/worst",
	       "uncalibrated hd rms");
}

static void print_row(const char *name, s32 t_mdegc, const struct outcome *o)
{
	const struct score *f = &o->sc[CORR_FULL], *d = &o->sc[CORR_DRIVER];
	const struct score *site = &o->sc[CORR_SITE];

	printf("%-5s %5.0f %-6s %3u/%-3u %5.2f %5.2f %6.2f %6.3f | %5.2f %5.2f %6.2f %6.2f |"
	       " %+6.2f          %5.2f %6.2f  |"
	       " %5.2f %6.2f %6.2f      | %7.1f\n",
	       name, t_mdegc / 1000.0,
	       o->fit.status == MAGCAL_OK ? "ok" : "FAIL", o->fit.used,
	       o->fit.rejected, o->fit.coverage, o->fit.uncertainty_deg,
	       o->fit.field_ut, o->bias_err,
	       f->mag_rms, f->mag_abs_rms, f->head_rms, f->head_worst,
	       100 * o->wmm_error, site->mag_abs_rms, site->head_rms,
	       d->mag_rms, d->head_rms, d->head_worst,
	       o->sc[CORR_NONE].head_rms);
}

/* The table of point 5: every board passes with the full correction */
static void test_accuracy_table(void **state)
{
	struct score all[CORR_COUNT] = { { 0 } };
	double sq[CORR_COUNT][3] = { { 0 } };
	unsigned int b, t, k, n = 0, worst = 0;
	struct outcome o, worst_o;
	char name[16];
	bool ok = true;

	memset(&worst_o, 0, sizeof(worst_o));
	printf("magnetometer calibration against the truth: %d boards x %zu "
	       "temperatures, %d-sample sessions (tumble %.0f deg/sample), "
	       "%d orientations x %d samples, noise %.1f uT rms\n",
	       BOARDS, ARRAY_SIZE(temperatures_mdegc), SESSION_SAMPLES,
	       TUMBLE_MDEG / 1000.0, ORIENTATIONS, AVERAGE, NOISE_NT / 1000.0);
	print_header();
	for (b = 0; b < BOARDS; b++) {
		for (t = 0; t < ARRAY_SIZE(temperatures_mdegc); t++) {
			evaluate(b, temperatures_mdegc[t], NULL, NULL, 0, &o);
			snprintf(name, sizeof(name), "%u", b);
			print_row(name, temperatures_mdegc[t], &o);
			ok &= o.fit.status == MAGCAL_OK &&
			      passes(&o.sc[CORR_FULL]) &&
			      passes(&o.sc[CORR_SITE]);
			for (k = 0; k < CORR_COUNT; k++) {
				sq[k][0] += o.sc[k].mag_rms * o.sc[k].mag_rms;
				sq[k][1] += o.sc[k].head_rms * o.sc[k].head_rms;
				all[k].head_worst = fmax(all[k].head_worst,
							 o.sc[k].head_worst);
				all[k].mag_abs_rms += o.sc[k].mag_abs_rms *
						      o.sc[k].mag_abs_rms;
			}
			if (o.sc[CORR_FULL].head_worst >=
			    worst_o.sc[CORR_FULL].head_worst) {
				worst_o = o;
				worst = b;
			}
			n++;
		}
	}
	for (k = 0; k < CORR_COUNT; k++) {
		all[k].mag_rms = sqrt(sq[k][0] / n);
		all[k].head_rms = sqrt(sq[k][1] / n);
		all[k].mag_abs_rms = sqrt(all[k].mag_abs_rms / n);
		all[k].mag_judged = k == CORR_SITE ? all[k].mag_abs_rms :
						     all[k].mag_rms;
		printf("overall %-14s: |B| error rms vs g*F %.2f uT, vs F "
		       "%.2f uT (judged vs %s), heading rms %.2f deg, worst "
		       "%.2f deg: %s\n",
		       corr_names[k], all[k].mag_rms, all[k].mag_abs_rms,
		       corr_judged[k], all[k].head_rms, all[k].head_worst,
		       passes(&all[k]) ? "pass" : "FAIL");
	}
	printf("worst board (full correction, by worst heading): %u, "
	       "heading rms %.2f worst %.2f deg, |B| rms %.2f uT; "
	       "driver only on it: heading rms %.2f worst %.2f deg\n", worst,
	       worst_o.sc[CORR_FULL].head_rms, worst_o.sc[CORR_FULL].head_worst,
	       worst_o.sc[CORR_FULL].mag_rms, worst_o.sc[CORR_DRIVER].head_rms,
	       worst_o.sc[CORR_DRIVER].head_worst);
	printf("limits: |B| rms <= %.1f uT, heading rms <= %.1f deg, worst <= "
	       "%.1f deg; g = det(S)^(1/3), the board's overall soft-iron gain "
	       "motion cannot observe; site's F: the true F with a WMM error "
	       "uniform within +-%.1f %% per board\n", LIMIT_MAG_RMS_UT,
	       LIMIT_HEAD_RMS_DEG, LIMIT_HEAD_WORST_DEG, 100 * WMM_ERROR);
	assert_true(ok);
	assert_true(passes(&all[CORR_FULL]));
	assert_true(passes(&all[CORR_SITE]));
	/* the judgment can fail: an uncalibrated board does */
	assert_false(passes(&all[CORR_NONE]));
}

/*
 * A magnet passes through the session: a naive fit that keeps every
 * sample fails the judgment; the robust fit rejects the magnet and
 * passes, or says it failed. A strong magnet (350 uT peak over 60 of the
 * 300 samples) and a weak one (40 uT over 30 samples), which a naive fit
 * would take for a good calibration.
 */
static void magnet(unsigned int board, const s32 peak_nt[3], u32 samples)
{
	struct magcal_config naive;
	struct outcome o;

	magcal_config_default(&naive);
	naive.outlier_ut = 1e6;		/* no sample is ever an outlier */
	naive.max_residual_ut = 1e6;	/* and no residual too high */
	naive.max_uncertainty_deg = 1e6;	/* nor the fit uncertain */
	evaluate(board, 25000, &naive, peak_nt, samples, &o);
	print_header();
	print_row("naive", 25000, &o);
	assert_false(o.fit.status == MAGCAL_OK && passes(&o.sc[CORR_FULL]));

	evaluate(board, 25000, NULL, peak_nt, samples, &o);
	print_row("rbst", 25000, &o);
	assert_true(o.fit.rejected >= samples * 2 / 3);
	if (o.fit.status == MAGCAL_OK)
		assert_true(passes(&o.sc[CORR_FULL]));
	else
		printf("robust fit: %s\n", magcal_status_str(o.fit.status));
}

static void test_disturbance_strong(void **state)
{
	static const s32 peak_nt[3] = { 300000, -150000, 80000 };

	magnet(1, peak_nt, 60);
}

static void test_disturbance_weak(void **state)
{
	static const s32 peak_nt[3] = { 0, 30000, -25000 };

	magnet(2, peak_nt, 30);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_accuracy_table),
		cmocka_unit_test(test_disturbance_strong),
		cmocka_unit_test(test_disturbance_weak),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
