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
#include "magsim.h"

#define BOARDS			8
#define SESSION_SAMPLES		300
#define NOISE_NT		400
#define TUMBLE_MDEG		6000
#define LIMIT_MAG_RMS_UT	1.0
#define LIMIT_HEAD_RMS_DEG	2.0
#define LIMIT_HEAD_WORST_DEG	5.0
/* the site's field from the WMM: relative error, uniform within +- */
#define WMM_ERROR		0.005

static const s32 temperatures_mdegc[] = { -10000, 25000, 60000 };


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


static const char *const corr_names[CORR_COUNT] = {
	"full", "full, site's F", "driver only", "uncalibrated",
};

/* Which magnitude a correction is judged against */
static const char *const corr_judged[CORR_COUNT] = {
	"g*F", "F", "g*F", "g*F",
};

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
