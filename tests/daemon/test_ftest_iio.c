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
 *
 * Step 2 runs on the chip's other IIO device, the magnetometer's
 * (as9888-magn beside as9888-accel): its selftest attribute is a FIFO here,
 * answered by a thread as the driver would (the "1" written, then the
 * verdict), and its debugfs readings are judged. Without the magnetometer
 * device step 2 fails, naming where it is missing.
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "fake_sysfs.h"
#include "ftest/ftest.h"

#define SCAN	"scan_elements"

/* Attributes the test changes, with the values the tree starts with */
static const char *const initial[][2] = {
	{ "in_accel_x_calibbias", "0" },
	{ "in_accel_y_calibbias", "5" },
	{ "in_accel_z_calibbias", "-7" },
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
 * the timestamp, which the test leaves out (the magnetometer's channels are
 * on its own device)
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
	fake_put(f->dev, "sampling_frequency_available", "1 2 5 10 20 25 50 100 125\n");
	/* device nodes where there are none: a chip on this machine is not used */
	snprintf(dir, sizeof(dir), "%s/dev", f->root);
	setenv("AS9888_DEVDIR", dir, 1);

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

/*
 * One run from the initial tree with the attribute @name a directory,
 * which cannot be read: its first failure, which must be at @step
 */
static const struct judgment *fails_unreadable(const struct fake_sysfs *f,
					       const char *name,
					       const char *step,
					       struct ftest_result *res)
{
	const struct judgment *j;
	char path[1024];

	put_initial(f);
	snprintf(path, sizeof(path), "%s/%s", f->dev, name);
	assert_int_equal(unlink(path), 0);
	assert_int_equal(mkdir(path, 0700), 0);
	run(f, res);
	assert_int_equal(rmdir(path), 0);
	j = report_first_failure(&res->report);
	assert_non_null(j);
	assert_string_equal(j->step, step);

	return j;
}

/*
 * Steps 1, 2 and as much of 3 as goes without the driver: a failed
 * judgment returns 0, an interface that fails -errno
 */
static int run_with_step2(const struct fake_sysfs *f, struct ftest_result *res)
{
	struct ftest_opts o;

	ftest_opts_default(&o);
	o.lpf = true;
	memset(res, 0, sizeof(*res));

	return ftest_run_iio(f->dev, &o, res);
}

/*
 * The driver's selftest attribute of the magnetometer device, as a FIFO
 * answered by a thread: what the test writes, then @verdict to read
 */
struct selftest_fifo {
	char path[600];
	const char *verdict;
	char written[16];
	pthread_t thread;
	atomic_bool done;
};

static void *answer_selftest(void *arg)
{
	struct selftest_fifo *s = arg;
	ssize_t n, have = 0;
	int fd;

	fd = open(s->path, O_RDONLY);
	if (fd < 0)
		return NULL;
	while ((n = read(fd, s->written + have,
			 sizeof(s->written) - 1 - (size_t)have)) > 0)
		have += n;
	close(fd);
	fd = open(s->path, O_WRONLY);
	if (fd < 0)
		return NULL;
	n = write(fd, s->verdict, strlen(s->verdict));
	close(fd);
	atomic_store(&s->done, n == (ssize_t)strlen(s->verdict));

	return NULL;
}

static void selftest_fifo_start(const struct fake_sysfs *f,
				struct selftest_fifo *s, const char *verdict)
{
	memset(s, 0, sizeof(*s));
	snprintf(s->path, sizeof(s->path), "%s/selftest", f->magn);
	s->verdict = verdict;
	assert_int_equal(mkfifo(s->path, 0600), 0);
	assert_int_equal(pthread_create(&s->thread, NULL, answer_selftest, s), 0);
}

/* Wait for the thread; one the test never answered is cancelled */
static bool selftest_fifo_stop(struct selftest_fifo *s)
{
	bool done = atomic_load(&s->done);

	if (!done)
		pthread_cancel(s->thread);
	pthread_join(s->thread, NULL);
	unlink(s->path);

	return atomic_load(&s->done);
}

/*
 * The magnetometer's adjusted readings in debugfs (iio:device1), and other
 * ones, outside the windows, where the accelerometer device's would be
 */
static void put_selftest_readings(const struct fake_sysfs *f, const char *magn)
{
	char dir[512];

	snprintf(dir, sizeof(dir), "%s/debug", f->root);
	setenv("AS9888_DEBUGFS", dir, 1);
	fake_mkdir(f->root, "debug/iio/iio:device0");
	fake_mkdir(f->root, "debug/iio/iio:device1");
	snprintf(dir, sizeof(dir), "%s/debug/iio/iio:device0", f->root);
	fake_put(dir, "selftest_readings", "0.000 0.000 0.000\n");
	snprintf(dir, sizeof(dir), "%s/debug/iio/iio:device1", f->root);
	fake_put(dir, "selftest_readings", magn);
}

static void expect_pass(const struct report *r, const char *step,
			const char *name, const char *measured)
{
	const struct judgment *j = find(r, step, name);

	if (j->result != JUDGMENT_PASS)
		fail_msg("%s \"%s\": %s, \"%s\"", step, name,
			 judgment_result_str(j->result), j->measured);
	if (measured && !strstr(j->measured, measured))
		fail_msg("%s \"%s\": \"%s\", not \"%s\"", step, name,
			 j->measured, measured);
}

static void attributes_put_back(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char chardev[128];

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
	snprintf(chardev, sizeof(chardev), "%s/dev/iio:device0", f->root);
	assert_string_equal(j->name, chardev);
	all_put_back(f);
	ftest_result_free(&res);
}

/* @name's modification time set long ago, and whether it is still that */
static void set_old(const struct fake_sysfs *f, const char *name)
{
	const struct timespec old[2] = { { .tv_sec = 946684800 },
					 { .tv_sec = 946684800 } };
	char path[1024];

	snprintf(path, sizeof(path), "%s/%s", f->dev, name);
	assert_int_equal(utimensat(AT_FDCWD, path, old, 0), 0);
}

static bool still_old(const struct fake_sysfs *f, const char *name)
{
	char path[1024];
	struct stat st;

	snprintf(path, sizeof(path), "%s/%s", f->dev, name);
	assert_int_equal(stat(path, &st), 0);

	return st.st_mtim.tv_sec == 946684800;
}

/*
 * The buffer set up as the test wants it already (its trigger, length and
 * the fastest rate offered, 125 Hz in this tree): those attributes are
 * neither written nor put back
 */
static void set_up_attributes_untouched(void **state)
{
	static const char *const as_wanted[][2] = {
		{ "trigger/current_trigger", "as9888-dev0\n" },
		{ "buffer/length", "256\n" },
		{ "sampling_frequency", "125\n" },
		{ "in_accel_oversampling_ratio", "4\n" },
	};
	const struct fake_sysfs *f = *state;
	struct ftest_result res;
	size_t i;

	put_initial(f);
	for (i = 0; i < sizeof(as_wanted) / sizeof(as_wanted[0]); i++) {
		fake_put(f->dev, as_wanted[i][0], as_wanted[i][1]);
		set_old(f, as_wanted[i][0]);
	}
	set_old(f, SCAN "/in_accel_x_en");
	run(f, &res);
	assert_string_equal(report_first_failure(&res.report)->step, "3-3");
	for (i = 0; i < sizeof(as_wanted) / sizeof(as_wanted[0]); i++)
		if (!still_old(f, as_wanted[i][0]))
			fail_msg("%s written, though it read what the test wants",
				 as_wanted[i][0]);
	/* one the test changes is written, and put back */
	assert_false(still_old(f, SCAN "/in_accel_x_en"));
	put_initial(f);
	ftest_result_free(&res);
}

static void unusable_calibration_stops(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	/* calibbias cannot be read: the test stops before changing anything */
	j = fails_unreadable(f, "in_accel_y_calibbias", "1-4", &res);
	assert_string_equal(j->name, "device attributes");
	if (!strstr(j->measured, "/in_accel_y_calibbias: Is a directory"))
		fail_msg("unclear: %s", j->measured);
	put_initial(f);
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

/*
 * A run with step 2 against the magnetometer device's @readings in debugfs
 * and the driver's @verdict: its result in @res, its return value; the
 * test fails unless the run wrote "1" to the magnetometer device's
 * selftest and read the verdict
 */
static int run_selftest(const struct fake_sysfs *f, const char *readings,
			const char *verdict, struct ftest_result *res)
{
	struct selftest_fifo st;
	bool answered;
	int ret;

	put_initial(f);
	put_selftest_readings(f, readings);
	selftest_fifo_start(f, &st, verdict);
	ret = run_with_step2(f, res);
	answered = selftest_fifo_stop(&st);
	unsetenv("AS9888_DEBUGFS");
	if (!answered)
		fail_msg("the magnetometer device's selftest was not run and read (written \"%s\"); first failure %s",
			 st.written, report_first_failure(&res->report) ?
			 report_first_failure(&res->report)->measured : "none");
	assert_string_equal(st.written, "1");

	return ret;
}

/*
 * Step 2 through the magnetometer device: the selftest attribute and the
 * debugfs readings are its own, not the accelerometer device's
 */
static void selftest_through_magn(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char magn[PATH_MAX];
	int ret;

	assert_non_null(realpath(f->magn, magn));
	ret = run_selftest(f, "-19.922 15.234 598.828\n", "pass\n", &res);
	expect_pass(&res.report, "2-4", "magnetometer device", magn);
	expect_pass(&res.report, "2-4", "measurement completes", magn);
	expect_pass(&res.report, "2-15", "self-test verdict readable", "pass");
	expect_pass(&res.report, "2-17", "self-test X after adjustment", "-19.92");
	expect_pass(&res.report, "2-19", "self-test Y after adjustment", "15.23");
	expect_pass(&res.report, "2-21", "self-test Z after adjustment", "598.83");
	expect_pass(&res.report, "2-13", "normal measurement without overflow",
		    "pass");
	/* step 2 passed whole: the first failure is the absent chardev */
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "3-3");
	assert_true(ret < 0);
	all_put_back(f);
	ftest_result_free(&res);
}

/* The driver's "fail" with readings outside a window fails step 2 */
static void selftest_fail_through_magn(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	assert_int_equal(run_selftest(f, "-19.922 15.234 120.000\n", "fail\n",
				      &res), 0);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "2-21");
	assert_string_equal(j->measured, "120.00");
	all_put_back(f);
	ftest_result_free(&res);
}

/*
 * The driver's "fail" with every reading inside its window (an overflow or
 * HST in the normal measurement, which the readings do not show): 2-13
 * fails on the verdict alone
 */
static void selftest_verdict_fail_windows_met(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	assert_int_equal(run_selftest(f, "-19.922 15.234 598.828\n", "fail\n",
				      &res), 0);
	expect_pass(&res.report, "2-21", "self-test Z after adjustment", "598.83");
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "2-13");
	assert_string_equal(j->measured, "driver's verdict fail");
	all_put_back(f);
	ftest_result_free(&res);
}

/*
 * No magnetometer device beside the accelerometer's: step 2 fails at once,
 * saying where it looked; no self-test judgment passes
 */
static void selftest_without_magn_fails(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char bus[PATH_MAX], want[PATH_MAX + 16];
	size_t i;

	assert_non_null(realpath(f->magn, bus));
	*strrchr(bus, '/') = '\0';
	put_initial(f);
	put_selftest_readings(f, "-19.922 15.234 598.828\n");
	fake_magn_present(f, false);
	assert_int_equal(run_with_step2(f, &res), 0);
	fake_magn_present(f, true);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->step, "2-4");
	assert_string_equal(j->name, "magnetometer device");
	assert_string_equal(j->limits, "the chip's as9888-magn IIO device");
	snprintf(want, sizeof(want), "none in %s: ", bus);
	if (strncmp(j->measured, want, strlen(want)))
		fail_msg("unclear: %s", j->measured);
	for (i = 0; i < res.report.count; i++)
		if (!strncmp(res.report.items[i].step, "2-", 2) &&
		    res.report.items[i].result == JUDGMENT_PASS)
			fail_msg("%s \"%s\" passed without the magnetometer",
				 res.report.items[i].id, res.report.items[i].name);
	all_put_back(f);
	ftest_result_free(&res);
	unsetenv("AS9888_DEBUGFS");
}

/*
 * The device's current trigger is its data-ready trigger already (as the
 * driver leaves it when it binds): the IIO core names only registered
 * triggers there, so the test takes it without looking through the bus;
 * here the bus's trigger0 is another device's, which a look would not
 * accept. Any other current trigger and the bus decides (no_trigger_fails).
 */
static void current_trigger_taken(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char dir[512];

	snprintf(dir, sizeof(dir), "%s/bus/iio/devices/trigger0", f->root);
	fake_put(dir, "name", "as9888-dev7\n");
	put_initial(f);
	fake_put(f->dev, "trigger/current_trigger", "as9888-dev0\n");
	run(f, &res);
	fake_put(dir, "name", "as9888-dev0\n");
	j = find(&res.report, "3-1", "data-ready trigger");
	assert_int_equal(j->result, JUDGMENT_PASS);
	assert_string_equal(j->measured, "as9888-dev0");
	assert_string_equal(report_first_failure(&res.report)->step, "3-3");
	put_initial(f);
	ftest_result_free(&res);

	/* another device's trigger current: the bus has none of this one */
	fake_put(dir, "name", "as9888-dev7\n");
	fake_put(f->dev, "trigger/current_trigger", "as9888-dev7\n");
	run(f, &res);
	fake_put(dir, "name", "as9888-dev0\n");
	j = report_first_failure(&res.report);
	assert_string_equal(j->id, "3-1.trigger");
	put_initial(f);
	ftest_result_free(&res);
}

/* current_trigger unreadable: 3-1 fails naming it, nothing left changed */
static void current_trigger_unreadable(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;

	j = fails_unreadable(f, "trigger/current_trigger", "3-1", &res);
	assert_non_null(strstr(j->name, "trigger/current_trigger"));
	fake_put(f->dev, "trigger/current_trigger", "\n");
	all_put_back(f);
	ftest_result_free(&res);
}

/*
 * INT1 not wired to the driver: no data-ready trigger of this device (only
 * another's); step 3 stops at 3-1.trigger, saying to use the raw backend,
 * and the attributes go back
 */
static void no_trigger_fails(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char dir[512];

	snprintf(dir, sizeof(dir), "%s/bus/iio/devices/trigger0", f->root);
	fake_put(dir, "name", "as9888-dev7\n");
	put_initial(f);
	run(f, &res);
	fake_put(dir, "name", "as9888-dev0\n");
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->id, "3-1.trigger");
	assert_non_null(strstr(j->measured, "INT1 is not wired to the driver"));
	assert_non_null(strstr(j->measured, "--backend raw"));
	all_put_back(f);
	ftest_result_free(&res);
}

/*
 * D11's INT1 check through the driver: the buffer's character device is
 * there (a FIFO, kept open for writing by the test, so that a read waits
 * as on a trigger that does not fire) and no sample ever comes: the first
 * level run stalls, and the INT1 pin check fails, saying what came
 */
static void int1_silent_fails(void **state)
{
	const struct fake_sysfs *f = *state;
	const struct judgment *j;
	struct ftest_result res;
	char path[1024];
	int keep;

	put_initial(f);
	snprintf(path, sizeof(path), "%s/dev", f->root);
	assert_true(!mkdir(path, 0700) || errno == EEXIST);
	snprintf(path, sizeof(path), "%s/dev/iio:device0", f->root);
	assert_int_equal(mkfifo(path, 0600), 0);
	keep = open(path, O_RDWR | O_CLOEXEC);
	assert_true(keep >= 0);
	run(f, &res);
	close(keep);
	assert_int_equal(unlink(path), 0);
	j = report_first_failure(&res.report);
	assert_non_null(j);
	assert_string_equal(j->id, "3-3.int1");
	assert_string_equal(j->name, "INT1 pin check (D11)");
	if (!strstr(j->measured, "0 of ") ||
	    !strstr(j->measured, "from as9888-dev0, then none for"))
		fail_msg("unclear: %s", j->measured);
	j = find(&res.report, "3-3", "samples delivered (INT1, ST1, EMPT)");
	assert_int_equal(j->result, JUDGMENT_FAIL);
	all_put_back(f);
	ftest_result_free(&res);
}

/*
 * The timestamp is not a channel of the test: it is off while the test
 * runs (written) and on again after (put back)
 */
static void timestamp_off_and_back(void **state)
{
	const struct fake_sysfs *f = *state;
	struct ftest_result res;

	put_initial(f);
	set_old(f, SCAN "/in_timestamp_en");
	run(f, &res);
	assert_false(still_old(f, SCAN "/in_timestamp_en"));
	all_put_back(f);
	ftest_result_free(&res);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(attributes_put_back),
		cmocka_unit_test(set_up_attributes_untouched),
		cmocka_unit_test(unusable_calibration_stops),
		cmocka_unit_test(held_buffer_stops),
		cmocka_unit_test(selftest_through_magn),
		cmocka_unit_test(selftest_fail_through_magn),
		cmocka_unit_test(selftest_verdict_fail_windows_met),
		cmocka_unit_test(selftest_without_magn_fails),
		cmocka_unit_test(no_trigger_fails),
		cmocka_unit_test(current_trigger_taken),
		cmocka_unit_test(current_trigger_unreadable),
		cmocka_unit_test(timestamp_off_and_back),
		cmocka_unit_test(int1_silent_fails),
	};

	return cmocka_run_group_tests_name("ftest-iio", tests, setup,
					   fake_sysfs_teardown);
}
