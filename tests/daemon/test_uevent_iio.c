// SPDX-License-Identifier: GPL-2.0
/*
 * Kernel uevent parsing and the IIO restore path against a sysfs tree laid
 * out like the driver's (the accelerometer's iio:deviceN with its
 * attributes, the magnetometer's iio:deviceM and the NVMEM provider beside
 * it, the bus/iio/devices symlinks) and a debugfs tree: which device is
 * found for what, what a record puts into calibbias, and the driver's
 * values the daemon refuses to read.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "fake_sysfs.h"
#include "chip/iio_cal.h"
#include "common/record.h"
#include "commands/session.h"
#include "service/uevent.h"

static void parse_iio_add(void **state)
{
	static const char msg[] =
		"add@/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0\0"
		"ACTION=add\0DEVPATH=/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0\0"
		"SUBSYSTEM=iio\0DEVTYPE=iio_device\0MAJOR=250\0MINOR=0\0SEQNUM=1234";
	struct uevent ev;

	assert_int_equal(uevent_parse(msg, sizeof(msg), &ev), 0);
	assert_string_equal(ev.action, "add");
	assert_string_equal(ev.devpath, "/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0");
	assert_string_equal(ev.subsystem, "iio");
	assert_string_equal(ev.devtype, "iio_device");
	assert_true(uevent_is_appearance(&ev));
}

static void parse_bind(void **state)
{
	static const char msg[] = "bind@/devices/x/1-000c\0ACTION=bind\0"
				  "SUBSYSTEM=i2c\0DRIVER=as9888_i2c\0";
	static const char other[] = "bind@/devices/x/1-0050\0ACTION=bind\0"
				    "SUBSYSTEM=i2c\0DRIVER=at24\0";
	struct uevent ev;

	/* a bind is followed by the IIO device's own add: not counted twice */
	assert_int_equal(uevent_parse(msg, sizeof(msg), &ev), 0);
	assert_string_equal(ev.driver, "as9888_i2c");
	assert_false(uevent_is_appearance(&ev));
	assert_int_equal(uevent_parse(other, sizeof(other), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
}

static void parse_not_appearance(void **state)
{
	static const char remove[] = "remove@/devices/x/iio:device0\0"
				     "SUBSYSTEM=iio\0DEVTYPE=iio_device\0";
	static const char trigger[] = "add@/devices/x/trigger0\0"
				      "SUBSYSTEM=iio\0DEVTYPE=iio_trigger\0";
	struct uevent ev;

	assert_int_equal(uevent_parse(remove, sizeof(remove), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
	assert_int_equal(uevent_parse(trigger, sizeof(trigger), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
}

static void parse_garbage(void **state)
{
	static const char udev[] = "libudev\0\xfe\xed\xca\xfe";
	struct uevent ev;
	char big[600];

	assert_int_equal(uevent_parse(udev, sizeof(udev), &ev), -EINVAL);
	assert_int_equal(uevent_parse("add", 3, &ev), -EINVAL);
	assert_int_equal(uevent_parse("@x\0", 3, &ev), -EINVAL);
	assert_int_equal(uevent_parse("", 0, &ev), -EINVAL);
	/* over-long fields are cut, never overflow */
	memset(big, 'a', sizeof(big));
	memcpy(big, "add@/", 5);
	big[400] = '\0';
	memcpy(big + 401, "SUBSYSTEM=", 10);
	assert_int_equal(uevent_parse(big, sizeof(big), &ev), 0);
	assert_int_equal(strlen(ev.devpath), sizeof(ev.devpath) - 1);
	assert_int_equal(strlen(ev.subsystem), sizeof(ev.subsystem) - 1);
}

static const struct calib_record test_record = {
	.dac = { 0x0f, 0x8e, 0x8c },
	.level_mean_q16 = { -26214, 6553, 258 * 65536 + 6554 },
	.t_level_mdegc = 24583,
	.gravity = { 0, 0, -1 },
	.samples = 16,
	.created = 1795305600,
};

static void write_record_from(const struct fake_sysfs *f, const char *path,
			      const uint8_t *eeprom, bool simulated)
{
	struct calib_record rec = test_record;
	char buf[RECORD_MAX_SIZE];
	int len;

	memcpy(rec.eeprom, eeprom, AS9888_EEPROM_LEN);
	rec.simulated = simulated;
	len = record_format(&rec, buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, path, buf, (size_t)len);
}

static void write_record(const struct fake_sysfs *f, const char *path,
			 const uint8_t *eeprom)
{
	write_record_from(f, path, eeprom, false);
}

static void find_device(void **state)
{
	struct fake_sysfs *f = *state;
	char dir[IIO_PATH_MAX], want[IIO_PATH_MAX];

	assert_int_equal(iio_find_device(NULL, dir, sizeof(dir)), 0);
	snprintf(want, sizeof(want), "%s/bus/iio/devices/iio:device0", f->root);
	assert_string_equal(dir, want);
	assert_int_equal(iio_find_device("/devices/i2c/1-000c/iio:device0", dir,
					 sizeof(dir)), 0);
	assert_string_equal(dir, f->dev);
	/* a bind of the bus device finds the IIO device below it */
	assert_int_equal(iio_find_device("/devices/i2c/1-000c", dir, sizeof(dir)), 0);
	assert_string_equal(dir, f->dev);
	assert_int_equal(iio_find_device("/devices/i2c/1-000d", dir, sizeof(dir)),
			 -ENOENT);
	assert_int_equal(iio_find_device("/devices/i2c/1-000c/../1-000c", dir,
					 sizeof(dir)), -ENOENT);
	/* the magnetometer device is not the one calibrated */
	assert_int_equal(iio_find_device("/devices/i2c/1-000c/iio:device1", dir,
					 sizeof(dir)), -ENOENT);
}

/* An IIO device @name as iio:device@n below @bus (e.g. "devices/i2c/1-000d") */
static void add_device(const struct fake_sysfs *f, const char *bus,
		       unsigned int n, const char *name)
{
	char sub[256], dir[512], text[64];

	snprintf(sub, sizeof(sub), "%s/iio:device%u", bus, n);
	fake_mkdir(f->root, sub);
	snprintf(dir, sizeof(dir), "%s/%s", f->root, sub);
	snprintf(text, sizeof(text), "%s\n", name);
	fake_put(dir, "name", text);
}

/* realpath() of @path, failing the test when it has none */
static void resolved(const char *path, char *out)
{
	if (!realpath(path, out))
		fail_msg("%s: %s", path, strerror(errno));
}

/* The magnetometer of the same chip: the sibling below the same bus device */
static void find_magn(void **state)
{
	struct fake_sysfs *f = *state;
	char link[IIO_PATH_MAX], dir[IIO_PATH_MAX], parent[IIO_PATH_MAX];
	char want[PATH_MAX], want_parent[PATH_MAX], got[PATH_MAX], other[512];
	char moved[600];

	resolved(f->magn, want);
	snprintf(other, sizeof(other), "%s/devices/i2c/1-000c", f->root);
	resolved(other, want_parent);
	/*
	 * from the bus link, as iio_find_device(NULL) gives it: named by its
	 * own bus link, which leads to the sibling
	 */
	snprintf(link, sizeof(link), "%s/bus/iio/devices/iio:device0", f->root);
	*parent = '\0';
	assert_int_equal(iio_find_magn(link, dir, sizeof(dir), parent,
				       sizeof(parent)), 0);
	snprintf(other, sizeof(other), "%s/bus/iio/devices/iio:device1", f->root);
	assert_string_equal(dir, other);
	resolved(dir, got);
	assert_string_equal(got, want);
	/* found: the bus device is not looked up */
	assert_string_equal(parent, "");
	/*
	 * its bus link not there yet (device_add() makes it after the
	 * directory): named through the accelerometer's ..
	 */
	snprintf(moved, sizeof(moved), "%s/bus/iio/devices/gone-link", f->root);
	assert_int_equal(rename(other, moved), 0);
	assert_int_equal(iio_find_magn(link, dir, sizeof(dir), NULL, 0), 0);
	assert_int_equal(rename(moved, other), 0);
	snprintf(moved, sizeof(moved), "%s/../iio:device1", link);
	assert_string_equal(dir, moved);
	resolved(dir, got);
	assert_string_equal(got, want);
	/* from the device's own directory: its sibling there */
	assert_int_equal(iio_find_magn(f->dev, dir, sizeof(dir), NULL, 0), 0);
	assert_string_equal(dir, f->magn);

	/* a second chip's devices: each accelerometer finds its own */
	add_device(f, "devices/i2c/1-000d", 3, "as9888-magn");
	add_device(f, "devices/i2c/1-000d", 2, "as9888-accel");
	add_device(f, "devices/i2c/1-000d", 4, "bmc150_magn");
	assert_int_equal(iio_find_magn(f->dev, dir, sizeof(dir), NULL, 0), 0);
	assert_string_equal(dir, want);
	snprintf(other, sizeof(other), "%s/devices/i2c/1-000d/iio:device2", f->root);
	assert_int_equal(iio_find_magn(other, dir, sizeof(dir), NULL, 0), 0);
	snprintf(other, sizeof(other), "%s/devices/i2c/1-000d/iio:device3", f->root);
	resolved(other, want);
	assert_string_equal(dir, want);

	/* none beside it: -ENOENT, and where it was looked for */
	fake_magn_present(f, false);
	*parent = '\0';
	assert_int_equal(iio_find_magn(link, dir, sizeof(dir), parent,
				       sizeof(parent)), -ENOENT);
	assert_string_equal(parent, want_parent);
	fake_magn_present(f, true);
	/* an accelerometer directory that does not exist */
	snprintf(other, sizeof(other), "%s/devices/i2c/1-000e/iio:device5", f->root);
	*parent = '\0';
	assert_int_equal(iio_find_magn(other, dir, sizeof(dir), parent,
				       sizeof(parent)), -ENOENT);
	assert_string_equal(parent, "");
}

static void expect(const struct fake_sysfs *f, const char *name,
		   const char *want)
{
	char buf[128];

	fake_get(f->dev, name, buf, sizeof(buf));
	if (strcmp(buf, want))
		fail_msg("%s reads \"%s\", not \"%s\"", name, buf, want);
}

static void restore_applies(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	fake_reset_calibration(f);
	write_record(f, "cal", fake_example_eeprom);
	snprintf(path, sizeof(path), "%s/cal", f->root);
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	/*
	 * Ot_L = A + St(t_L) G with the record's DAC, moved to the factory
	 * DAC (EAxDA 0x0d 0x8f 0x8c: linear -13 -15 12) by one DAC step per
	 * linear code (2048 / (gain + 16) LSB), at t_L = 24.583 degC:
	 *   X: -26214 + (-13 - -15) * 3050403 = 6074592 = 92.690918 LSB
	 *   Y:   6553 + (-15 - -14) * 2631720 = -2625167 = -40.056870 LSB
	 *   Z: 16914842 - St 16950406 (no DAC change) = -35564 = -0.542664 LSB
	 * then to t_RT = 23.75 degC with Kote 2.4, 9.857, -4.286 LSB/degC
	 * (-0.833 degC): 90.691, -48.270, 3.028 LSB; as calibbias, minus
	 * that / St_RT (260, 261, 259) * 1024: -357.2, 189.4, -11.97
	 */
	expect(f, "in_accel_x_calibbias", "-357");
	expect(f, "in_accel_y_calibbias", "189");
	expect(f, "in_accel_z_calibbias", "-12");
}

static void restore_refuses_other_chip(void **state)
{
	struct fake_sysfs *f = *state;
	uint8_t other[AS9888_EEPROM_LEN];
	char path[256];

	memcpy(other, fake_example_eeprom, sizeof(other));
	other[AS9888_EE_EHC(0)] ^= 1;
	fake_reset_calibration(f);
	write_record(f, "other", other);
	snprintf(path, sizeof(path), "%s/other", f->root);
	assert_int_equal(iio_restore(path, f->dev, false), -ENODEV);
	expect(f, "in_accel_x_calibbias", "0\n");
	expect(f, "in_accel_y_calibbias", "0\n");
}

/*
 * A simulator's record is never applied to the driver (restore, rollback,
 * the daemon), unless the caller itself runs on the simulator
 */
static void restore_refuses_simulated_record(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	fake_reset_calibration(f);
	write_record_from(f, "sim", fake_example_eeprom, true);
	snprintf(path, sizeof(path), "%s/sim", f->root);
	assert_int_equal(iio_restore(path, f->dev, false), -EPERM);
	expect(f, "in_accel_x_calibbias", "0\n");
	expect(f, "in_accel_y_calibbias", "0\n");
	assert_int_equal(iio_restore(path, f->dev, true), 0);
	expect(f, "in_accel_x_calibbias", "-357");
}

/* A record whose level data give no calibration changes nothing */
static void apply_refuses_uncomputable_record(void **state)
{
	struct fake_sysfs *f = *state;
	struct calib_record rec = test_record;

	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	fake_reset_calibration(f);
	rec.t_level_mdegc = 90000;
	assert_int_equal(iio_apply_record(f->dev, &rec), -ERANGE);
	expect(f, "in_accel_x_calibbias", "0\n");
	expect(f, "in_accel_z_calibbias", "0\n");
}

/* A calibration attribute that cannot be written fails the apply */
static void apply_reports_write_failure(void **state)
{
	struct fake_sysfs *f = *state;
	struct calib_record rec = test_record;
	char path[1024];

	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	snprintf(path, sizeof(path), "%s/in_accel_z_calibbias", f->dev);
	assert_int_equal(unlink(path), 0);
	assert_int_equal(mkdir(path, 0755), 0);
	assert_int_equal(iio_apply_record(f->dev, &rec), -EISDIR);
	assert_int_equal(rmdir(path), 0);
	fake_reset_calibration(f);
}

/*
 * A value the driver refuses half-way (a bus error on Z): X and Y, written
 * before it, go back to the calibration in effect before
 */
static void apply_all_or_nothing(void **state)
{
	struct fake_sysfs *f = *state;
	struct as9888_accel_cal cal = { .bias = { 100, -200, 300 } };
	char err[IIO_ERR_LEN], path[1024];

	fake_reset_calibration(f);
	fake_put(f->dev, "in_accel_x_calibbias", "7\n");
	fake_put(f->dev, "in_accel_y_calibbias", "-8\n");
	/*
	 * Z reads a number but refuses writes, even root's: a read-only
	 * sysctl (the highest capability number, about 40)
	 */
	snprintf(path, sizeof(path), "%s/in_accel_z_calibbias", f->dev);
	assert_int_equal(unlink(path), 0);
	assert_int_equal(symlink("/proc/sys/kernel/cap_last_cap", path), 0);
	assert_int_not_equal(iio_write_accel_cal(f->dev, &cal, err, sizeof(err)), 0);
	assert_int_equal(unlink(path), 0);
	expect(f, "in_accel_x_calibbias", "7");
	expect(f, "in_accel_y_calibbias", "-8");
	if (!strstr(err, "in_accel_z_calibbias"))
		fail_msg("unclear: %s", err);
	fake_reset_calibration(f);
}

/* The driver's calibration as read: every value checked */
static void read_calibration(void **state)
{
	struct fake_sysfs *f = *state;
	struct as9888_accel_cal cal;
	char err[IIO_ERR_LEN];

	fake_reset_calibration(f);
	fake_put(f->dev, "in_accel_y_calibbias", "-1\n");
	fake_put(f->dev, "in_accel_z_calibbias", "-8192\n");
	assert_int_equal(iio_read_accel_cal(f->dev, &cal, err, sizeof(err)), 0);
	assert_int_equal(cal.bias[0], 0);
	assert_int_equal(cal.bias[1], -1);
	assert_int_equal(cal.bias[2], -AS9888_CALIBBIAS_MAX);
	fake_reset_calibration(f);
}

static void refused(const struct fake_sysfs *f, const char *name,
		    const char *value, const char *why)
{
	struct as9888_accel_cal cal = { .bias = { 4711 } };
	char err[IIO_ERR_LEN], quoted[64];

	fake_reset_calibration(f);
	fake_put(f->dev, name, value);
	if (!iio_read_accel_cal(f->dev, &cal, err, sizeof(err)))
		fail_msg("%s \"%s\" accepted", name, value);
	/* the message names the attribute, the value and the reason */
	snprintf(quoted, sizeof(quoted), "/%s reads \"%.*s\": ", name,
		 (int)strcspn(value, "\n"), value);
	if (!strstr(err, quoted) || !strstr(err, why))
		fail_msg("%s \"%s\": unclear error \"%s\"", name, value, err);
	assert_int_equal(cal.bias[0], 4711);
}

static void read_calibration_refuses_bad_values(void **state)
{
	struct fake_sysfs *f = *state;
	static const char *const malformed[] = {
		"abc\n", "1.2.3\n", "\n", "", "-\n", "1.5 2\n", "0x10\n",
		"1.0000001\n", "25.5\n",
	};
	size_t i;

	for (i = 0; i < sizeof(malformed) / sizeof(malformed[0]); i++) {
		refused(f, "in_accel_y_calibbias", malformed[i], "malformed");
		refused(f, "in_accel_z_calibbias", malformed[i], "malformed");
	}
	refused(f, "in_accel_x_calibbias", "99999999999\n", "out of range");
	refused(f, "in_accel_z_calibbias", "8193\n", "out of range (-8192..8192)");
	refused(f, "in_accel_z_calibbias", "-8193\n", "out of range");
	fake_reset_calibration(f);
}

static void debugfs_file(void **state)
{
	struct fake_sysfs *f = *state;
	char dir[512], buf[64], path[IIO_PATH_MAX], want[IIO_PATH_MAX];

	unsetenv("AS9888_DEBUGFS");
	assert_string_equal(iio_debugfs_root(), "/sys/kernel/debug");
	setenv("AS9888_DEBUGFS", "", 1);
	assert_string_equal(iio_debugfs_root(), "/sys/kernel/debug");

	fake_mkdir(f->root, "debug/iio/iio:device0");
	snprintf(dir, sizeof(dir), "%s/debug", f->root);
	setenv("AS9888_DEBUGFS", dir, 1);
	snprintf(dir, sizeof(dir), "%s/debug/iio/iio:device0", f->root);
	fake_put(dir, "selftest_readings", "-19.922 15.234 598.828\n");
	/* the device as the bus link names it: the same debugfs directory */
	snprintf(dir, sizeof(dir), "%s/bus/iio/devices/iio:device0", f->root);
	assert_int_equal(iio_read_debugfs(dir, "selftest_readings", buf,
					  sizeof(buf), path, sizeof(path)), 22);
	assert_string_equal(buf, "-19.922 15.234 598.828");
	snprintf(want, sizeof(want), "%s/debug/iio/iio:device0/selftest_readings",
		 f->root);
	assert_string_equal(path, want);
	assert_int_equal(iio_read_debugfs(dir, "nothing", buf, sizeof(buf), path,
					  sizeof(path)), -ENOENT);
	unsetenv("AS9888_DEBUGFS");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(parse_iio_add),
		cmocka_unit_test(parse_bind),
		cmocka_unit_test(parse_not_appearance),
		cmocka_unit_test(parse_garbage),
		cmocka_unit_test(find_device),
		cmocka_unit_test(find_magn),
		cmocka_unit_test(restore_applies),
		cmocka_unit_test(restore_refuses_other_chip),
		cmocka_unit_test(restore_refuses_simulated_record),
		cmocka_unit_test(apply_refuses_uncomputable_record),
		cmocka_unit_test(apply_reports_write_failure),
		cmocka_unit_test(apply_all_or_nothing),
		cmocka_unit_test(read_calibration),
		cmocka_unit_test(read_calibration_refuses_bad_values),
		cmocka_unit_test(debugfs_file),
	};

	return cmocka_run_group_tests_name("uevent-iio", tests, fake_sysfs_setup,
					  fake_sysfs_teardown);
}
