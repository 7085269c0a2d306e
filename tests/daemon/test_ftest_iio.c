// SPDX-License-Identifier: GPL-2.0
/*
 * The factory test through the driver (ftest_iio.c) against a sysfs tree
 * laid out like the driver's, as far as one goes without the driver: step
 * 1 and the set-up of step 3 run, the buffer's character device is absent
 * so the first level run fails. Every attribute the test changed must be
 * put back, and a calibration the driver reports in a form the daemon
 * cannot use must stop the test with a message that says which and why.
 * A buffer another program keeps enabled past --busy-timeout stops the
 * test at 1-4 with a message that says what to do, and changes nothing.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "fake_sysfs.h"
#include "ftest.h"

#define SCAN	"scan_elements"

/* Attributes the test changes, with the values the tree starts with */
static const char *const initial[][2] = {
	{ "in_accel_x_calibbias", "0" },
	{ "in_accel_y_calibbias", "5" },
	{ "in_accel_z_calibbias", "-7" },
	{ "in_accel_x_caliboffset", "-0.542664" },
	{ "in_accel_calibtemp", "24583" },
	{ "in_accel_oversampling_ratio", "1" },
	{ "sampling_frequency", "130" },
	{ "buffer/enable", "0" },
	{ "buffer/length", "2" },
	{ "trigger/current_trigger", "" },
	{ SCAN "/in_accel_x_en", "0" },
	{ SCAN "/in_accel_y_en", "0" },
	{ SCAN "/in_accel_z_en", "0" },
	{ SCAN "/in_temp_en", "0" },
	{ SCAN "/in_timestamp_en", "1" },
};

/*
 * The accelerometer device's buffer: compensated accelerometer, TMPS and
 * the timestamp (the magnetometer's channels are on its own device)
 */
static const char *const scan_types[][3] = {
	{ "in_accel_x", "0", "le:s16/16>>0" },
	{ "in_accel_y", "1", "le:s16/16>>0" },
	{ "in_accel_z", "2", "le:s16/16>>0" },
	{ "in_temp", "3", "le:u8/16>>0" },
	{ "in_timestamp", "4", "le:s64/64>>0" },
};

static void put_initial(const struct fake_sysfs *f)
{
	size_t i;

	for (i = 0; i < sizeof(initial) / sizeof(initial[0]); i++) {
		char text[64];

		snprintf(text, sizeof(text), "%s\n", initial[i][1]);
		fake_put(f->dev, initial[i][0], text);
	}
}

static int setup(void **state)
{
	struct fake_sysfs *f;
	char dir[512], name[128];
	size_t i;

	fake_sysfs_setup(state);
	f = *state;
	fake_mkdir(f->dev, "buffer");
	fake_mkdir(f->dev, "trigger");
	fake_mkdir(f->dev, SCAN);
	fake_mkdir(f->root, "bus/iio/devices/trigger0");
	snprintf(dir, sizeof(dir), "%s/bus/iio/devices/trigger0", f->root);
	fake_put(dir, "name", "as9888-dev0\n");
	snprintf(dir, sizeof(dir), "%s/" SCAN, f->dev);
	for (i = 0; i < sizeof(scan_types) / sizeof(scan_types[0]); i++) {
		snprintf(name, sizeof(name), "%s_index", scan_types[i][0]);
		fake_put(dir, name, scan_types[i][1]);
		snprintf(name, sizeof(name), "%s_type", scan_types[i][0]);
		fake_put(dir, name, scan_types[i][2]);
	}
	put_initial(f);

	return 0;
}

static void all_put_back(const struct fake_sysfs *f)
{
	char buf[64];
	size_t i;

	for (i = 0; i < sizeof(initial) / sizeof(initial[0]); i++) {
		fake_get(f->dev, initial[i][0], buf, sizeof(buf));
		buf[strcspn(buf, "\n")] = '\0';
		if (strcmp(buf, initial[i][1]))
			fail_msg("%s left at \"%s\", not put back to \"%s\"",
				 initial[i][0], buf, initial[i][1]);
	}
}

static const struct judgment *find(const struct report *r, const char *step,
				   const char *name)
{
	size_t i;

	for (i = 0; i < r->count; i++)
		if (!strcmp(r->items[i].step, step) &&
		    !strcmp(r->items[i].name, name))
			return &r->items[i];
	fail_msg("no judgment %s \"%s\"", step, name);
	return NULL;
}

static void run_for(const struct fake_sysfs *f, struct ftest_result *res,
		    uint32_t busy_timeout_ms)
{
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.busy_timeout_ms = busy_timeout_ms;
	o.level_only = true;
	o.lpf = true;
	memset(res, 0, sizeof(*res));
	assert_true(ftest_run_iio(f->dev, &o, res) < 0);
}

static void run(const struct fake_sysfs *f, struct ftest_result *res)
{
	run_for(f, res, FTEST_BUSY_TIMEOUT_MS_DEFAULT);
}

static void attributes_put_back(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	if (!access("/dev/iio:device0", F_OK))
		skip();
	put_initial(f);
	run(f, &res);
	/* step 1 wrote the EEPROM's DAC values and read them back */
	j = find(&res.report, "1-39", "register R/W check (D10)");
	assert_int_equal(j->result, JUDGMENT_PASS);
	assert_string_equal(j->measured, "DAC 0x0d 0x8f 0x8c");
	/* step 3 got as far as the buffer's character device */
	j = find(&res.report, "3-1", "data-ready trigger");
	assert_int_equal(j->result, JUDGMENT_PASS);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "3-3");
	assert_string_equal(j->name, "/dev/iio:device0");
	all_put_back(f);
	ftest_result_free(&res);
}

static void unusable_calibration_stops(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	put_initial(f);
	fake_put(f->dev, "in_accel_y_caliboffset", "1.2.3\n");
	run(f, &res);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "3-1");
	assert_string_equal(j->name, "driver's calibration readable");
	if (!strstr(j->measured, "/in_accel_y_caliboffset reads \"1.2.3\": malformed"))
		fail_msg("unclear: %s", j->measured);
	all_put_back(f);
	ftest_result_free(&res);
	fake_reset_calibration(f);
}

static void held_buffer_stops(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char buf[64];

	put_initial(f);
	fake_put(f->dev, "buffer/enable", "1\n");
	run_for(f, &res, 0);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "1-4");
	assert_string_equal(j->name, "device free for the test");
	if (!strstr(j->measured, "busy for 0 s: stop the program holding it") ||
	    !strstr(j->measured, "--busy-timeout"))
		fail_msg("unclear: %s", j->measured);
	/* nothing was touched: the calibration and the DAC are as found */
	fake_get(f->dev, "in_accel_y_calibbias", buf, sizeof(buf));
	buf[strcspn(buf, "\n")] = '\0';
	assert_string_equal(buf, "5");
	ftest_result_free(&res);
	put_initial(f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(attributes_put_back),
		cmocka_unit_test(unusable_calibration_stops),
		cmocka_unit_test(held_buffer_stops),
	};

	return cmocka_run_group_tests_name("ftest-iio", tests, setup,
					   fake_sysfs_teardown);
}
