// SPDX-License-Identifier: GPL-2.0
/*
 * What the test engine reads from the driver's buffer: sample layouts from
 * _index/_type and values from sample bytes. Bad types are refused, never
 * half-used.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "iio_scan.h"

static void type_accepted(void **state)
{
	struct iio_scan_channel c;

	assert_int_equal(iio_scan_parse_type("le:s12/16>>0", &c), 0);
	assert_true(c.is_signed);
	assert_false(c.big_endian);
	assert_int_equal(c.bytes, 2);
	assert_int_equal(c.realbits, 12);
	assert_int_equal(c.shift, 0);

	assert_int_equal(iio_scan_parse_type("be:u8/16>>4", &c), 0);
	assert_false(c.is_signed);
	assert_true(c.big_endian);
	assert_int_equal(c.shift, 4);

	assert_int_equal(iio_scan_parse_type("le:s64/64>>0", &c), -EINVAL);
	assert_int_equal(iio_scan_parse_type("le:u32/32>>0", &c), 0);
	assert_int_equal(c.bytes, 4);
}

static void type_refused(void **state)
{
	static const char *const bad[] = {
		"", "le", "le:", "le:s12", "le:s12/16", "xe:s12/16>>0",
		"le:x12/16>>0", "le:s0/16>>0", "le:s17/16>>0", "le:s12/16>>5",
		"le:s12/24>>0", "le:s-1/16>>0", "le:s12/16>>-1",
		"le:s12/16>>0 junk", "le:s12/16X2>>0", "LE:s12/16>>0",
	};
	struct iio_scan_channel c = { .bytes = 99 };
	size_t i;

	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		if (iio_scan_parse_type(bad[i], &c) != -EINVAL)
			fail_msg("accepted \"%s\"", bad[i]);
	}
	/* nothing half-parsed */
	assert_int_equal(c.bytes, 99);
}

/* The driver's buffer: accel X/Y/Z (0..2) and temperature (6), 16 bits each */
static void layout_follows_index(void **state)
{
	struct iio_scan_channel c[4] = {
		{ .index = 6, .bytes = 2 }, { .index = 0, .bytes = 2 },
		{ .index = 2, .bytes = 2 }, { .index = 1, .bytes = 2 },
	};

	assert_int_equal(iio_scan_layout(c, 4), 8);
	assert_int_equal(c[1].offset, 0);
	assert_int_equal(c[3].offset, 2);
	assert_int_equal(c[2].offset, 4);
	assert_int_equal(c[0].offset, 6);
}

static void layout_aligns(void **state)
{
	struct iio_scan_channel c[3] = {
		{ .index = 0, .bytes = 1 }, { .index = 1, .bytes = 4 },
		{ .index = 2, .bytes = 2 },
	};

	assert_int_equal(iio_scan_layout(c, 3), 10);
	assert_int_equal(c[0].offset, 0);
	assert_int_equal(c[1].offset, 4);
	assert_int_equal(c[2].offset, 8);
}

static void layout_refuses_duplicate_index(void **state)
{
	struct iio_scan_channel c[2] = {
		{ .index = 3, .bytes = 2 }, { .index = 3, .bytes = 2 },
	};

	assert_int_equal(iio_scan_layout(c, 2), -EINVAL);
}

static void values(void **state)
{
	/* -2048, 2047, a temperature code 0x88 in u8/16, big-endian -1 */
	static const uint8_t sample[] = {
		0x00, 0xf8, 0xff, 0x07, 0x88, 0x00, 0xff, 0xff, 0x30, 0x01,
	};
	struct iio_scan_channel c = { .bytes = 2, .realbits = 12, .is_signed = true };

	c.offset = 0;
	assert_int_equal(iio_scan_value(&c, sample), -2048);
	c.offset = 2;
	assert_int_equal(iio_scan_value(&c, sample), 2047);
	c = (struct iio_scan_channel){ .offset = 4, .bytes = 2, .realbits = 8 };
	assert_int_equal(iio_scan_value(&c, sample), 0x88);
	c = (struct iio_scan_channel){ .offset = 6, .bytes = 2, .realbits = 16,
				       .is_signed = true, .big_endian = true };
	assert_int_equal(iio_scan_value(&c, sample), -1);
	/* 0x0130 >> 4 = 0x13, 4 bits: 0x3, signed: 3 */
	c = (struct iio_scan_channel){ .offset = 8, .bytes = 2, .realbits = 4,
				       .shift = 4, .is_signed = true };
	assert_int_equal(iio_scan_value(&c, sample), 3);
	/* 0x0130 >> 0, 6 bits: 0x30 = -16 signed */
	c.shift = 0;
	c.realbits = 6;
	assert_int_equal(iio_scan_value(&c, sample), -16);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(type_accepted),
		cmocka_unit_test(type_refused),
		cmocka_unit_test(layout_follows_index),
		cmocka_unit_test(layout_aligns),
		cmocka_unit_test(layout_refuses_duplicate_index),
		cmocka_unit_test(values),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
