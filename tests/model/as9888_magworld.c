// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 chip model: fixed-point geometry of the magnetic world. See
 * as9888_magworld.h for the conventions.
 *
 * Ranges: quaternion components and rotation matrix entries are Q30 values
 * of magnitude <= 2^30 (a little more after rounding), so a product of two
 * is below 2^61 and a sum of four below 2^63.
 */

#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/math64.h>
#include <linux/types.h>

#include "as9888_magworld.h"
#include "as9888_unit.h"

/* pi in Q30, rounded */
#define PI_Q30			3373259426LL
#define MDEG_HALF_TURN		180000
#define MDEG_QUARTER		90000
#define MDEG_OCTANT		45000
#define MDEG_TURN		360000
#define Q30_HALF		(1LL << 29)

/* v / 2^30 rounded to nearest, ties away from zero; |v| < 2^62 */
static s64 q30_round(s64 v)
{
	if (v >= 0)
		return (v + Q30_HALF) / AS9888_Q30_ONE;
	return -((-v + Q30_HALF) / AS9888_Q30_ONE);
}

static s64 q30_mul(s64 a, s64 b)
{
	return q30_round(a * b);
}

/* num / den rounded to nearest, ties away from zero; den > 0 */
static s64 div_round(s64 num, s64 den)
{
	if (num >= 0)
		return div64_s64(num + den / 2, den);
	return -div64_s64(-num + den / 2, den);
}

/* sin and cos of x radians (Q30), 0 <= x <= pi/4: Taylor, Horner form */
static void sincos_octant(s64 x, s64 *s, s64 *c)
{
	static const s64 sin_den[] = { 12 * 13, 10 * 11, 8 * 9, 6 * 7,
				       4 * 5, 2 * 3 };
	static const s64 cos_den[] = { 11 * 12, 9 * 10, 7 * 8, 5 * 6,
				       3 * 4, 1 * 2 };
	s64 x2 = q30_mul(x, x);
	s64 acc = AS9888_Q30_ONE;
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(sin_den); i++)
		acc = AS9888_Q30_ONE - div_round(q30_mul(x2, acc), sin_den[i]);
	*s = q30_mul(x, acc);
	acc = AS9888_Q30_ONE;
	for (i = 0; i < ARRAY_SIZE(cos_den); i++)
		acc = AS9888_Q30_ONE - div_round(q30_mul(x2, acc), cos_den[i]);
	*c = acc;
}

void as9888_mw_sincos(s64 mdeg, s32 *sin_q30, s32 *cos_q30)
{
	s64 a = mdeg - div64_s64(mdeg, MDEG_TURN) * MDEG_TURN;
	s64 s, c, t;
	u32 quadrant, r;

	if (a < 0)
		a += MDEG_TURN;
	quadrant = (u32)a / MDEG_QUARTER;
	r = (u32)a % MDEG_QUARTER;
	if (r <= MDEG_OCTANT) {
		sincos_octant(div_round((s64)r * PI_Q30, MDEG_HALF_TURN),
			      &s, &c);
	} else {
		/* sin r = cos(90 - r), cos r = sin(90 - r) */
		sincos_octant(div_round((s64)(MDEG_QUARTER - r) * PI_Q30,
					MDEG_HALF_TURN), &c, &s);
	}
	switch (quadrant) {
	case 1:
		t = s;
		s = c;
		c = -t;
		break;
	case 2:
		s = -s;
		c = -c;
		break;
	case 3:
		t = s;
		s = -c;
		c = t;
		break;
	default:
		break;
	}
	*sin_q30 = (s32)clamp_t(s64, s, -AS9888_Q30_ONE, AS9888_Q30_ONE);
	*cos_q30 = (s32)clamp_t(s64, c, -AS9888_Q30_ONE, AS9888_Q30_ONE);
}

int as9888_mw_normalise_q30(const s64 *v, int n, s32 *out)
{
	s64 w[AS9888_QUAT_LEN];
	u64 max = 0, sq = 0, norm;
	int i;

	if (n < 1 || n > AS9888_QUAT_LEN)
		return -EINVAL;
	for (i = 0; i < n; i++) {
		u64 a = v[i] < 0 ? -(u64)v[i] : (u64)v[i];

		w[i] = v[i];
		if (a > max)
			max = a;
	}
	if (!max)
		return -EINVAL;
	/* bring the largest component to 2^29..2^30: precision, no overflow */
	while (max >= (1ULL << 30)) {
		for (i = 0; i < n; i++)
			w[i] = div64_s64(w[i], 2);
		max >>= 1;
	}
	while (max < (1ULL << 29)) {
		for (i = 0; i < n; i++)
			w[i] *= 2;
		max <<= 1;
	}
	for (i = 0; i < n; i++)
		sq += (u64)(w[i] * w[i]);
	norm = as9888_unit_isqrt(sq);
	for (i = 0; i < n; i++)
		out[i] = (s32)clamp_t(s64, div_round(w[i] * AS9888_Q30_ONE,
						     (s64)norm),
				      -AS9888_Q30_ONE, AS9888_Q30_ONE);
	return 0;
}

void as9888_mw_quat_mul(const s32 a[AS9888_QUAT_LEN],
			const s32 b[AS9888_QUAT_LEN],
			s32 out[AS9888_QUAT_LEN])
{
	s64 aw = a[0], ax = a[1], ay = a[2], az = a[3];
	s64 bw = b[0], bx = b[1], by = b[2], bz = b[3];
	s64 p[AS9888_QUAT_LEN];
	s32 q[AS9888_QUAT_LEN];
	int i;

	p[0] = q30_round(aw * bw - ax * bx - ay * by - az * bz);
	p[1] = q30_round(aw * bx + ax * bw + ay * bz - az * by);
	p[2] = q30_round(aw * by - ax * bz + ay * bw + az * bx);
	p[3] = q30_round(aw * bz + ax * by - ay * bx + az * bw);
	if (as9888_mw_normalise_q30(p, AS9888_QUAT_LEN, q)) {
		/* two zero quaternions: the identity */
		q[0] = AS9888_Q30_ONE;
		q[1] = q[2] = q[3] = 0;
	}
	for (i = 0; i < AS9888_QUAT_LEN; i++)
		out[i] = q[i];
}

void as9888_mw_quat_axis_angle(const s32 axis_q30[3], s64 mdeg,
			       s32 q[AS9888_QUAT_LEN])
{
	s32 s, c;
	int i;

	as9888_mw_sincos(div64_s64(mdeg, 2), &s, &c);
	q[0] = c;
	for (i = 0; i < 3; i++)
		q[i + 1] = (s32)q30_mul(s, axis_q30[i]);
}

void as9888_mw_quat_from_up(const s32 up[3], s32 heading_mdeg,
			    s32 q[AS9888_QUAT_LEN])
{
	static const s32 world_up[3] = { 0, 0, AS9888_Q30_ONE };
	s64 v[3] = { up[0], up[1], up[2] };
	s32 u[3], tilt[AS9888_QUAT_LEN], turn[AS9888_QUAT_LEN];
	s64 t[AS9888_QUAT_LEN];

	if (as9888_mw_normalise_q30(v, 3, u)) {
		u[0] = u[1] = 0;
		u[2] = AS9888_Q30_ONE;
	}
	/* the shortest rotation taking u to z: (1 + u.z, u x z), normalised */
	t[0] = AS9888_Q30_ONE + u[2];
	t[1] = u[1];
	t[2] = -(s64)u[0];
	t[3] = 0;
	if (as9888_mw_normalise_q30(t, AS9888_QUAT_LEN, tilt)) {
		/* upside down: the half turn about the sensor's X axis */
		tilt[0] = tilt[2] = tilt[3] = 0;
		tilt[1] = AS9888_Q30_ONE;
	}
	as9888_mw_quat_axis_angle(world_up, -(s64)heading_mdeg, turn);
	as9888_mw_quat_mul(turn, tilt, q);
}

/* Rotation matrix of a unit quaternion, Q30 */
static void rot_matrix(const s32 q[AS9888_QUAT_LEN], s64 r[3][3])
{
	s64 w = q[0], x = q[1], y = q[2], z = q[3];
	s64 one = AS9888_Q30_ONE * AS9888_Q30_ONE;

	r[0][0] = q30_round(one - 2 * (y * y + z * z));
	r[0][1] = q30_round(2 * (x * y - w * z));
	r[0][2] = q30_round(2 * (x * z + w * y));
	r[1][0] = q30_round(2 * (x * y + w * z));
	r[1][1] = q30_round(one - 2 * (x * x + z * z));
	r[1][2] = q30_round(2 * (y * z - w * x));
	r[2][0] = q30_round(2 * (x * z - w * y));
	r[2][1] = q30_round(2 * (y * z + w * x));
	r[2][2] = q30_round(one - 2 * (x * x + y * y));
}

void as9888_mw_up_from_quat(const s32 q[AS9888_QUAT_LEN], s32 up[3])
{
	s64 r[3][3];
	s32 v[3];
	int i;

	rot_matrix(q, r);
	for (i = 0; i < 3; i++)
		v[i] = (s32)div_round(r[2][i] * AS9888_UNIT_UP_ONE,
				      AS9888_Q30_ONE);
	if (as9888_unit_normalise(v, up)) {
		up[0] = up[1] = 0;
		up[2] = AS9888_UNIT_UP_ONE;
	}
}

void as9888_mw_to_sensor(const s32 q[AS9888_QUAT_LEN], const s64 world[3],
			 s64 sensor[3])
{
	s64 r[3][3];
	int i;

	rot_matrix(q, r);
	for (i = 0; i < 3; i++)
		sensor[i] = q30_round(r[0][i] * world[0] + r[1][i] * world[1] +
				      r[2][i] * world[2]);
}

void as9888_mw_earth_world_nt(s32 f_nt, s32 incl_mdeg, s32 decl_mdeg,
			      s64 world[3])
{
	s32 si, ci, sd, cd;
	s64 h;

	as9888_mw_sincos(incl_mdeg, &si, &ci);
	as9888_mw_sincos(decl_mdeg, &sd, &cd);
	h = q30_mul(f_nt, ci);
	world[0] = q30_mul(h, sd);
	world[1] = q30_mul(h, cd);
	world[2] = -q30_mul(f_nt, si);
}
