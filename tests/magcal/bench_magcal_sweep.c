// SPDX-License-Identifier: GPL-2.0
/*
 * Issue 39: the compass calibration swept over boards x rotation speeds x
 * Earth fields x disturbances, on the chip model through the userspace
 * simulator, printing what a user would get:
 *  - learning time: the session as magn-calibrate runs it (one sample
 *    every MAGN_SESSION_INTERVAL_NS, a fit after every
 *    MAGN_SESSION_SOLVE_EVERY kept samples, done at MAGCAL_OK with
 *    MAGN_SESSION_COVERAGE for samples of MAGN_SOURCE_AVERAGE
 *    measurements, at the timeout a last fit of the store held to the
 *    same rule: magn_session_done()), or
 *    the refusal and its reason;
 *  - for a stored calibration: heading rms/worst over ORIENTATIONS random
 *    orientations (full correction: driver's calibbias/calibscale and the
 *    residual matrix) and |B| rms against the site's field, the fit given
 *    that field (magn-calibrate --earth-field, with a WMM error of up to
 *    0.5 %).
 * Targets (issue 39): every undisturbed run learned within 60 s, heading
 * <= 1 deg rms and <= 3 deg worst, |B| <= 1 uT rms; under a disturbance
 * a stored calibration never has a heading error above 5 deg (a refusal
 * is fine). The exit status is 1 when a target is missed.
 *
 * The boards whose soft iron turns the field (asymmetric, issue 39
 * point 3) are judged without the turn and through the stored
 * calibration's path: the daemon's conversion of the fit with the turn
 * it trusts (the identity when its uncertainty is above 0.3 deg),
 * <record>.magn written and read, the driver's and userspace's parts.
 *
 * --slow: the slowest speed alone (1 deg per sample, the model's
 * tumble at 20 deg/s) over SLOW_SEEDS seeds the other modes do not use,
 * every board and Earth field of the full sweep, undisturbed and under
 * each of the full sweep's magnets, so that what is claimed at that speed
 * is not carried by a few runs: it prints the runs that miss a target and
 * a summary, and exits 1 when one does.
 *
 * Usage: bench_magcal_sweep [--full|--turned|--slow]   (default: a short
 * sweep; --turned: the turned boards alone)
 */

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "magcal.h"
#include "common/magn_cal.h"
#include "magn/magn_session.h"
#include "magsim.h"
#include "common/record.h"

/* when the sweep's calibrations are "stored" (any time: it is not judged) */
#define STORED_AT		1795392000

/* magn-calibrate's session (daemon/src/magn/magn_session.h) */
#define INTERVAL_S		(MAGN_SESSION_INTERVAL_NS / 1e9)
#define TIMEOUT_S		120.0
#define NOISE_NT		400
#define WMM_ERROR		0.005

#define TARGET_LEARN_S		60.0
#define TARGET_HEAD_RMS		1.0
#define TARGET_HEAD_WORST	3.0
#define TARGET_MAG_RMS		1.0
#define TARGET_DISTURBED_WORST	5.0

/*
 * --slow: seeds per board and Earth field (and per board and magnet),
 * numbered from SLOW_SEED_CLEAN and SLOW_SEED_MAGNET (the other modes'
 * are below 400)
 */
#define SLOW_SEEDS		5
#define SLOW_SEED_CLEAN		1000
#define SLOW_SEED_MAGNET	3000
#define SLOW_SPEED		1.0
#define SLOW_BOARDS		8

/* An Earth field: magnitude, inclination (dip) */
struct earth {
	double f_ut;
	double incl_deg;
};

/* A slow magnet: peak, duration, start within the session */
struct magnet {
	double peak_ut;
	double dur_s;
	double start_s;
};

static const double speeds_short[] = { 1, 3, 6 };
static const double speeds_full[] = { 1, 2, 3, 4, 6 };
static const struct earth earths_short[] = { { 22, -30 }, { 48, 60 },
					     { 68, 75 } };
/* the Earth's field is 22..67 uT (the WMM's extremes) */
static const struct earth earths_full[] = { { 22, 0 }, { 25, -30 },
					    { 48, 60 }, { 58, -70 },
					    { 65, 75 }, { 67, -72 } };
static const struct magnet magnets_short[] = {
	{ 18, 38, 5 }, { 8, 30, 20 }, { 30, 60, 0 }, { 5, 10, 30 },
	{ 12, 20, 40 },
};
static const struct magnet magnets_full[] = {
	{ 5, 10, 0 }, { 5, 60, 10 }, { 8, 30, 20 }, { 12, 20, 40 },
	{ 15, 45, 5 }, { 18, 38, 5 }, { 18, 38, 30 }, { 22, 15, 50 },
	{ 25, 60, 0 }, { 30, 10, 15 }, { 30, 60, 0 }, { 10, 50, 45 },
};

struct run {
	bool stored;
	enum magcal_status status;
	double learn_s;
	double coverage;
	double drift_ut;
	double dip_drift_deg;
	double turn_deg;
	bool turn_trusted;
	struct score sc;
	struct score turned;	/* with the turn applied (turned boards) */
};

/*
 * Turn the soft iron of @u by @deg about the axis (1, 2, 3): S' = Rot S,
 * an asymmetric soft iron (a magnitude fit cannot see Rot)
 */
static void rotate_soft(struct as9888_unit *u, double deg)
{
	double a[3] = { 1 / sqrt(14), 2 / sqrt(14), 3 / sqrt(14) };
	double c = cos(deg * DEG), sn = sin(deg * DEG), rot[3][3], out[9];
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			rot[i][j] = (i == j) * c + (1 - c) * a[i] * a[j] +
				    sn * (i == j ? 0 :
					  ((j - i + 3) % 3 == 1 ? -1 : 1) *
					  a[3 - i - j]);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (k = 0, out[i * 3 + j] = 0; k < 3; k++)
				out[i * 3 + j] += rot[i][k] *
						  u->soft_ppm[k * 3 + j];
	for (i = 0; i < 9; i++)
		u->soft_ppm[i] = (s32)lrint(out[i]);
}

/*
 * The stack through the stored calibration's path: the daemon's
 * conversion of the fit (magn_session_to_record(), the turn with it when
 * trusted), <record>.magn written and read back, split between the
 * driver and userspace as restore and libas9888magn split it
 */
static bool stack_stored(const struct chip *c, const struct magcal_result *r,
			 struct stack *st)
{
	char text[RECORD_MAX_SIZE], err[256];
	struct magn_driver_cal d;
	struct calib_magn m, back;
	struct magn_user_cal u;
	uint64_t chip;
	int len, i;

	if (magn_session_to_record(r, STORED_AT, &m, err, sizeof(err)))
		return false;
	len = record_magn_format(&m, c->ee.raw, STORED_AT, text, sizeof(text));
	if (len < 0 || record_magn_parse(text, (size_t)len, &back, &chip, err,
					 sizeof(err)) ||
	    magn_driver_split(&back, c->ee.raw, &d))
		return false;
	magn_user_split(&back, c->ee.raw, &d, &u);
	for (i = 0; i < 3; i++) {
		st->calibbias[i] = d.calibbias[i];
		st->calibscale[i] = d.calibscale_micro[i] / 1e6;
		st->offset[i] = u.offset_ut[i];
		memcpy(st->resid[i], u.residual[i], sizeof(st->resid[i]));
	}
	return true;
}

/* Board @b: hard iron 20..400 uT, soft iron 0.9..1.1, cross terms +-0.06 */
static void board_unit(unsigned int b, const struct earth *e, unsigned int seed,
		       struct as9888_unit *u)
{
	double h[3], n = 0, mag;
	int i, j;

	rng_state = 0xb0a4d000ULL + b;
	as9888_unit_default(u);
	u->seed = 4000 + b * 31 + seed;
	u->world = AS9888_UNIT_WORLD_EARTH | AS9888_UNIT_WORLD_ORIENTATION;
	u->earth_nt = (s32)lrint(e->f_ut * 1000);
	u->incl_mdeg = (s32)lrint(e->incl_deg * 1000);
	u->decl_mdeg = (s32)between(-15000, 15000);
	mag = between(20, 400);
	for (i = 0; i < 3; i++) {
		h[i] = between(-1, 1);
		n += h[i] * h[i];
	}
	for (i = 0; i < 3; i++) {
		u->hard_nt[i] = (s32)lrint(h[i] / sqrt(n) * mag * 1000);
		u->soft_ppm[i * 4] = (s32)between(900000, 1100000);
		for (j = i + 1; j < 3; j++)
			u->soft_ppm[i * 3 + j] = u->soft_ppm[j * 3 + i] =
				(s32)between(-60000, 60000);
	}
	u->magn_noise_nt = NOISE_NT;
	for (i = 0; i < 4; i++)
		u->orientation[i] = (s32)between(-1000000, 1000000);
	rng_state = 0x7a1d0000ULL + b * 977 + seed;
}

/*
 * One sample as magn_source_read() takes it from the chip: the mean of
 * MAGN_SOURCE_AVERAGE measurements. The device turns by @speed once per
 * sample (the sweep's speeds are degrees per 50 ms) and its measurements
 * are taken in that orientation: the model turns its device per
 * measurement and wanders its axis per turn, so five turns of a fifth
 * would be a more erratic motion than the one the speeds always meant.
 * A hand turning 1-6 degrees in 50 ms moves less than 5 degrees during
 * the measurements: their mean is off the sphere by under 0.05 uT.
 */
static void sample(struct chip *c, struct as9888_model *m, double speed,
		   double mut[3], double accel[3])
{
	struct reading rd;
	int k, i;

	memset(mut, 0, 3 * sizeof(*mut));
	memset(accel, 0, 3 * sizeof(*accel));
	for (k = 0; k < MAGN_SOURCE_AVERAGE; k++) {
		as9888_model_set_tumble(m, as9888_sim_now_ns(c->sim),
					k ? 0 : (u32)lrint(speed * 1000));
		measure(c, &rd);
		for (i = 0; i < 3; i++) {
			mut[i] += rd.count[i] * c->scale_ut[i] /
				  MAGN_SOURCE_AVERAGE;
			accel[i] += rd.accel_g[i] / MAGN_SOURCE_AVERAGE;
		}
	}
}

/*
 * A user who follows magn-calibrate's progress lines ("to cover more:
 * turn it about the chip's X axis, +Y toward +Z"): at each line the user
 * takes the named axis, as a hand does, not quite (a random vector of up
 * to a third in each component added: 15 degrees off in the mean, 25 in
 * one of twenty, 35 at most), and turns about it by the
 * speed every sample until the next line. Before the first line (no
 * estimate of the centre yet) the model's own tumble turns the device.
 */
static void follow_hint(const struct magcal_session *s, const double mut[3],
			double user_axis[3], bool *have)
{
	struct magn_hint h;
	double v[3], n = 0;
	int i;

	if (magn_session_hint(s, mut, NULL, &h))
		return;
	for (i = 0; i < 3; i++) {
		v[i] = (i == h.axis ? h.sign : 0) + between(-1, 1) / 3;
		n += v[i] * v[i];
	}
	for (i = 0; i < 3; i++)
		user_axis[i] = v[i] / sqrt(n);
	*have = true;
}

/* The device turned by @deg about @axis of its own (sensor) frame */
static void turn_device(struct chip *c, struct as9888_model *m,
			const double axis[3], double deg)
{
	s32 q[AS9888_QUAT_LEN], dq[AS9888_QUAT_LEN], a[3];
	int i;

	for (i = 0; i < 3; i++)
		a[i] = (s32)lrint(axis[i] * AS9888_Q30_ONE);
	as9888_model_orientation(m, q);
	as9888_mw_quat_axis_angle(a, (s64)lrint(deg * 1000), dq);
	/* sensor to world: a turn in the sensor's frame multiplies on the right */
	as9888_mw_quat_mul(q, dq, q);
	as9888_model_set_orientation(m, as9888_sim_now_ns(c->sim), q);
}

/* One session as magn-calibrate runs it, then the judgment */
static void run_one(unsigned int b, const struct earth *e, double speed,
		    const struct magnet *mag, unsigned int seed, double rot_deg,
		    bool guided, struct run *out)
{
	unsigned int kept = 0, next_solve = MAGN_SESSION_SOLVE_EVERY, n, i;
	unsigned int total = (unsigned int)(TIMEOUT_S / INTERVAL_S);
	unsigned int dist_at = mag ? (unsigned int)(mag->start_s / INTERVAL_S) :
				     0;
	static const s32 none[3];
	struct magcal_config cfg;
	struct magcal_session *s;
	struct magcal_result r;
	struct as9888_model *m;
	struct as9888_unit u;
	unsigned int next_progress = MAGN_SESSION_PROGRESS_EVERY;
	unsigned int next_line = MAGN_SESSION_PROGRESS_SAMPLES;
	double mut[3], accel[3], user_axis[3] = { 1, 0, 0 };
	bool have_axis = false;
	struct stack st;
	struct chip c;

	memset(out, 0, sizeof(*out));
	board_unit(b, e, seed, &u);
	if (rot_deg)
		rotate_soft(&u, rot_deg);
	magcal_config_default(&cfg);
	cfg.max_drift_ut = MAGN_SESSION_MAX_DRIFT_UT;
	cfg.reference_field_ut = e->f_ut * (1 + between(-WMM_ERROR, WMM_ERROR));
	s = magcal_new(&cfg);
	chip_open(&c, &u);
	m = as9888_sim_model(c.sim);
	r.status = MAGCAL_NO_COVERAGE;
	for (n = 0; n < total; n++) {
		if (mag && n == dist_at) {
			s32 d[3];
			double v[3], norm = 0;

			for (i = 0; i < 3; i++) {
				v[i] = between(-1, 1);
				norm += v[i] * v[i];
			}
			for (i = 0; i < 3; i++)
				d[i] = (s32)lrint(v[i] / sqrt(norm) *
						  mag->peak_ut * 1000);
			as9888_model_set_disturbance(m,
				as9888_sim_now_ns(c.sim), d,
				(u32)lrint(mag->dur_s / INTERVAL_S *
					   MAGN_SOURCE_AVERAGE));
		}
		if (guided && have_axis)
			turn_device(&c, m, user_axis, speed);
		sample(&c, m, guided && have_axis ? 0 : speed, mut, accel);
		if (magcal_add(s, mut, accel) > 0)
			kept++;
		/* magn_session_run()'s progress lines */
		if (kept >= next_progress || n + 1 >= next_line) {
			next_progress = kept + MAGN_SESSION_PROGRESS_EVERY;
			next_line = n + 1 + MAGN_SESSION_PROGRESS_SAMPLES;
			if (guided)
				follow_hint(s, mut, user_axis, &have_axis);
		}
		if (kept >= next_solve) {
			next_solve = kept + MAGN_SESSION_SOLVE_EVERY;
			magcal_solve(s, &r);
			if (magn_session_done(&r, true))
				break;
		}
	}
	if (n == total)
		magcal_solve(s, &r);
	as9888_model_set_tumble(m, as9888_sim_now_ns(c.sim), 0);
	/* the magnet gone: the calibration is judged, not the magnet */
	as9888_model_set_disturbance(m, as9888_sim_now_ns(c.sim), none, 0);
	out->status = r.status;
	out->coverage = r.coverage;
	out->drift_ut = r.drift_ut;
	out->dip_drift_deg = r.dip_drift_deg;
	out->turn_deg = r.turn_deg;
	out->turn_trusted = r.turn_trusted;
	out->learn_s = (n + (n < total)) * INTERVAL_S;
	out->stored = magn_session_done(&r, true) && stack_from(&c, &r, &st);
	if (out->stored) {
		struct score sc[CORR_COUNT];

		judge(&c, &u, &st, &st, sc);
		out->sc = sc[CORR_SITE];
		if (rot_deg) {
			struct stack tst;

			if (stack_stored(&c, &r, &tst)) {
				judge(&c, &u, &tst, &tst, sc);
				out->turned = sc[CORR_SITE];
			} else {
				out->turned.head_rms = out->turned.head_worst = INFINITY;
			}
		}
	}
	as9888_sim_free(c.sim);
	magcal_free(s);
}

static void print_run(unsigned int b, const struct earth *e, double speed,
		      const struct magnet *mag, const struct run *r,
		      const char *verdict)
{
	char dist[40] = "none";

	if (mag)
		snprintf(dist, sizeof(dist), "%2.0fuT/%2.0fs@%2.0fs",
			 mag->peak_ut, mag->dur_s, mag->start_s);
	printf("%5u %4.0f/%+3.0f %5.1f %-14s %-32s %6.1f %5.2f %5.2f %5.2f",
	       b, e->f_ut, e->incl_deg, speed, dist,
	       r->stored ? "stored" :
	       r->status == MAGCAL_OK ? "too little covered" :
	       magcal_status_str(r->status),
	       r->learn_s, r->coverage, r->drift_ut, r->dip_drift_deg);
	if (r->stored)
		printf(" %6.2f %6.2f %6.2f", r->sc.head_rms, r->sc.head_worst,
		       r->sc.mag_abs_rms);
	else
		printf(" %6s %6s %6s", "-", "-", "-");
	printf("  %s\n", verdict);
	fflush(stdout);
}

/*
 * The soft iron turned by 1.5 and 3 deg on each of @boards boards in the
 * field @e at 4 deg per sample: without the turn, and as stored
 * (the turn with it when trusted)
 */
static void turned_report(unsigned int boards, const struct earth *e)
{
	unsigned int b, k;
	struct run r;

	for (k = 0; k < 2; k++) {
		double rot = k ? 3 : 1.5, sq = 0, worst = 0, turn = 0;
		double tsq = 0, tworst = 0;
		unsigned int cnt = 0, trusted = 0;

		for (b = 0; b < boards; b++) {
			run_one(b, e, 4, NULL, 300 + b, rot, false, &r);
			if (!r.stored)
				continue;
			cnt++;
			turn += r.turn_deg;
			trusted += r.turn_trusted;
			sq += r.sc.head_rms * r.sc.head_rms;
			worst = fmax(worst, r.sc.head_worst);
			tsq += r.turned.head_rms * r.turned.head_rms;
			tworst = fmax(tworst, r.turned.head_worst);
		}
		printf("soft iron turned by %.1f deg: %u/%u boards learned, turn seen %.2f deg (mean), trusted on %u; without it: heading rms %.2f deg, worst %.2f deg; as stored (<record>.magn with the turn): heading rms %.2f deg, worst %.2f deg\n",
		       rot, cnt, boards, cnt ? turn / cnt : 0, trusted,
		       cnt ? sqrt(sq / cnt) : 0, worst,
		       cnt ? sqrt(tsq / cnt) : 0, tworst);
	}
}

/* Is @r an undisturbed run that meets every target? */
static bool clean_ok(const struct run *r)
{
	return r->stored && r->learn_s <= TARGET_LEARN_S &&
	       r->sc.head_rms <= TARGET_HEAD_RMS &&
	       r->sc.head_worst <= TARGET_HEAD_WORST &&
	       r->sc.mag_abs_rms <= TARGET_MAG_RMS;
}

/*
 * --slow: SLOW_SPEED over SLOW_SEEDS new seeds, undisturbed and under
 * every magnet of the full sweep; the stored runs that miss a target
 * printed (the learning time is summed up). Returns the number of runs
 * that missed a target.
 */
static unsigned int slow_report(bool guided)
{
	unsigned int sd, b, j, k, runs = 0, stored = 0, fast = 0, good = 0;
	unsigned int inexact = 0, mruns = 0, mstored = 0, wrong = 0;
	double longest = 0, rms_max = 0, worst = 0, mworst = 0;
	struct run r;

	printf("compass calibration sweep (slow%s): %.0f deg per sample; %u boards x %zu Earth fields x %u seeds undisturbed, x %zu magnets x %u seeds; the stored runs that miss a target:\n",
	       guided ? ", the user following the progress lines" : "",
	       SLOW_SPEED, SLOW_BOARDS, ARRAY_SIZE(earths_full), SLOW_SEEDS,
	       ARRAY_SIZE(magnets_full), SLOW_SEEDS);
	for (sd = 0; sd < SLOW_SEEDS; sd++) {
		for (b = 0; b < SLOW_BOARDS; b++) {
			for (j = 0; j < ARRAY_SIZE(earths_full); j++) {
				const struct earth *e = &earths_full[j];
				bool exact;

				run_one(b, e, SLOW_SPEED, NULL,
					SLOW_SEED_CLEAN + sd * 64 + j, 0,
					guided, &r);
				runs++;
				good += clean_ok(&r);
				if (!r.stored)
					continue;
				stored++;
				fast += r.learn_s <= TARGET_LEARN_S;
				longest = fmax(longest, r.learn_s);
				rms_max = fmax(rms_max, r.sc.head_rms);
				worst = fmax(worst, r.sc.head_worst);
				exact = r.sc.head_rms <= TARGET_HEAD_RMS &&
					r.sc.head_worst <= TARGET_HEAD_WORST &&
					r.sc.mag_abs_rms <= TARGET_MAG_RMS;
				inexact += !exact;
				if (!exact)
					print_run(b, e, SLOW_SPEED, NULL, &r,
						  "MISSED");
			}
			for (k = 0; k < ARRAY_SIZE(magnets_full); k++) {
				const struct earth *e = &earths_full[
					(b + k + sd) % ARRAY_SIZE(earths_full)];
				bool bad;

				run_one(b, e, SLOW_SPEED, &magnets_full[k],
					SLOW_SEED_MAGNET + sd * 64 + k, 0,
					guided, &r);
				mruns++;
				if (!r.stored)
					continue;
				mstored++;
				mworst = fmax(mworst, r.sc.head_worst);
				bad = r.sc.head_worst > TARGET_DISTURBED_WORST;
				wrong += bad;
				if (bad)
					print_run(b, e, SLOW_SPEED,
						  &magnets_full[k], &r,
						  "WRONG STORED");
			}
		}
	}
	printf("undisturbed: %u runs, %u stored, %u of them within %.0f s (longest %.1f s); %u stored beyond heading %.0f deg rms / %.0f deg worst or |B| %.0f uT rms (largest run rms %.2f deg, worst %.2f deg)\n",
	       runs, stored, fast, TARGET_LEARN_S, longest, inexact,
	       TARGET_HEAD_RMS, TARGET_HEAD_WORST, TARGET_MAG_RMS, rms_max,
	       worst);
	printf("disturbed: %u runs, %u refused, %u stored, of them %u with a heading error above %.0f deg (worst stored %.2f deg)\n",
	       mruns, mruns - mstored, mstored, wrong, TARGET_DISTURBED_WORST,
	       mworst);
	printf("targets: %s (%u undisturbed runs missed, %u wrong stored)\n",
	       runs - good || wrong ? "MISSED" : "met", runs - good, wrong);
	return runs - good + wrong;
}

int main(int argc, char **argv)
{
	bool full = argc > 1 && !strcmp(argv[1], "--full");
	const double *speeds = full ? speeds_full : speeds_short;
	const struct earth *earths = full ? earths_full : earths_short;
	const struct magnet *magnets = full ? magnets_full : magnets_short;
	unsigned int nspeed = full ? ARRAY_SIZE(speeds_full) :
				     ARRAY_SIZE(speeds_short);
	unsigned int nearth = full ? ARRAY_SIZE(earths_full) :
				     ARRAY_SIZE(earths_short);
	unsigned int nmag = full ? ARRAY_SIZE(magnets_full) :
				   ARRAY_SIZE(magnets_short);
	unsigned int boards = full ? 8 : 3;
	unsigned int b, k, j, clean = 0, learned = 0, disturbed = 0;
	unsigned int refused = 0, wrong = 0, missed = 0;
	double max_learn = 0, head_sq = 0, head_rms_max = 0, head_worst = 0;
	double mag_rms_max = 0, disturbed_worst = 0;
	/* per speed: runs, learned, learned within the target, longest */
	unsigned int sp_runs[8] = { 0 }, sp_learned[8] = { 0 }, sp_fast[8] = { 0 };
	double sp_longest[8] = { 0 };
	struct run r;

	if (argc == 2 && !strcmp(argv[1], "--turned")) {
		turned_report(8, &earths_full[2]);
		return 0;
	}
	if (argc == 2 && !strcmp(argv[1], "--slow"))
		return slow_report(false) ? 1 : 0;
	if (argc == 2 && !strcmp(argv[1], "--guided"))
		return slow_report(true) ? 1 : 0;
	if (argc > 2 || (argc == 2 && !full)) {
		fprintf(stderr, "usage: %s [--full|--turned|--slow|--guided]\n", argv[0]);
		return 2;
	}
	printf("compass calibration sweep (%s): %u boards x %u speeds x %u Earth fields, then %u slow magnets per board; noise %.1f uT rms a measurement, %d measurements a sample; speed = deg the device turns per sample, %.0f samples a second\n",
	       full ? "full" : "short", boards, nspeed, nearth, nmag,
	       NOISE_NT / 1000.0, MAGN_SOURCE_AVERAGE, 1 / INTERVAL_S);
	printf("%5s %8s %5s %-14s %-32s %6s %5s %5s %5s %6s %6s %6s\n",
	       "board", "F/dip", "speed", "disturbance", "result", "time",
	       "cover", "drift", "ddip", "hd rms", "worst", "|B|rms");
	for (b = 0; b < boards; b++) {
		for (k = 0; k < nspeed; k++) {
			for (j = 0; j < nearth; j++) {
				bool ok;

				run_one(b, &earths[j], speeds[k], NULL, k * 16 + j,
					0, false, &r);
				clean++;
				sp_runs[k]++;
				sp_learned[k] += r.stored;
				sp_fast[k] += r.stored &&
					      r.learn_s <= TARGET_LEARN_S;
				if (r.stored)
					sp_longest[k] = fmax(sp_longest[k],
							     r.learn_s);
				ok = clean_ok(&r);
				missed += !ok;
				if (r.stored) {
					learned++;
					max_learn = fmax(max_learn, r.learn_s);
					head_sq += r.sc.head_rms * r.sc.head_rms;
					head_rms_max = fmax(head_rms_max,
							    r.sc.head_rms);
					head_worst = fmax(head_worst,
							  r.sc.head_worst);
					mag_rms_max = fmax(mag_rms_max,
							   r.sc.mag_abs_rms);
				}
				print_run(b, &earths[j], speeds[k], NULL, &r,
					  ok ? "" : "MISSED");
			}
		}
		for (k = 0; k < nmag; k++) {
			const struct earth *e = &earths[(b + k) % nearth];
			double speed = speeds[(b * 7 + k) % nspeed];
			bool bad;

			run_one(b, e, speed, &magnets[k], 100 + k, 0, false, &r);
			disturbed++;
			refused += !r.stored;
			bad = r.stored &&
			      r.sc.head_worst > TARGET_DISTURBED_WORST;
			wrong += bad;
			if (r.stored)
				disturbed_worst = fmax(disturbed_worst,
						       r.sc.head_worst);
			print_run(b, e, speed, &magnets[k], &r,
				  bad ? "WRONG STORED" : "");
		}
	}
	printf("undisturbed: %u/%u learned, longest %.1f s (target <= %.0f s); heading rms over runs %.2f deg, largest run rms %.2f deg (<= %.1f), worst %.2f deg (<= %.1f); |B| rms with the site's field, largest %.2f uT (<= %.1f)\n",
	       learned, clean, max_learn, TARGET_LEARN_S,
	       learned ? sqrt(head_sq / learned) : 0, head_rms_max,
	       TARGET_HEAD_RMS, head_worst, TARGET_HEAD_WORST, mag_rms_max,
	       TARGET_MAG_RMS);
	for (k = 0; k < nspeed; k++)
		printf("speed %.0f deg/sample: %u/%u learned, %u within %.0f s, longest %.1f s\n",
		       speeds[k], sp_learned[k], sp_runs[k], sp_fast[k],
		       TARGET_LEARN_S, sp_longest[k]);
	printf("disturbed: %u runs, %u refused, %u stored, of them %u with a heading error above %.0f deg (worst stored %.2f deg)\n",
	       disturbed, refused, disturbed - refused, wrong,
	       TARGET_DISTURBED_WORST, disturbed_worst);
	/* not a target: what the fit cannot learn (issue 39, point 3) */
	if (full)
		turned_report(boards, &earths_full[2]);
	printf("targets: %s (%u undisturbed runs missed, %u wrong stored)\n",
	       missed || wrong ? "MISSED" : "met", missed, wrong);
	return missed || wrong ? 1 : 0;
}
