/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The calibration record of step 4 and its text file format (documented in
 * daemon/RECORD.md): parse, validate, format.
 */
#ifndef AS9888_RECORD_H
#define AS9888_RECORD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "as9888_calib.h"

#define RECORD_FORMAT_NAME	"as9888-calibration"
#define RECORD_FORMAT_VERSION	1
/* A record file is a few hundred bytes; anything larger is not one */
#define RECORD_MAX_SIZE		4096

/**
 * struct calib_record - the calibration of one chip
 * @eeprom:	the chip's 21 EEPROM bytes: its factory data and its identity
 * @dac:	the offset DAC register values written (DACopt)
 * @level_mean_q16: level-test mean A per axis with @dac applied, LSB Q16
 * @t_level_mdegc: level-test temperature t_L
 * @gravity:	direction of gravity during the level test (one axis +-1)
 * @samples:	N, samples averaged
 * @lpf:	the level test ran with the low-pass filter on
 * @created:	when the record was made, seconds since the epoch (UTC)
 * @simulated:	made on the simulator, not on a chip ("source = simulator");
 *		restore on a real backend refuses it
 */
struct calib_record {
	uint8_t eeprom[AS9888_EEPROM_LEN];
	uint8_t dac[AS9888_AXES];
	int32_t level_mean_q16[AS9888_AXES];
	int32_t t_level_mdegc;
	int8_t gravity[AS9888_AXES];
	uint32_t samples;
	bool lpf;
	int64_t created;
	bool simulated;
};

/* FNV-1a 64 of the EEPROM bytes: the chip identity shown to people */
uint64_t record_fingerprint(const uint8_t eeprom[AS9888_EEPROM_LEN]);
uint32_t record_crc32(const void *data, size_t len);

/*
 * Check every field's range and consistency. Returns 0 or -EINVAL with
 * the reason in @err.
 */
int record_validate(const struct calib_record *rec, char *err, size_t errlen);

/*
 * Format as text into @buf. Returns the length (without NUL) or -ENOSPC.
 */
int record_format(const struct calib_record *rec, char *buf, size_t size);

/*
 * Parse and validate a record file's text (need not be NUL terminated).
 * Returns 0, or -EINVAL with "line N: problem" in @err.
 */
int record_parse(const char *text, size_t len, struct calib_record *rec,
		 char *err, size_t errlen);

/* Ot_L per axis: A + St(t_L) * G, from the record */
int record_level_offsets(const struct calib_record *rec,
			 const struct as9888_eeprom *ee,
			 int32_t ot_l_q16[AS9888_AXES]);

#endif
