// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the IIO buffer layout the daemon builds from sysfs.
 * The input is up to 8 lines "INDEX TYPE" (scan_elements' _index and
 * _type), then a line "--" and the bytes of one sample. Every channel the
 * layout places lies within the sample, and its value is read from there
 * only.
 */
#include <stdio.h>

#include "fuzz_text.h"
#include "iio_scan.h"

#define CHANNELS_MAX	8
#define SAMPLE_MAX	256

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct iio_scan_channel c[CHANNELS_MAX];
	uint8_t sample[SAMPLE_MAX] = { 0 };
	char *text = fuzz_text(data, size), *line, *next, *raw = NULL;
	unsigned int n = 0, i;
	int bytes;

	if (!text)
		return 0;
	for (line = text; line && n < CHANNELS_MAX; line = next) {
		char type[64];
		unsigned int index;

		next = strchr(line, '\n');
		if (next)
			*next++ = '\0';
		if (!strcmp(line, "--")) {
			raw = next;
			break;
		}
		if (sscanf(line, "%u %63s", &index, type) != 2)
			continue;
		memset(&c[n], 0, sizeof(c[n]));
		if (iio_scan_parse_type(type, &c[n]))
			continue;
		if (!c[n].bytes || c[n].bytes > 8 || c[n].realbits > 8 * c[n].bytes)
			abort();
		c[n++].index = index;
	}
	bytes = n ? iio_scan_layout(c, n) : -1;
	if (bytes > 0) {
		if (bytes > SAMPLE_MAX) {
			free(text);
			return 0;
		}
		if (raw)
			memcpy(sample, raw, strnlen(raw, (size_t)bytes));
		for (i = 0; i < n; i++) {
			if (c[i].offset + c[i].bytes > (unsigned int)bytes ||
			    (unsigned int)bytes % c[i].bytes)
				abort();
			iio_scan_value64(&c[i], sample);
			if (c[i].bytes <= 4)
				iio_scan_value(&c[i], sample);
		}
	}
	free(text);

	return 0;
}
