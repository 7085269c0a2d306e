/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The magnetometer's calibration of a record as people and programs read
 * it (show, the daemon's "magn" request): what the record holds and what
 * follows from it for the driver (calibbias, calibscale) and for
 * userspace (the residual matrix R, the offset e, the bias an Android HAL
 * reports; magn_cal.h).
 */
#ifndef AS9888_MAGN_SHOW_H
#define AS9888_MAGN_SHOW_H

#include <stdio.h>

#include "common/record.h"

/* Lines "magnetometer ..." for show; nothing when @rec has none */
void magn_show_text(FILE *out, const struct calib_record *rec);

/*
 * A JSON object (no trailing newline) with the calibration, at @indent
 * spaces; "null" when @rec has none
 */
void magn_show_json(FILE *out, const struct calib_record *rec, int indent);

#endif
