/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 chip model: the magnetic world around the simulated unit.
 *
 * Fixed-point geometry for the model: sine and cosine, quaternions and
 * rotations, the Earth's field in the world frame. Like the rest of the
 * model it builds in userspace and in the in-kernel test adapter: integer
 * arithmetic only, no libc, no floating point, no undefined behaviour for
 * any input.
 *
 * Conventions (docs/DECISIONS.md, "Simulated units: magnetic world"):
 *  - Q30: 1.0 is 2^30 (AS9888_Q30_ONE). Angles are millidegrees.
 *  - The world frame is East-North-Up (x east, y north, z up, right
 *    handed), north being geographic (true) north.
 *  - An orientation is the unit quaternion q = (w, x, y, z) in Q30 that
 *    rotates sensor-frame vectors into the world frame: v_world = R(q) v.
 *    The field and gravity the chip sees are R(q)^T applied to the world's.
 *  - The Earth's field of magnitude F, inclination I (positive: the field
 *    points down, northern hemisphere) and declination D (positive: magnetic
 *    north east of true north) is F (cos I sin D, cos I cos D, -sin I).
 *  - Heading: the compass azimuth (clockwise from true north) of the
 *    sensor's +Y axis when the sensor is level (Z up). An orientation given
 *    as (up, heading) is the shortest rotation that takes the sensor's up
 *    vector to the world's up, followed by a turn of -heading about the
 *    world's up (a clockwise turn seen from above). Upside down (up = -Z)
 *    the tilt is the half turn about the sensor's X axis.
 *
 * Sine and cosine are a Taylor series on [0, 45] degrees after range
 * reduction to one octant, exact to about 2 Q30 units (2e-9).
 */
#ifndef AS9888_MAGWORLD_H
#define AS9888_MAGWORLD_H

#include <linux/types.h>

#define AS9888_Q30_ONE		(1LL << 30)
#define AS9888_QUAT_LEN		4

/* Sine and cosine of @mdeg millidegrees (any value), Q30. */
void as9888_mw_sincos(s64 mdeg, s32 *sin_q30, s32 *cos_q30);

/*
 * Scale @n components of @v (any scale, |v[i]| < 2^31) to a unit vector in
 * Q30. Returns -EINVAL for the zero vector (@out then untouched).
 */
int as9888_mw_normalise_q30(const s64 *v, int n, s32 *out);

/* out = a * b (Hamilton product), renormalised to a unit quaternion. */
void as9888_mw_quat_mul(const s32 a[AS9888_QUAT_LEN],
			const s32 b[AS9888_QUAT_LEN],
			s32 out[AS9888_QUAT_LEN]);

/* Rotation of @mdeg millidegrees about the unit axis @axis_q30. */
void as9888_mw_quat_axis_angle(const s32 axis_q30[3], s64 mdeg,
			       s32 q[AS9888_QUAT_LEN]);

/*
 * Orientation of a sensor whose up vector (sensor frame, any scale, not
 * zero) is @up, turned to @heading_mdeg (see the conventions above).
 */
void as9888_mw_quat_from_up(const s32 up[3], s32 heading_mdeg,
			    s32 q[AS9888_QUAT_LEN]);

/* The world's up in the sensor frame, normalised to 1e6 (as unit.up). */
void as9888_mw_up_from_quat(const s32 q[AS9888_QUAT_LEN], s32 up[3]);

/* sensor = R(q)^T world; |world[i]| <= 2^32. */
void as9888_mw_to_sensor(const s32 q[AS9888_QUAT_LEN], const s64 world[3],
			 s64 sensor[3]);

/* The Earth's field in the world frame, nT (|F| <= 1 T). */
void as9888_mw_earth_world_nt(s32 f_nt, s32 incl_mdeg, s32 decl_mdeg,
			      s64 world[3]);

#endif /* AS9888_MAGWORLD_H */
