// SPDX-License-Identifier: GPL-2.0
/*
 * The datasheet's order against the application note's literal order
 * (--sequence) on the simulated chip, virtual time: every unit gives the
 * same judgments (id, verdict, measured text) and the same record in both;
 * the datasheet's order is the faster; and a stall that lets the next
 * measurement end before a sample's overlapped read is detected by the
 * chip's own ST1 (the samples are taken again, nothing is judged on
 * another measurement's data).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "as9888_regs.h"
#include "as9888_sim.h"
#include "as9888_unit.h"
#include "chip/backend_sim.h"
#include "ftest/ftest.h"

/*
 * A transport that stalls: after the @stall_at-th MS write that starts a
 * measurement (from 1: 1 the magnetometer's, 2 the self-test, 3..12 the
 * first level run at N = 10, 13..22 the second), the next transfer comes
 * @stall_ns late, as a process descheduled
 * between two transfers would
 */
struct stalling {
	struct transport base;
	struct transport *inner;
	int ms_writes;
	int stall_at;
	uint64_t stall_ns;
	bool stall_next;
	uint64_t every_ns;	/* before every transfer: a slow host */
};

static struct stalling *to_st(struct transport *t)
{
	return (struct stalling *)t;
}

static void maybe_stall(struct stalling *s)
{
	transport_sleep_ns(s->inner, s->every_ns);
	if (s->stall_next) {
		s->stall_next = false;
		transport_sleep_ns(s->inner, s->stall_ns);
	}
}

static int st_read(struct transport *t, uint8_t reg, uint8_t *buf, size_t len)
{
	maybe_stall(to_st(t));
	return transport_read(to_st(t)->inner, reg, buf, len);
}

static int st_write(struct transport *t, uint8_t reg, const uint8_t *buf,
		    size_t len)
{
	struct stalling *s = to_st(t);
	int ret;

	maybe_stall(s);
	ret = transport_write(s->inner, reg, buf, len);
	if (!ret && reg == AS9888_REG_MS && len == 1 && (buf[0] == AS9888_MS_SINGLE || buf[0] == AS9888_MS_SELF_TEST) &&
	    ++s->ms_writes == s->stall_at)
		s->stall_next = true;
	return ret;
}

static int st_set_rstn(struct transport *t, bool level)
{
	return to_st(t)->inner->ops->set_rstn(to_st(t)->inner, level);
}

static bool st_pin_monitored(struct transport *t, enum transport_pin pin)
{
	return to_st(t)->inner->ops->pin_monitored(to_st(t)->inner, pin);
}

static int st_wait_pin(struct transport *t, enum transport_pin pin,
		       uint64_t timeout_ns)
{
	return to_st(t)->inner->ops->wait_pin(to_st(t)->inner, pin, timeout_ns);
}

static uint64_t st_now_ns(struct transport *t)
{
	return transport_now_ns(to_st(t)->inner);
}

static void st_sleep_ns(struct transport *t, uint64_t ns)
{
	transport_sleep_ns(to_st(t)->inner, ns);
}

static void st_destroy(struct transport *t)
{
	transport_destroy(to_st(t)->inner);
}

static const struct transport_ops stalling_ops = {
	.read = st_read,
	.write = st_write,
	.set_rstn = st_set_rstn,
	.pin_monitored = st_pin_monitored,
	.wait_pin = st_wait_pin,
	.now_ns = st_now_ns,
	.sleep_ns = st_sleep_ns,
	.destroy = st_destroy,
};

/*
 * Run @text with @o on a simulator, stalling as @stall_at/@stall_ns say,
 * every transfer @every_ns late
 */
static void run_slow(const char *text, const struct ftest_opts *o, int stall_at,
		     uint64_t stall_ns, uint64_t every_ns, struct ftest_result *res)
{
	struct as9888_unit_error uerr;
	struct as9888_unit unit;
	struct stalling st = {
		.base = { .ops = &stalling_ops, .name = "sim" },
		.stall_at = stall_at,
		.stall_ns = stall_ns,
		.every_ns = every_ns,
	};
	char err[256];

	as9888_unit_default(&unit);
	if (as9888_unit_parse(text, strlen(text), &unit, &uerr))
		fail_msg("unit line %u: %s", uerr.line, uerr.msg);
	assert_int_equal(backend_sim_open_unit(&unit, true, &st.inner, err,
					       sizeof(err)), 0);
	memset(res, 0, sizeof(*res));
	ftest_run(&st.base, o, res);
	transport_destroy(&st.base);
}

static void run(const char *text, const struct ftest_opts *o, int stall_at,
		uint64_t stall_ns, struct ftest_result *res)
{
	run_slow(text, o, stall_at, stall_ns, 0, res);
}

static void assert_same_reports(const struct ftest_result *a,
				const struct ftest_result *b, const char *unit)
{
	size_t i;

	if (a->report.count != b->report.count)
		fail_msg("%s: %zu judgments in the datasheet's order, %zu in the note's",
			 unit, a->report.count, b->report.count);
	for (i = 0; i < a->report.count; i++) {
		const struct judgment *x = &a->report.items[i], *y = &b->report.items[i];

		if (strcmp(x->id, y->id) || x->result != y->result ||
		    strcmp(x->measured, y->measured))
			fail_msg("%s: judgment %zu: %s %d \"%s\" vs %s %d \"%s\"", unit,
				 i, x->id, x->result, x->measured, y->id, y->result,
				 y->measured);
	}
	assert_int_equal(a->have_calibration, b->have_calibration);
	if (a->have_calibration)
		assert_memory_equal(&a->rec, &b->rec, sizeof(a->rec));
	assert_memory_equal(a->offset_q16, b->offset_q16, sizeof(a->offset_q16));
}

static const char *const units[] = {
	"",
	"offset = 110 -80 60\nnoise = 0.5\n",
	"noise = 2\nseed = 5\n",
	"up = 1 0 0\nseed = 3\n",
	"up = 0 -1 0\noffset = -30 20 5\n",
	"temperature = 60\nnoise = 1.5\nseed = 9\n",
	"temperature = 90\n",
	"fault = wia\n",
	"fault = rstn_open\n",
	"fault = eeprom_blank\n",
	"fault = int1_open\n",
	"fault = int2_open\n",
	"fault = no_drdy\n",
	"fault = hofl\n",
	"fault = selftest_weak\n",
	"fault = saturate_z\n",
	"fault = stuck_x\n",
	"noise = 12\nseed = 2\n",
	"offset = 900 0 0\n",
};

/*
 * Both orders, with and without keep-going, a pilot and the filter, and
 * the field recalibration (level only)
 */
static void both_orders_agree(void **state)
{
	struct ftest_result a, b;
	unsigned int i, variant;

	for (i = 0; i < sizeof(units) / sizeof(units[0]); i++) {
		for (variant = 0; variant < 8; variant++) {
			struct ftest_opts o;
			char name[160];

			ftest_opts_default(&o);
			o.keep_going = variant & 1;
			if (variant & 2) {
				o.permissible_error_q16 = 65536 / 2;
				o.lpf = true;
			}
			if (variant & 4) {
				/* a product user's recalibration: step 2 skipped */
				o.level_only = true;
				o.user_mode = true;
				o.fluctuation = FTEST_USER_FLUCTUATION;
			}
			snprintf(name, sizeof(name), "unit \"%s\" variant %u", units[i], variant);
			run(units[i], &o, 0, 0, &a);
			o.note_order = true;
			run(units[i], &o, 0, 0, &b);
			assert_same_reports(&a, &b, name);
			assert_int_equal(a.overlap_lost, 0);
			/* a run that passes is never slower in the datasheet's order */
			if (a.have_calibration && a.duration_ns > b.duration_ns)
				fail_msg("%s: %llu ns in the datasheet's order, %llu in the note's",
					 name, (unsigned long long)a.duration_ns,
					 (unsigned long long)b.duration_ns);
			ftest_result_free(&a);
			ftest_result_free(&b);
		}
	}
}

/*
 * N = 16, virtual clock: each of the 30 gaps between two level samples
 * loses the rest of a sample's read (r(9) = 277.5 us) and more comes off
 * steps 1 and 2 (docs/DECISIONS.md)
 */
static void datasheet_order_is_faster(void **state)
{
	struct ftest_result a, b;
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.samples = 16;
	run("seed = 1\n", &o, 0, 0, &a);
	o.note_order = true;
	run("seed = 1\n", &o, 0, 0, &b);
	print_message("N = 16: datasheet order %.3f ms, note order %.3f ms\n",
		      a.duration_ns / 1e6, b.duration_ns / 1e6);
	assert_true(b.duration_ns - a.duration_ns > 30 * 277500ULL);
	ftest_result_free(&a);
	ftest_result_free(&b);
}

/*
 * A stall after the k-th level MS write long enough for that measurement
 * to end before the previous sample's overlapped read: the chip's ST1 in
 * that burst shows it, both measurements are dropped and taken again,
 * and the run passes (without the check the ST1 judgment would fail on
 * the newer measurement's cleared DRDY, or a sample be counted twice).
 */
static void stall_is_detected(void **state)
{
	/* the first sample of a run has no sample before it to lose */
	static const struct { int at; uint32_t lost; } cases[] = {
		{ 3, 0 }, { 4, 2 }, { 8, 2 }, { 12, 2 }, { 13, 0 }, { 14, 2 }, { 22, 2 },
	};
	struct ftest_result res;
	struct ftest_opts o;
	unsigned int i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		ftest_opts_default(&o);
		run("seed = 4\n", &o, cases[i].at, 3000 * 1000ULL, &res);
		if (report_first_failure(&res.report)) {
			report_print_text(stderr, &res.report);
			fail_msg("stall after MS write %d: the run failed", cases[i].at);
		}
		assert_true(res.have_calibration);
		assert_int_equal(res.overlap_lost, cases[i].lost);
		assert_int_equal(res.rec.samples, 10);
		ftest_result_free(&res);
	}
}

/* A stall during the self-test, before the magnetometer sample's read */
static void stall_in_step2(void **state)
{
	struct ftest_result a, b;
	struct ftest_opts o;
	size_t i;

	ftest_opts_default(&o);
	/* MS write 2 starts the self-test: stall past its end */
	run("", &o, 2, 10000 * 1000ULL, &a);
	if (report_first_failure(&a.report)) {
		report_print_text(stderr, &a.report);
		fail_msg("stall in step 2: the run failed");
	}
	assert_int_equal(a.overlap_lost, 2);
	assert_true(a.have_calibration);
	/*
	 * Steps 1 and 2 judged as without a stall (the magnetometer is
	 * noiseless); the level samples differ: the measurement taken again
	 * drew the accelerometer's noise too
	 */
	o.note_order = true;
	run("", &o, 0, 0, &b);
	for (i = 0; i < b.report.count && b.report.items[i].step[0] != '3'; i++) {
		assert_string_equal(a.report.items[i].id, b.report.items[i].id);
		assert_int_equal(a.report.items[i].result, b.report.items[i].result);
		assert_string_equal(a.report.items[i].measured, b.report.items[i].measured);
	}
	assert_string_equal(a.report.items[i].step, "3-4");
	ftest_result_free(&a);
	ftest_result_free(&b);
}

/*
 * fault = nak fails every 50th transfer: the orders make different
 * transfers, so it hits different steps, but both end on a bus failure
 */
static void nak_fails_both(void **state)
{
	struct ftest_result res;
	struct ftest_opts o;
	int order;

	for (order = 0; order < 2; order++) {
		const struct judgment *j;

		ftest_opts_default(&o);
		o.note_order = order;
		run("fault = nak\n", &o, 0, 0, &res);
		j = report_first_failure(&res.report);
		assert_non_null(j);
		assert_non_null(strstr(j->measured, "bus transfer failed"));
		assert_false(res.have_calibration);
		print_message("nak, %s order: fails at %s\n",
			      order ? "the note's" : "the datasheet's", j->id);
		ftest_result_free(&res);
	}
}

/*
 * A slow host (every transfer 800 us late, as in an emulated guest): the
 * self-test's cycle (MS write, 16-byte read) takes 2.1 ms, beyond 3/4 of
 * t_ACC, so the level runs go in the note's order and lose nothing: the
 * same record as the note's order (without the budget every overlapped
 * read would come after the next measurement ended)
 */
static void slow_host_keeps_its_samples(void **state)
{
	struct ftest_result a, b;
	struct ftest_opts o;

	ftest_opts_default(&o);
	run_slow("seed = 6\n", &o, 0, 0, 800 * 1000ULL, &a);
	if (report_first_failure(&a.report)) {
		report_print_text(stderr, &a.report);
		fail_msg("slow host: the run failed");
	}
	assert_int_equal(a.overlap_lost, 0);
	o.note_order = true;
	run("seed = 6\n", &o, 0, 0, &b);
	assert_same_reports(&a, &b, "slow host");
	ftest_result_free(&a);
	ftest_result_free(&b);
}

/*
 * A cycle beyond the budget that still beats the conversion (0.5 ms late
 * after an MS write: the read ends 0.94 ms into the 1.2 ms): the run reads
 * its pending sample and goes on in the note's order, nothing lost, the
 * same record as the note's order (a pending sample left unread would
 * set DOR on the next one and fail 3-4)
 */
static void over_budget_switches(void **state)
{
	static const int at[] = { 4, 8, 12, 14, 20 };
	struct ftest_result a, b;
	struct ftest_opts o;
	unsigned int i;

	ftest_opts_default(&o);
	o.note_order = true;
	run("seed = 7\n", &o, 0, 0, &b);
	for (i = 0; i < sizeof(at) / sizeof(at[0]); i++) {
		o.note_order = false;
		run("seed = 7\n", &o, at[i], 500 * 1000ULL, &a);
		assert_int_equal(a.overlap_lost, 0);
		assert_same_reports(&a, &b, "over budget");
		ftest_result_free(&a);
	}
	ftest_result_free(&b);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(both_orders_agree),
		cmocka_unit_test(datasheet_order_is_faster),
		cmocka_unit_test(stall_is_detected),
		cmocka_unit_test(stall_in_step2),
		cmocka_unit_test(nak_fails_both),
		cmocka_unit_test(slow_host_keeps_its_samples),
		cmocka_unit_test(over_budget_switches),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
