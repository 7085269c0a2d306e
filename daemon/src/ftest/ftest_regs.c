// SPDX-License-Identifier: GPL-2.0
/*
 * The factory test's device when the test owns the chip: its registers
 * behind a transport (the simulator, or i2c-dev and libgpiod), so every
 * step of the application note and every pin check of D11 is made here.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "as9888_regs.h"
#include "ftest/ftest_internal.h"

/**
 * struct regs_dev - the test device of this file
 * @chip:	the chip
 * @overlap:	the datasheet's order (not @o->note_order): the bus works
 *		while the chip waits or converts (docs/DECISIONS.md, "The
 *		datasheet's order")
 * @engine:	the whole test runs, not step 1 alone (ftest_step1())
 * @rstn_due:	the D11 RSTN read-back waits for t_EEP
 * @trims_due:	the D10 read-back of @trim waits for the next conversion
 * @dac_due:	the D2 read-back of @dac waits for the next conversion
 * @int_setup:	step 2-1's INT1EN, INT2EN and SLCT2 are written
 * @slow:	the self-test's cycle did not fit the accelerometer's budget
 *		(cycle_fits()): the level runs start in the note's order
 * @trim:	the trim registers written (REF1..AZDA)
 * @dac:	the DAC values written at 3-24
 */
struct regs_dev {
	struct chip chip;
	bool overlap;
	bool engine;
	bool rstn_due;
	bool trims_due;
	bool dac_due;
	bool int_setup;
	bool slow;
	uint8_t trim[AS9888_TRIM_LEN];
	uint8_t dac[AS9888_AXES];
};

/*
 * The datasheet's order keeps a cycle (an MS write and the overlapped read
 * of the last sample) within 3/4 of an accelerometer conversion. A slower
 * cycle (a slow host: an emulated guest, a loaded machine) turns the rest
 * of the run to the note's order before a stall costs samples.
 */
#define OVERLAP_BUDGET_NUM	3
#define OVERLAP_BUDGET_DEN	4

static struct regs_dev *regs_dev(struct ftest_ctx *x)
{
	return x->dev;
}

static struct chip *regs_chip(struct ftest_ctx *x)
{
	return &regs_dev(x)->chip;
}

/* D11: a written R/W register must read 0x00 after a reset pulse */
static int regs_check_rstn(struct ftest_ctx *x)
{
	uint8_t val;
	int ret;

	ret = transport_read_reg(regs_chip(x)->t, AS9888_REG_INT1EN, &val);
	if (ret)
		return ftest_io_failed(x, "1-2.rstn", "RSTN pin check (D11)", ret);
	ftest_judge(x, "1-2.rstn", "RSTN pin check (D11)", val == 0,
		    "INT1EN reads 0x00 after reset", "INT1EN 0x%02x", val);
	ftest_value(x, val, 0, 0, "code");

	return 0;
}

/* Step 1 and D11's RSTN check */
static int regs_identify(struct ftest_ctx *x)
{
	struct chip *c = regs_chip(x);
	struct transport *t = c->t;
	uint8_t wia;
	int ret;

	ret = chip_reset(c);
	if (ret == -EOPNOTSUPP) {
		ftest_skip(x, "1-2.reset", "reset pulse (RSTN)", "backend has no reset line");
		ret = 0;
	} else if (ret) {
		return ftest_io_failed(x, "1-2.reset", "reset pulse (RSTN)", ret);
	}

	ret = transport_read_reg(t, AS9888_REG_WIA, &wia);
	if (ret)
		return ftest_io_failed(x, "1-4", "device ID (WIA)", ret);
	ftest_judge(x, "1-4", "device ID (WIA)", wia == AS9888_WIA_VAL, "0x48",
		    "0x%02x", wia);
	ftest_value(x, wia, AS9888_WIA_VAL, AS9888_WIA_VAL, "code");
	if (wia != AS9888_WIA_VAL)
		return x->stop ? -ENODEV : 0;

	/* D11: INT1EN written, a reset pulse, INT1EN must read 0x00 */
	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = chip_reset(c);
	if (ret == -EOPNOTSUPP) {
		ftest_skip(x, "1-2.rstn", "RSTN pin check (D11)", "RSTN not controlled");
		return 0;
	}
	if (ret)
		return ftest_io_failed(x, "1-2.rstn", "RSTN pin check (D11)", ret);
	/* the datasheet's order reads INT1EN back during t_EEP */
	if (regs_dev(x)->overlap) {
		regs_dev(x)->rstn_due = true;
		return 0;
	}

	return regs_check_rstn(x);
}

/*
 * Step 2-1 (DR1EN, and DR2EN so that INT2 can be checked too, D11; MEN):
 * in the datasheet's order during t_EEP, INT1EN and INT2EN in one write
 */
static int regs_int_setup(struct ftest_ctx *x)
{
	static const uint8_t inten[] = { AS9888_INTEN_DR_MSK, AS9888_INTEN_DR_MSK };
	struct regs_dev *d = regs_dev(x);
	struct transport *t = d->chip.t;
	int ret;

	if (d->overlap) {
		ret = transport_write(t, AS9888_REG_INT1EN, inten, sizeof(inten));
	} else {
		ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
		if (!ret)
			ret = transport_write_reg(t, AS9888_REG_INT2EN,
						  AS9888_INTEN_DR_MSK);
	}
	d->chip.int1_dr = !ret;
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_SLCT2, AS9888_SLCT2_MEN_MSK);
	if (ret)
		return ftest_io_failed(x, "2-1", "interrupt and MEN set-up", ret);
	d->int_setup = true;

	return 0;
}

static int regs_eeprom(struct ftest_ctx *x)
{
	struct regs_dev *d = regs_dev(x);
	struct chip *c = &d->chip;
	uint8_t raw[AS9888_EEPROM_LEN];
	uint64_t ready, now;
	int ret;

	ret = chip_set_mode(c, AS9888_MS_EEPROM);
	if (ret)
		return ftest_io_failed(x, "1-5", "EEPROM access mode", ret);
	ready = transport_now_ns(c->t) + AS9888_T_EEP_US * NS_PER_US;
	/* t_EEP restricts the EEPROM only: the other registers work meanwhile */
	if (d->rstn_due) {
		d->rstn_due = false;
		ret = regs_check_rstn(x);
		if (ret || x->stop)
			return ret;
	}
	if (d->overlap && d->engine && !x->o->level_only) {
		ret = regs_int_setup(x);
		if (ret)
			return ret;
	}
	now = transport_now_ns(c->t);
	if (now < ready)
		transport_sleep_ns(c->t, ready - now);
	ret = transport_read(c->t, AS9888_REG_EEPROM, raw, sizeof(raw));
	if (ret)
		return ftest_io_failed(x, "1-7", "EEPROM read", ret);

	return ftest_check_eeprom(x, raw);
}

/* Steps 1-28..1-39 and the read-back check of D10 */
static int regs_check_trims(struct ftest_ctx *x)
{
	const uint8_t *trim = regs_dev(x)->trim;
	uint8_t back[AS9888_TRIM_LEN];
	int i, ret;

	ret = transport_read(regs_chip(x)->t, AS9888_REG_REF1, back, sizeof(back));
	if (ret)
		return ftest_io_failed(x, "1-39", "register R/W check (D10)", ret);

	for (i = 0; i < AS9888_TRIM_LEN; i++)
		if (back[i] != trim[i])
			break;
	if (i < AS9888_TRIM_LEN)
		ftest_judge(x, "1-39", "register R/W check (D10)", false,
			    "read-back equals written",
			    "register 0x%02x wrote 0x%02x read 0x%02x",
			    AS9888_REG_REF1 + i, trim[i], back[i]);
	else
		ftest_judge(x, "1-39", "register R/W check (D10)", true,
			    "read-back equals written", "10 trim registers match");
	FTEST_BOOL(x, i == AS9888_TRIM_LEN);

	return 0;
}

static int regs_trims(struct ftest_ctx *x)
{
	const struct as9888_eeprom *ee = &x->res->ee;
	struct regs_dev *d = regs_dev(x);
	struct chip *c = &d->chip;
	struct transport *t = c->t;
	uint8_t *trim = d->trim;
	int axis, ret;

	ret = chip_set_mode(c, AS9888_MS_POWER_DOWN);
	if (ret)
		return ftest_io_failed(x, "1-28", "power-down mode", ret);
	/*
	 * 1-29: the note waits t_PD before the trims; the datasheet restricts
	 * only the entry into a mode, and 0x30..0x39 to power-down, which the
	 * MS write entered
	 */
	if (!d->overlap)
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
	ret = transport_write(t, AS9888_REG_REF1, trim, AS9888_TRIM_LEN);
	if (ret)
		return ftest_io_failed(x, "1-30", "trim load", ret);
	memcpy(x->dac, &trim[AS9888_REG_AXDA - AS9888_REG_REF1], AS9888_AXES);
	/* the datasheet's order reads them back while the chip converts */
	if (d->overlap && d->engine) {
		d->trims_due = true;
		return 0;
	}

	return regs_check_trims(x);
}

static int regs_step1(struct ftest_ctx *x)
{
	int ret;

	ret = regs_identify(x);
	if (!ret && !x->stop)
		ret = regs_eeprom(x);
	if (!ret && !x->stop)
		ret = regs_trims(x);

	return ret;
}

static int regs_check_dac(struct ftest_ctx *x)
{
	const uint8_t *dac = regs_dev(x)->dac;
	uint8_t back[AS9888_AXES];
	int ret;

	ret = transport_read(regs_chip(x)->t, AS9888_REG_AXDA, back, AS9888_AXES);
	if (ret)
		return ftest_io_failed(x, "3-26", "DAC read-back", ret);
	memcpy(x->dac, back, AS9888_AXES);
	ftest_judge(x, "3-26", "DAC written (3-24..3-26, D2)",
		    !memcmp(back, dac, AS9888_AXES), "read-back equals DACopt",
		    "0x%02x 0x%02x 0x%02x", back[0], back[1], back[2]);
	FTEST_BOOL(x, !memcmp(back, dac, AS9888_AXES));

	return 0;
}

/*
 * The project's own read-backs that the datasheet's order makes while the
 * chip converts (reading changes nothing); judged before anything of the
 * measurement, so the report's order is the note's
 */
static int regs_overlap_checks(struct ftest_ctx *x)
{
	struct regs_dev *d = regs_dev(x);
	int ret = 0;

	if (d->trims_due) {
		d->trims_due = false;
		ret = regs_check_trims(x);
		if (ret || x->stop)
			return ret;
	}
	if (d->dac_due) {
		d->dac_due = false;
		ret = regs_check_dac(x);
	}

	return ret;
}

/* Start a measurement, then make the checks that wait for one */
static int begin(struct ftest_ctx *x, uint8_t ms, bool men, const char *step)
{
	int ret;

	ret = chip_start(regs_chip(x), ms, chip_measure_time_us(men, x->o->lpf));
	if (ret)
		return ftest_io_failed(x, step, "measurement", ret);

	return regs_overlap_checks(x);
}

/*
 * Wait for the measurement begin() started. Reports the pin checks (D11)
 * with @check_pins; with INT1 dead and keep_going, the rest of the test
 * polls DRDY.
 */
static int end(struct ftest_ctx *x, bool men, const char *step,
	       bool check_pins)
{
	struct chip *c = regs_chip(x);
	struct transport *t = c->t;
	uint64_t us = chip_measure_time_us(men, x->o->lpf);
	bool int1 = c->use_int1;
	char id[JUDGMENT_ID_LEN];
	enum chip_wait how;
	int ret;

	ret = chip_wait(c, &how);
	if (ret)
		return ftest_io_failed(x, step, "measurement", ret);

	snprintf(id, sizeof(id), "%s.int1", step);
	if (check_pins && int1) {
		ftest_judge(x, id, "INT1 pin check (D11)", how == CHIP_WAIT_INT1,
			    "rises within the measurement time + 5 ms",
			    how == CHIP_WAIT_INT1 ? "rose" : "stayed low");
		FTEST_BOOL(x, how == CHIP_WAIT_INT1);
	} else if (check_pins) {
		ftest_skip(x, id, "INT1 pin check (D11)", "INT1 not monitored");
	}
	snprintf(id, sizeof(id), "%s.int2", step);

	if (check_pins && t->ops->pin_monitored(t, TRANSPORT_INT2)) {
		/* INT2 is driven at the same instant as INT1 */
		ret = how == CHIP_WAIT_TIMEOUT ? 0 :
		      t->ops->wait_pin(t, TRANSPORT_INT2, 0);
		if (ret < 0)
			return ftest_io_failed(x, id, "INT2 pin check (D11)", ret);
		ftest_judge(x, id, "INT2 pin check (D11)", ret > 0,
			    "rises within the measurement time + 5 ms",
			    ret > 0 ? "rose" : "stayed low");
		FTEST_BOOL(x, ret > 0);
	} else if (check_pins) {
		ftest_skip(x, id, "INT2 pin check (D11)", "INT2 not monitored");
	}

	if (how == CHIP_WAIT_TIMEOUT) {
		snprintf(id, sizeof(id), "%s.drdy", step);
		ftest_judge(x, id, "measurement completes", false,
			    "DRDY within the measurement time + 5 ms",
			    "no data ready after %llu us",
			    (unsigned long long)us + 5000);
		x->stop = true;
		return -ETIMEDOUT;
	}
	if (int1 && how == CHIP_WAIT_DRDY)
		c->use_int1 = false;

	return 0;
}

/* A measurement in the note's order: start, wait, read the whole sample */
static int measure(struct ftest_ctx *x, uint8_t ms, bool men,
		   const char *step, bool check_pins, struct chip_sample *s)
{
	int ret;

	ret = begin(x, ms, men, step);
	if (!ret && !x->stop)
		ret = end(x, men, step, check_pins);
	if (ret || x->stop)
		return ret;
	ret = chip_read_sample(regs_chip(x), men, s);
	if (ret)
		return ftest_io_failed(x, step, "sample read", ret);

	return 0;
}

/*
 * An overlapped read found the next measurement ended: its data were read
 * as the last sample's, and ST2 marked them read (clearing DRDY). Both
 * measurements are lost; the chip is in power-down since at most now.
 */
static void overlap_lost(struct ftest_ctx *x)
{
	struct chip *c = regs_chip(x);

	c->pd_since_ns = transport_now_ns(c->t);
	c->powered_down = true;
	x->res->overlap_lost += 2;
}

static int read_st1(struct ftest_ctx *x, const char *step, uint8_t *st1)
{
	int ret;

	ret = transport_read_reg(regs_chip(x)->t, AS9888_REG_ST1, st1);

	return ret ? ftest_io_failed(x, step, "sample read", ret) : 0;
}

/* Whether the cycle that started at @t0 fits the overlap budget */
static bool cycle_fits(struct ftest_ctx *x, uint64_t t0)
{
	uint64_t budget = chip_measure_time_us(false, x->o->lpf) * NS_PER_US *
			  OVERLAP_BUDGET_NUM / OVERLAP_BUDGET_DEN;

	return transport_now_ns(regs_chip(x)->t) - t0 <= budget;
}

/* 2-5..2-13 after the first magnetometer measurement */
static void judge_magnetometer(struct ftest_ctx *x, const struct chip_sample *s)
{
	static const char *const ovf_step[] = { "2-7", "2-9", "2-11" };
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		char name[32];

		snprintf(name, sizeof(name), "magnetometer %c no overflow",
			 ftest_axis_name[axis]);
		ftest_judge(x, ovf_step[axis], name,
			    !as9888_mag_overflow(s->mag[axis]), "-4096 < H < 4095",
			    "%d", s->mag[axis]);
		ftest_value(x, s->mag[axis], -4095, 4094, "LSB");
		if (x->stop)
			return;
	}
	ftest_judge(x, "2-13", "ST2 normal end", s->st2 == 0, "0x00", "0x%02x",
		    s->st2);
	ftest_value(x, s->st2, 0, 0, "code");
}

/* 2-16..2-23 after the self-test */
static void judge_selftest(struct ftest_ctx *x, const struct chip_sample *s)
{
	const struct as9888_eeprom *ee = &x->res->ee;
	int axis;

	ftest_judge(x, "2-16", "ST1 data ready (self-test)",
		    s->st1 == AS9888_ST1_DRDY_MSK, "0x01", "0x%02x", s->st1);
	ftest_value(x, s->st1, AS9888_ST1_DRDY_MSK, AS9888_ST1_DRDY_MSK, "code");
	if (x->stop)
		return;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		uint8_t ehc = ee->axis[axis].ehc;
		char note[24];

		snprintf(note, sizeof(note), " (raw %d)", s->mag[axis]);
		if (!ftest_judge_selftest_axis(x, axis,
					       as9888_selftest_ok(axis, s->mag[axis], ehc),
					       as9888_mag_adjust_q8(s->mag[axis], ehc),
					       note) && x->stop)
			return;
	}
	ftest_judge(x, "2-23", "ST2 normal end (self-test)", s->st2 == 0, "0x00",
		    "0x%02x", s->st2);
	ftest_value(x, s->st2, 0, 0, "code");
}

/*
 * The datasheet's order of step 2: the magnetometer sample is read (but
 * for INT1ST and ST1) while the self-test converts. A stall that lets the
 * self-test end first loses that sample: the magnetometer is noiseless, so
 * both measurements are taken again in the note's order.
 */
static int step2_overlapped(struct ftest_ctx *x, struct chip_sample *s)
{
	uint64_t t0 = transport_now_ns(regs_chip(x)->t);
	bool newer;
	int ret;

	ret = begin(x, AS9888_MS_SELF_TEST, true, "2-15");
	if (ret || x->stop)
		return ret;
	ret = chip_read_overlapped(regs_chip(x), s, &newer);
	if (ret)
		return ftest_io_failed(x, "2-4", "sample read", ret);
	if (newer) {
		overlap_lost(x);
		ret = measure(x, AS9888_MS_SINGLE, true, "2-4", false, s);
		if (ret || x->stop)
			return ret;
		judge_magnetometer(x, s);
		if (x->stop)
			return 0;
		ret = measure(x, AS9888_MS_SELF_TEST, true, "2-15", false, s);
		if (!ret && !x->stop)
			judge_selftest(x, s);
		return ret;
	}
	/* the same cycle as a level sample's: predicts the level runs */
	regs_dev(x)->slow = !cycle_fits(x, t0);
	judge_magnetometer(x, s);
	if (x->stop)
		return 0;
	ret = end(x, true, "2-15", false);
	if (!ret && !x->stop)
		ret = chip_read_sample(regs_chip(x), true, s);
	if (ret)
		return x->stop ? ret : ftest_io_failed(x, "2-15", "sample read", ret);
	judge_selftest(x, s);

	return 0;
}

/* Step 2: magnetometer, normal measurement then self-test */
static int regs_step2(struct ftest_ctx *x)
{
	struct regs_dev *d = regs_dev(x);
	struct transport *t = d->chip.t;
	struct chip_sample s;
	uint8_t int1st;
	int ret;

	if (!d->int_setup) {
		ret = regs_int_setup(x);
		if (ret)
			return ret;
	}

	ret = begin(x, AS9888_MS_SINGLE, true, "2-4");
	if (!ret && !x->stop)
		ret = end(x, true, "2-4", true);
	if (ret || x->stop)
		return ret;
	if (d->overlap) {
		ret = transport_read_reg(t, AS9888_REG_INT1ST, &int1st);
		if (ret)
			return ftest_io_failed(x, "2-5", "INT1ST", ret);
		ret = read_st1(x, "2-4", &s.st1);
		if (ret)
			return ret;
	} else {
		ret = chip_read_sample(&d->chip, true, &s);
		if (ret)
			return ftest_io_failed(x, "2-4", "sample read", ret);
		ret = transport_read_reg(t, AS9888_REG_INT1ST, &int1st);
		if (ret)
			return ftest_io_failed(x, "2-5", "INT1ST", ret);
	}

	ftest_judge(x, "2-5", "INT1ST reflects INT1", int1st == 0x01, "0x01",
		    "0x%02x", int1st);
	ftest_value(x, int1st, 1, 1, "code");
	if (x->stop)
		return 0;
	ftest_judge(x, "2-6", "ST1 data ready", s.st1 == AS9888_ST1_DRDY_MSK,
		    "0x01", "0x%02x", s.st1);
	ftest_value(x, s.st1, AS9888_ST1_DRDY_MSK, AS9888_ST1_DRDY_MSK, "code");
	if (x->stop)
		return 0;
	if (d->overlap)
		return step2_overlapped(x, &s);

	judge_magnetometer(x, &s);
	if (x->stop)
		return 0;
	ret = measure(x, AS9888_MS_SELF_TEST, true, "2-15", false, &s);
	if (ret || x->stop)
		return ret;
	judge_selftest(x, &s);

	return 0;
}

/*
 * Take N accelerometer-only samples (steps 3-2..3-13 or 3-27..3-38). The
 * datasheet's order reads only ST1 before the next MS write and the rest
 * of the sample while the next one converts; the last sample of the run
 * is read whole. A stall that lets the next measurement end before that
 * read loses both (overlap_lost()); the run then goes on in the note's
 * order, so that it ends whatever the machine does. A cycle beyond the
 * budget (cycle_fits()) does the same before anything is lost.
 */
static int regs_level_collect(struct ftest_ctx *x, uint32_t n, const char *step,
			      struct level_run *r)
{
	struct regs_dev *d = regs_dev(x);
	bool overlap = d->overlap && !d->slow, pending = false;
	struct chip_sample s;
	uint32_t got = 0;
	int ret;

	level_run_init(r);
	while (got + pending < n) {
		uint64_t t0 = transport_now_ns(d->chip.t);
		bool newer = false;

		if (!overlap && pending) {
			/* back to the note's order: the last sample first */
			ret = chip_read_rest(&d->chip, &s);
			if (ret)
				return ftest_io_failed(x, step, "sample read", ret);
			level_run_add(r, &s);
			got++;
			pending = false;
			continue;
		}
		if (!overlap) {
			ret = measure(x, AS9888_MS_SINGLE, false, step, false, &s);
			if (ret || x->stop)
				return ret;
			level_run_add(r, &s);
			got++;
			continue;
		}
		ret = begin(x, AS9888_MS_SINGLE, false, step);
		if (ret || x->stop)
			return ret;
		if (pending) {
			ret = chip_read_overlapped(&d->chip, &s, &newer);
			if (ret)
				return ftest_io_failed(x, step, "sample read", ret);
			pending = false;
			if (newer) {
				overlap_lost(x);
				overlap = false;
				continue;
			}
			level_run_add(r, &s);
			got++;
			overlap = cycle_fits(x, t0);
		}
		ret = end(x, false, step, false);
		if (ret || x->stop)
			return ret;
		ret = read_st1(x, step, &s.st1);
		if (ret)
			return ret;
		pending = true;
	}
	if (pending) {
		ret = chip_read_rest(&d->chip, &s);
		if (ret)
			return ftest_io_failed(x, step, "sample read", ret);
		level_run_add(r, &s);
	}

	return 0;
}

static int regs_write_dac(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES])
{
	struct regs_dev *d = regs_dev(x);
	int ret;

	/* the chip is in power-down after a single measurement */
	ret = transport_write(d->chip.t, AS9888_REG_AXDA, dac, AS9888_AXES);
	if (ret)
		return ftest_io_failed(x, "3-24", "DAC write", ret);
	memcpy(d->dac, dac, AS9888_AXES);
	/* the datasheet's order reads it back while the next run's first sample converts */
	if (d->overlap) {
		d->dac_due = true;
		return 0;
	}

	return regs_check_dac(x);
}

static int regs_level_setup(struct ftest_ctx *x)
{
	struct chip *c = regs_chip(x);
	int ret;

	/* DR1EN stays from step 2-1; without step 2 (level only) it is set here */
	if (!c->int1_dr) {
		ret = transport_write_reg(c->t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
		if (ret)
			return ftest_io_failed(x, "3-1", "INT1EN set-up", ret);
		c->int1_dr = true;
	}
	ret = transport_write_reg(c->t, AS9888_REG_SLCT2,
				  x->o->lpf ? AS9888_SLCT2_ALPF_MSK : 0);
	if (ret)
		return ftest_io_failed(x, "3-1", "SLCT2 set-up", ret);

	return 0;
}

/*
 * Leave the chip idle whatever happened; a failure here changes nothing.
 * A chip known to be in power-down (a single measurement ends there) needs
 * no MS = 0.
 */
static void regs_finish(struct ftest_ctx *x)
{
	struct chip *c = regs_chip(x);

	if (!c->powered_down)
		chip_set_mode(c, AS9888_MS_POWER_DOWN);
}

static uint64_t regs_now_ns(struct ftest_ctx *x)
{
	return transport_now_ns(regs_chip(x)->t);
}

static void regs_sleep_ns(struct ftest_ctx *x, uint64_t ns)
{
	transport_sleep_ns(regs_chip(x)->t, ns);
}

static const struct ftest_device_ops regs_ops = {
	.step1 = regs_step1,
	.step2 = regs_step2,
	.level_setup = regs_level_setup,
	.level_collect = regs_level_collect,
	.write_dac = regs_write_dac,
	.finish = regs_finish,
	.now_ns = regs_now_ns,
	.sleep_ns = regs_sleep_ns,
};

static void regs_dev_init(struct regs_dev *d, struct transport *t,
			  const struct ftest_opts *o, bool engine)
{
	memset(d, 0, sizeof(*d));
	chip_init(&d->chip, t);
	d->overlap = !o->note_order;
	d->engine = engine;
}

int ftest_run(struct transport *t, const struct ftest_opts *o,
	      struct ftest_result *res)
{
	struct regs_dev d;
	struct ftest_ctx x = { .ops = &regs_ops, .dev = &d, .o = o, .res = res };

	regs_dev_init(&d, t, o, true);

	return ftest_engine_run(&x);
}

int ftest_step1(struct transport *t, const struct ftest_opts *o,
		struct ftest_result *res)
{
	struct regs_dev d;
	struct ftest_ctx x = { .ops = &regs_ops, .dev = &d, .o = o, .res = res };
	int ret;

	regs_dev_init(&d, t, o, false);
	ret = regs_step1(&x);
	if (ret)
		return ret;

	return x.stop ? -EIO : 0;
}
