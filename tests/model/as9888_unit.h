/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 simulated unit description (datasheet section 8).
 *
 * A unit is the physics and the factory data of one simulated chip: its
 * EEPROM, the true accelerometer offset, its posture, die temperature,
 * noise, the ambient magnetic field, the noise seed and injected faults.
 *
 * Everything is fixed point so that the same file builds in the kernel (the
 * in-kernel test adapter) and in userspace. No libc, no floating point.
 *
 * Text format (one "key = value" per line, '#' starts a comment, every key
 * optional, each key at most once):
 *
 *   eeprom            = 21 hex bytes (0x40..0x54), "9a" or "0x9a"
 *   offset            = x y z      LSB, up to 3 decimals, |v| <= 4096
 *   up                = x y z      any scale, up to 6 decimals, |v| <= 1000,
 *                                  not all zero; normalised
 *   temperature       = t          degC, up to 3 decimals, -50..150
 *   temperature_drift = d          degC/s, up to 6 decimals, |d| <= 100
 *   noise             = n          LSB rms, up to 3 decimals, 0..100
 *   field             = x y z      uT, up to 3 decimals, |v| <= 5000
 *   seed              = n          decimal or 0x hex, 64 bit
 *   fault             = a, b ...   fault names (or "none"), comma and/or
 *                                  space separated
 *
 * The magnetic world (tests/model/as9888_magworld.h has the conventions;
 * docs/DECISIONS.md "Simulated units: magnetic world" the reasons):
 *
 *   earth             = F I D      the Earth's field in the world frame:
 *                                  magnitude uT (0..200), inclination deg
 *                                  (-90..90, positive down), declination
 *                                  deg (-180..180, positive east), up to 3
 *                                  decimals each. The field then turns with
 *                                  the device; not with "field"
 *   heading           = h          deg, up to 3 decimals, |h| <= 360: turn
 *                                  about the world's up after the tilt of
 *                                  "up" (level: azimuth of the sensor's +Y)
 *   orientation       = w x y z    sensor-to-world rotation quaternion, any
 *                                  scale, up to 6 decimals, |v| <= 1000, not
 *                                  all zero; not with "up" or "heading"
 *   hard_iron         = x y z      uT, sensor frame, up to 3 decimals,
 *                                  |v| <= 2000
 *   soft_iron         = 9 values   3x3 matrix, row major, up to 6 decimals,
 *                                  |v| <= 2 (default: the identity)
 *   magn_noise        = n          uT rms per axis, up to 3 decimals, 0..100
 *   disturbance       = x y z n    a magnet passing by: peak uT in the
 *                                  sensor frame (up to 3 decimals, |v| <=
 *                                  2000) over the next n magnetometer
 *                                  measurements (0..1000000) with a half-sine
 *                                  profile; n = 0: a constant extra field
 *   tumble            = d          deg per measurement, up to 3 decimals,
 *                                  0..90: a seeded random motion through
 *                                  orientations, one step per measurement
 *
 * The magnetometer reads S (B + d) + h + noise: B the external field in
 * the sensor frame (R(q)^T earth with "earth", else "field" as given), d
 * the disturbance, S the soft-iron matrix, h the hard iron. With none of
 * these keys a unit reads "field" exactly as before.
 *
 * Vector items may be separated by spaces, tabs or commas. More decimal
 * places than the precision are accepted only if they are zeros.
 */
#ifndef AS9888_UNIT_H
#define AS9888_UNIT_H

#include <linux/bits.h>
#include <linux/types.h>

#define AS9888_UNIT_EEPROM_LEN		21
#define AS9888_UNIT_AXES		3

/* Fixed-point scales of struct as9888_unit */
#define AS9888_UNIT_UP_ONE		1000000		/* unit vector = 1e6 */

/* Accepted ranges (the parser rejects, the model clamps) */
#define AS9888_UNIT_OFFSET_MAX_MLSB	4096000
#define AS9888_UNIT_TEMP_MIN_MDEGC	(-50000)
#define AS9888_UNIT_TEMP_MAX_MDEGC	150000
#define AS9888_UNIT_DRIFT_MAX_UDEGC_S	100000000
#define AS9888_UNIT_NOISE_MAX_MLSB	100000
#define AS9888_UNIT_FIELD_MAX_NT	5000000
#define AS9888_UNIT_EARTH_MAX_NT	200000
#define AS9888_UNIT_INCL_MAX_MDEG	90000
#define AS9888_UNIT_DECL_MAX_MDEG	180000
#define AS9888_UNIT_HEADING_MAX_MDEG	360000
#define AS9888_UNIT_ORIENT_MAX		1000000000	/* 1000, 6 decimals */
#define AS9888_UNIT_IRON_MAX_NT		2000000
#define AS9888_UNIT_SOFT_ONE		1000000		/* 1.0 */
#define AS9888_UNIT_SOFT_MAX		2000000
#define AS9888_UNIT_MNOISE_MAX_NT	100000
#define AS9888_UNIT_DIST_MAX_SAMPLES	1000000
#define AS9888_UNIT_TUMBLE_MAX_MDEG	90000

/* struct as9888_unit.world: which parts of the magnetic world are set */
#define AS9888_UNIT_WORLD_EARTH		BIT(0)	/* "earth" given */
#define AS9888_UNIT_WORLD_ORIENTATION	BIT(1)	/* "orientation" given */

/* Injected faults, datasheet section 8 */
enum as9888_fault {
	AS9888_FAULT_NO_DRDY		= BIT(0),  /* measurements never end */
	AS9888_FAULT_INT1_OPEN		= BIT(1),  /* INT1 pin never rises */
	AS9888_FAULT_INT2_OPEN		= BIT(2),  /* INT2 pin never rises */
	AS9888_FAULT_RSTN_OPEN		= BIT(3),  /* reset pulses do nothing */
	AS9888_FAULT_WIA		= BIT(4),  /* WIA reads 0x47 */
	AS9888_FAULT_EEPROM_BLANK	= BIT(5),  /* EEPROM reads all 0xff */
	AS9888_FAULT_STUCK_X		= BIT(6),  /* accel X constant */
	AS9888_FAULT_SATURATE_Z		= BIT(7),  /* accel Z reads 2047 */
	AS9888_FAULT_NAK		= BIT(8),  /* every 50th transfer fails */
	AS9888_FAULT_SELFTEST_WEAK	= BIT(9),  /* self-test Z about 150 */
	AS9888_FAULT_HOFL		= BIT(10), /* magnetometer overflow */
};

#define AS9888_FAULT_COUNT		11
#define AS9888_FAULT_ALL		(BIT(AS9888_FAULT_COUNT) - 1)

/**
 * struct as9888_unit - one simulated unit
 * @eeprom:		the 21 EEPROM bytes, 0x40 first
 * @offset_mlsb:	true accelerometer offset at 25 degC with the EEPROM
 *			DAC values, milli-LSB, X Y Z
 * @up:			sensor-frame direction pointing up, normalised to
 *			AS9888_UNIT_UP_ONE (1e6)
 * @temperature_mdegc:	die temperature at power-on, millidegrees Celsius
 * @drift_udegc_s:	temperature drift, microdegrees Celsius per second
 * @noise_mlsb:		accelerometer noise, milli-LSB rms with ALPF = 0
 * @field_nt:		ambient magnetic field, nanotesla, X Y Z
 * @seed:		noise generator seed
 * @faults:		enum as9888_fault bits
 * @world:		AS9888_UNIT_WORLD_* bits
 * @earth_nt:		Earth's field magnitude, nanotesla
 * @incl_mdeg:		its inclination, millidegrees (positive down)
 * @decl_mdeg:		its declination, millidegrees (positive east)
 * @heading_mdeg:	turn about the world's up after the tilt, millidegrees
 * @orientation:	sensor-to-world quaternion w x y z, any scale (1e6
 *			per unit as parsed); used with AS9888_UNIT_WORLD_ORIENTATION
 * @hard_nt:		hard iron, nanotesla, sensor frame
 * @soft_ppm:		soft-iron matrix, row major, 1e6 = 1.0
 * @magn_noise_nt:	magnetometer noise, nanotesla rms per axis
 * @dist_nt:		disturbance peak, nanotesla, sensor frame
 * @dist_samples:	its length in magnetometer measurements (0: constant)
 * @tumble_mdeg:	random motion, millidegrees per measurement (0: still)
 */
struct as9888_unit {
	u8 eeprom[AS9888_UNIT_EEPROM_LEN];
	s32 offset_mlsb[AS9888_UNIT_AXES];
	s32 up[AS9888_UNIT_AXES];
	s32 temperature_mdegc;
	s32 drift_udegc_s;
	u32 noise_mlsb;
	s32 field_nt[AS9888_UNIT_AXES];
	u64 seed;
	u32 faults;
	u32 world;
	s32 earth_nt;
	s32 incl_mdeg;
	s32 decl_mdeg;
	s32 heading_mdeg;
	s32 orientation[4];
	s32 hard_nt[AS9888_UNIT_AXES];
	s32 soft_ppm[AS9888_UNIT_AXES * AS9888_UNIT_AXES];
	u32 magn_noise_nt;
	s32 dist_nt[AS9888_UNIT_AXES];
	u32 dist_samples;
	u32 tumble_mdeg;
};

#define AS9888_UNIT_ERROR_MSG_LEN	96

/**
 * struct as9888_unit_error - where and why parsing failed
 * @line:	1-based line number of the offending line (0: none)
 * @msg:	NUL-terminated message, e.g. "unknown key 'foo'"
 */
struct as9888_unit_error {
	unsigned int line;
	char msg[AS9888_UNIT_ERROR_MSG_LEN];
};

/* The healthy, level, 25 degC unit with the datasheet example EEPROM. */
void as9888_unit_default(struct as9888_unit *u);

/*
 * Parse a unit description of @len bytes (no NUL needed). Keys that are
 * not given keep the as9888_unit_default() values. Returns 0, or -EINVAL
 * with @err (may be NULL) naming the line and the problem; @u is then
 * left with the defaults plus the keys parsed before the error.
 */
int as9888_unit_parse(const char *text, unsigned int len,
		      struct as9888_unit *u, struct as9888_unit_error *err);

/* Name of one fault bit ("nak"), or NULL for an unknown bit. */
const char *as9888_fault_name(u32 fault_bit);

/*
 * Normalise a vector (any scale, |component| <= 2^31 - 1) to
 * AS9888_UNIT_UP_ONE. Returns -EINVAL for the zero vector.
 */
int as9888_unit_normalise(const s32 in[AS9888_UNIT_AXES],
			  s32 out[AS9888_UNIT_AXES]);

/* Integer square root, rounded down. */
u64 as9888_unit_isqrt(u64 x);

#endif /* AS9888_UNIT_H */
