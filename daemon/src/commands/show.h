/* SPDX-License-Identifier: GPL-2.0 */
/* "show": the calibration of a record at a temperature (datasheet 6). */
#ifndef AS9888_SHOW_H
#define AS9888_SHOW_H

#include <stdbool.h>
#include <stdio.h>

#include "common/record.h"

/**
 * struct show_result - sensitivity and offset of each axis at a temperature
 * @t_mdegc:		the temperature
 * @st_q16:		St(t), LSB/g Q16
 * @ot_q16:		Ot(t), LSB Q16
 * @kote_milli:		Kote, mLSB/degC (for people)
 * @warnings:		EEPROM warnings
 */
struct show_result {
	int32_t t_mdegc;
	int32_t st_q16[AS9888_AXES];
	int32_t ot_q16[AS9888_AXES];
	int32_t kote_milli[AS9888_AXES];
	uint32_t warnings;
};

/* Without @t_given, the level-test temperature is used */
int show_compute(const struct calib_record *rec, bool t_given, int32_t t_mdegc,
		 struct show_result *s, char *err, size_t errlen);
void show_print_text(FILE *out, const struct calib_record *rec,
		     const struct show_result *s);
void show_print_json(FILE *out, const struct calib_record *rec,
		     const struct show_result *s);

#endif
