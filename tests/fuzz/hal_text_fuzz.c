// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the text the sensors HAL's core reads (hal/): its
 * configuration file, the mount matrix, sampling_frequency_available and
 * numeric attributes. What is accepted is within its limits; what is
 * refused leaves the configuration as it was.
 */
#include <math.h>
#include <string.h>

#include "as9888_hal.h"
#include "fuzz_text.h"
#include "hal_attr.h"
#include "hal_layout.h"
#include "iio_mount.h"
#include "hal_stream.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *s = fuzz_text(data, size);
	struct as9888_hal_config c, was;
	double m[3][3], d;
	long rates[8], l;
	char err[256];
	int n, i;

	if (!s)
		return 0;
	as9888_hal_config_defaults(&c);
	was = c;
	if (as9888_hal_config_parse(s, &c, err, sizeof(err))) {
		if (memcmp(&c, &was, sizeof(c)))
			abort();
	} else if (c.feed_interval_ms < 100 || c.feed_interval_ms > 60000 ||
		   !memchr(c.parent, '\0', sizeof(c.parent)) ||
		   !memchr(c.socket, '\0', sizeof(c.socket))) {
		abort();
	}
	if (!iio_mount_parse(s, m))
		for (i = 0; i < 9; i++)
			if (!isfinite(m[i / 3][i % 3]))
				abort();
	n = hal_parse_rates(s, rates, 8);
	for (i = 1; i < n; i++)
		if (rates[i] <= rates[i - 1] || rates[0] < 1)
			abort();
	if (!hal_parse_double(s, &d) && !isfinite(d))
		abort();
	hal_parse_long(s, &l);
	free(s);

	return 0;
}
