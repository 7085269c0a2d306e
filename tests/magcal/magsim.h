/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The chip model behind the userspace simulator, as the magnetometer's
 * calibration sees it: a board opened as the driver probes it (its
 * accelerometer level-calibrated as the daemon does), one measurement at a
 * time, the deployed correction (the driver's calibbias and calibscale,
 * userspace's residual matrix) and the judgment of a correction against
 * the model's truth (|B| and the tilt-compensated heading over random
 * orientations). Shared by the accuracy test and the sweep benchmark.
 */
#ifndef MAGSIM_H
#define MAGSIM_H

#include <stdbool.h>
#include <stdint.h>

#include "as9888_calib.h"
#include "as9888_sim.h"
#include "magcal.h"

#define DEG			(M_PI / 180.0)
/* orientations judged, samples averaged in each (a display's smoothing) */
#define ORIENTATIONS		200
#define AVERAGE			16
/* judged orientations keep +Y within this of the horizon */
#define MAX_PITCH_DEG		60.0

/* the tests' random numbers: splitmix64 on this state */
extern uint64_t rng_state;

struct chip {
	struct as9888_sim *sim;
	struct as9888_eeprom ee;
	struct as9888_accel_cal cal;	/* the accelerometer's, level test */
	double scale_ut[3];	/* uT per count: in_magn_scale */
};

struct reading {
	s16 count[3];		/* magnetometer, chip counts */
	s16 raw_accel[3];
	u8 tmps;
	double accel_g[3];	/* compensated as the driver does */
};

/* CORR_SITE: the full correction of the fit given the site's field */

enum correction { CORR_FULL, CORR_SITE, CORR_DRIVER, CORR_NONE, CORR_COUNT };

/* What the driver is given (calibbias, calibscale) and R for userspace */

struct stack {
	int calibbias[3];
	double calibscale[3];
	double resid[3][3];
	double offset[3];	/* e: what whole-LSB calibbias leaves, uT */
};

struct score {
	double mag_rms;		/* vs F * g */
	double mag_abs_rms;	/* vs F */
	double mag_judged;	/* the one of the two corr_judged[] names */
	double head_rms;
	double head_worst;
};

double uniform(void);
double between(double lo, double hi);
void chip_write(struct chip *c, u8 reg, u8 v);
void level_calibrate(struct chip *c);
/* Power on, read the EEPROM, load the trim (the driver's probe) */
void chip_open(struct chip *c, const struct as9888_unit *u);
/* One single measurement: counts, and the accelerometer compensated */
void measure(struct chip *c, struct reading *r);
/* False when the driver cannot take the fit (its ranges) */
bool stack_from(const struct chip *c, const struct magcal_result *r,
		struct stack *st);
/* The field a consumer gets, uT, with correction @k */
void corrected(const struct chip *c, const struct stack *st,
	       enum correction k, const double count[3], double out[3]);
/* A random orientation whose +Y is within MAX_PITCH_DEG of the horizon */
void pick_orientation(s32 q[4]);
/* True heading of +Y for the model's orientation now */
double true_heading(struct as9888_model *m);
double angle_diff(double a, double b);
/*
 * Score the corrections @st (and @site, the fit given the site's field)
 * of board @u against the truth over ORIENTATIONS orientations
 */
void judge(struct chip *c, const struct as9888_unit *u,
	   const struct stack *st, const struct stack *site,
	   struct score sc[CORR_COUNT]);

#endif
