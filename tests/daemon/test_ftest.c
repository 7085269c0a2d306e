// SPDX-License-Identifier: GPL-2.0
/*
 * The factory test engine against the simulated chip (virtual time): a
 * healthy unit passes in every posture; every fault of datasheet section 8
 * and every limit of the application note fails at its own step.
 */
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
#include "chip/transport.h"

/*
 * A transport between the engine and the simulator that changes one value
 * of one accelerometer sample as it is read: the first sample of the
 * first level run (@after_dac 0) or of the first run after the DAC write of
 * 3-24 (@after_dac 1). ST1 comes in a read of its own, TMPS, EMPT and ST2
 * in one burst (chip_read_sample()). The simulated chip is not touched.
 */
enum tamper_field { TAMPER_NONE, TAMPER_ST1, TAMPER_TMPS_PLUS, TAMPER_EMPT, TAMPER_ST2 };

struct tamper {
	struct transport t;	/* first: the engine's handle */
	struct transport *in;
	enum tamper_field field;
	uint8_t val;		/* the value, or for TMPS the codes added */
	int after_dac;
	int dac_writes;
	bool done;
};

static int tamper_read(struct transport *t, uint8_t reg, uint8_t *buf, size_t len)
{
	struct tamper *tp = (struct tamper *)t;
	int ret = transport_read(tp->in, reg, buf, len);

	if (ret || tp->done || tp->dac_writes != tp->after_dac)
		return ret;
	if (tp->field == TAMPER_ST1 && reg == AS9888_REG_ST1 && len == 1) {
		buf[0] = tp->val;
		tp->done = true;
	} else if (tp->field != TAMPER_ST1 && reg == AS9888_REG_TMPS &&
		   len == AS9888_REG_ST2 - AS9888_REG_TMPS + 1) {
		if (tp->field == TAMPER_TMPS_PLUS)
			buf[0] += tp->val;
		else if (tp->field == TAMPER_EMPT)
			buf[AS9888_REG_EMPT - AS9888_REG_TMPS] = tp->val;
		else
			buf[AS9888_REG_ST2 - AS9888_REG_TMPS] = tp->val;
		tp->done = true;
	}

	return 0;
}

static int tamper_write(struct transport *t, uint8_t reg, const uint8_t *buf,
			size_t len)
{
	struct tamper *tp = (struct tamper *)t;

	if (reg == AS9888_REG_AXDA)
		tp->dac_writes++;
	return transport_write(tp->in, reg, buf, len);
}

static int tamper_set_rstn(struct transport *t, bool level)
{
	struct transport *in = ((struct tamper *)t)->in;

	return in->ops->set_rstn(in, level);
}

static bool tamper_pin_monitored(struct transport *t, enum transport_pin pin)
{
	struct transport *in = ((struct tamper *)t)->in;

	return in->ops->pin_monitored(in, pin);
}

static int tamper_wait_pin(struct transport *t, enum transport_pin pin,
			   uint64_t timeout_ns)
{
	struct transport *in = ((struct tamper *)t)->in;

	return in->ops->wait_pin(in, pin, timeout_ns);
}

static uint64_t tamper_now_ns(struct transport *t)
{
	return transport_now_ns(((struct tamper *)t)->in);
}

static void tamper_sleep_ns(struct transport *t, uint64_t ns)
{
	struct transport *in = ((struct tamper *)t)->in;

	in->ops->sleep_ns(in, ns);
}

static void tamper_destroy(struct transport *t)
{
	transport_destroy(((struct tamper *)t)->in);
}

static const struct transport_ops tamper_ops = {
	.read = tamper_read,
	.write = tamper_write,
	.set_rstn = tamper_set_rstn,
	.pin_monitored = tamper_pin_monitored,
	.wait_pin = tamper_wait_pin,
	.now_ns = tamper_now_ns,
	.sleep_ns = tamper_sleep_ns,
	.destroy = tamper_destroy,
};

/* @tp (may be NULL): the change to make between the engine and the chip */
static void run_unit_tampered(const char *text, const struct ftest_opts *opts,
			      struct tamper *tp, struct ftest_result *res)
{
	struct as9888_unit_error uerr;
	struct as9888_unit unit;
	struct ftest_opts o;
	struct transport *t;
	char err[256];

	as9888_unit_default(&unit);
	if (as9888_unit_parse(text, strlen(text), &unit, &uerr))
		fail_msg("unit line %u: %s", uerr.line, uerr.msg);
	assert_int_equal(backend_sim_open_unit(&unit, true, &t, err, sizeof(err)), 0);
	if (tp) {
		tp->t.ops = &tamper_ops;
		tp->t.name = t->name;
		tp->in = t;
		t = &tp->t;
	}
	if (opts) {
		o = *opts;
	} else {
		ftest_opts_default(&o);
	}
	/*
	 * A tamper counts the engine's bursts in the note's order (every
	 * register of a sample read before the next MS write); the datasheet
	 * order reads ST1 alone and the rest while the next sample converts.
	 * test_sequence.c holds the two orders to the same judgments.
	 */
	if (tp)
		o.note_order = true;
	memset(res, 0, sizeof(*res));
	ftest_run(t, &o, res);
	if (tp)
		assert_true(tp->done);	/* the change was made */
	transport_destroy(t);
}

static void run_unit(const char *text, const struct ftest_opts *opts,
		     struct ftest_result *res)
{
	run_unit_tampered(text, opts, NULL, res);
}

/* The first failed judgment is at @step; with @name_part, its name says so */
static void expect_failure_tampered(const char *text, const struct ftest_opts *o,
				    struct tamper *tp, const char *step,
				    const char *name_part)
{
	struct ftest_result res;
	const struct judgment *j;

	run_unit_tampered(text, o, tp, &res);
	j = report_first_failure(&res.report);
	if (!j) {
		report_print_text(stderr, &res.report);
		fail_msg("unit passed, expected a failure at %s", step);
	}
	if (strcmp(j->step, step) ||
	    (name_part && !strstr(j->name, name_part) && !strstr(j->measured, name_part))) {
		report_print_text(stderr, &res.report);
		fail_msg("failed at %s (%s: %s), expected %s (%s)", j->step,
			 j->name, j->measured, step, name_part ? name_part : "");
	}
	assert_false(res.have_calibration);
	ftest_result_free(&res);
}

static void expect_failure(const char *text, const struct ftest_opts *o,
			   const char *step, const char *name_part)
{
	expect_failure_tampered(text, o, NULL, step, name_part);
}

static void expect_pass_tampered(const char *text, const struct ftest_opts *o,
				 struct tamper *tp, struct ftest_result *res)
{
	run_unit_tampered(text, o, tp, res);
	if (report_first_failure(&res->report)) {
		report_print_text(stderr, &res->report);
		fail_msg("unit failed");
	}
	assert_true(res->have_calibration);
}

static void expect_pass(const char *text, const struct ftest_opts *o,
			struct ftest_result *res)
{
	expect_pass_tampered(text, o, NULL, res);
}

static void healthy_unit_passes(void **state)
{
	struct ftest_result res;
	int axis;

	expect_pass("", NULL, &res);
	/* steps of every phase were judged */
	assert_true(res.report.count > 40);
	assert_string_equal(res.report.items[0].step, "1-4");
	assert_string_equal(res.report.items[res.report.count - 1].step, "3-47");
	/* offset 0 at 25 degC with the factory DAC: DACopt = EEPROM DAC */
	assert_memory_equal(res.rec.dac, ((u8[]){ 0x0d, 0x8f, 0x8c }), 3);
	assert_memory_equal(res.rec.gravity, ((s8[]){ 0, 0, -1 }), 3);
	assert_int_equal(res.rec.t_level_mdegc, 25000);
	assert_int_equal(res.rec.samples, 10);
	for (axis = 0; axis < 3; axis++)
		assert_true(res.offset_q16[axis] > -2 * 65536 &&
			    res.offset_q16[axis] < 2 * 65536);
	/* vertical axis reads St(25 degC) of Z: 259 * (1 - 0.00165625 * 1.25) */
	assert_true(res.rec.level_mean_q16[2] > 257 * 65536 &&
		    res.rec.level_mean_q16[2] < 260 * 65536);
	ftest_result_free(&res);
}

/* The DAC optimisation cancels a real offset: Ot_L after the DAC change
 * is within half a DAC step (plus noise) of zero */
static void offset_is_cancelled(void **state)
{
	struct ftest_result res;
	int axis;

	expect_pass("offset = 110 -80 60\nnoise = 0.5\n", NULL, &res);
	for (axis = 0; axis < 3; axis++) {
		s32 half_step = as9888_dac_step_q16(res.ee.axis[axis].ga) / 2;

		assert_true(res.offset_q16[axis] <= half_step + 65536 &&
			    res.offset_q16[axis] >= -half_step - 65536);
	}
	/* X: gain 28, 110 LSB -> rint(44 / 2048 * 110) = 2 codes: lin -13 - 2 */
	assert_int_equal(as9888_dac2lin(0x1c, res.rec.dac[0]), -15);
	ftest_result_free(&res);
}

static void every_posture_passes(void **state)
{
	static const struct {
		const char *up;
		s8 g[3];
	} postures[] = {
		{ "up = 0 0 1\n", { 0, 0, -1 } },
		{ "up = 0 0 -1\n", { 0, 0, 1 } },
		{ "up = 1 0 0\n", { -1, 0, 0 } },
		{ "up = -1 0 0\n", { 1, 0, 0 } },
		{ "up = 0 1 0\n", { 0, -1, 0 } },
		{ "up = 0 -1 0\n", { 0, 1, 0 } },
	};
	unsigned int i;

	for (i = 0; i < sizeof(postures) / sizeof(postures[0]); i++) {
		struct ftest_result res;
		struct ftest_opts o;

		expect_pass(postures[i].up, NULL, &res);
		assert_memory_equal(res.rec.gravity, postures[i].g, 3);
		ftest_result_free(&res);

		/* and with the posture given instead of detected */
		ftest_opts_default(&o);
		o.gravity_given = true;
		memcpy(o.gravity, postures[i].g, 3);
		expect_pass(postures[i].up, &o, &res);
		ftest_result_free(&res);
	}
}

static void wrong_gravity_given_fails(void **state)
{
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.gravity_given = true;
	memcpy(o.gravity, ((s8[]){ 0, 0, 1 }), 3);
	expect_failure("", &o, "3-23", "other way");
	memcpy(o.gravity, ((s8[]){ -1, 0, 0 }), 3);
	expect_failure("", &o, "3-23", "not level");
}

/* D8: 35 degrees of tilt: a horizontal axis reads more than St/2 */
static void tilted_unit_fails(void **state)
{
	expect_failure("up = 0.574 0 0.819\n", NULL, "3-23", "horizontal axis");
	/* 20 degrees is still level in the sense of D8 */
	struct ftest_result res;

	expect_pass("up = 0.342 0 0.940\n", NULL, &res);
	ftest_result_free(&res);
}

/* D6: the optimum lies beyond the DAC range */
static void offset_beyond_dac_range(void **state)
{
	/*
	 * X factory DAC at +67 codes; a -100 LSB offset needs two more
	 * (the offset must stay below St/2 for the unit to count as level)
	 */
	expect_failure("eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c c3 8f 8c 04 65 c3 88 50\n"
		       "offset = -100 0 0\n", NULL, "3-23", "beyond DAC range");
}

static void noisy_unit_fails_fluctuation(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	expect_failure("noise = 12\nseed = 7\n", NULL, "3-20", "fluctuation");
	/* the same unit passes a looser, environment-specific limit */
	ftest_opts_default(&o);
	o.fluctuation = 200;
	expect_pass("noise = 12\nseed = 7\n", &o, &res);
	ftest_result_free(&res);
}

/* Note 2: N from the pilot noise; too noisy fails */
static void permissible_error(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.fluctuation = 4095;
	o.permissible_error_q16 = 65536;	/* 1 LSB */
	expect_pass("noise = 4\nseed = 3\n", &o, &res);
	/* sigma about 4: N about 16, never fewer than 10 */
	assert_true(res.rec.samples >= 10 && res.rec.samples <= 40);
	ftest_result_free(&res);

	o.permissible_error_q16 = 65536 / 100;	/* 0.01 LSB */
	expect_failure("noise = 4\nseed = 3\n", &o, "3-3", "too noisy");
}

static void lpf_run(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.lpf = true;
	expect_pass("", &o, &res);
	assert_true(res.rec.lpf);
	ftest_result_free(&res);
}

/* Note 4b: a temperature that moves during averaging is waited out, then fails */
static void drifting_temperature(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	/* slow drift: passes, t_L is the measured one */
	expect_pass("temperature = 30\ntemperature_drift = 0.5\n", NULL, &res);
	assert_true(res.rec.t_level_mdegc >= 29375 && res.rec.t_level_mdegc <= 31250);
	ftest_result_free(&res);

	ftest_opts_default(&o);
	o.stable_timeout_ms = 300;
	expect_failure("temperature = -20\ntemperature_drift = 100\n", &o, "3-5",
		       "temperature stable");
}

static void temperature_out_of_spec(void **state)
{
	/* 90 degC: TMPS below 0x28 */
	expect_failure("temperature = 90\n", NULL, "3-5", "TMPS");
}

/* Every fault of datasheet section 8 at its step */
static void faults(void **state)
{
	expect_failure("fault = wia\n", NULL, "1-4", "WIA");
	expect_failure("fault = rstn_open\n", NULL, "1-2", "RSTN");
	expect_failure("fault = eeprom_blank\n", NULL, "1-27", "blank");
	expect_failure("fault = int1_open\n", NULL, "2-4", "INT1");
	expect_failure("fault = int2_open\n", NULL, "2-4", "INT2");
	expect_failure("fault = no_drdy\n", NULL, "2-4", "INT1");
	expect_failure("fault = hofl\n", NULL, "2-7", "overflow");
	expect_failure("fault = selftest_weak\n", NULL, "2-21", "self-test Z");
	expect_failure("fault = saturate_z\n", NULL, "3-12", "Z below 2047");
	expect_failure("fault = stuck_x\n", NULL, "3-23", "not level");
}

static void nak_fault_reports_bus_error(void **state)
{
	struct ftest_result res;
	const struct judgment *j;

	run_unit("fault = nak\n", NULL, &res);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_non_null(strstr(j->measured, "bus transfer failed"));
	assert_false(res.have_calibration);
	ftest_result_free(&res);
}

/* Without INT1, DRDY polling carries the test (keep-going after 2-4) */
static void keep_going_polls_drdy(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.keep_going = true;
	run_unit("fault = int1_open\n", &o, &res);
	assert_string_equal(report_first_failure(&res.report)->step, "2-4");
	assert_true(res.have_calibration);
	assert_string_equal(res.report.items[res.report.count - 1].step, "3-47");
	ftest_result_free(&res);
}

/* no_drdy with keep-going: the measurement timeout ends the test */
static void no_drdy_times_out(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;
	size_t i;
	bool timed_out = false;

	ftest_opts_default(&o);
	o.keep_going = true;
	run_unit("fault = no_drdy\n", &o, &res);
	for (i = 0; i < res.report.count; i++)
		if (strstr(res.report.items[i].name, "measurement completes"))
			timed_out = res.report.items[i].result == JUDGMENT_FAIL;
	assert_true(timed_out);
	assert_false(res.have_calibration);
	ftest_result_free(&res);
}

/*
 * A bad status register on the first sample of a level run fails its step
 * (the first offending sample has index 0), in both level runs
 */
static void bad_status_on_first_sample(void **state)
{
	static const struct {
		enum tamper_field field;
		uint8_t val;
		const char *step[2];
		const char *name;
	} cases[] = {
		{ TAMPER_ST1, AS9888_ST1_DRDY_MSK | AS9888_ST1_DOR_MSK,
		  { "3-4", "3-29" }, "sample 0: 0x03" },
		{ TAMPER_ST1, 0x00, { "3-4", "3-29" }, "sample 0: 0x00" },
		{ TAMPER_EMPT, 0x01, { "3-6", "3-31" }, "sample 0: 0x01" },
		{ TAMPER_ST2, 0x00, { "3-13", "3-38" }, "sample 0: 0x00" },
		{ TAMPER_ST2, AS9888_ST2_HST_MSK | AS9888_ST2_HOFL_MSK,
		  { "3-13", "3-38" }, "sample 0: 0x" },
	};
	unsigned int i;
	int pass;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		for (pass = 0; pass < 2; pass++) {
			struct tamper tp = {
				.field = cases[i].field, .val = cases[i].val,
				.after_dac = pass,
			};

			expect_failure_tampered("", NULL, &tp, cases[i].step[pass],
						cases[i].name);
		}
	}
}

/*
 * Note 4b: a TMPS spread of 1 code during averaging is stable, 2 codes are
 * not (no time to wait it out: the run is judged as taken); with time to
 * wait, the unstable run is taken again, and the new run passes
 */
static void tmps_spread_limit(void **state)
{
	static const char *const step[2] = { "3-5", "3-30" };
	struct ftest_result res;
	struct ftest_opts o;
	int pass;

	ftest_opts_default(&o);
	o.stable_timeout_ms = 0;
	for (pass = 0; pass < 2; pass++) {
		struct tamper one = { .field = TAMPER_TMPS_PLUS, .val = 1, .after_dac = pass };
		struct tamper two = { .field = TAMPER_TMPS_PLUS, .val = 2, .after_dac = pass };

		expect_pass_tampered("", &o, &one, &res);
		ftest_result_free(&res);
		expect_failure_tampered("", &o, &two, step[pass], "temperature stable");
	}

	ftest_opts_default(&o);
	for (pass = 0; pass < 2; pass++) {
		struct tamper two = { .field = TAMPER_TMPS_PLUS, .val = 2, .after_dac = pass };

		expect_pass_tampered("", &o, &two, &res);
		ftest_result_free(&res);
	}
}

/* Note 2: N = AS9888_SAMPLES_MAX is allowed, one more is not */
static void samples_max_boundary(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.permissible_error_q16 = 4 * 65536;	/* a noiseless unit: N is the floor */
	o.samples = AS9888_SAMPLES_MAX;
	expect_pass("", &o, &res);
	assert_int_equal(res.rec.samples, AS9888_SAMPLES_MAX);
	ftest_result_free(&res);

	o.samples = AS9888_SAMPLES_MAX + 1;
	expect_failure("", &o, "3-3", "N 4097 (environment too noisy)");
}

/* D8 through the engine: the vertical axis reads less than St/2 */
static void not_vertical_fails(void **state)
{
	/* Z reads St(25 degC) - 150 = about 108 LSB, below St/2 = 129 */
	expect_failure("offset = 0 0 -150\n", NULL, "3-23",
		       "vertical axis reads less than St/2");
}

/* D8 through the engine: a given gravity that is not one axis, +-1 */
static void invalid_gravity_given_fails(void **state)
{
	static const s8 bad[][3] = { { 0, 0, 0 }, { 1, 0, -1 }, { 0, 0, -2 } };
	struct ftest_opts o;
	unsigned int i;

	ftest_opts_default(&o);
	o.gravity_given = true;
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		memcpy(o.gravity, bad[i], 3);
		expect_failure("", &o, "3-23", "invalid gravity direction");
	}
}

/* The same seed gives the same calibration */
static void deterministic(void **state)
{
	struct ftest_result a, b;

	expect_pass("noise = 3\nseed = 99\n", NULL, &a);
	expect_pass("noise = 3\nseed = 99\n", NULL, &b);
	assert_memory_equal(a.rec.level_mean_q16, b.rec.level_mean_q16,
			    sizeof(a.rec.level_mean_q16));
	ftest_result_free(&a);
	ftest_result_free(&b);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(healthy_unit_passes),
		cmocka_unit_test(offset_is_cancelled),
		cmocka_unit_test(every_posture_passes),
		cmocka_unit_test(wrong_gravity_given_fails),
		cmocka_unit_test(tilted_unit_fails),
		cmocka_unit_test(offset_beyond_dac_range),
		cmocka_unit_test(noisy_unit_fails_fluctuation),
		cmocka_unit_test(permissible_error),
		cmocka_unit_test(lpf_run),
		cmocka_unit_test(drifting_temperature),
		cmocka_unit_test(temperature_out_of_spec),
		cmocka_unit_test(faults),
		cmocka_unit_test(nak_fault_reports_bus_error),
		cmocka_unit_test(keep_going_polls_drdy),
		cmocka_unit_test(no_drdy_times_out),
		cmocka_unit_test(deterministic),
		cmocka_unit_test(bad_status_on_first_sample),
		cmocka_unit_test(tmps_spread_limit),
		cmocka_unit_test(samples_max_boundary),
		cmocka_unit_test(not_vertical_fails),
		cmocka_unit_test(invalid_gravity_given_fails),
	};

	return cmocka_run_group_tests_name("ftest", tests, NULL, NULL);
}
