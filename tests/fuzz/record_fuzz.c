// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the calibration record parser must never crash, hang
 * or read out of bounds, and whatever it accepts must be a valid record
 * that formats back to text it accepts again.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "record.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct calib_record rec, again;
	char text[RECORD_MAX_SIZE], err[256];
	int len;

	if (record_parse((const char *)data, size, &rec, err, sizeof(err)))
		return 0;
	if (record_validate(&rec, err, sizeof(err)))
		abort();
	len = record_format(&rec, text, sizeof(text));
	if (len < 0 || record_parse(text, (size_t)len, &again, err, sizeof(err)))
		abort();
	if (memcmp(&rec, &again, sizeof(rec)))
		abort();

	return 0;
}
