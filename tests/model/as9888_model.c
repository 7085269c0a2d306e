// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 chip model. See as9888_model.h for the contract and the decisions
 * taken where the datasheet is silent.
 *
 * Arithmetic: every accelerometer contribution is computed in nano-LSB
 * (1e-9 LSB) in s64 and rounded once, half to even, at the end. The
 * ranges clamped in as9888_model_init() keep every product below 2^63:
 *   sensitivity  St_RT * (4e9 + 5 * K * dT) <= 271 * 6.4e9   (0.25 nLSB/g)
 *                * (gain + 16) / (egain + 16) <= 8.5e12
 *                * up (<= 1e6)                <= 8.5e18
 *   Kote term    256 * 12e6 * 175000          <= 5.4e17
 *   DAC term     254 * 2048e9                 <= 5.3e14
 */

#include <linux/bitops.h>
#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/math64.h>
#include <linux/types.h>

#include "as9888_model.h"

#define NANO			1000000000LL
#define TRIM_LEN		10
#define TRIM_GA(axis)		(4 + (axis))
#define TRIM_DA(axis)		(7 + (axis))
#define TRIM_REF3		2
#define ELAPSED_MAX_MS		10000000000ULL
/* Kste/100 per millidegree = (KSTE_BASE + KSTE_STEP * idx) / 8e8 */
#define KSTE_BASE		(-3425)
#define KSTE_STEP		350
/* One mag LSB before adjustment is 300 nT */
#define MAG_NT_PER_LSB		300
/* The magnetometer noise and the tumble draw from streams of their own */
#define MRNG_SALT		0x6d61676e6f697365ULL	/* "magnoise" */
#define TRNG_SALT		0x74756d626c652121ULL	/* "tumble!!" */
/* Tumble: the axis wanders by up to 1/4 of a unit per step and axis */
#define TUMBLE_WANDER_SHIFT	3
#define MDEG_HALF_TURN		180000
#define SOFT_LEN		(AS9888_UNIT_AXES * AS9888_UNIT_AXES)

static s64 clamp_s64(s64 v, s64 lo, s64 hi)
{
	if (v < lo)
		return lo;
	if (v > hi)
		return hi;
	return v;
}

/* num / den rounded to nearest, ties to even; den > 0, den < 2^62 */
static s64 div_round_even(s64 num, s64 den)
{
	s64 q = div64_s64(num, den);
	s64 r = num - q * den;

	if (r < 0) {
		q--;
		r += den;
	}
	if (2 * r > den || (2 * r == den && (q & 1)))
		q++;
	return q;
}

/* splitmix64 */
static u64 rng_next(u64 *state)
{
	u64 z;

	*state += 0x9e3779b97f4a7c15ULL;
	z = *state;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
	return z ^ (z >> 31);
}

/*
 * Standard normal deviate (Irwin-Hall, 12 uniforms: mean 0, variance 1,
 * bounded to +-6) in Q16.
 */
static s64 gauss_q16(u64 *state)
{
	u64 sum = 0;
	int i;

	for (i = 0; i < 6; i++) {
		u64 r = rng_next(state);

		sum += r & 0xffffffffULL;
		sum += r >> 32;
	}
	/* sum is Q32 in 0..12; round to Q16 and centre */
	return (s64)((sum + 0x8000ULL) >> 16) - 6LL * 65536;
}

static int dac2lin(u8 ga, u8 da)
{
	int lin = da >= 0x80 ? da - 0x80 : -(int)da;

	return (ga & BIT(6)) ? -lin : lin;
}

static s32 unit_clamp(s32 v, s32 lo, s32 hi)
{
	return (s32)clamp_s64(v, lo, hi);
}

static void sanitize_unit(struct as9888_unit *u)
{
	int i;

	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		u->offset_mlsb[i] = unit_clamp(u->offset_mlsb[i],
					       -AS9888_UNIT_OFFSET_MAX_MLSB,
					       AS9888_UNIT_OFFSET_MAX_MLSB);
		u->up[i] = unit_clamp(u->up[i], -AS9888_UNIT_UP_ONE,
				      AS9888_UNIT_UP_ONE);
		u->field_nt[i] = unit_clamp(u->field_nt[i],
					    -AS9888_UNIT_FIELD_MAX_NT,
					    AS9888_UNIT_FIELD_MAX_NT);
	}
	u->temperature_mdegc = unit_clamp(u->temperature_mdegc,
					  AS9888_UNIT_TEMP_MIN_MDEGC,
					  AS9888_UNIT_TEMP_MAX_MDEGC);
	u->drift_udegc_s = unit_clamp(u->drift_udegc_s,
				      -AS9888_UNIT_DRIFT_MAX_UDEGC_S,
				      AS9888_UNIT_DRIFT_MAX_UDEGC_S);
	if (u->noise_mlsb > AS9888_UNIT_NOISE_MAX_MLSB)
		u->noise_mlsb = AS9888_UNIT_NOISE_MAX_MLSB;
	u->faults &= AS9888_FAULT_ALL;
	u->earth_nt = unit_clamp(u->earth_nt, 0, AS9888_UNIT_EARTH_MAX_NT);
	u->incl_mdeg = unit_clamp(u->incl_mdeg, -AS9888_UNIT_INCL_MAX_MDEG,
				  AS9888_UNIT_INCL_MAX_MDEG);
	u->decl_mdeg = unit_clamp(u->decl_mdeg, -AS9888_UNIT_DECL_MAX_MDEG,
				  AS9888_UNIT_DECL_MAX_MDEG);
	u->heading_mdeg = unit_clamp(u->heading_mdeg,
				     -AS9888_UNIT_HEADING_MAX_MDEG,
				     AS9888_UNIT_HEADING_MAX_MDEG);
	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		u->hard_nt[i] = unit_clamp(u->hard_nt[i],
					   -AS9888_UNIT_IRON_MAX_NT,
					   AS9888_UNIT_IRON_MAX_NT);
		u->dist_nt[i] = unit_clamp(u->dist_nt[i],
					   -AS9888_UNIT_IRON_MAX_NT,
					   AS9888_UNIT_IRON_MAX_NT);
	}
	for (i = 0; i < SOFT_LEN; i++)
		u->soft_ppm[i] = unit_clamp(u->soft_ppm[i],
					    -AS9888_UNIT_SOFT_MAX,
					    AS9888_UNIT_SOFT_MAX);
	if (u->magn_noise_nt > AS9888_UNIT_MNOISE_MAX_NT)
		u->magn_noise_nt = AS9888_UNIT_MNOISE_MAX_NT;
	if (u->dist_samples > AS9888_UNIT_DIST_MAX_SAMPLES)
		u->dist_samples = AS9888_UNIT_DIST_MAX_SAMPLES;
	if (u->tumble_mdeg > AS9888_UNIT_TUMBLE_MAX_MDEG)
		u->tumble_mdeg = AS9888_UNIT_TUMBLE_MAX_MDEG;
}

/* ---- the magnetic world ---- */

static void set_identity(s32 q[AS9888_QUAT_LEN])
{
	q[0] = AS9888_Q30_ONE;
	q[1] = q[2] = q[3] = 0;
}

/* The orientation from the unit: a quaternion, or up and heading */
static void orient_from_unit(struct as9888_model *m)
{
	s64 v[AS9888_QUAT_LEN];
	int i;

	if (!(m->unit.world & AS9888_UNIT_WORLD_ORIENTATION)) {
		as9888_mw_quat_from_up(m->unit.up, m->unit.heading_mdeg,
				       m->quat);
		return;
	}
	for (i = 0; i < AS9888_QUAT_LEN; i++)
		v[i] = m->unit.orientation[i];
	if (as9888_mw_normalise_q30(v, AS9888_QUAT_LEN, m->quat))
		set_identity(m->quat);
	as9888_mw_up_from_quat(m->quat, m->unit.up);
}

/* A uniform Q30 value in [-2^31, 2^31) >> shift */
static s64 rng_wander(u64 *state, unsigned int shift)
{
	s64 r = (s64)(rng_next(state) & 0xffffffffULL) - (1LL << 31);

	return div64_s64(r, 1LL << shift);
}

static void tumble_axis_init(struct as9888_model *m)
{
	s64 v[AS9888_UNIT_AXES];
	int i;

	for (i = 0; i < AS9888_UNIT_AXES; i++)
		v[i] = rng_wander(&m->trng, 0);
	if (as9888_mw_normalise_q30(v, AS9888_UNIT_AXES, m->omega)) {
		m->omega[0] = AS9888_Q30_ONE;
		m->omega[1] = m->omega[2] = 0;
	}
}

/* One step of the tumble: the axis wanders, the device turns about it */
static void tumble_step(struct as9888_model *m)
{
	s64 v[AS9888_UNIT_AXES];
	s32 dq[AS9888_QUAT_LEN];
	int i;

	for (i = 0; i < AS9888_UNIT_AXES; i++)
		v[i] = m->omega[i] + rng_wander(&m->trng, TUMBLE_WANDER_SHIFT);
	/* a zero sum (cannot happen with a unit axis) keeps the old axis */
	as9888_mw_normalise_q30(v, AS9888_UNIT_AXES, m->omega);
	as9888_mw_quat_axis_angle(m->omega, m->unit.tumble_mdeg, dq);
	as9888_mw_quat_mul(m->quat, dq, m->quat);
	as9888_mw_up_from_quat(m->quat, m->unit.up);
}

void as9888_model_field_nt(const struct as9888_model *m,
			   s64 field[AS9888_UNIT_AXES])
{
	s64 world[AS9888_UNIT_AXES];
	int i;

	if (!(m->unit.world & AS9888_UNIT_WORLD_EARTH)) {
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			field[i] = m->unit.field_nt[i];
		return;
	}
	as9888_mw_earth_world_nt(m->unit.earth_nt, m->unit.incl_mdeg,
				 m->unit.decl_mdeg, world);
	as9888_mw_to_sensor(m->quat, world, field);
}

/* The disturbance of this magnetometer measurement, added to @field */
static void add_disturbance(struct as9888_model *m,
			    s64 field[AS9888_UNIT_AXES])
{
	u32 n = m->unit.dist_samples;
	s32 s = AS9888_Q30_ONE, c;
	int i;

	if (n) {
		if (m->dist_done >= n)
			return;
		m->dist_done++;
		as9888_mw_sincos(div64_s64((s64)MDEG_HALF_TURN * m->dist_done,
					   (s64)n + 1), &s, &c);
	}
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		field[i] += div_round_even((s64)m->unit.dist_nt[i] * s,
					   AS9888_Q30_ONE);
}

/*
 * What the magnetometer senses in a measurement, nT: S (B + d) + h +
 * noise. Noise: Q16 deviate * nT rms.
 */
static void magn_sensed_nt(struct as9888_model *m, s64 out[AS9888_UNIT_AXES])
{
	const s32 *soft = m->unit.soft_ppm;
	s64 b[AS9888_UNIT_AXES];
	int i;

	as9888_model_field_nt(m, b);
	add_disturbance(m, b);
	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		const s32 *row = &soft[i * AS9888_UNIT_AXES];

		out[i] = div_round_even((s64)row[0] * b[0] +
					(s64)row[1] * b[1] +
					(s64)row[2] * b[2],
					AS9888_UNIT_SOFT_ONE) +
			 m->unit.hard_nt[i];
	}
	if (!m->unit.magn_noise_nt)
		return;
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		out[i] += div_round_even(gauss_q16(&m->mrng) *
					 m->unit.magn_noise_nt, 65536);
}

static bool has_fault(const struct as9888_model *m, u32 fault)
{
	return (m->unit.faults & fault) != 0;
}

/* Registers to their reset values; the pins low; no measurement. */
static void reset_registers(struct as9888_model *m)
{
	int i;

	if (m->measuring)
		m->stats.aborted++;
	m->measuring = false;
	m->ms = AS9888_MS_POWER_DOWN;
	m->int1en = 0;
	m->int2en = 0;
	m->slct1 = 0;
	m->slct2 = 0;
	m->st1 = 0;
	m->st2 = 0;
	m->tmps = 0;
	for (i = 0; i < AS9888_UNIT_AXES; i++) {
		m->mag[i] = 0;
		m->acc[i] = 0;
	}
	for (i = 0; i < TRIM_LEN; i++)
		m->trim[i] = 0;
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		m->trim[TRIM_DA(i)] = 0x80;
	m->dr1 = false;
	m->dr2 = false;
	m->unread = false;
}

void as9888_model_init(struct as9888_model *m, const struct as9888_unit *unit,
		       u64 now_ns)
{
	*m = (struct as9888_model){ };
	if (unit)
		m->unit = *unit;
	else
		as9888_unit_default(&m->unit);
	sanitize_unit(&m->unit);
	m->bus = AS9888_BUS_I2C;
	m->now_ns = now_ns;
	m->init_ns = now_ns;
	m->rng = m->unit.seed;
	m->mrng = m->unit.seed ^ MRNG_SALT;
	m->trng = m->unit.seed ^ TRNG_SALT;
	orient_from_unit(m);
	tumble_axis_init(m);
	m->powered = true;
	m->rstn = true;
	m->rstn_pin = true;
	m->boot_end_ns = now_ns + AS9888_T_BOOT_NS;
	m->pd_since_ns = now_ns;
	m->mode_since_ns = now_ns;
	reset_registers(m);
}

void as9888_model_set_bus(struct as9888_model *m, enum as9888_bus bus)
{
	m->bus = bus == AS9888_BUS_SPI ? AS9888_BUS_SPI : AS9888_BUS_I2C;
}

s32 as9888_model_temperature_mdegc(const struct as9888_model *m, u64 now_ns)
{
	u64 elapsed_ms = 0;
	s64 t;

	if (now_ns > m->init_ns)
		elapsed_ms = div64_u64(now_ns - m->init_ns, 1000000);
	if (elapsed_ms > ELAPSED_MAX_MS)
		elapsed_ms = ELAPSED_MAX_MS;
	/* udegC/s * ms / 1e6 = mdegC; |product| <= 1e8 * 1e10 */
	t = m->unit.temperature_mdegc +
	    div_round_even((s64)m->unit.drift_udegc_s * (s64)elapsed_ms,
			   1000000);
	return (s32)clamp_s64(t, AS9888_UNIT_TEMP_MIN_MDEGC,
			      AS9888_UNIT_TEMP_MAX_MDEGC);
}

static s64 kote_term_nlsb(const u8 *ee, int axis, s32 t_mdegc)
{
	int dt9 = sign_extend32(((u32)(ee[7 + axis] >> 7) << 8) |
				ee[10 + axis], 8);
	int et1 = ee[19];
	int et2 = ee[20];
	int d = et1 - et2;
	s64 dt = (s64)t_mdegc - 25000;

	/*
	 * Kote = dt9 * 1.5 / dT, dT = d / 1.6 degC: dt9 * 12 / (5 d) LSB/degC.
	 * D4 fallback dT = 35 degC: dt9 * 3 / 70.
	 */
	if (et1 >= 0x28 && et1 <= 0xe0 && et2 >= 0x28 && et2 <= 0xe0 &&
	    d >= 16 && d <= 128)
		return div_round_even(dt9 * 12000000LL * dt, 5LL * d);
	return div_round_even(dt9 * 3000000LL * dt, 70);
}

s64 as9888_model_accel_nlsb(const struct as9888_model *m, int axis,
			    s32 t_mdegc)
{
	const u8 *ee = m->unit.eeprom;
	u8 ega, egtd, aga, ada;
	s64 st_rt, k, dt, a, b, v;
	s32 t_rt, tc;
	int egain, gain, lin;

	if (axis < 0 || axis >= AS9888_UNIT_AXES)
		return 0;
	t_mdegc = (s32)clamp_s64(t_mdegc, AS9888_UNIT_TEMP_MIN_MDEGC,
				 AS9888_UNIT_TEMP_MAX_MDEGC);
	ega = ee[7 + axis];
	egtd = ee[16 + axis];
	aga = m->trim[TRIM_GA(axis)];
	ada = m->trim[TRIM_DA(axis)];
	egain = ega & 0x3f;
	gain = aga & 0x3f;

	/* Sensitivity St(t), section 6.3-6.4, in 0.25 nLSB/g */
	st_rt = 256 + sign_extend32(egtd & 0x1f, 4);
	k = KSTE_BASE + KSTE_STEP * (s64)(egtd >> 5);
	tc = 136 + sign_extend32(ee[2] >> 3, 4);
	t_rt = (176 - tc) * 625;
	dt = (s64)t_mdegc - t_rt;
	a = st_rt * (4 * NANO + 5 * k * dt);
	/* k_gain */
	b = div_round_even(a * (gain + 16), egain + 16);
	/* projection on the axis; 0.25 nLSB -> nLSB */
	v = div_round_even(b * m->unit.up[axis], 4LL * AS9888_UNIT_UP_ONE);

	/* O(t): offset, Kote, DAC */
	v += (s64)m->unit.offset_mlsb[axis] * 1000000;
	v += kote_term_nlsb(ee, axis, t_mdegc);
	lin = dac2lin(aga, ada) - dac2lin(ega, ee[13 + axis]);
	v += div_round_even((s64)lin * 2048 * NANO, gain + 16);
	return v;
}

static bool ref3_ok(const struct as9888_model *m)
{
	return m->trim[TRIM_REF3] == (0x18 | (m->unit.eeprom[2] & 0x07));
}

static s16 sample_accel(struct as9888_model *m, int axis, s32 t_mdegc,
			s64 noise_q16, bool alpf)
{
	s64 v, noise_den;

	if (!ref3_ok(m) || m->trim[TRIM_GA(axis)] == 0)
		return 2047;
	/* noise: q16 * mLSB * 1e6 / 65536 (ALPF halves it) */
	noise_den = alpf ? 131072 : 65536;
	v = as9888_model_accel_nlsb(m, axis, t_mdegc) +
	    div_round_even(noise_q16 * m->unit.noise_mlsb * 1000000,
			   noise_den);
	return (s16)clamp_s64(div_round_even(v, NANO), -2048, 2047);
}

static s16 sample_mag(struct as9888_model *m, int axis, s64 sensed_nt,
		      s32 gen_lsb, bool *ofl)
{
	u8 ehc = m->unit.eeprom[4 + axis];
	s64 num = (sensed_nt + (s64)gen_lsb * MAG_NT_PER_LSB) * 256;
	s64 raw = div_round_even(num, (s64)MAG_NT_PER_LSB * (ehc + 128));

	if (raw <= -4096 || raw >= 4095)
		*ofl = true;
	return (s16)clamp_s64(raw, -4096, 4095);
}

/* End of a measurement at @t_ns */
static void complete_measurement(struct as9888_model *m, u64 t_ns)
{
	bool self_test = m->ms == AS9888_MS_SELF_TEST;
	s32 t = as9888_model_temperature_mdegc(m, t_ns);
	bool ofl = false;
	int i;

	if (m->unit.tumble_mdeg)
		tumble_step(m);
	m->tmps = (u8)clamp_s64(div_round_even(220000 - 2 * (s64)t, 1250),
				0, 255);
	if (self_test || m->meas_men) {
		static const s32 gen[AS9888_UNIT_AXES] = {
			AS9888_MODEL_SELFTEST_X,
			AS9888_MODEL_SELFTEST_Y,
			AS9888_MODEL_SELFTEST_Z,
		};
		s64 sensed[AS9888_UNIT_AXES];

		magn_sensed_nt(m, sensed);
		for (i = 0; i < AS9888_UNIT_AXES; i++) {
			s32 g = self_test ? gen[i] : 0;

			if (self_test && i == 2 &&
			    has_fault(m, AS9888_FAULT_SELFTEST_WEAK))
				g = AS9888_MODEL_SELFTEST_WEAK_Z;
			m->mag[i] = sample_mag(m, i, sensed[i], g, &ofl);
		}
		if (has_fault(m, AS9888_FAULT_HOFL)) {
			m->mag[0] = 4095;
			ofl = true;
		}
		m->st2 = ofl ? AS9888_ST2_HOFL_MSK : 0;
	} else {
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			m->mag[i] = 0;
		m->st2 = AS9888_ST2_HST_MSK;
	}
	if (!self_test) {
		s64 noise[AS9888_UNIT_AXES];

		for (i = 0; i < AS9888_UNIT_AXES; i++)
			noise[i] = gauss_q16(&m->rng);
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			m->acc[i] = sample_accel(m, i, t, noise[i],
						 m->meas_alpf);
		if (has_fault(m, AS9888_FAULT_STUCK_X))
			m->acc[0] = AS9888_MODEL_STUCK_X_VALUE;
		if (has_fault(m, AS9888_FAULT_SATURATE_Z))
			m->acc[2] = 2047;
	}

	if (m->unread)
		m->st1 |= AS9888_ST1_DOR_MSK;
	m->st1 |= AS9888_ST1_DRDY_MSK;
	m->unread = true;
	if (m->int1en & AS9888_INTEN_DR_MSK) {
		if (!m->dr1)
			m->dr1_rises++;
		m->dr1 = true;
	}
	if (m->int2en & AS9888_INTEN_DR_MSK) {
		if (!m->dr2)
			m->dr2_rises++;
		m->dr2 = true;
	}

	m->measuring = false;
	m->ms = AS9888_MS_POWER_DOWN;
	m->pd_since_ns = t_ns;
	m->mode_since_ns = t_ns;
	m->stats.measurements++;
	if (self_test || m->meas_men)
		m->stats.magn_measurements++;
}

static u64 reset_effect_ns(const struct as9888_model *m)
{
	return m->reset_pending ? m->rstn_fell_ns + AS9888_T_RSTL_NS : U64_MAX;
}

static u64 measurement_end_ns(const struct as9888_model *m)
{
	if (!m->measuring || has_fault(m, AS9888_FAULT_NO_DRDY))
		return U64_MAX;
	return m->meas_end_ns;
}

u64 as9888_model_next_event_ns(const struct as9888_model *m)
{
	return min(reset_effect_ns(m), measurement_end_ns(m));
}

void as9888_model_advance(struct as9888_model *m, u64 now_ns)
{
	if (now_ns < m->now_ns)
		now_ns = m->now_ns;
	m->now_ns = now_ns;

	for (;;) {
		u64 meas = measurement_end_ns(m);
		u64 rst = reset_effect_ns(m);

		if (meas <= rst && meas <= now_ns) {
			complete_measurement(m, meas);
		} else if (rst < meas && rst <= now_ns) {
			m->reset_pending = false;
			reset_registers(m);
			m->pd_since_ns = rst;
			m->mode_since_ns = rst;
			m->stats.resets++;
		} else {
			break;
		}
	}
}

void as9888_model_set_power(struct as9888_model *m, u64 now_ns, bool on)
{
	as9888_model_advance(m, now_ns);
	if (on == m->powered)
		return;
	m->powered = on;
	if (!on) {
		if (m->rstn_pin)
			m->stats.backpowered++;
		reset_registers(m);
		m->reset_pending = false;
		m->stats.power_offs++;
		return;
	}
	m->boot_end_ns = m->now_ns + AS9888_T_BOOT_NS;
	m->pd_since_ns = m->now_ns;
	m->mode_since_ns = m->now_ns;
}

void as9888_model_set_temperature(struct as9888_model *m, u64 now_ns,
				  s32 t_mdegc)
{
	as9888_model_advance(m, now_ns);
	m->unit.temperature_mdegc = t_mdegc;
	sanitize_unit(&m->unit);
	/* the drift counts from this instant */
	m->init_ns = m->now_ns;
}

void as9888_model_set_up(struct as9888_model *m, u64 now_ns,
			 const s32 up[AS9888_UNIT_AXES])
{
	int i;

	as9888_model_advance(m, now_ns);
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		m->unit.up[i] = up[i];
	sanitize_unit(&m->unit);
	m->unit.world &= ~AS9888_UNIT_WORLD_ORIENTATION;
	orient_from_unit(m);
}

void as9888_model_set_heading(struct as9888_model *m, u64 now_ns,
			      s32 heading_mdeg)
{
	as9888_model_advance(m, now_ns);
	m->unit.heading_mdeg = heading_mdeg;
	sanitize_unit(&m->unit);
	m->unit.world &= ~AS9888_UNIT_WORLD_ORIENTATION;
	orient_from_unit(m);
}

void as9888_model_set_orientation(struct as9888_model *m, u64 now_ns,
				  const s32 q[AS9888_QUAT_LEN])
{
	int i;

	as9888_model_advance(m, now_ns);
	if (!q[0] && !q[1] && !q[2] && !q[3])
		return;
	for (i = 0; i < AS9888_QUAT_LEN; i++)
		m->unit.orientation[i] = q[i];
	m->unit.world |= AS9888_UNIT_WORLD_ORIENTATION;
	orient_from_unit(m);
}

void as9888_model_orientation(const struct as9888_model *m,
			      s32 q[AS9888_QUAT_LEN])
{
	int i;

	for (i = 0; i < AS9888_QUAT_LEN; i++)
		q[i] = m->quat[i];
}

void as9888_model_set_earth(struct as9888_model *m, u64 now_ns, s32 f_nt,
			    s32 incl_mdeg, s32 decl_mdeg)
{
	as9888_model_advance(m, now_ns);
	m->unit.earth_nt = f_nt;
	m->unit.incl_mdeg = incl_mdeg;
	m->unit.decl_mdeg = decl_mdeg;
	m->unit.world |= AS9888_UNIT_WORLD_EARTH;
	sanitize_unit(&m->unit);
}

void as9888_model_set_hard_iron(struct as9888_model *m, u64 now_ns,
				const s32 h_nt[AS9888_UNIT_AXES])
{
	int i;

	as9888_model_advance(m, now_ns);
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		m->unit.hard_nt[i] = h_nt[i];
	sanitize_unit(&m->unit);
}

void as9888_model_set_soft_iron(struct as9888_model *m, u64 now_ns,
				const s32 s_ppm[SOFT_LEN])
{
	int i;

	as9888_model_advance(m, now_ns);
	for (i = 0; i < SOFT_LEN; i++)
		m->unit.soft_ppm[i] = s_ppm[i];
	sanitize_unit(&m->unit);
}

void as9888_model_set_magn_noise(struct as9888_model *m, u64 now_ns,
				 u32 noise_nt)
{
	as9888_model_advance(m, now_ns);
	m->unit.magn_noise_nt = noise_nt;
	sanitize_unit(&m->unit);
}

void as9888_model_set_disturbance(struct as9888_model *m, u64 now_ns,
				  const s32 d_nt[AS9888_UNIT_AXES], u32 n)
{
	int i;

	as9888_model_advance(m, now_ns);
	for (i = 0; i < AS9888_UNIT_AXES; i++)
		m->unit.dist_nt[i] = d_nt[i];
	m->unit.dist_samples = n;
	m->dist_done = 0;
	sanitize_unit(&m->unit);
}

void as9888_model_set_tumble(struct as9888_model *m, u64 now_ns,
			     u32 tumble_mdeg)
{
	as9888_model_advance(m, now_ns);
	m->unit.tumble_mdeg = tumble_mdeg;
	sanitize_unit(&m->unit);
}

void as9888_model_set_noise(struct as9888_model *m, u64 now_ns,
			    u32 noise_mlsb)
{
	as9888_model_advance(m, now_ns);
	m->unit.noise_mlsb = noise_mlsb;
	sanitize_unit(&m->unit);
}

void as9888_model_set_rstn(struct as9888_model *m, u64 now_ns, bool level)
{
	as9888_model_advance(m, now_ns);
	if (!m->powered && level && !m->rstn_pin)
		m->stats.backpowered++;
	m->rstn_pin = level;
	if (has_fault(m, AS9888_FAULT_RSTN_OPEN) || level == m->rstn)
		return;
	if (!m->powered) {
		/* nothing to reset; a rising edge after power-on boots it */
		m->rstn = level;
		m->reset_pending = false;
		return;
	}
	m->rstn = level;
	if (!level) {
		m->rstn_fell_ns = m->now_ns;
		m->reset_pending = true;
		return;
	}
	if (m->reset_pending) {
		/* shorter than t_RSTL: a glitch, ignored */
		m->reset_pending = false;
		return;
	}
	m->boot_end_ns = m->now_ns + AS9888_T_BOOT_NS;
	m->pd_since_ns = m->now_ns;
	m->mode_since_ns = m->now_ns;
}

bool as9888_model_pin(struct as9888_model *m, u64 now_ns,
		      enum as9888_pin pin)
{
	as9888_model_advance(m, now_ns);
	if (pin == AS9888_PIN_INT1)
		return m->dr1 && !has_fault(m, AS9888_FAULT_INT1_OPEN);
	if (pin == AS9888_PIN_INT2)
		return m->dr2 && !has_fault(m, AS9888_FAULT_INT2_OPEN);
	return false;
}

u32 as9888_model_pin_rises(const struct as9888_model *m, enum as9888_pin pin)
{
	if (pin == AS9888_PIN_INT1)
		return has_fault(m, AS9888_FAULT_INT1_OPEN) ? 0 : m->dr1_rises;
	if (pin == AS9888_PIN_INT2)
		return has_fault(m, AS9888_FAULT_INT2_OPEN) ? 0 : m->dr2_rises;
	return 0;
}

/* Count a transfer; true when the chip does not answer it. */
static bool transfer_fails(struct as9888_model *m)
{
	bool nak = false;

	m->stats.transfers++;
	if (++m->nak_count >= AS9888_MODEL_NAK_PERIOD) {
		m->nak_count = 0;
		nak = has_fault(m, AS9888_FAULT_NAK);
	}
	if (!m->powered)
		m->stats.unpowered_transfers++;
	if (!m->powered || !m->rstn || m->now_ns < m->boot_end_ns)
		nak = true;
	if (nak)
		m->stats.naks++;
	return nak;
}

static u8 next_addr(const struct as9888_model *m, u8 reg)
{
	return m->bus == AS9888_BUS_SPI ? (reg + 1) & 0x7f : (u8)(reg + 1);
}

static void deassert(struct as9888_model *m)
{
	m->dr1 = false;
	m->dr2 = false;
	m->st1 &= ~AS9888_ST1_DRDY_MSK;
}

static void write_ms(struct as9888_model *m, u8 v)
{
	u64 now = m->now_ns;
	u64 dur;

	if (v == AS9888_MS_POWER_DOWN) {
		if (m->measuring) {
			m->measuring = false;
			m->stats.aborted++;
		}
		if (m->ms != AS9888_MS_POWER_DOWN) {
			m->pd_since_ns = now;
			m->mode_since_ns = now;
		}
		m->ms = AS9888_MS_POWER_DOWN;
		deassert(m);
		return;
	}
	if (v != AS9888_MS_SINGLE && v != AS9888_MS_EEPROM &&
	    v != AS9888_MS_SELF_TEST)
		return;		/* reserved */
	if (m->ms != AS9888_MS_POWER_DOWN || m->measuring ||
	    now - m->pd_since_ns < AS9888_T_PD_NS)
		return;		/* not from power-down, or before t_PD */

	m->ms = v;
	m->mode_since_ns = now;
	deassert(m);
	if (v == AS9888_MS_EEPROM)
		return;
	m->meas_men = v == AS9888_MS_SELF_TEST ||
		      (m->slct2 & AS9888_SLCT2_MEN_MSK);
	m->meas_alpf = m->slct2 & AS9888_SLCT2_ALPF_MSK;
	if (m->meas_men)
		dur = AS9888_T_MAG_NS;
	else if (m->meas_alpf)
		dur = AS9888_T_ACC_LPF_NS;
	else
		dur = AS9888_T_ACC_NS;
	m->measuring = true;
	m->meas_end_ns = now + dur;
}

u8 as9888_model_peek(const struct as9888_model *m, u8 reg)
{
	switch (reg) {
	case AS9888_REG_INT1EN:
		return m->int1en;
	case AS9888_REG_INT2EN:
		return m->int2en;
	case AS9888_REG_SLCT1:
		return m->slct1;
	case AS9888_REG_SLCT2:
		return m->slct2;
	case AS9888_REG_MS:
		return m->ms;
	case AS9888_REG_REF1 ... AS9888_REG_AZDA:
		return m->trim[reg - AS9888_REG_REF1];
	default:
		return 0;
	}
}

static u8 read_byte(struct as9888_model *m, u8 reg)
{
	u8 v;

	switch (reg) {
	case AS9888_REG_WIA:
		return has_fault(m, AS9888_FAULT_WIA) ? AS9888_WIA_FAULT_VAL :
							AS9888_WIA_VAL;
	case AS9888_REG_INT1ST:
		v = m->dr1 ? AS9888_INTST_DR_MSK : 0;
		m->dr1 = false;
		return v;
	case AS9888_REG_INT2ST:
		v = m->dr2 ? AS9888_INTST_DR_MSK : 0;
		m->dr2 = false;
		return v;
	case AS9888_REG_ST1:
		return m->st1;
	case AS9888_REG_HXL ... AS9888_REG_HXL + 5:
		v = reg - AS9888_REG_HXL;
		return (u8)((u16)m->mag[v >> 1] >> ((v & 1) * 8));
	case AS9888_REG_TMPS:
		return m->tmps;
	case AS9888_REG_A1XL ... AS9888_REG_A1XL + 5:
		v = reg - AS9888_REG_A1XL;
		return (u8)((u16)m->acc[v >> 1] >> ((v & 1) * 8));
	case AS9888_REG_ST2:
		m->st1 &= ~(AS9888_ST1_DRDY_MSK | AS9888_ST1_DOR_MSK);
		m->unread = false;
		return m->st2;
	case AS9888_REG_EEPROM ... AS9888_REG_EEPROM_END:
		if (m->ms != AS9888_MS_EEPROM ||
		    m->now_ns - m->mode_since_ns < AS9888_T_EEP_NS)
			return 0;
		if (has_fault(m, AS9888_FAULT_EEPROM_BLANK))
			return 0xff;
		return m->unit.eeprom[reg - AS9888_REG_EEPROM];
	default:
		/* configuration and trim; 0 for EMPT and unlisted registers */
		return as9888_model_peek(m, reg);
	}
}

static void write_byte(struct as9888_model *m, u8 reg, u8 v)
{
	switch (reg) {
	case AS9888_REG_INT1EN:
		m->int1en = v;
		break;
	case AS9888_REG_INT2EN:
		m->int2en = v;
		break;
	case AS9888_REG_SLCT1:
		m->slct1 = v;
		break;
	case AS9888_REG_SLCT2:
		m->slct2 = v;
		break;
	case AS9888_REG_MS:
		write_ms(m, v);
		break;
	case AS9888_REG_REF1 ... AS9888_REG_AZDA:
		if (m->ms != AS9888_MS_POWER_DOWN || m->measuring)
			break;
		if (reg >= AS9888_REG_AXGA && reg < AS9888_REG_AXDA)
			v &= 0x7f;
		m->trim[reg - AS9888_REG_REF1] = v;
		break;
	default:
		break;		/* read-only and unlisted registers */
	}
}

int as9888_model_read(struct as9888_model *m, u64 now_ns, u8 reg, u8 *buf,
		      unsigned int len)
{
	unsigned int i;

	if (!buf && len)
		return -EINVAL;
	as9888_model_advance(m, now_ns);
	m->stats.reads++;
	if (m->bus == AS9888_BUS_SPI)
		reg &= 0x7f;
	if (transfer_fails(m)) {
		if (m->bus == AS9888_BUS_I2C)
			return -EIO;
		for (i = 0; i < len; i++)
			buf[i] = 0xff;
		return 0;
	}
	for (i = 0; i < len; i++) {
		buf[i] = read_byte(m, reg);
		reg = next_addr(m, reg);
	}
	m->stats.bytes_read += len;
	return 0;
}

int as9888_model_write(struct as9888_model *m, u64 now_ns, u8 reg,
		       const u8 *buf, unsigned int len)
{
	unsigned int i;

	if (!buf && len)
		return -EINVAL;
	as9888_model_advance(m, now_ns);
	m->stats.writes++;
	if (m->bus == AS9888_BUS_SPI)
		reg &= 0x7f;
	if (transfer_fails(m))
		return m->bus == AS9888_BUS_I2C ? -EIO : 0;
	for (i = 0; i < len; i++) {
		write_byte(m, reg, buf[i]);
		reg = next_addr(m, reg);
	}
	m->stats.bytes_written += len;
	return 0;
}
