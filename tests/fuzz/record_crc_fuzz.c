// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the calibration record parser past its checksum.
 * Random text almost never carries a valid crc32, so this target drops any
 * crc32 line and appends the right one: every input reaches the key,
 * range and consistency checks. What the parser accepts must validate,
 * format back, and parse again to the same record.
 */
#include <stdio.h>

#include "fuzz_text.h"
#include "common/record.h"

#define CRC_LINE	"crc32 = "

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char text[RECORD_MAX_SIZE + 32], out[RECORD_MAX_SIZE], err[256];
	struct calib_record rec, again;
	const char *crc;
	size_t len = size;
	int n;

	if (size > RECORD_MAX_SIZE)
		return 0;
	memcpy(text, data, size);
	/* everything from a crc32 line at a line start on is replaced */
	crc = memmem(text, len, CRC_LINE, strlen(CRC_LINE));
	if (crc && (crc == text || crc[-1] == '\n'))
		len = (size_t)(crc - text);
	if (len && text[len - 1] != '\n')
		text[len++] = '\n';
	n = snprintf(text + len, sizeof(text) - len, CRC_LINE "%08x\n",
		     record_crc32(text, len));
	len += (size_t)n;

	if (record_parse(text, len, &rec, err, sizeof(err)))
		return 0;
	if (record_validate(&rec, err, sizeof(err)))
		abort();
	n = record_format(&rec, out, sizeof(out));
	if (n < 0 || record_parse(out, (size_t)n, &again, err, sizeof(err)) ||
	    memcmp(&rec, &again, sizeof(rec)))
		abort();

	return 0;
}
