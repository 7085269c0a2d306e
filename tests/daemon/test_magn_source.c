// SPDX-License-Identifier: GPL-2.0
/*
 * magn-calibrate's samples: from the simulated chip's registers (the
 * built-in unit's field of 20, -5, -40 uT, lying with +z up), refused
 * on another chip; from the driver's attributes with its own calibration
 * taken out again; an overflow is a sample to skip, not an error.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "backend_sim.h"
#include "fake_sysfs.h"
#include "magn_source.h"

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
		assert_true(r.t_ns >= before + 7300000);	/* t_MAG */
		for (axis = 0; axis < AS9888_AXES; axis++)
			sum[axis] += r.field_ut[axis];
		/* the unit's "up" is +z: about +256 LSB there, little elsewhere */
		assert_true(r.accel[2] > 200 && fabs(r.accel[0]) < 40 &&
			    fabs(r.accel[1]) < 40);
	}
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
	char err[512];

	fake_magn_calibration(f, true);
	fake_put(f->magn, "in_magn_x_calibbias", "10\n");
	fake_put(f->magn, "in_magn_x_calibscale", "1.500000\n");
	fake_put(f->magn, "in_magn_y_calibbias", "-4\n");
	put_raw(f, m, a);
	assert_int_equal(magn_source_open_iio(f->dev, f->magn, fake_example_eeprom,
					      &s, err, sizeof(err)), 0);
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
					      &s, err, sizeof(err)), 0);
	assert_int_equal(magn_source_read(s, &r, err, sizeof(err)), 0);
	assert_true(fabs(r.field_ut[0] - 165 * 0.3) < 1e-9);
	magn_source_close(s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(chip_samples),
		cmocka_unit_test(chip_other_refused),
		cmocka_unit_test(iio_samples),
	};

	return cmocka_run_group_tests_name("magn-source", tests,
					  fake_sysfs_setup, fake_sysfs_teardown);
}
