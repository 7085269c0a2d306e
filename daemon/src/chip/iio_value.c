// SPDX-License-Identifier: GPL-2.0
/* The AS9888 driver's attribute values as text (iio_value.h). */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "chip/iio_value.h"

#define IIO_MILLI_PLACES	3
#define IIO_MILLI		1000
/* Integer digits beyond this are out of range: 10^12 * 10^6 < 2^63 */
#define IIO_INT_DIGITS_MAX	12
/* Beyond any adjusted self-test reading: 4096 * (255 + 128) / 256 */
#define IIO_SELFTEST_ABS_MAX	8192

static bool is_digit(char c)
{
	return c >= '0' && c <= '9';
}

/*
 * A decimal at the start of @s: an optional "-", digits, and optionally
 * "." with 1..@places digits, followed by @stop (and nothing else). Its
 * value times 10^@places in *@out, and where it ends in *@end.
 */
static int parse_decimal(const char *s, unsigned int places, char stop,
			 int64_t *out, const char **end)
{
	unsigned int n_int = 0, n_frac = 0;
	int64_t ip = 0, fp = 0;
	bool neg = *s == '-';

	if (neg)
		s++;
	for (; is_digit(*s); s++, n_int++)
		if (n_int < IIO_INT_DIGITS_MAX)
			ip = ip * 10 + (*s - '0');
	if (!n_int)
		return -EINVAL;
	if (*s == '.') {
		for (s++; is_digit(*s); s++, n_frac++) {
			if (n_frac == places)
				return -EINVAL;
			fp = fp * 10 + (*s - '0');
		}
		if (!n_frac)
			return -EINVAL;
	}
	if (*s != stop)
		return -EINVAL;
	if (n_int > IIO_INT_DIGITS_MAX)
		return -ERANGE;
	for (; n_frac < places; n_frac++)
		fp *= 10;
	for (n_frac = 0; n_frac < places; n_frac++)
		ip *= 10;
	*out = neg ? -(ip + fp) : ip + fp;
	*end = s;

	return 0;
}

int iio_int_parse(const char *s, long min, long max, long *out)
{
	const char *end;
	int64_t v;
	int ret;

	ret = parse_decimal(s, 0, '\0', &v, &end);
	if (ret)
		return ret;
	if (v < min || v > max)
		return -ERANGE;
	*out = (long)v;

	return 0;
}

const char *iio_value_strerror(int err)
{
	switch (err) {
	case -EINVAL:
		return "malformed: not a plain decimal number";
	case -ERANGE:
		return "out of range";
	case -ENODATA:
		return "no value yet";
	default:
		return strerror(-err);
	}
}

int iio_parse_selftest_verdict(const char *s, enum iio_selftest_verdict *v)
{
	if (!strcmp(s, "pass"))
		*v = IIO_SELFTEST_PASS;
	else if (!strcmp(s, "fail"))
		*v = IIO_SELFTEST_FAIL;
	else if (!strcmp(s, "none"))
		*v = IIO_SELFTEST_NONE;
	else
		return -EINVAL;

	return 0;
}

int iio_parse_selftest_readings(const char *s, int32_t adj_q8[AS9888_AXES])
{
	int32_t q8[AS9888_AXES];
	int64_t milli;
	int axis, ret;

	if (!strcmp(s, "none"))
		return -ENODATA;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = parse_decimal(s, IIO_MILLI_PLACES,
				    axis < AS9888_AXES - 1 ? ' ' : '\0',
				    &milli, &s);
		if (ret || milli <= -IIO_SELFTEST_ABS_MAX * IIO_MILLI ||
		    milli >= IIO_SELFTEST_ABS_MAX * IIO_MILLI)
			return -EINVAL;
		/* three places are finer than 1/256: the Q8 value is exact */
		q8[axis] = (int32_t)as9888_div_round_s64(milli * AS9888_Q8_ONE,
							 IIO_MILLI);
		s++;
	}
	memcpy(adj_q8, q8, sizeof(q8));

	return 0;
}

int iio_parse_rate_max(const char *s, long max, long *hz)
{
	long best = 0;
	int64_t v;
	int ret;

	for (;;) {
		const char *end;

		/* each rate but the last ends at a space */
		ret = parse_decimal(s, 0, strchr(s, ' ') ? ' ' : '\0', &v, &end);
		if (ret)
			return ret;
		if (v < 1 || v > max)
			return -ERANGE;
		if (v > best)
			best = (long)v;
		if (!*end)
			break;
		s = end + 1;
	}
	*hz = best;

	return 0;
}
