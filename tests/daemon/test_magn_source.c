// SPDX-License-Identifier: GPL-2.0
/*
 * magn-calibrate's samples: from the simulated chip's registers (the
 * built-in unit's field of 20, -5, -40 uT, lying with +z up), refused
 * on another chip; from the driver's attributes with its own calibration
 * taken out again; an overflow is a sample to skip, not an error. Through
 * the driver, a buffered capture of both devices on the shared trigger
 * (the character devices FIFOs here) pairs the samples of one measurement
 * by their timestamps; where the capture cannot be had or stops, sysfs.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "chip/backend_sim.h"
#include "fake_sysfs.h"
#include "magn/magn_source.h"

static struct calib_record sim_record(const uint8_t *eeprom)
{
	struct calib_record rec = {
		.dac = { 0x0d, 0x8f, 0x8c },	/* the EEPROM's EAxDA */
		.gravity = { 0, 0, -1 },
		.samples = 16,
	};

	memcpy(rec.eeprom, eeprom, AS9888_EEPROM_LEN);

	return rec;
}

static struct transport *open_sim(void)
{
	struct backend_sim_opts o = { .unit_path = NULL, .virtual_clock = true };
	struct transport *t;
	char err[256];

	if (backend_sim_open(&o, &t, err, sizeof(err)))
		fail_msg("simulator: %s", err);

	return t;
}

static void chip_samples(void **state)
{
	static const double want[AS9888_AXES] = { 20, -5, -40 };
	double mount[AS9888_AXES][AS9888_AXES];
	struct magn_source *s;
	struct magn_reading r;
	double sum[AS9888_AXES] = { 0 };
	char err[256];
	int n, axis;

	(void)state;
	struct calib_record rec = sim_record(fake_example_eeprom);

	assert_int_equal(magn_source_open_chip(open_sim(), &rec, &s, err,
					       sizeof(err)), 0);
	for (n = 0; n < 20; n++) {
		uint64_t before = magn_source_now_ns(s);

		assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
		/* MAGN_SOURCE_AVERAGE measurements of t_MAG each */
		assert_int_equal(r.measurements, MAGN_SOURCE_AVERAGE);
		assert_true(r.t_ns >= before + MAGN_SOURCE_AVERAGE * 7300000ULL);
		for (axis = 0; axis < AS9888_AXES; axis++)
			sum[axis] += r.field_ut[axis];
		/* the unit's "up" is +z: about +256 LSB there, little elsewhere */
		assert_true(r.accel[2] > 200 && fabs(r.accel[0]) < 40 &&
			    fabs(r.accel[1]) < 40);
	}
	/* the chip's registers: no device frame */
	assert_false(magn_source_mount(s, mount));
	for (axis = 0; axis < AS9888_AXES; axis++)
		if (fabs(sum[axis] / n - want[axis]) > 0.6)
			fail_msg("axis %d reads %.3f uT, not %.1f", axis,
				 sum[axis] / n, want[axis]);
	magn_source_close(s);
}

static void chip_other_refused(void **state)
{
	uint8_t other[AS9888_EEPROM_LEN];
	struct magn_source *s = NULL;
	struct calib_record rec;
	char err[256];

	(void)state;
	memcpy(other, fake_example_eeprom, sizeof(other));
	other[AS9888_EE_EHC(2)] ^= 1;
	rec = sim_record(other);
	assert_int_equal(magn_source_open_chip(open_sim(), &rec, &s, err,
					       sizeof(err)), -ENODEV);
	assert_null(s);
	assert_non_null(strstr(err, "factory-test"));
}

/* What @log holds so far */
static void log_text(FILE *log, char *buf, size_t size)
{
	size_t n;

	fflush(log);
	rewind(log);
	n = fread(buf, 1, size - 1, log);
	buf[n] = '\0';
}

static void put_raw(const struct fake_sysfs *f, const char *m[3],
		    const char *a[3])
{
	static const char *const mn[] = { "in_magn_x_raw", "in_magn_y_raw", "in_magn_z_raw" };
	static const char *const an[] = { "in_accel_x_raw", "in_accel_y_raw", "in_accel_z_raw" };
	int i;

	for (i = 0; i < 3; i++) {
		fake_put(f->magn, mn[i], m[i]);
		fake_put(f->dev, an[i], a[i]);
	}
}

static void iio_samples(void **state)
{
	const char *m[3] = { "165\n", "-20\n", "0\n" };
	const char *a[3] = { "3\n", "-1\n", "255\n" };
	struct fake_sysfs *f = *state;
	struct magn_source *s;
	struct magn_reading r;
	char err[512], text[1024];
	FILE *log;

	fake_magn_calibration(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "10\n");
	fake_put(f->magn, "in_magn_x_calibscale", "1.500000\n");
	fake_put(f->magn, "in_magn_y_calibbias", "-4\n");
	put_raw(f, m, a);
	log = tmpfile();
	assert_non_null(log);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	/* the tree has no buffers: sysfs, and the log says why */
	log_text(log, text, sizeof(text));
	assert_non_null(strstr(text, "no buffered capture"));
	assert_non_null(strstr(text, "(no buffer)"));
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	/* 165 / 1.5 - 10 = 100 LSB of 0.3 uT; -20 + 4 = -16 LSB of 0.305859 */
	assert_true(fabs(r.field_ut[0] - 30.0) < 1e-9);
	assert_true(fabs(r.field_ut[1] - -16 * 0.3 * 261 / 256) < 1e-9);
	assert_true(fabs(r.field_ut[2]) < 1e-9);
	assert_true(r.accel[0] == 3 && r.accel[1] == -1 && r.accel[2] == 255);
	/* a reading that is no number is an error naming the file */
	fake_put(f->magn, "in_magn_z_raw", "x\n");
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "in_magn_z_raw"));
	magn_source_close(s);

	/* an older driver: no attributes, the reading is the count */
	fake_magn_calibration(f, false);
	put_raw(f, m, a);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      NULL, &s, err, sizeof(err)), 0);
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_true(fabs(r.field_ut[0] - 165 * 0.3) < 1e-9);
	magn_source_close(s);
	fclose(log);
}

/* Attributes a buffer has, with the values the tree starts with */
static const char *const buffer_attrs[][2] = {
	{ "buffer/enable", "0" },
	{ "buffer/length", "2" },
	{ "trigger/current_trigger", "" },
	{ "sampling_frequency", "50" },
	{ "current_timestamp_clock", "realtime" },
};

/*
 * Give both devices a buffer (scan elements as the driver's: three axes,
 * the accelerometer's temperature, the timestamp) and character devices
 * that are FIFOs below <root>/dev
 */
static void put_buffers(const struct fake_sysfs *f)
{
	static const char *const chans[][4] = {
		{ "in_accel_x", "0", "le:s16/16>>0", "0" },
		{ "in_accel_y", "1", "le:s16/16>>0", "0" },
		{ "in_accel_z", "2", "le:s16/16>>0", "0" },
		{ "in_temp", "3", "le:u8/16>>0", "1" },
		{ "in_magn_x", "0", "le:s13/16>>0", "0" },
		{ "in_magn_y", "1", "le:s13/16>>0", "0" },
		{ "in_magn_z", "2", "le:s13/16>>0", "0" },
	};
	const char *dirs[2] = { f->dev, f->magn };
	char dir[512], name[600];
	size_t i, k;

	for (k = 0; k < 2; k++) {
		fake_mkdir(dirs[k], "buffer");
		fake_mkdir(dirs[k], "trigger");
		fake_mkdir(dirs[k], "scan_elements");
		for (i = 0; i < sizeof(buffer_attrs) / sizeof(buffer_attrs[0]); i++) {
			snprintf(name, sizeof(name), "%s\n", buffer_attrs[i][1]);
			fake_put(dirs[k], buffer_attrs[i][0], name);
		}
		snprintf(dir, sizeof(dir), "%s/scan_elements", dirs[k]);
		fake_put(dir, "in_timestamp_index", k ? "3" : "4");
		fake_put(dir, "in_timestamp_type", "le:s64/64>>0");
		fake_put(dir, "in_timestamp_en", "0");
		for (i = k ? 4 : 0; i < (k ? 7 : 4); i++) {
			snprintf(name, sizeof(name), "%s_index", chans[i][0]);
			fake_put(dir, name, chans[i][1]);
			snprintf(name, sizeof(name), "%s_type", chans[i][0]);
			fake_put(dir, name, chans[i][2]);
			snprintf(name, sizeof(name), "%s_en", chans[i][0]);
			fake_put(dir, name, chans[i][3]);
		}
	}
	snprintf(dir, sizeof(dir), "%s/dev", f->root);
	mkdir(dir, 0700);
	setenv("AS9888_DEVDIR", dir, 1);
	for (k = 0; k < 2; k++) {
		snprintf(name, sizeof(name), "%s/iio:device%zu", dir, k);
		unlink(name);
		assert_int_equal(mkfifo(name, 0600), 0);
	}
}

/* Every buffer attribute as the tree started with it */
static void buffers_as_found(const struct fake_sysfs *f)
{
	const char *dirs[2] = { f->dev, f->magn };
	char buf[64], dir[512];
	size_t i, k;

	for (k = 0; k < 2; k++) {
		for (i = 0; i < sizeof(buffer_attrs) / sizeof(buffer_attrs[0]); i++) {
			fake_get(dirs[k], buffer_attrs[i][0], buf, sizeof(buf));
			buf[strcspn(buf, "\n")] = '\0';
			if (strcmp(buf, buffer_attrs[i][1]))
				fail_msg("%s/%s left at \"%s\", not \"%s\"", dirs[k],
					 buffer_attrs[i][0], buf, buffer_attrs[i][1]);
		}
		snprintf(dir, sizeof(dir), "%s/scan_elements", dirs[k]);
		fake_get(dir, "in_timestamp_en", buf, sizeof(buf));
		assert_int_equal(atoi(buf), 0);
	}
	snprintf(dir, sizeof(dir), "%s/scan_elements", f->dev);
	fake_get(dir, "in_temp_en", buf, sizeof(buf));
	assert_int_equal(atoi(buf), 1);
}

/* @dir/@name holds @want (a newline after it or not, as sysfs reads) */
static void expect_attr(const char *dir, const char *name, const char *want)
{
	char buf[64];

	fake_get(dir, name, buf, sizeof(buf));
	buf[strcspn(buf, "\n")] = '\0';
	if (strcmp(buf, want))
		fail_msg("%s/%s is \"%s\", not \"%s\"", dir, name, buf, want);
}

/* A sample of three s16 axes and a timestamp, as the layout puts it */
static void put_sample(int fd, int16_t x, int16_t y, int16_t z, int64_t ts)
{
	uint8_t b[16];
	int16_t v[3] = { x, y, z };
	int i;

	for (i = 0; i < 3; i++) {
		b[2 * i] = (uint8_t)((uint16_t)v[i] & 0xff);
		b[2 * i + 1] = (uint8_t)((uint16_t)v[i] >> 8);
	}
	b[6] = b[7] = 0;
	for (i = 0; i < 8; i++)
		b[8 + i] = (uint8_t)((uint64_t)ts >> (8 * i));
	assert_int_equal(write(fd, b, sizeof(b)), (ssize_t)sizeof(b));
}

static int open_writer(const struct fake_sysfs *f, int n)
{
	char path[512];
	int fd;

	snprintf(path, sizeof(path), "%s/dev/iio:device%d", f->root, n);
	fd = open(path, O_WRONLY | O_NONBLOCK);
	assert_true(fd >= 0);

	return fd;
}

static void iio_buffered(void **state)
{
	const char *m[3] = { "7\n", "8\n", "9\n" };
	const char *a[3] = { "1\n", "2\n", "3\n" };
	static const int16_t mx[5] = { 160, 172, 163, 168, 162 };
	static const int16_t ax[5] = { 1, 6, 2, 5, 1 };
	struct fake_sysfs *f = *state;
	char err[512], text[1024], dir[512];
	struct magn_source *s;
	struct magn_reading r;
	int fa, fm, i;
	FILE *log = tmpfile();

	assert_non_null(log);
	fake_magn_calibration(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "10\n");
	fake_put(f->magn, "in_magn_x_calibscale", "1.500000\n");
	put_raw(f, m, a);
	put_buffers(f);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	log_text(log, text, sizeof(text));
	assert_non_null(strstr(text, "both devices' buffers on as9888-dev0 at 100 Hz"));
	assert_non_null(strstr(text, "5 measurements averaged a sample"));
	/* both buffers on the chip's trigger, the axes and the timestamp */
	expect_attr(f->dev, "trigger/current_trigger", "as9888-dev0");
	expect_attr(f->magn, "trigger/current_trigger", "as9888-dev0");
	expect_attr(f->dev, "buffer/enable", "1");
	expect_attr(f->magn, "buffer/enable", "1");
	expect_attr(f->magn, "sampling_frequency", "100");
	expect_attr(f->dev, "sampling_frequency", "100");
	snprintf(dir, sizeof(dir), "%s/scan_elements", f->dev);
	expect_attr(dir, "in_temp_en", "0");
	expect_attr(dir, "in_accel_y_en", "1");

	fa = open_writer(f, 0);
	fm = open_writer(f, 1);
	/*
	 * The magnetometer's first sample has no partner (the accelerometer's
	 * buffer started after it): dropped. Then five measurements, their
	 * two timestamps a few microseconds apart, averaged into one sample
	 */
	put_sample(fm, 1, 1, 1, 1000);
	for (i = 0; i < 5; i++) {
		put_sample(fm, mx[i], -20, 0, 10001000 + i * 10000000LL);
		put_sample(fa, ax[i], -1, 255, 10004000 + i * 10000000LL);
	}
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_int_equal(r.measurements, 5);
	/*
	 * the mean of 160..172 is 165 (none of them is); 165 / 1.5 - 10 =
	 * 100 LSB of 0.3 uT: the driver's calibration undone
	 */
	assert_true(fabs(r.field_ut[0] - 30.0) < 1e-9);
	assert_true(fabs(r.field_ut[1] - -20 * 0.3 * 261 / 256) < 1e-9);
	assert_true(fabs(r.accel[0] - 3) < 1e-12 && r.accel[1] == -1 &&
		    r.accel[2] == 255);
	/* the third measurement of the next sample saturated: no sample */
	for (i = 0; i < 5; i++) {
		put_sample(fm, i == 2 ? 4095 : 7, 0, 0, 60001000 + i * 10000000LL);
		put_sample(fa, 1, 2, 3, 60002000 + i * 10000000LL);
	}
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), -ERANGE);

	/*
	 * the capture ends (the devices' ends closed) after two more
	 * measurements: the sample is their mean and one sysfs read's, and
	 * sysfs reads from then on, one measurement a sample
	 */
	close(fa);
	close(fm);
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_int_equal(r.measurements, 3);
	assert_true(fabs(r.field_ut[0] - (7 / 1.5 - 10) * 0.3) < 1e-9);
	assert_true(fabs(r.accel[0] - 1) < 1e-12 && fabs(r.accel[2] - 3) < 1e-12);
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_int_equal(r.measurements, 1);
	assert_true(fabs(r.field_ut[0] - (7 / 1.5 - 10) * 0.3) < 1e-9);
	assert_true(r.accel[0] == 1 && r.accel[1] == 2 && r.accel[2] == 3);
	log_text(log, text, sizeof(text));
	assert_non_null(strstr(text, "the buffered capture stopped"));
	magn_source_close(s);
	buffers_as_found(f);
	/* no trigger put back as a newline: sysfs takes no empty write */
	fake_get(f->magn, "trigger/current_trigger", text, sizeof(text));
	assert_string_equal(text, "\n");

	/*
	 * another program's buffer on the magnetometer, found after the
	 * accelerometer was set up: no capture, the accelerometer's
	 * attributes put back, sysfs
	 */
	fake_put(f->magn, "buffer/enable", "1\n");
	rewind(log);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	log_text(log, text, sizeof(text));
	assert_non_null(strstr(text, "another program has the buffer enabled"));
	expect_attr(f->dev, "trigger/current_trigger", "");
	expect_attr(f->dev, "buffer/enable", "0");
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_true(r.accel[0] == 1);
	magn_source_close(s);
	fake_put(f->magn, "buffer/enable", "0\n");
	buffers_as_found(f);
	fclose(log);
}

/*
 * The device's frame: the driver's in_magn_mount_matrix read at open;
 * none, or one that is no mount matrix (said), leaves the chip's axes
 */
static void iio_mount(void **state)
{
	const char *m[3] = { "165\n", "-20\n", "0\n" };
	const char *a[3] = { "3\n", "-1\n", "255\n" };
	struct fake_sysfs *f = *state;
	double mount[AS9888_AXES][AS9888_AXES];
	char err[512], text[1024], path[600];
	struct magn_source *s;
	FILE *log = tmpfile();

	assert_non_null(log);
	fake_magn_calibration(f, false);
	put_raw(f, m, a);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	assert_false(magn_source_mount(s, mount));
	magn_source_close(s);

	fake_put(f->magn, "in_magn_mount_matrix", "0, -1, 0; 1, 0, 0; 0, 0, 1\n");
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	assert_true(magn_source_mount(s, mount));
	assert_true(mount[0][1] == -1 && mount[1][0] == 1 && mount[2][2] == 1 &&
		    mount[0][0] == 0);
	magn_source_close(s);

	/* a device tree's long decimals: 170 characters, read whole */
	fake_put(f->magn, "in_magn_mount_matrix",
		 "0.707106781186548, -0.707106781186548, 0.000000000000000; "
		 "0.707106781186548, 0.707106781186548, 0.000000000000000; "
		 "0.000000000000000, 0.000000000000000, 1.000000000000000\n");
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	assert_true(magn_source_mount(s, mount));
	assert_true(fabs(mount[0][1] + 0.707106781186548) < 1e-12 &&
		    mount[2][2] == 1);
	magn_source_close(s);

	fake_put(f->magn, "in_magn_mount_matrix", "0, -1, 0; 1, 0, 0\n");
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      log, &s, err, sizeof(err)), 0);
	assert_false(magn_source_mount(s, mount));
	log_text(log, text, sizeof(text));
	assert_non_null(strstr(text, "in_magn_mount_matrix reads \"0, -1, 0; 1, 0, 0\", not a mount matrix: turns are named in the chip's axes"));
	magn_source_close(s);
	snprintf(path, sizeof(path), "%s/in_magn_mount_matrix", f->magn);
	assert_int_equal(unlink(path), 0);
	fclose(log);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(chip_samples),
		cmocka_unit_test(chip_other_refused),
		cmocka_unit_test(iio_samples),
		cmocka_unit_test(iio_buffered),
		cmocka_unit_test(iio_mount),
	};

	return cmocka_run_group_tests_name("magn-source", tests,
					  fake_sysfs_setup, fake_sysfs_teardown);
}
