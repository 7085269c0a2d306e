/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Double-precision reference of the datasheet's section 6, written straight
 * from the formulas and independent of the fixed-point unit under test.
 */
#ifndef AS9888_CALIB_REF_H
#define AS9888_CALIB_REF_H

#include <stdint.h>

double ref_tmps_to_degc(double tmps);
double ref_t_rt(uint8_t eref3);
double ref_sensitivity(uint8_t eagtd, uint8_t eref3, double t);
/* Kote in LSB/degC from EAxGA (bit 7 used), EAxDT, ET1, ET2 (with D4) */
double ref_kote(uint8_t eaga, uint8_t eadt, uint8_t et1, uint8_t et2);
double ref_offset(double kote, double ot_l, double t_l, double t);
int ref_dac2lin(uint8_t ga, uint8_t da);
int ref_lin2dac(uint8_t ga, int lin);
/* DACopt before the clamp, as a linear code */
double ref_dac_opt_lin(uint8_t ga, uint8_t da, uint8_t ee_gain, double ot_l);

#endif
