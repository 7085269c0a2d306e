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
#include "ftest_internal.h"

/* Step 1 and D11's RSTN check */
static int regs_identify(struct ftest_ctx *x)
{
	struct chip *c = x->dev;
	struct transport *t = c->t;
	uint8_t wia, val;
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

	/* D11: a written R/W register must read 0x00 after a reset pulse */
	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = chip_reset(c);
	if (ret == -EOPNOTSUPP) {
		ftest_skip(x, "1-2.rstn", "RSTN pin check (D11)", "RSTN not controlled");
		return 0;
	}
	if (!ret)
		ret = transport_read_reg(t, AS9888_REG_INT1EN, &val);
	if (ret)
		return ftest_io_failed(x, "1-2.rstn", "RSTN pin check (D11)", ret);
	ftest_judge(x, "1-2.rstn", "RSTN pin check (D11)", val == 0,
		    "INT1EN reads 0x00 after reset", "INT1EN 0x%02x", val);
	ftest_value(x, val, 0, 0, "code");

	return 0;
}

static int regs_eeprom(struct ftest_ctx *x)
{
	struct chip *c = x->dev;
	uint8_t raw[AS9888_EEPROM_LEN];
	int ret;

	ret = chip_set_mode(c, AS9888_MS_EEPROM);
	if (ret)
		return ftest_io_failed(x, "1-5", "EEPROM access mode", ret);
	transport_sleep_ns(c->t, AS9888_T_EEP_US * NS_PER_US);
	ret = transport_read(c->t, AS9888_REG_EEPROM, raw, sizeof(raw));
	if (ret)
		return ftest_io_failed(x, "1-7", "EEPROM read", ret);

	return ftest_check_eeprom(x, raw);
}

/* Steps 1-28..1-39 and the read-back check of D10 */
static int regs_trims(struct ftest_ctx *x)
{
	const struct as9888_eeprom *ee = &x->res->ee;
	struct chip *c = x->dev;
	struct transport *t = c->t;
	uint8_t trim[AS9888_TRIM_LEN], back[AS9888_TRIM_LEN];
	int axis, i, ret;

	ret = chip_set_mode(c, AS9888_MS_POWER_DOWN);
	if (ret)
		return ftest_io_failed(x, "1-28", "power-down mode", ret);
	/* 1-29: the trim registers take writes t_PD after power-down */
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
	ret = transport_write(t, AS9888_REG_REF1, trim, sizeof(trim));
	if (ret)
		return ftest_io_failed(x, "1-30", "trim load", ret);
	memcpy(x->dac, &trim[AS9888_REG_AXDA - AS9888_REG_REF1], AS9888_AXES);
	ret = transport_read(t, AS9888_REG_REF1, back, sizeof(back));
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

/*
 * Start a measurement and wait for it. Reports the INT1 pin check (D11)
 * the first time @int_step is given; with INT1 dead and keep_going, the
 * rest of the test polls DRDY.
 */
static int measure(struct ftest_ctx *x, uint8_t ms, bool men,
		   const char *step, bool check_pins, struct chip_sample *s)
{
	struct chip *c = x->dev;
	struct transport *t = c->t;
	uint64_t us = chip_measure_time_us(men, x->o->lpf);
	bool int1 = c->use_int1;
	char id[JUDGMENT_ID_LEN];
	enum chip_wait how;
	int ret;

	ret = chip_measure(c, ms, us, &how);
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

	ret = chip_read_sample(c, men, s);
	if (ret)
		return ftest_io_failed(x, step, "sample read", ret);

	return 0;
}

/* Step 2: magnetometer, normal measurement then self-test */
static int regs_step2(struct ftest_ctx *x)
{
	static const char *const ovf_step[] = { "2-7", "2-9", "2-11" };
	const struct as9888_eeprom *ee = &x->res->ee;
	struct chip *c = x->dev;
	struct transport *t = c->t;
	struct chip_sample s;
	uint8_t int1st;
	int axis, ret;

	/* 2-1: DR1EN, and DR2EN so that INT2 can be checked too (D11) */
	ret = transport_write_reg(t, AS9888_REG_INT1EN, AS9888_INTEN_DR_MSK);
	c->int1_dr = !ret;
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_INT2EN,
					  AS9888_INTEN_DR_MSK);
	if (!ret)
		ret = transport_write_reg(t, AS9888_REG_SLCT2,
					  AS9888_SLCT2_MEN_MSK);
	if (ret)
		return ftest_io_failed(x, "2-1", "interrupt and MEN set-up", ret);

	ret = measure(x, AS9888_MS_SINGLE, true, "2-4", true, &s);
	if (ret || x->stop)
		return ret;

	ret = transport_read_reg(t, AS9888_REG_INT1ST, &int1st);
	if (ret)
		return ftest_io_failed(x, "2-5", "INT1ST", ret);
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
	for (axis = 0; axis < AS9888_AXES; axis++) {
		char name[32];

		snprintf(name, sizeof(name), "magnetometer %c no overflow",
			 ftest_axis_name[axis]);
		ftest_judge(x, ovf_step[axis], name,
			    !as9888_mag_overflow(s.mag[axis]), "-4096 < H < 4095",
			    "%d", s.mag[axis]);
		ftest_value(x, s.mag[axis], -4095, 4094, "LSB");
		if (x->stop)
			return 0;
	}
	ftest_judge(x, "2-13", "ST2 normal end", s.st2 == 0, "0x00", "0x%02x",
		    s.st2);
	ftest_value(x, s.st2, 0, 0, "code");
	if (x->stop)
		return 0;

	ret = measure(x, AS9888_MS_SELF_TEST, true, "2-15", false, &s);
	if (ret || x->stop)
		return ret;
	ftest_judge(x, "2-16", "ST1 data ready (self-test)",
		    s.st1 == AS9888_ST1_DRDY_MSK, "0x01", "0x%02x", s.st1);
	ftest_value(x, s.st1, AS9888_ST1_DRDY_MSK, AS9888_ST1_DRDY_MSK, "code");
	if (x->stop)
		return 0;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		uint8_t ehc = ee->axis[axis].ehc;
		char note[24];

		snprintf(note, sizeof(note), " (raw %d)", s.mag[axis]);
		if (!ftest_judge_selftest_axis(x, axis,
					       as9888_selftest_ok(axis, s.mag[axis], ehc),
					       as9888_mag_adjust_q8(s.mag[axis], ehc),
					       note) && x->stop)
			return 0;
	}
	ftest_judge(x, "2-23", "ST2 normal end (self-test)", s.st2 == 0, "0x00",
		    "0x%02x", s.st2);
	ftest_value(x, s.st2, 0, 0, "code");

	return 0;
}

/* Take N accelerometer-only samples (steps 3-2..3-13 or 3-27..3-38) */
static int regs_level_collect(struct ftest_ctx *x, uint32_t n, const char *step,
			      struct level_run *r)
{
	struct chip_sample s;
	uint32_t i;
	int ret;

	level_run_init(r);
	for (i = 0; i < n; i++) {
		ret = measure(x, AS9888_MS_SINGLE, false, step, false, &s);
		if (ret)
			return ret;
		level_run_add(r, &s);
	}

	return 0;
}

static int regs_write_dac(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES])
{
	struct chip *c = x->dev;
	struct transport *t = c->t;
	uint8_t back[AS9888_AXES];
	int ret;

	/* the chip is in power-down after a single measurement */
	ret = transport_write(t, AS9888_REG_AXDA, dac, AS9888_AXES);
	if (ret)
		return ftest_io_failed(x, "3-24", "DAC write", ret);
	ret = transport_read(t, AS9888_REG_AXDA, back, AS9888_AXES);
	if (ret)
		return ftest_io_failed(x, "3-26", "DAC read-back", ret);
	memcpy(x->dac, back, AS9888_AXES);
	ftest_judge(x, "3-26", "DAC written (3-24..3-26, D2)",
		    !memcmp(back, dac, AS9888_AXES), "read-back equals DACopt",
		    "0x%02x 0x%02x 0x%02x", back[0], back[1], back[2]);
	FTEST_BOOL(x, !memcmp(back, dac, AS9888_AXES));

	return 0;
}

static int regs_level_setup(struct ftest_ctx *x)
{
	struct chip *c = x->dev;
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
	struct chip *c = x->dev;

	if (!c->powered_down)
		chip_set_mode(c, AS9888_MS_POWER_DOWN);
}

static uint64_t regs_now_ns(struct ftest_ctx *x)
{
	struct chip *c = x->dev;

	return transport_now_ns(c->t);
}

static void regs_sleep_ns(struct ftest_ctx *x, uint64_t ns)
{
	struct chip *c = x->dev;

	transport_sleep_ns(c->t, ns);
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

int ftest_run(struct transport *t, const struct ftest_opts *o,
	      struct ftest_result *res)
{
	struct chip c;
	struct ftest_ctx x = { .ops = &regs_ops, .dev = &c, .o = o, .res = res };

	chip_init(&c, t);

	return ftest_engine_run(&x);
}

int ftest_step1(struct transport *t, const struct ftest_opts *o,
		struct ftest_result *res)
{
	struct chip c;
	struct ftest_ctx x = { .ops = &regs_ops, .dev = &c, .o = o, .res = res };
	int ret;

	chip_init(&c, t);
	ret = regs_step1(&x);
	if (ret)
		return ret;

	return x.stop ? -EIO : 0;
}
