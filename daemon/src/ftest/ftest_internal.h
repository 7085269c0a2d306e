/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Inside the factory test: the judgments and the level logic (ftest.c) are
 * the same whatever reaches the chip; a test device supplies the rest. Two
 * devices exist: the registers behind a transport (ftest_regs.c) and the
 * AS9888 IIO driver's interfaces (ftest_iio.c).
 */
#ifndef AS9888_FTEST_INTERNAL_H
#define AS9888_FTEST_INTERNAL_H

#include "chip/chip.h"
#include "ftest/ftest.h"

#define NS_PER_US	1000ULL
#define NS_PER_MS	1000000ULL

struct ftest_ctx;

/* The statistics of one level run of N samples */
struct level_run {
	uint32_t n;
	int64_t sum[AS9888_AXES];
	int16_t min[AS9888_AXES];
	int16_t max[AS9888_AXES];
	int64_t tmps_sum;
	uint8_t tmps_min;
	uint8_t tmps_max;
	/*
	 * The driver reads ST1, EMPT and ST2 itself and does not deliver a
	 * sample that fails its checks: the status fields below are then
	 * not seen.
	 */
	bool status_by_driver;
	/* first offending sample of each per-sample check, or -1 */
	int bad_st1, bad_tmps, bad_empt, bad_st2;
	uint8_t bad_st1_val, bad_tmps_val, bad_empt_val, bad_st2_val;
	/*
	 * per axis, samples at -2048 ([0]) and at 2047 ([1]) (3-7..3-12),
	 * and the first of them
	 */
	uint32_t saturated[AS9888_AXES][2];
	int bad_acc[AS9888_AXES][2];
	int64_t sq_sum[AS9888_AXES];
};

void level_run_init(struct level_run *r);
void level_run_add(struct level_run *r, const struct chip_sample *s);

/**
 * struct ftest_device_ops - what a test device does
 * @step1:	identify the chip, judge its EEPROM (ftest_check_eeprom())
 *		and load the DAC values (@o->apply_dac or the EEPROM's) into
 *		x->dac, checking them by read-back
 * @step2:	the magnetometer test
 * @level_setup: step 3-1: accelerometer only, low-pass filter per @o->lpf
 * @level_collect: take @n accelerometer samples into @r (from
 *		level_run_init()); @step names the step for failures
 * @write_dac:	steps 3-24..3-26: write @dac, read it back into x->dac and
 *		judge the read-back
 * @finish:	leave the chip idle and release the device; always called
 * @now_ns:	the clock the test runs on
 * @sleep_ns:	sleep on that clock
 */
struct ftest_device_ops {
	int (*step1)(struct ftest_ctx *x);
	int (*step2)(struct ftest_ctx *x);
	int (*level_setup)(struct ftest_ctx *x);
	int (*level_collect)(struct ftest_ctx *x, uint32_t n, const char *step,
			     struct level_run *r);
	int (*write_dac)(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES]);
	void (*finish)(struct ftest_ctx *x);
	uint64_t (*now_ns)(struct ftest_ctx *x);
	void (*sleep_ns)(struct ftest_ctx *x, uint64_t ns);
};

/**
 * struct ftest_ctx - one run of the test
 * @ops:	the test device
 * @dev:	its state
 * @o:		the options
 * @res:	the result being built
 * @stop:	a judgment failed and the test must stop
 * @dac:	the DAC values in the chip
 */
struct ftest_ctx {
	const struct ftest_device_ops *ops;
	void *dev;
	const struct ftest_opts *o;
	struct ftest_result *res;
	bool stop;
	uint8_t dac[AS9888_AXES];
};

extern const char *const ftest_axis_name;

/* Record a judgment; a failed one stops the test unless keep_going */
bool ftest_judge(struct ftest_ctx *x, const char *step, const char *name,
		 bool ok, const char *limits, const char *fmt, ...)
	__attribute__((format(printf, 6, 7)));
void ftest_skip(struct ftest_ctx *x, const char *step, const char *name,
		const char *why);
/*
 * The last judgment as a number: @v within @lo..@hi inclusive (NAN: no such
 * limit), in @unit. A check of a condition uses the unit "bool", 1 = true.
 */
void ftest_value(struct ftest_ctx *x, double v, double lo, double hi,
		 const char *unit);
#define FTEST_BOOL(x, ok)	ftest_value(x, (ok) ? 1 : 0, 1, 1, "bool")
/* A failure to reach the chip ends the test: returns @err */
int ftest_io_failed(struct ftest_ctx *x, const char *step, const char *what,
		    int err);

/*
 * Steps 1-5..1-27 once the EEPROM is read: decode and judge it, and refuse
 * a chip that is not @o->expect_eeprom. 0 or -errno (the test stops).
 */
int ftest_check_eeprom(struct ftest_ctx *x,
		       const uint8_t raw[AS9888_EEPROM_LEN]);

/*
 * The self-test judgment of one axis (steps 2-17..2-22): @ok as the caller
 * found it, @adj_q8 the adjusted reading, @note appended to it
 */
bool ftest_judge_selftest_axis(struct ftest_ctx *x, int axis, bool ok,
			       int32_t adj_q8, const char *note);
/* The same judgment not made: the reading is not available, @why */
void ftest_skip_selftest_axis(struct ftest_ctx *x, int axis, const char *why);

/* Steps 1..3 on @x's device, then its finish(); see ftest_run() */
int ftest_engine_run(struct ftest_ctx *x);

#endif
