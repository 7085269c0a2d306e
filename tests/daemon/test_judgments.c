// SPDX-License-Identifier: GPL-2.0
/*
 * Every judgment of the application note made to fail: the simulated chip
 * behind a tampering transport that changes what chosen register reads
 * return (a status bit, a data value in one sample, a read-back), and the
 * factory test must fail at exactly the judgment's step (a judgment that
 * an earlier one always precedes, like the maximum after the per-sample
 * range, with --keep-going: it must be among the failures). With
 * AS9888_REPORT_DIR set, each run's JSON report is written there (for
 * tests/daemon/report.sh, which validates them against the schema).
 *
 * Sample bursts (the reads of one sample, ST1 first, ST2 last) are
 * numbered from 0: burst 0 is the magnetometer measurement of step 2,
 * burst 1 the self-test (ST1..HZH, then ST2), bursts 2..11 the first level
 * run (N = 10), bursts 12..21 the second (ST1, then TMPS..ST2: the
 * magnetometer is off in step 3).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "as9888_regs.h"
#include "as9888_unit.h"
#include "chip/backend_sim.h"
#include "ftest/ftest.h"
#include "ftest/ftest_print.h"

#define ANY	-1
#define PASS1	2
#define PASS2	12

/*
 * Replace the byte at @reg with @value (and @reg + 1 with @value_hi when
 * @wide) in sample bursts @first..@last, or, for @burst == false, in the
 * @nth read (from 1) that covers @reg.
 */
struct tamper_rule {
	uint8_t reg;
	int value;
	bool wide;
	bool burst;
	int first;
	int last;
	int nth;
};

struct tamper {
	struct transport base;
	struct transport *inner;
	const struct tamper_rule *rule;
	int bursts;
	int covering_reads;
	/* what the test sent: INT1EN writes, reads of magnetometer data, the last write */
	int int1en_writes;
	int mag_reads;
	int accel_reads;
	int transfers;
	uint8_t last_reg, last_val;
};

static struct tamper *to_tamper(struct transport *t)
{
	return (struct tamper *)t;
}

static int tamper_read(struct transport *t, uint8_t reg, uint8_t *buf,
		       size_t len)
{
	struct tamper *x = to_tamper(t);
	const struct tamper_rule *r = x->rule;
	bool hit = false;
	int ret;

	ret = transport_read(x->inner, reg, buf, len);
	if (ret)
		return ret;
	x->transfers++;
	if (reg <= AS9888_REG_HXL + 5 && reg + len > AS9888_REG_HXL)
		x->mag_reads++;
	if (reg <= AS9888_REG_A1XL + 5 && reg + len > AS9888_REG_A1XL)
		x->accel_reads++;

	if (r->reg >= reg && r->reg < reg + len) {
		if (r->burst)
			hit = reg >= AS9888_REG_ST1 && reg <= AS9888_REG_ST2 &&
			      x->bursts >= r->first &&
			      (r->last == ANY || x->bursts <= r->last);
		else
			hit = ++x->covering_reads == r->nth;
	}
	/* a sample's last read, the one of ST2, ends its burst */
	if (reg <= AS9888_REG_ST2 && reg + len > AS9888_REG_ST2)
		x->bursts++;
	if (hit) {
		buf[r->reg - reg] = (uint8_t)r->value;
		if (r->wide)
			buf[r->reg - reg + 1] = (uint8_t)((unsigned int)r->value >> 8);
	}

	return 0;
}

static int tamper_write(struct transport *t, uint8_t reg, const uint8_t *buf,
			size_t len)
{
	struct tamper *x = to_tamper(t);

	x->transfers++;
	x->int1en_writes += reg == AS9888_REG_INT1EN;
	x->last_reg = reg;
	x->last_val = buf[len - 1];
	return transport_write(x->inner, reg, buf, len);
}

static int tamper_set_rstn(struct transport *t, bool level)
{
	struct transport *in = to_tamper(t)->inner;

	return in->ops->set_rstn(in, level);
}

static bool tamper_monitored(struct transport *t, enum transport_pin pin)
{
	struct transport *in = to_tamper(t)->inner;

	return in->ops->pin_monitored(in, pin);
}

static int tamper_wait_pin(struct transport *t, enum transport_pin pin,
			   uint64_t timeout_ns)
{
	struct transport *in = to_tamper(t)->inner;

	return in->ops->wait_pin(in, pin, timeout_ns);
}

static uint64_t tamper_now(struct transport *t)
{
	return transport_now_ns(to_tamper(t)->inner);
}

static void tamper_sleep(struct transport *t, uint64_t ns)
{
	transport_sleep_ns(to_tamper(t)->inner, ns);
}

static void tamper_destroy(struct transport *t)
{
	transport_destroy(to_tamper(t)->inner);
}

static const struct transport_ops tamper_ops = {
	.read = tamper_read,
	.write = tamper_write,
	.set_rstn = tamper_set_rstn,
	.pin_monitored = tamper_monitored,
	.wait_pin = tamper_wait_pin,
	.now_ns = tamper_now,
	.sleep_ns = tamper_sleep,
	.destroy = tamper_destroy,
};

struct judgment_case {
	const char *step;
	const char *name_part;
	struct tamper_rule rule;
};

#define BURST(r, v, f, l)	{ .reg = (r), .value = (v), .burst = true, .first = (f), .last = (l) }
#define BURST16(r, v, f, l)	{ .reg = (r), .value = (v), .wide = true, .burst = true, .first = (f), .last = (l) }
#define NTH(r, v, n)		{ .reg = (r), .value = (v), .nth = (n) }

#define HX	AS9888_REG_HXL
#define HY	(AS9888_REG_HXL + 2)
#define HZ	(AS9888_REG_HXL + 4)
#define AX	AS9888_REG_A1XL
#define AY	(AS9888_REG_A1XL + 2)
#define AZ	(AS9888_REG_A1XL + 4)

static const struct judgment_case cases[] = {
	/* step 1: the trim read-back (D10) */
	{ "1-39", "R/W check", NTH(AS9888_REG_AXGA + 1, 0x00, 1) },
	/* step 2: normal magnetometer measurement */
	{ "2-5", "INT1ST", NTH(AS9888_REG_INT1ST, 0x00, 1) },
	{ "2-6", "ST1", BURST(AS9888_REG_ST1, 0x03, 0, 0) },
	{ "2-7", "magnetometer X", BURST16(HX, 4095, 0, 0) },
	{ "2-7", "magnetometer X", BURST16(HX, -4096, 0, 0) },
	{ "2-9", "magnetometer Y", BURST16(HY, 4095, 0, 0) },
	{ "2-11", "magnetometer Z", BURST16(HZ, -4096, 0, 0) },
	{ "2-13", "ST2", BURST(AS9888_REG_ST2, 0x08, 0, 0) },
	/* self-test: EHC X 0x80 (x1.0), Y 0x85, Z 0x7b */
	{ "2-16", "ST1", BURST(AS9888_REG_ST1, 0x00, 1, 1) },
	{ "2-17", "self-test X", BURST16(HX, 101, 1, 1) },
	{ "2-17", "self-test X", BURST16(HX, -101, 1, 1) },
	{ "2-19", "self-test Y", BURST16(HY, 100, 1, 1) },	/* 102.3 adjusted */
	{ "2-21", "self-test Z", BURST16(HZ, 1030, 1, 1) },	/* 1010.9 adjusted */
	{ "2-21", "self-test Z", BURST16(HZ, 305, 1, 1) },	/* 299.3 adjusted */
	{ "2-23", "ST2", BURST(AS9888_REG_ST2, 0x00 | 0x08, 1, 1) },
	/* step 3, first level run */
	{ "3-4", "ST1", BURST(AS9888_REG_ST1, 0x03, PASS1 + 4, PASS1 + 4) },
	{ "3-5", "TMPS", BURST(AS9888_REG_TMPS, 0xe1, PASS1 + 2, PASS1 + 2) },
	{ "3-5", "TMPS", BURST(AS9888_REG_TMPS, 0x27, PASS1, PASS1) },
	{ "3-6", "EMPT", BURST(AS9888_REG_EMPT, 0x01, PASS1 + 9, PASS1 + 9) },
	{ "3-13", "ST2", BURST(AS9888_REG_ST2, 0x00, PASS1 + 1, PASS1 + 1) },
	{ "3-7", "X above -2048", BURST16(AX, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-8", "X below 2047", BURST16(AX, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-9", "Y above -2048", BURST16(AY, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-10", "Y below 2047", BURST16(AY, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-11", "Z above -2048", BURST16(AZ, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-12", "Z below 2047", BURST16(AZ, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-14", "maximum of X", BURST16(AX, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-15", "maximum of Y", BURST16(AY, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-16", "maximum of Z", BURST16(AZ, 2047, PASS1 + 3, PASS1 + 3) },
	{ "3-17", "minimum of X", BURST16(AX, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-18", "minimum of Y", BURST16(AY, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-19", "minimum of Z", BURST16(AZ, -2048, PASS1 + 5, PASS1 + 5) },
	{ "3-20", "fluctuation of X", BURST16(AX, 16, PASS1 + 6, PASS1 + 6) },
	{ "3-21", "fluctuation of Y", BURST16(AY, -17, PASS1 + 6, PASS1 + 6) },
	{ "3-22", "fluctuation of Z", BURST16(AZ, 280, PASS1 + 6, PASS1 + 6) },
	/* the DAC read-back is the second read covering AXDA */
	{ "3-26", "DAC written", NTH(AS9888_REG_AXDA + 2, 0x80, 2) },
	/* step 3, second level run with DACopt */
	{ "3-29", "ST1", BURST(AS9888_REG_ST1, 0x03, PASS2 + 4, PASS2 + 4) },
	{ "3-30", "TMPS", BURST(AS9888_REG_TMPS, 0xe1, PASS2, PASS2) },
	{ "3-31", "EMPT", BURST(AS9888_REG_EMPT, 0x80, PASS2 + 9, PASS2 + 9) },
	{ "3-38", "ST2", BURST(AS9888_REG_ST2, 0x0a, PASS2 + 1, PASS2 + 1) },
	{ "3-32", "X above -2048", BURST16(AX, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-33", "X below 2047", BURST16(AX, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-34", "Y above -2048", BURST16(AY, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-35", "Y below 2047", BURST16(AY, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-36", "Z above -2048", BURST16(AZ, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-37", "Z below 2047", BURST16(AZ, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-39", "maximum of X", BURST16(AX, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-40", "maximum of Y", BURST16(AY, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-41", "maximum of Z", BURST16(AZ, 2047, PASS2 + 3, PASS2 + 3) },
	{ "3-42", "minimum of X", BURST16(AX, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-43", "minimum of Y", BURST16(AY, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-44", "minimum of Z", BURST16(AZ, -2048, PASS2 + 5, PASS2 + 5) },
	{ "3-45", "fluctuation of X", BURST16(AX, -16, PASS2 + 6, PASS2 + 6) },
	{ "3-46", "fluctuation of Y", BURST16(AY, 17, PASS2 + 6, PASS2 + 6) },
	{ "3-47", "fluctuation of Z", BURST16(AZ, 240, PASS2 + 6, PASS2 + 6) },
};

/* Run the factory test on a noiseless unit behind a tamperer with @rule */
static struct tamper last_run;

static int run_tampered(const struct tamper_rule *rule, bool keep_going,
			struct ftest_result *res)
{
	struct as9888_unit unit;
	struct tamper x = { 0 };
	struct ftest_opts o;
	char err[256];

	as9888_unit_default(&unit);
	unit.noise_mlsb = 0;	/* fluctuation 0 unless tampered */
	assert_int_equal(backend_sim_open_unit(&unit, true, &x.inner, err,
					       sizeof(err)), 0);
	x.base.ops = &tamper_ops;
	x.base.name = "tamper";
	x.rule = rule;
	ftest_opts_default(&o);
	o.keep_going = keep_going;
	/* the burst numbering above is the note's order (test_sequence.c: both agree) */
	o.note_order = true;
	memset(res, 0, sizeof(*res));
	ftest_run(&x.base, &o, res);
	res->backend = "sim";
	transport_destroy(&x.base);
	last_run = x;

	return x.bursts;
}

/*
 * The maxima and minima (3-14..3-19, 3-39..3-44) judge what the per-sample
 * range (3-7..3-12, 3-32..3-37) judged first: they run with keep_going
 */
static bool preceded(const char *step)
{
	int n;

	if (strncmp(step, "3-", 2))
		return false;
	n = atoi(step + 2);

	return (n >= 14 && n <= 19) || (n >= 39 && n <= 44);
}

/* The case's judgment among the failures: the first, or any with keep_going */
static const struct judgment *failed_judgment(const struct judgment_case *c,
					      const struct report *r)
{
	const struct judgment *j;
	size_t i;

	for (i = 0; i < r->count; i++) {
		j = &r->items[i];
		if (j->result != JUDGMENT_FAIL)
			continue;
		if (!strcmp(j->step, c->step) &&
		    (strstr(j->name, c->name_part) || strstr(j->measured, c->name_part)))
			return j;
		if (!preceded(c->step))
			return NULL;
	}

	return NULL;
}

/* With AS9888_REPORT_DIR set, the JSON report as case-N.json there */
static void save_report(unsigned int n, const struct ftest_result *res)
{
	const char *dir = getenv("AS9888_REPORT_DIR");
	char path[4096];
	FILE *f;

	if (!dir)
		return;
	snprintf(path, sizeof(path), "%s/case-%02u.json", dir, n);
	f = fopen(path, "w");
	assert_non_null(f);
	ftest_print_json(f, res, path, false);
	assert_int_equal(fclose(f), 0);
}

static void run_case(unsigned int n, const struct judgment_case *c)
{
	struct ftest_result res;
	const struct judgment *j;

	run_tampered(&c->rule, preceded(c->step), &res);
	save_report(n, &res);
	j = failed_judgment(c, &res.report);
	if (!j) {
		j = report_first_failure(&res.report);
		report_print_text(stderr, &res.report);
		fail_msg("tampering 0x%02x = %d: expected failure at %s (%s), got %s",
			 c->rule.reg, c->rule.value, c->step, c->name_part,
			 j ? j->step : "none");
	}
	/* no calibration from a failed run: with keep_going, none stored */
	assert_true(preceded(c->step) || !res.have_calibration);
	ftest_result_free(&res);
}

static void untampered_unit_passes(void **state)
{
	static const struct tamper_rule none = { .reg = 0x7f, .nth = 1000 };
	struct ftest_result res;
	int bursts = run_tampered(&none, false, &res);

	save_report(99, &res);
	assert_null(report_first_failure(&res.report));
	/* the burst numbering the cases rely on */
	assert_int_equal(bursts, PASS2 + 10);
	/*
	 * No redundant transfer: INT1EN written for the RSTN check and in 2-1
	 * only (not again in 3-1), magnetometer data read in step 2's two
	 * bursts only (step 3 skips its 6 bytes), accelerometer data only in
	 * step 3 (2 x 10 reads, none in step 2), and no MS = 0 at the end
	 * (the last single measurement left the chip in power-down); the
	 * last write is the second level run's last MS = single
	 */
	assert_int_equal(last_run.int1en_writes, 2);
	assert_int_equal(last_run.mag_reads, 2);
	assert_int_equal(last_run.accel_reads, 2 * 10);
	assert_int_equal(last_run.last_reg, AS9888_REG_MS);
	assert_int_equal(last_run.last_val, AS9888_MS_SINGLE);
	print_message("%d bus transfers in a passing run at N = 10\n",
		      last_run.transfers);
	ftest_result_free(&res);
}

static void every_judgment_fails(void **state)
{
	unsigned int i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++)
		run_case(i, &cases[i]);
	print_message("%zu tampered judgments failed at their steps\n",
		      sizeof(cases) / sizeof(cases[0]));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(untampered_unit_passes),
		cmocka_unit_test(every_judgment_fails),
	};

	return cmocka_run_group_tests_name("judgments", tests, NULL, NULL);
}
