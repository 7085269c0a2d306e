// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the driver's attribute values as the daemon reads them
 * (iio_value.h): the self-test verdict and the debugfs self-test readings,
 * and integers. Readings and integers accepted are within their limits.
 */
#include "fuzz_text.h"
#include "chip/iio_value.h"

#define READING_LIMIT_Q8	(8192 * 256)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *s = fuzz_text(data, size);
	int32_t adj[AS9888_AXES];
	enum iio_selftest_verdict v;
	long l;
	int axis;

	if (!s)
		return 0;
	iio_parse_selftest_verdict(s, &v);
	if (!iio_parse_selftest_readings(s, adj))
		for (axis = 0; axis < AS9888_AXES; axis++)
			if (adj[axis] >= READING_LIMIT_Q8 || adj[axis] <= -READING_LIMIT_Q8)
				abort();
	if (!iio_int_parse(s, -1000, 1000, &l) && (l < -1000 || l > 1000))
		abort();
	free(s);

	return 0;
}
