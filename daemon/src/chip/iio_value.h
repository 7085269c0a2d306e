/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 driver's attribute values as text, parsed and formatted
 * (Documentation/ABI/testing/sysfs-bus-iio-as9888): integers, the
 * self-test verdict and the adjusted
 * self-test readings of debugfs. Pure text, no files: every parser refuses
 * a malformed or out-of-range value whole and leaves its output untouched.
 */
#ifndef AS9888_IIO_VALUE_H
#define AS9888_IIO_VALUE_H

#include <stddef.h>
#include <stdint.h>

#include "as9888_calib.h"

/* A decimal integer within @min..@max: 0, -EINVAL (malformed) or -ERANGE */
int iio_int_parse(const char *s, long min, long max, long *out);

/* What iio_int_parse() said, for a message */
const char *iio_value_strerror(int err);

/* The selftest attribute's one word */
enum iio_selftest_verdict {
	IIO_SELFTEST_NONE,	/* "none": no test has run */
	IIO_SELFTEST_PASS,	/* "pass" */
	IIO_SELFTEST_FAIL,	/* "fail" */
};

/* "pass", "fail" or "none": 0, or -EINVAL for anything else */
int iio_parse_selftest_verdict(const char *s, enum iio_selftest_verdict *v);

/*
 * debugfs selftest_readings: "X Y Z", the adjusted readings in LSB with up
 * to three decimals, back in Q8 exactly (1/1000 is finer than 1/256).
 * 0, -ENODATA for "none" (no test has run), -EINVAL for anything else or a
 * reading no chip gives (|X| >= 8192).
 */
int iio_parse_selftest_readings(const char *s, int32_t adj_q8[AS9888_AXES]);

/*
 * sampling_frequency_available of the data-ready trigger's rates, whole
 * hertz separated by single spaces ("1 2 5 ... 400"): the fastest, within
 * 1..@max. 0, -EINVAL (malformed, empty, a fraction) or -ERANGE (a rate
 * outside 1..@max); *@hz is left untouched on error.
 */
int iio_parse_rate_max(const char *s, long max, long *hz);

#endif
