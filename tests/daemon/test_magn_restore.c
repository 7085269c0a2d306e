// SPDX-License-Identifier: GPL-2.0
/*
 * The magnetometer's part of a record in the driver, against the fake
 * sysfs tree: restore writes in_magn_<axis>_calibbias = rint(-b / scale)
 * and _calibscale = W's diagonal on the as9888-magn device and reads them
 * back; a record without one puts the driver's defaults back; an older
 * driver without the attributes, or no magnetometer device, leaves the
 * accelerometer's restore standing. And the arithmetic of the split: the
 * driver's output corrected by userspace's residual is W * (m - b).
 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "commands/cli.h"
#include "commands/commands.h"
#include "fake_sysfs.h"
#include "chip/iio_cal.h"
#include "common/magn_cal.h"
#include "chip/magn_iio.h"
#include "magn_example.h"
#include "common/record.h"
#include "commands/session.h"

static const struct calib_record test_record = {
	.dac = { 0x0f, 0x8e, 0x8c },
	.level_mean_q16 = { -26214, 6553, 258 * 65536 + 6554 },
	.t_level_mdegc = 24583,
	.gravity = { 0, 0, -1 },
	.samples = 16,
	.created = 1795305600,
};

static void write_record(const struct fake_sysfs *f, const char *name,
			 bool with_magn, char *path, size_t size)
{
	struct calib_record rec = test_record;
	char buf[RECORD_MAX_SIZE];
	int len;

	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	if (with_magn)
		rec.magn = magn_example;
	len = record_format(&rec, buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, name, buf, (size_t)len);
	snprintf(path, size, "%s/%s", f->root, name);
}

static void expect(const char *dir, const char *name, const char *want)
{
	char buf[128];

	fake_get(dir, name, buf, sizeof(buf));
	if (strcmp(buf, want))
		fail_msg("%s reads \"%s\", not \"%s\"", name, buf, want);
}

static void expect_accel_restored(const struct fake_sysfs *f)
{
	/* test_uevent_iio.c's restore_applies derives these */
	expect(f->dev, "in_accel_x_calibbias", "-357");
	expect(f->dev, "in_accel_y_calibbias", "189");
	expect(f->dev, "in_accel_z_calibbias", "-12");
}

static void reset(const struct fake_sysfs *f, bool magn_attrs)
{
	fake_reset_calibration(f);
	fake_magn_calibration(f, magn_attrs);
}

static void restore_writes_magn(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	expect_accel_restored(f);
	/*
	 * The example EEPROM's EHC 0x80 0x85 0x7b: 0.3 * (EHC + 128) / 256 =
	 * 0.3, 0.305859, 0.294141 uT per LSB; -b / that: -100, 148.76,
	 * -340.82
	 */
	expect(f->magn, "in_magn_x_calibbias", "-100");
	expect(f->magn, "in_magn_y_calibbias", "149");
	expect(f->magn, "in_magn_z_calibbias", "-341");
	expect(f->magn, "in_magn_x_calibscale", "1.020000");
	expect(f->magn, "in_magn_y_calibscale", "0.985000");
	expect(f->magn, "in_magn_z_calibscale", "1.003000");
}

/* A format 1 record (the old code's) restores, and clears a calibration */
static void format1_restores_defaults(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "77\n");
	fake_put(f->magn, "in_magn_z_calibscale", "1.500000\n");
	write_record(f, "cal1", false, path, sizeof(path));
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "0");
	expect(f->magn, "in_magn_z_calibscale", "1.000000");
}

/* An older driver: no magnetometer attributes; the accelerometer's part stands */
static void old_driver_keeps_accel(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256], probe[512];

	reset(f, false);
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	expect_accel_restored(f);
	snprintf(probe, sizeof(probe), "%s/in_magn_x_calibbias", f->magn);
	assert_int_equal(access(probe, F_OK), -1);
}

static void no_magn_device_keeps_accel(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	fake_magn_present(f, false);
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	expect_accel_restored(f);
	fake_magn_present(f, true);
	expect(f->magn, "in_magn_x_calibbias", "0\n");
}

/* The magnetometer device registered just after the accelerometer's */
static void *magn_appears_later(void *arg)
{
	struct timespec ts = { .tv_nsec = 100000000 };

	nanosleep(&ts, NULL);
	fake_magn_present(arg, true);

	return NULL;
}

static void restore_waits_for_magn_device(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];
	pthread_t t;

	reset(f, true);
	write_record(f, "cal2", true, path, sizeof(path));
	fake_magn_present(f, false);
	assert_int_equal(pthread_create(&t, NULL, magn_appears_later, f), 0);
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	assert_int_equal(pthread_join(t, NULL), 0);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "-100");
	expect(f->magn, "in_magn_z_calibscale", "1.003000");
}

/* An attribute that cannot be written fails the restore, saying which */
static void magn_write_failure_reported(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256], attr[512];

	reset(f, true);
	snprintf(attr, sizeof(attr), "%s/in_magn_y_calibscale", f->magn);
	assert_int_equal(unlink(attr), 0);
	fake_mkdir(f->magn, "in_magn_y_calibscale");
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore(path, f->dev, false), -EISDIR);
	assert_int_equal(rmdir(attr), 0);
}

/* A driver that reads back something else (it rounded, refused) is caught */
static void magn_read_back_checked(void **state)
{
	struct fake_sysfs *f = *state;
	struct magn_driver_cal d, got;
	char err[IIO_ERR_LEN];

	reset(f, true);
	magn_driver_identity(&d);
	d.calibbias[1] = 12;
	d.calibscale_micro[2] = 1250000;
	assert_int_equal(magn_iio_write(f->magn, &d, err, sizeof(err)), 0);
	assert_int_equal(magn_iio_read(f->magn, &got, err, sizeof(err)), 0);
	assert_memory_equal(&d, &got, sizeof(d));
	expect(f->magn, "in_magn_z_calibscale", "1.250000");
	/* what sysfs prints is parsed, the rest refused */
	fake_put(f->magn, "in_magn_z_calibscale", "1.25\n");
	assert_int_equal(magn_iio_read(f->magn, &got, err, sizeof(err)), 0);
	assert_int_equal(got.calibscale_micro[2], 1250000);
	fake_put(f->magn, "in_magn_z_calibscale", "-1.000000\n");
	assert_int_equal(magn_iio_read(f->magn, &got, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "in_magn_z_calibscale"));
	fake_put(f->magn, "in_magn_x_calibbias", "5000\n");
	assert_int_equal(magn_iio_read(f->magn, &got, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "in_magn_x_calibbias"));
}

/*
 * restore --device: the restore unit started for one device may write
 * only that device's directory. The accelerometer's device gets its part,
 * the magnetometer left as it was
 */
static void device_accel_alone(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "77\n");
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore_device(path, f->dev), 0);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "77\n");
	expect(f->magn, "in_magn_z_calibscale", "1.000000\n");
}

/* ... and the magnetometer's its own, the accelerometer left as it was */
static void device_magn_alone(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	write_record(f, "cal2", true, path, sizeof(path));
	assert_int_equal(iio_restore_device(path, f->magn), 0);
	expect(f->dev, "in_accel_x_calibbias", "0\n");
	expect(f->dev, "in_accel_z_calibbias", "0\n");
	expect(f->magn, "in_magn_x_calibbias", "-100");
	expect(f->magn, "in_magn_y_calibbias", "149");
	expect(f->magn, "in_magn_z_calibbias", "-341");
	expect(f->magn, "in_magn_y_calibscale", "0.985000");
	/* a format 1 record puts the driver's defaults back */
	fake_put(f->magn, "in_magn_x_calibscale", "1.500000\n");
	write_record(f, "cal1", false, path, sizeof(path));
	assert_int_equal(iio_restore_device(path, f->magn), 0);
	expect(f->magn, "in_magn_x_calibbias", "0");
	expect(f->magn, "in_magn_x_calibscale", "1.000000");
	expect(f->dev, "in_accel_x_calibbias", "0\n");
}

/* Any other IIO device is refused, and nothing is written */
static void device_other_refused(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256], name[64];

	reset(f, true);
	write_record(f, "cal2", true, path, sizeof(path));
	fake_get(f->magn, "name", name, sizeof(name));
	fake_put(f->magn, "name", "bmc150_magn\n");
	assert_int_equal(iio_restore_device(path, f->magn), -ENODEV);
	fake_put(f->magn, "name", name);
	expect(f->magn, "in_magn_x_calibbias", "0\n");
	assert_int_equal(iio_restore_device(path, f->root), -ENOENT);
	expect(f->dev, "in_accel_x_calibbias", "0\n");
}

/* The magnetometer of another chip (its EEPROM) is refused */
static void device_magn_other_chip(void **state)
{
	struct fake_sysfs *f = *state;
	struct calib_record rec = test_record;
	char buf[RECORD_MAX_SIZE], path[256];
	int len;

	reset(f, true);
	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	rec.eeprom[AS9888_EE_EHC(1)] ^= 1;
	rec.magn = magn_example;
	len = record_format(&rec, buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, "other", buf, (size_t)len);
	snprintf(path, sizeof(path), "%s/other", f->root);
	assert_int_equal(iio_restore_device(path, f->magn), -ENODEV);
	expect(f->magn, "in_magn_x_calibbias", "0\n");
}

/*
 * <record>.magn written beside "cal1" (a format 1 record): the example
 * calibration of the record's generation, or shifted by @created_delta
 * seconds (another change of the record), or @garbage
 */
static void write_magn_file(const struct fake_sysfs *f, long created_delta,
			    const char *garbage)
{
	char buf[RECORD_MAX_SIZE];
	int len;

	if (garbage) {
		fake_put(f->root, "cal1.magn", garbage);
		return;
	}
	len = record_magn_format(&magn_example, fake_example_eeprom,
				 test_record.created + created_delta, buf,
				 sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, "cal1.magn", buf, (size_t)len);
}

/*
 * A <record>.magn that cannot be used (not valid, or of another change of
 * the record: the two files are one generation) does not stop restore
 * applying the accelerometer's part; the magnetometer is left as it was,
 * and the restore fails unless it was for the accelerometer's device alone
 */
static void bad_magn_file_keeps_accel(void **state)
{
	struct fake_sysfs *f = *state;
	char path[256];

	reset(f, true);
	write_record(f, "cal1", false, path, sizeof(path));
	/* of the record's generation: used */
	write_magn_file(f, 0, NULL);
	assert_int_equal(iio_restore(path, f->dev, false), 0);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "-100");

	reset(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "77\n");
	write_magn_file(f, 1, NULL);
	assert_int_equal(iio_restore(path, f->dev, false), -ESTALE);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "77\n");

	/* the magnetometer left as it was (not reset to the defaults) */
	reset(f, true);
	fake_put(f->magn, "in_magn_x_calibscale", "1.250000\n");
	write_magn_file(f, 0, "format = as9888-magnetometer 1\ntorn");
	assert_int_equal(iio_restore(path, f->dev, false), -EINVAL);
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibscale", "1.250000\n");

	/* restore --device: the accelerometer's needs no .magn */
	reset(f, true);
	fake_put(f->magn, "in_magn_x_calibscale", "1.250000\n");
	assert_int_equal(iio_restore_device(path, f->dev), 0);
	expect_accel_restored(f);
	assert_int_equal(iio_restore_device(path, f->magn), -EINVAL);
	expect(f->magn, "in_magn_x_calibscale", "1.250000\n");
	assert_int_equal(unlink(path), 0);
	snprintf(path, sizeof(path), "%s/cal1.magn", f->root);
	assert_int_equal(unlink(path), 0);
}

/* @rec (the example chip's) as a record file @name below the tree's root */
static void put_record(const struct fake_sysfs *f, const char *name,
		       struct calib_record *rec)
{
	char buf[RECORD_MAX_SIZE];
	int len;

	memcpy(rec->eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	len = record_format(rec, buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, name, buf, (size_t)len);
}

/*
 * rollback through the driver when the device takes only part of the
 * rolled-back record (its .magn is of another change, so the
 * accelerometer's part is applied and the magnetometer's not): the pairs
 * are swapped back and the record of before applied again, so that the
 * chip runs what the files say
 */
static void rollback_partly_taken_put_back(void **state)
{
	static const char *const names[] = { "rb", "rb.previous", "rb.magn",
					     "rb.magn.previous", "rb.lock" };
	struct fake_sysfs *f = *state;
	struct calib_record cur = test_record, prev = test_record;
	char path[256], before[4][RECORD_MAX_SIZE], buf[RECORD_MAX_SIZE];
	char *argv[] = { "as9888-calibd", "rollback", "--backend", "iio",
			 "--record", path, NULL };
	struct cli_opts o;
	unsigned int i;
	int len;

	reset(f, true);
	put_record(f, "rb", &cur);
	prev.created -= 100;
	prev.level_mean_q16[0] += 8 * 65536;
	put_record(f, "rb.previous", &prev);
	len = record_magn_format(&magn_example, fake_example_eeprom, cur.created,
				 buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, "rb.magn", buf, (size_t)len);
	/* of neither record: the magnetometer's pair is left by the rollback */
	len = record_magn_format(&magn_example, fake_example_eeprom,
				 cur.created - 200, buf, sizeof(buf));
	assert_true(len > 0);
	fake_put_bytes(f->root, "rb.magn.previous", buf, (size_t)len);
	for (i = 0; i < 4; i++)
		fake_get(f->root, names[i], before[i], sizeof(before[i]));
	snprintf(path, sizeof(path), "%s/rb", f->root);
	assert_int_equal(cli_parse(6, argv, &o, buf, sizeof(buf)), 0);

	assert_int_equal(cmd_rollback(&o), EXIT_FAILURE);
	for (i = 0; i < 4; i++) {
		fake_get(f->root, names[i], buf, sizeof(buf));
		assert_string_equal(buf, before[i]);
	}
	expect_accel_restored(f);
	expect(f->magn, "in_magn_x_calibbias", "-100");
	for (i = 0; i < 5; i++) {
		snprintf(path, sizeof(path), "%s/%s", f->root, names[i]);
		unlink(path);
	}
}

/*
 * magn-calibrate and the field mode change only the magnetometer's part:
 * that part alone is applied, on the record's chip, never from a record
 * made on the simulator
 */
static void magn_checked_alone(void **state)
{
	struct fake_sysfs *f = *state;
	struct calib_record rec = test_record;

	reset(f, true);
	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	rec.magn = magn_example;
	assert_int_equal(iio_apply_magn_checked(f->dev, &rec, "rec"), 0);
	expect(f->dev, "in_accel_x_calibbias", "0\n");
	expect(f->magn, "in_magn_x_calibbias", "-100");
	expect(f->magn, "in_magn_y_calibscale", "0.985000");

	reset(f, true);
	rec.simulated = true;
	assert_int_equal(iio_apply_magn_checked(f->dev, &rec, "rec"), -EPERM);
	expect(f->magn, "in_magn_x_calibbias", "0\n");
	rec.simulated = false;
	rec.eeprom[AS9888_EE_EHC(2)] ^= 1;
	assert_int_equal(iio_apply_magn_checked(f->dev, &rec, "rec"), -ENODEV);
	expect(f->magn, "in_magn_x_calibbias", "0\n");
}

/* A hard iron the driver's +-4096 LSB cannot cancel is refused, not clipped */
static void split_refuses_out_of_range(void **state)
{
	uint8_t ee[AS9888_EEPROM_LEN];
	struct calib_magn m = magn_example;
	struct magn_driver_cal d;

	(void)state;
	memcpy(ee, fake_example_eeprom, sizeof(ee));
	ee[AS9888_EE_EHC(0)] = 0;	/* 0.15 uT per LSB */
	m.hard_iron_nt[0] = 700000;	/* 4666.7 LSB */
	assert_int_equal(magn_driver_split(&m, ee, &d), -ERANGE);
	m.hard_iron_nt[0] = 600000;	/* 4000 LSB */
	assert_int_equal(magn_driver_split(&m, ee, &d), 0);
	assert_int_equal(d.calibbias[0], -4000);
}

/*
 * The driver's output y = D * (m + c * s), corrected by userspace's part,
 * is W * (m - b) for any field; uncalibrated W * m minus the HAL's bias
 * is the same
 */
static void split_recombines(void **state)
{
	struct magn_driver_cal d;
	struct magn_user_cal u;
	double s[AS9888_AXES];
	int n, i;

	(void)state;
	assert_int_equal(magn_driver_split(&magn_example, fake_example_eeprom, &d), 0);
	magn_user_split(&magn_example, fake_example_eeprom, &d, &u);
	magn_scale_ut(fake_example_eeprom, s);
	srand(5);
	for (n = 0; n < 1000; n++) {
		double m[3], y[3], f[3], want[3], unc[3];

		for (i = 0; i < 3; i++)
			m[i] = (rand() / (double)RAND_MAX - 0.5) * 400;
		for (i = 0; i < 3; i++)
			y[i] = d.calibscale_micro[i] / 1e6 *
			       (m[i] + d.calibbias[i] * s[i]);
		magn_correct_driver(&u, y, f);
		magn_correct_raw(&u, m, want);
		for (i = 0; i < 3; i++) {
			double expect_i = 0;
			int j;

			for (j = 0; j < 3; j++)
				expect_i += u.soft[i][j] *
					    (m[j] - magn_example.hard_iron_nt[j] / 1000.0);
			assert_true(fabs(want[i] - expect_i) < 1e-9);
			assert_true(fabs(f[i] - want[i]) < 1e-9);
		}
		for (i = 0; i < 3; i++) {
			int j;

			unc[i] = 0;
			for (j = 0; j < 3; j++)
				unc[i] += u.soft[i][j] * m[j];
			assert_true(fabs(unc[i] - u.hal_bias_ut[i] - want[i]) < 1e-9);
		}
	}
	/* rounding the bias to whole LSB leaves at most half an LSB, times D */
	for (i = 0; i < 3; i++)
		assert_true(fabs(u.offset_ut[i]) <= s[i] / 2 * 1.02 + 1e-12);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(restore_writes_magn),
		cmocka_unit_test(format1_restores_defaults),
		cmocka_unit_test(old_driver_keeps_accel),
		cmocka_unit_test(no_magn_device_keeps_accel),
		cmocka_unit_test(restore_waits_for_magn_device),
		cmocka_unit_test(magn_write_failure_reported),
		cmocka_unit_test(magn_read_back_checked),
		cmocka_unit_test(device_accel_alone),
		cmocka_unit_test(device_magn_alone),
		cmocka_unit_test(device_other_refused),
		cmocka_unit_test(device_magn_other_chip),
		cmocka_unit_test(bad_magn_file_keeps_accel),
		cmocka_unit_test(rollback_partly_taken_put_back),
		cmocka_unit_test(magn_checked_alone),
		cmocka_unit_test(split_refuses_out_of_range),
		cmocka_unit_test(split_recombines),
	};

	return cmocka_run_group_tests_name("magn-restore", tests,
					  fake_sysfs_setup, fake_sysfs_teardown);
}
