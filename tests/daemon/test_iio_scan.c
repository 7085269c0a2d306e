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

	assert_int_equal(iio_scan_parse_type("le:s64/64>>0", &c), 0);
	assert_int_equal(c.bytes, 8);
	assert_int_equal(c.realbits, 64);
	assert_int_equal(iio_scan_parse_type("le:s65/64>>0", &c), -EINVAL);
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

	/* 10 bytes of channels, the sample padded to 4 as the IIO core does */
	assert_int_equal(iio_scan_layout(c, 3), 12);
	assert_int_equal(c[0].offset, 0);
	assert_int_equal(c[1].offset, 4);
	assert_int_equal(c[2].offset, 8);
}

/* The driver's buffer with its timestamp: 4 x 16 bits, then 64 bits at 8 */
static void layout_timestamp(void **state)
{
	struct iio_scan_channel c[5] = {
		{ .index = 0, .bytes = 2 }, { .index = 1, .bytes = 2 },
		{ .index = 2, .bytes = 2 }, { .index = 6, .bytes = 2 },
		{ .index = 7, .bytes = 8 },
	};

	assert_int_equal(iio_scan_layout(c, 5), 16);
	assert_int_equal(c[4].offset, 8);
	assert_int_equal(iio_scan_layout(c, 3), 6);
	/* one 16-bit channel and the timestamp: 2 bytes, padding, 8 */
	c[1] = c[4];
	assert_int_equal(iio_scan_layout(c, 2), 16);
	assert_int_equal(c[1].offset, 8);
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

/* A timestamp: le:s64/64>>0, nanoseconds beyond 32 bits */
static void values64(void **state)
{
	static const uint8_t sample[] = {
		0x15, 0xcd, 0x5b, 0x07, 0x01, 0x00, 0x00, 0x00,
		0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff,
	};
	struct iio_scan_channel c;

	assert_int_equal(iio_scan_parse_type("le:s64/64>>0", &c), 0);
	c.offset = 0;
	assert_true(iio_scan_value64(&c, sample) == 0x1075bcd15LL);
	c.offset = 8;
	assert_true(iio_scan_value64(&c, sample) == -1);
	/* a 16-bit channel the same through both */
	c = (struct iio_scan_channel){ .offset = 1, .bytes = 2, .realbits = 16,
				       .is_signed = true };
	assert_true(iio_scan_value64(&c, sample) == (int16_t)0x5bcd);
	assert_int_equal(iio_scan_value(&c, sample), (int16_t)0x5bcd);
	c.offset = 8;
	assert_true(iio_scan_value64(&c, sample) == -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(type_accepted),
		cmocka_unit_test(type_refused),
		cmocka_unit_test(layout_follows_index),
		cmocka_unit_test(layout_aligns),
		cmocka_unit_test(layout_timestamp),
		cmocka_unit_test(layout_refuses_duplicate_index),
		cmocka_unit_test(values),
		cmocka_unit_test(values64),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
