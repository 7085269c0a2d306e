// SPDX-License-Identifier: GPL-2.0
/*
 * The HAL core's parsing and conversion (hal/src): attributes, scan types
 * and sample decoding, the mount matrix, the rates, the configuration,
 * finding the devices; against a sysfs tree like the driver's
 * (tests/daemon/fake_sysfs.c). Every bad value must give an error that
 * names the file and never a crash.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "as9888_hal.h"
#include "fake_sysfs.h"
#include "hal_attr.h"
#include "hal_find.h"
#include "iio_mount.h"
#include "hal_layout.h"
#include "hal_stream.h"
#include "hal_test_tree.h"

static void attributes(void **state)
{
	struct fake_sysfs *f = *state;
	char err[512], buf[16];
	double d;
	long l;

	fake_put(f->dev, "a", "0.009576806\n");
	assert_int_equal(hal_attr_double(f->dev, "a", &d, err, sizeof(err)), 0);
	assert_float_equal(d, 0.009576806, 1e-12);
	fake_put(f->dev, "a", "-625\n");
	assert_int_equal(hal_attr_long(f->dev, "a", &l, err, sizeof(err)), 0);
	assert_int_equal(l, -625);
	/* each bad value refused, with the file and the text in the message */
	static const char *const bad[] = { "", "\n", "abc\n", "1.5x\n", " 1\n", "nan\n",
					   "inf\n", "1e999\n" };
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		fake_put(f->dev, "a", bad[i]);
		assert_int_equal(hal_attr_double(f->dev, "a", &d, err, sizeof(err)), -EINVAL);
		assert_non_null(strstr(err, "/a: \""));
	}
	fake_put(f->dev, "a", "1.5\n");
	assert_int_equal(hal_attr_long(f->dev, "a", &l, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "not a decimal integer"));
	fake_put_bytes(f->dev, "a", "1\0002", 3);
	assert_int_equal(hal_attr_read(f->dev, "a", buf, sizeof(buf), err, sizeof(err)),
			 -EINVAL);
	assert_non_null(strstr(err, "NUL"));
	fake_put(f->dev, "a", "0123456789abcdef0123\n");
	assert_int_equal(hal_attr_read(f->dev, "a", buf, sizeof(buf), err, sizeof(err)),
			 -EOVERFLOW);
	assert_int_equal(hal_attr_read(f->dev, "missing", buf, sizeof(buf), err, sizeof(err)),
			 -ENOENT);
	assert_non_null(strstr(err, "/missing: cannot read"));
}

static void mount_matrix(void **state)
{
	double m[3][3], out[3];
	static const double in[3] = { 1, 2, 3 };

	assert_int_equal(iio_mount_parse("0, 1, 0; -1, 0, 0; 0, 0, 1", m), 0);
	iio_mount_apply(m, in, out);
	/* a non-identity matrix: rows times the vector */
	assert_float_equal(out[0], 2, 1e-12);
	assert_float_equal(out[1], -1, 1e-12);
	assert_float_equal(out[2], 3, 1e-12);
	assert_int_equal(iio_mount_parse("0.5, 0, 0; 0, 0.866025, 0.5; 0, -0.5, 0.866025\n", m), 0);
	assert_float_equal(m[1][1], 0.866025, 1e-12);
	static const char *const bad[] = {
		"", "1, 0, 0; 0, 1, 0", "1, 0, 0; 0, 1, 0; 0, 0, 1; 1",
		"1 0 0 0 1 0 0 0 1", "1, 0, 0; 0, x, 0; 0, 0, 1", "nan, 0, 0; 0, 1, 0; 0, 0, 1",
		"1e300, 0, 0; 0, 1, 0; 0, 0, 1",
	};
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		assert_int_equal(iio_mount_parse(bad[i], m), -EINVAL);
}

static void rates(void **state)
{
	long r[4];

	assert_int_equal(hal_parse_rates("1 2 5 10", r, 4), 4);
	assert_int_equal(r[3], 10);
	assert_int_equal(hal_parse_rates("100", r, 4), 1);
	static const char *const bad[] = { "", "1 2 5 10 20", "1  2", "2 1", "1.5",
					   "0 1", "-1", " 1", "1,2", "99999999999999999999" };
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		assert_int_equal(hal_parse_rates(bad[i], r, 4), -EINVAL);
}

/* sign, shift, storage and byte order decoded, and the scale applied */
static void decoding(void **state)
{
	struct fake_sysfs *f = *state;
	struct hal_layout l;
	uint8_t s[32] = { 0 };
	int32_t raw[3];
	double v[3];
	int64_t ts;
	char err[512];

	hal_tree_channels(f);
	/* x: be:s13/16>>3 at index 0; y: le:u10/16>>2; z: le:s12/32>>4 */
	fake_put(f->magn, "scan_elements/in_magn_x_type", "be:s13/16>>3\n");
	fake_put(f->magn, "scan_elements/in_magn_y_type", "le:u10/16>>2\n");
	fake_put(f->magn, "scan_elements/in_magn_z_type", "le:s12/32>>4\n");
	fake_put(f->magn, "in_magn_y_offset", "-512\n");
	assert_int_equal(hal_layout_read(f->magn, "magn", 100, &l, err, sizeof(err)), 0);
	/* x at 0 (2 bytes), y at 2, z aligned at 4 (4 bytes), ts at 8: 16 bytes */
	assert_int_equal(l.chan[2].offset, 4);
	assert_int_equal(l.chan[3].offset, 8);
	assert_int_equal(l.sample_bytes, 16);
	/* x = -1000: 13-bit two's complement, shifted 3, big-endian */
	uint16_t xb = (uint16_t)((-1000 & 0x1fff) << 3);
	s[0] = (uint8_t)(xb >> 8);
	s[1] = (uint8_t)xb;
	/* y = 700 unsigned, shifted 2, little-endian, with junk in the low bits */
	uint16_t yb = (uint16_t)(700 << 2 | 3);
	s[2] = (uint8_t)yb;
	s[3] = (uint8_t)(yb >> 8);
	/* z = -2000 in 12 bits, shifted 4 in 32 bits */
	uint32_t zb = (uint32_t)(-2000 & 0xfff) << 4;
	memcpy(&s[4], &zb, 4);
	int64_t t = 1234567890123456789;
	memcpy(&s[8], &t, 8);
	assert_false(hal_layout_decode(&l, s, raw, v, &ts));
	assert_int_equal(raw[0], -1000);
	assert_int_equal(raw[1], 700);
	assert_int_equal(raw[2], -2000);
	assert_true(ts == t);
	/* gauss x 100: uT; the offset added before the scale */
	assert_float_equal(v[0], -1000 * 0.003 * 100, 1e-9);
	assert_float_equal(v[1], (700 - 512) * 0.00305859 * 100, 1e-9);
	/* the saturation mark: the signed limit of the channel */
	xb = (uint16_t)((4095 & 0x1fff) << 3);
	s[0] = (uint8_t)(xb >> 8);
	s[1] = (uint8_t)xb;
	assert_true(hal_layout_decode(&l, s, raw, v, &ts));
}

static void layout_errors(void **state)
{
	struct fake_sysfs *f = *state;
	struct hal_layout l;
	char err[512];
	static const struct { const char *file, *text, *says; } bad[] = {
		{ "scan_elements/in_accel_x_type", "le:s16\n", "no IIO scan type" },
		{ "scan_elements/in_accel_x_type", "xx:s16/16>>0\n", "no IIO scan type" },
		{ "scan_elements/in_accel_y_type", "le:s17/16>>0\n", "no IIO scan type" },
		{ "scan_elements/in_accel_z_type", "le:s12/16>>5\n", "no IIO scan type" },
		{ "scan_elements/in_accel_z_type", "le:s64/64>>0\n", "more than an axis" },
		{ "scan_elements/in_accel_x_index", "-1\n", "no scan index" },
		{ "scan_elements/in_accel_x_index", "one\n", "not a decimal integer" },
		{ "scan_elements/in_accel_y_index", "0\n", "share an index" },
		{ "scan_elements/in_timestamp_type", "le:s32/32>>0\n", "not 64 bits" },
		{ "in_accel_scale", "fast\n", "not a decimal number" },
		{ "in_accel_scale", "0\n", "scale is 0" },
		{ "in_accel_mount_matrix", "1, 0, 0\n", "no mount matrix" },
	};

	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		char was[128];

		hal_tree_channels(f);
		fake_get(f->dev, bad[i].file, was, sizeof(was));
		fake_put(f->dev, bad[i].file, bad[i].text);
		memset(err, 0, sizeof(err));
		assert_int_equal(hal_layout_read(f->dev, "accel", 1, &l, err, sizeof(err)),
				 -EINVAL);
		if (!strstr(err, bad[i].says))
			fail_msg("%s = %s: \"%s\" does not say \"%s\"", bad[i].file,
				 bad[i].text, err, bad[i].says);
		fake_put(f->dev, bad[i].file, was);
	}
	/* no scale at all */
	hal_tree_channels(f);
	hal_tree_remove(f->dev, "in_accel_scale");
	assert_int_equal(hal_layout_read(f->dev, "accel", 1, &l, err, sizeof(err)), -ENOENT);
	assert_non_null(strstr(err, "in_accel_scale"));
}

static void config(void **state)
{
	struct as9888_hal_config c, was;
	char err[256];

	as9888_hal_config_defaults(&c);
	assert_string_equal(c.sysfs, "/sys");
	assert_int_equal(as9888_hal_config_parse("# two chips\nparent 1-000d\n\n"
						 "  trigger  as9888-dev3  # the second\n"
						 "feed_interval_ms 2000", &c, err, sizeof(err)), 0);
	assert_string_equal(c.parent, "1-000d");
	assert_string_equal(c.trigger, "as9888-dev3");
	assert_int_equal(c.feed_interval_ms, 2000);
	was = c;
	static const struct { const char *text, *says; } bad[] = {
		{ "parent 1-000c\ncolour blue\n", "line 2: unknown key" },
		{ "parent a b\n", "line 1: one value" },
		{ "feed_interval_ms 10\n", "100..60000" },
		{ "feed_interval_ms -1000\n", "100..60000" },
		{ "feed_interval_ms 1000x\n", "100..60000" },
		{ "parent 0123456789012345678901234567890123456789012345678901234567890123456789\n",
		  "too long" },
	};
	for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		assert_int_equal(as9888_hal_config_parse(bad[i].text, &c, err, sizeof(err)),
				 -EINVAL);
		assert_non_null(strstr(err, bad[i].says));
		/* nothing taken from a refused text */
		assert_memory_equal(&c, &was, sizeof(c));
	}
	assert_int_equal(as9888_hal_config_load("/nonexistent/hal.conf", &c, err, sizeof(err)),
			 -ENOENT);
	assert_non_null(strstr(err, "/nonexistent/hal.conf"));
}

static void finding(void **state)
{
	struct fake_sysfs *f = *state;
	struct hal_devices d;
	char err[512];

	hal_tree_channels(f);
	assert_int_equal(hal_find_devices(f->root, "/dev", "", "", &d, err, sizeof(err)), 0);
	assert_string_equal(d.accel_node, "/dev/iio:device0");
	assert_string_equal(d.magn_node, "/dev/iio:device1");
	assert_string_equal(d.trigger, "as9888-dev0");
	assert_non_null(strstr(d.magn, "iio:device1"));
	/* by the bus device, for a board with two chips */
	assert_int_equal(hal_find_devices(f->root, "/dev", "1-000c", "hr1", &d, err,
					  sizeof(err)), 0);
	assert_string_equal(d.trigger, "hr1");
	assert_int_equal(hal_find_devices(f->root, "/dev", "1-000d", "", &d, err,
					  sizeof(err)), -ENODEV);
	assert_non_null(strstr(err, "below bus device 1-000d"));
	/* no data-ready trigger (no interrupt wired): the devices' own is kept */
	hal_tree_remove(f->root, "bus/iio/devices/trigger0/name");
	assert_int_equal(hal_find_devices(f->root, "/dev", "", "", &d, err, sizeof(err)), 0);
	assert_string_equal(d.trigger, "");
	/* no magnetometer device */
	fake_magn_present(f, false);
	assert_int_equal(hal_find_devices(f->root, "/dev", "", "", &d, err, sizeof(err)),
			 -ENODEV);
	assert_non_null(strstr(err, "no as9888-magn"));
	fake_magn_present(f, true);
	/* no IIO at all */
	assert_int_equal(hal_find_devices("/nonexistent", "/dev", "", "", &d, err,
					  sizeof(err)), -ENOENT);
	assert_non_null(strstr(err, "/nonexistent/bus/iio/devices"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(attributes, fake_sysfs_setup, fake_sysfs_teardown),
		cmocka_unit_test(mount_matrix),
		cmocka_unit_test(rates),
		cmocka_unit_test_setup_teardown(decoding, fake_sysfs_setup, fake_sysfs_teardown),
		cmocka_unit_test_setup_teardown(layout_errors, fake_sysfs_setup, fake_sysfs_teardown),
		cmocka_unit_test(config),
		cmocka_unit_test_setup_teardown(finding, fake_sysfs_setup, fake_sysfs_teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
