// SPDX-License-Identifier: GPL-2.0
/*
 * What E means, measured: the factory test with --permissible-error E on
 * seeded simulated units (virtual time), each stored level mean compared
 * with the model's noise-free value of the same axis, registers and
 * temperature (as9888_model_accel_nlsb()). The default (Note 2's rule) is
 * a one-sigma bound: |error| <= E in at least 68.27 % of axis means.
 * --confidence P promises |error| <= E with probability P per axis. Each
 * claim is checked on the observed fraction with a 3-sigma binomial
 * allowance; the default mode's runs are also held to P = 0.95 and must
 * fail it (the check can fail, and that is the difference between the
 * modes). The report's interval (mean -+ z * the achieved standard
 * error) must cover the true value as often as P says.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "as9888_sim.h"
#include "as9888_unit.h"
#include "chip/backend_sim.h"
#include "ftest/ftest.h"

#define RUNS		300
#define NOISE_LSB	"2"
#define E_LSB		0.5

struct coverage {
	unsigned int means;	/* axis means compared */
	unsigned int within_e;	/* |stored mean - true value| <= E */
	unsigned int in_interval; /* the report's interval holds the true value */
	uint32_t n_min, n_max;	/* N chosen */
};

static void run_seed(unsigned int seed, uint32_t confidence_1e4,
		     struct coverage *c)
{
	struct as9888_unit_error uerr;
	struct as9888_unit unit;
	struct ftest_result res;
	struct ftest_opts o;
	struct as9888_model *m;
	struct transport *t;
	char text[64], err[256];
	int32_t t_mdegc;
	int axis;

	snprintf(text, sizeof(text), "noise = " NOISE_LSB "\nseed = %u\n", seed);
	as9888_unit_default(&unit);
	if (as9888_unit_parse(text, strlen(text), &unit, &uerr))
		fail_msg("unit line %u: %s", uerr.line, uerr.msg);
	assert_int_equal(backend_sim_open_unit(&unit, true, &t, err, sizeof(err)), 0);
	ftest_opts_default(&o);
	o.permissible_error_q16 = (uint32_t)(E_LSB * 65536);
	o.confidence_1e4 = confidence_1e4;
	memset(&res, 0, sizeof(res));
	ftest_run(t, &o, &res);
	if (!res.have_calibration) {
		report_print_text(stderr, &res.report);
		fail_msg("seed %u: no calibration", seed);
	}

	m = as9888_sim_model(backend_sim_get(t));
	t_mdegc = as9888_model_temperature_mdegc(m, transport_now_ns(t));
	for (axis = 0; axis < 3; axis++) {
		/* the registers (DAC) are the stored run's */
		double truth = as9888_model_accel_nlsb(m, axis, t_mdegc) / 1e9;
		double mean = res.rec.level_mean_q16[axis] / 65536.0;
		double half = res.bound_z * res.level_se[axis];

		c->means++;
		c->within_e += fabs(mean - truth) <= E_LSB;
		c->in_interval += fabs(mean - truth) <= half;
	}
	if (!c->n_min || res.rec.samples < c->n_min)
		c->n_min = res.rec.samples;
	if (res.rec.samples > c->n_max)
		c->n_max = res.rec.samples;
	ftest_result_free(&res);
	transport_destroy(t);
}

static void measure(uint32_t confidence_1e4, struct coverage *c)
{
	unsigned int seed;

	memset(c, 0, sizeof(*c));
	for (seed = 1; seed <= RUNS; seed++)
		run_seed(seed, confidence_1e4, c);
}

/* The observed fraction @k of @n holds @p, allowing 3 binomial sigmas */
static bool holds(unsigned int k, unsigned int n, double p)
{
	return (double)k / n >= p - 3 * sqrt(p * (1 - p) / n);
}

static void report(const char *mode, const struct coverage *c)
{
	print_message("%s: N %u..%u, |error| <= E in %u of %u axis means (%.1f %%), "
		      "interval holds the true value in %u (%.1f %%)\n", mode,
		      c->n_min, c->n_max, c->within_e, c->means,
		      100.0 * c->within_e / c->means, c->in_interval,
		      100.0 * c->in_interval / c->means);
}

static void one_sigma_default(void **state)
{
	const double one_sigma = erf(M_SQRT1_2);	/* 0.6827 */
	struct coverage c;

	measure(0, &c);
	report("default (one sigma)", &c);
	assert_true(holds(c.within_e, c.means, one_sigma));
	assert_true(holds(c.in_interval, c.means, one_sigma));
	/* the default's N does not give the strict claim: this check fails */
	assert_false(holds(c.within_e, c.means, 0.95));
}

static void strict_bound(void **state)
{
	static const uint32_t p_1e4[] = { 9500, 9900 };
	unsigned int i;

	for (i = 0; i < sizeof(p_1e4) / sizeof(p_1e4[0]); i++) {
		double p = p_1e4[i] / 1e4;
		struct coverage c;
		char mode[32];

		measure(p_1e4[i], &c);
		snprintf(mode, sizeof(mode), "--confidence %.2f", p);
		report(mode, &c);
		assert_true(holds(c.within_e, c.means, p));
		assert_true(holds(c.in_interval, c.means, p));
	}
}

/* The quantile the N comes from */
static void normal_quantile(void **state)
{
	assert_float_equal(ftest_two_sided_z(0.95), 1.959964, 1e-5);
	assert_float_equal(ftest_two_sided_z(0.99), 2.575829, 1e-5);
	assert_float_equal(ftest_two_sided_z(erf(M_SQRT1_2)), 1.0, 1e-9);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(normal_quantile),
		cmocka_unit_test(one_sigma_default),
		cmocka_unit_test(strict_bound),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
