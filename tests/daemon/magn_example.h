/* SPDX-License-Identifier: GPL-2.0 */
/*
 * One magnetometer calibration for the tests: b = (30, -45.5, 100.25) uT,
 * W symmetric with cross terms, learned 2026-11-23T00:00:00Z. With the
 * example EEPROM (EHC 0x80 0x85 0x7b: 0.3, 0.305859, 0.294141 uT per LSB)
 * the driver gets calibbias -100 149 -341 and calibscale 1.02 0.985 1.003.
 */
#ifndef AS9888_TEST_MAGN_EXAMPLE_H
#define AS9888_TEST_MAGN_EXAMPLE_H

#include "common/record.h"

static const struct calib_magn magn_example = {
	.present = true,
	.hard_iron_nt = { 30000, -45500, 100250 },
	.soft_iron_micro = {
		{ 1020000, 12000, -31000 },
		{ 12000, 985000, 4000 },
		{ -31000, 4000, 1003000 },
	},
	.field_nt = 48512,
	.residual_nt = 321,
	.coverage_milli = 875,
	.samples = 300,
	.learned = 1795392000,
};

#endif
