// SPDX-License-Identifier: GPL-2.0
/*
 * The chip model behind the userspace simulator as a magnetometer
 * calibration sees it (magsim.h): shared by the accuracy test and the
 * sweep benchmark.
 */

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "magsim.h"

#define CALIBBIAS_MAX		4096
#define LEVEL_SAMPLES		32

uint64_t rng_state;

/* splitmix64: neighbouring seeds give unrelated sequences */
double uniform(void)
{
	uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	z ^= z >> 31;
	return (z >> 11) * (1.0 / 9007199254740992.0);
}

double between(double lo, double hi)
{
	return lo + (hi - lo) * uniform();
}

void chip_write(struct chip *c, u8 reg, u8 v)
{
	assert_int_equal(as9888_sim_write_reg(c->sim, reg, v), 0);
}

/*
 * The accelerometer's calibration, as the daemon's level test makes it
 * (lib/calib): the model's offsets are given at 25 degC, the EEPROM's
 * reference is t_RT, so the factory state alone leaves some 0.05 g.
 */
void level_calibrate(struct chip *c)
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
void chip_open(struct chip *c, const struct as9888_unit *u)
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

void measure(struct chip *c, struct reading *r)
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

/* False when the driver cannot take the fit (its ranges) */
bool stack_from(const struct chip *c, const struct magcal_result *r,
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
		st->offset[i] = 0;	/* left to R's rounding, as before */
		/* IIO_VAL_INT_PLUS_MICRO */
		st->calibscale[i] = round(diag[i] * 1e6) / 1e6;
	}
	return true;
}

/* The field a consumer gets, uT, with correction @k */
void corrected(const struct chip *c, const struct stack *st,
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
			 st->resid[i][0] * (drv[0] - st->offset[0]) +
			 st->resid[i][1] * (drv[1] - st->offset[1]) +
			 st->resid[i][2] * (drv[2] - st->offset[2]);
}

/* A random orientation whose +Y is within MAX_PITCH_DEG of the horizon */
void pick_orientation(s32 q[4])
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
double true_heading(struct as9888_model *m)
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

double angle_diff(double a, double b)
{
	double d = fmod(a - b, 360);

	if (d > 180)
		d -= 360;
	if (d < -180)
		d += 360;
	return d;
}

void judge(struct chip *c, const struct as9888_unit *u,
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
