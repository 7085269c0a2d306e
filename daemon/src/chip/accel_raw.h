/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The chip's own accelerometer output behind the driver's compensated
 * samples. The AS9888 driver returns every accelerometer value as
 * (raw - Ot(t)) / St(t) * 1024, rounded, with t the TMPS of the same burst;
 * the application note judges (and the level test averages) raw values,
 * so the factory test through the driver takes them back with the shared
 * arithmetic (as9888_accel_correction(), as9888_accel_uncompensate()).
 * That inverse is this daemon's, not a promise of the kernel: every sample
 * taken back is compensated again and must give the driver's value, or
 * the run fails and points to --backend raw (docs/DECISIONS.md, "Driver
 * v3: calibration ABI").
 */
#ifndef AS9888_ACCEL_RAW_H
#define AS9888_ACCEL_RAW_H

#include <stddef.h>
#include <stdint.h>

#include "as9888_calib.h"

/**
 * struct accel_comp - what the driver compensates the accelerometer with
 * @ee:		the chip's decoded EEPROM
 * @cal:	the driver's calibration (in_accel_*_calibbias)
 * @da:		the DAC register values in use (those of the calibbias)
 */
struct accel_comp {
	struct as9888_eeprom ee;
	struct as9888_accel_cal cal;
	uint8_t da[AS9888_AXES];
};

/*
 * The raw sample behind the compensated sample @out whose burst had TMPS
 * @tmps, into @raw; an axis at the limit of the driver's output (its mark
 * of a saturated chip) comes back as the chip's rail of that sign. 0;
 * -ERANGE when an axis gives back a value the chip cannot output or that
 * does not compensate to @out again (the calibration is not the one the
 * driver used, or the driver rounds differently); -EINVAL when Ot/St
 * cannot be computed at @tmps. @why says which axis and why; @raw is
 * untouched on failure.
 */
int accel_raw_recover(const struct accel_comp *c,
		      const int16_t out[AS9888_AXES], uint8_t tmps,
		      int16_t raw[AS9888_AXES], char *why, size_t whylen);

#endif
