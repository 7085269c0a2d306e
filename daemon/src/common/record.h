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
/*
 * Format 1: the accelerometer only. Format 2: the same keys plus the
 * magnetometer's (magn_*). A record without a magnetometer calibration is
 * still written as format 1, byte for byte as before, so that an older
 * as9888-calibd keeps reading it.
 */
#define RECORD_FORMAT_VERSION	1
#define RECORD_FORMAT_MAGN	2
/* A record file is a few hundred bytes; anything larger is not one */
#define RECORD_MAX_SIZE		4096

/* Limits of the magnetometer section (RECORD.md) */
#define RECORD_MAGN_BIAS_MAX_NT		1000000	/* hard iron: +-1000 uT */
#define RECORD_MAGN_DIAG_MIN_MICRO	500000	/* W's diagonal: the driver's */
#define RECORD_MAGN_DIAG_MAX_MICRO	2000000	/* calibscale range 0.5..2 */
#define RECORD_MAGN_CROSS_MAX_MICRO	500000	/* W's other terms: +-0.5 */
#define RECORD_MAGN_FIELD_MIN_NT	20000	/* the Earth's field: 20..70 uT */
#define RECORD_MAGN_FIELD_MAX_NT	70000
#define RECORD_MAGN_RESIDUAL_MAX_NT	20000
#define RECORD_MAGN_SAMPLES_MIN		10
#define RECORD_MAGN_SAMPLES_MAX		1000000
/*
 * The soft iron's turn (magn_rotation, only in <record>.magn): a rotation
 * of at most 5 degrees (magcal's largest), orthonormal to within the
 * rounding of its nine terms to micro units
 */
#define RECORD_MAGN_ROT_MAX_DEG		5
#define RECORD_MAGN_ROT_TOLERANCE	1e-5

/*
 * The magnetometer's calibration in its own file beside the record
 * (<record>.magn, daemon/RECORD.md), so that the record stays format 1,
 * which every build reads
 */
#define RECORD_MAGN_FILE_NAME		"as9888-magnetometer"
#define RECORD_MAGN_FILE_VERSION	1
#define RECORD_MAGN_SUFFIX		".magn"
/* The file a change replaced, kept beside each (<record>.previous) */
#define RECORD_PREVIOUS_SUFFIX		".previous"

/**
 * struct calib_magn - the magnetometer's calibration (format 2)
 * @present:	the record holds one (format 2)
 * @hard_iron_nt: hard iron b per axis, sensor frame, nT (uT with 3 decimals)
 * @soft_iron_micro: soft-iron correction W, row-major, 1e-6 units; symmetric.
 *		The calibrated field is W * (m - b)
 * @field_nt:	the fitted field magnitude |W * (m - b)|
 * @residual_nt: rms of |W * (m - b)| - field over the samples used
 * @coverage_milli: orientation coverage of those samples, 0..1000
 * @samples:	the number of samples the fit used
 * @learned:	when it was learned, seconds since the epoch (UTC)
 * @has_rotation: @rotation_micro is given (read from or written to
 *		<record>.magn); without it (a format 2 record's section) the
 *		rotation is the identity
 * @rotation_micro: Rrot, the soft iron's turn, row-major, 1e-6 units: the
 *		calibrated field is Rrot W (m - b)
 */
struct calib_magn {
	bool present;
	int32_t hard_iron_nt[AS9888_AXES];
	int32_t soft_iron_micro[AS9888_AXES][AS9888_AXES];
	int32_t field_nt;
	int32_t residual_nt;
	int32_t coverage_milli;
	uint32_t samples;
	int64_t learned;
	bool has_rotation;
	int32_t rotation_micro[AS9888_AXES][AS9888_AXES];
};

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
 * @magn:	the magnetometer's calibration, when learned (format 2)
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
	struct calib_magn magn;
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

/*
 * Check the magnetometer section alone (@magn->present set). 0 or -EINVAL
 * with the reason in @err.
 */
int record_magn_validate(const struct calib_magn *magn, char *err,
			 size_t errlen);

/*
 * The magnetometer's file <record>.magn: @m (a calibration, or none when
 * !@m->present) of the chip whose record has @eeprom, written at
 * @created. Returns the length or -ENOSPC/-EINVAL.
 */
int record_magn_format(const struct calib_magn *m,
		       const uint8_t eeprom[AS9888_EEPROM_LEN], int64_t created,
		       char *buf, size_t size);

/*
 * Parse and validate <record>.magn's text: the calibration into @m
 * (@m->present false for a file that holds none), the chip's fingerprint
 * into @chip. 0, or -EINVAL with "line N: problem" in @err.
 */
int record_magn_parse(const char *text, size_t len, struct calib_magn *m,
		      uint64_t *chip, char *err, size_t errlen);

/*
 * <record>.magn's text (or its .previous) judged against the record @rec
 * it belongs beside: valid, of @rec's chip, and of the same change of the
 * record (its "created" equal to @rec->created: a crash between the two
 * files' changes leaves them a generation apart). The calibration into @m
 * (@m->present false for a file that holds none). 0, or -EINVAL (not
 * valid), -EXDEV (another chip's) or -ESTALE (another generation's), with
 * why in @err (without the file's name).
 */
int record_magn_of(const struct calib_record *rec, const char *text,
		   size_t len, struct calib_magn *m, char *err, size_t errlen);

/* Ot_L per axis: A + St(t_L) * G, from the record */
int record_level_offsets(const struct calib_record *rec,
			 const struct as9888_eeprom *ee,
			 int32_t ot_l_q16[AS9888_AXES]);

#endif
