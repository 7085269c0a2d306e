// SPDX-License-Identifier: GPL-2.0
/* Double-precision reference of the datasheet's section 6 (see calib_ref.h). */
#include <math.h>

#include "calib_ref.h"

static int sext(unsigned int v, int bits)
{
	return (v & (1u << (bits - 1))) ? (int)v - (1 << bits) : (int)v;
}

double ref_tmps_to_degc(double tmps)
{
	return (176.0 - tmps) / 1.6;
}

double ref_t_rt(uint8_t eref3)
{
	return ref_tmps_to_degc(136 + sext(eref3 >> 3, 5));
}

double ref_sensitivity(uint8_t eagtd, uint8_t eref3, double t)
{
	static const double kste[8] = {
		-0.428125, -0.384375, -0.340625, -0.296875,
		-0.253125, -0.209375, -0.165625, -0.121875,
	};
	double st_rt = 256 + sext(eagtd & 0x1f, 5);

	return st_rt * (1.0 + kste[eagtd >> 5] / 100.0 * (t - ref_t_rt(eref3)));
}

double ref_kote(uint8_t eaga, uint8_t eadt, uint8_t et1, uint8_t et2)
{
	double dt = sext(((eaga >> 7) << 8) | eadt, 9);
	double delta = (et1 - et2) / 1.6;

	if (et1 < 0x28 || et1 > 0xe0 || et2 < 0x28 || et2 > 0xe0 ||
	    delta < 10.0 || delta > 80.0)
		delta = 35.0;

	return dt * 1.5 / delta;
}

double ref_offset(double kote, double ot_l, double t_l, double t)
{
	return kote * (t - t_l) + ot_l;
}

int ref_dac2lin(uint8_t ga, uint8_t da)
{
	int lin = da >= 0x80 ? da - 0x80 : -da;

	return (ga & 0x40) ? -lin : lin;
}

int ref_lin2dac(uint8_t ga, int lin)
{
	if (ga & 0x40)
		lin = -lin;
	return lin >= 0 ? lin + 0x80 : -lin;
}

double ref_dac_opt_lin(uint8_t ga, uint8_t da, uint8_t ee_gain, double ot_l)
{
	return ref_dac2lin(ga, da) - rint((ee_gain + 16) / 2048.0 * ot_l);
}
