// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the calibration record parser and the magnetometer
 * file's (<record>.magn) must never crash, hang or read out of bounds,
 * and whatever they accept must be valid and format back to text they
 * accept again, the same.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "common/record.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* What record_magn_parse() accepts formats back to the same */
static void magn_file(const uint8_t *data, size_t size)
{
	struct calib_magn m, again;
	char text[RECORD_MAX_SIZE], err[256];
	uint8_t eeprom[AS9888_EEPROM_LEN] = { 0 };
	uint64_t chip, chip2;
	int len;

	if (record_magn_parse((const char *)data, size, &m, &chip, err,
			      sizeof(err)))
		return;
	if (m.present && record_magn_validate(&m, err, sizeof(err)))
		abort();
	len = record_magn_format(&m, eeprom, 0, text, sizeof(text));
	if (len < 0 || record_magn_parse(text, (size_t)len, &again, &chip2, err,
					 sizeof(err)))
		abort();
	if (memcmp(&m, &again, sizeof(m)))
		abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct calib_record rec, again;
	char text[RECORD_MAX_SIZE], err[256];
	int len;

	magn_file(data, size);
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
