/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 chip model: the chip of datasheet sections 1-5 and 8 as a state
 * machine in virtual time.
 *
 * The same file builds in userspace (unit tests, the daemon's simulator)
 * and in a kernel module (the in-kernel test adapter): integer arithmetic
 * only, no libc, no allocation (the caller owns struct as9888_model), no
 * undefined behaviour for any input.
 *
 * Time comes from the caller: every entry point takes now_ns, a monotonic
 * nanosecond clock. A now_ns earlier than one seen before is treated as
 * the latest time seen. Internal events (end of a measurement, a reset
 * taking effect) are processed lazily when an entry point is called with a
 * time at or after the event; as9888_model_next_event_ns() tells a
 * simulator when to wake up.
 *
 * Timing used by the model (the datasheet minimums, exactly):
 * t_RSTL 5 us, t_BOOT 100 us, t_EEP 300 us, t_PD 100 us,
 * t_ACC 1.2 ms / 4.8 ms (ALPF), t_MAG 7.3 ms.
 *
 * Behaviour where the datasheet is silent (see also the .c file):
 *  - Power-on and the rising edge of a valid reset pulse both enter
 *    power-down at that instant, so t_PD is covered by t_BOOT.
 *  - Supply off (as9888_model_set_power()): like RSTN held low, the chip
 *    does not answer, its registers are at their reset values and the pins
 *    low; power-on starts t_BOOT. A transfer attempted while the supply is
 *    off is counted in stats.unpowered_transfers (a driver that talks to
 *    a chip it switched off), and RSTN driven high while the supply is off
 *    in stats.backpowered (the pin would feed the chip through its ESD
 *    diodes): once when the supply goes off with RSTN high, once when RSTN
 *    rises while the supply is off. Both are board-level errors of the
 *    host, so they are counted whatever the faults (also with rstn_open). The die temperature, the noise generator
 *    and the counters carry on (they belong to the unit, not to the chip's
 *    registers).
 *  - RSTN low: the chip does not answer (I2C NAK / SPI 0xff) while RSTN is
 *    low. Once RSTN has been low for t_RSTL the reset takes effect
 *    (registers to reset values, measurement aborted, pins low); a shorter
 *    low pulse is a glitch and changes nothing. Boot time t_BOOT starts at
 *    the rising edge of a valid pulse.
 *  - MS = 0x00 written in power-down is accepted: it does not restart the
 *    t_PD timer but, like every accepted MS write, deasserts INT1/INT2,
 *    clears DR1/DR2 and DRDY. DOR is only cleared by reading ST2.
 *  - An accepted MS write also clears DR1/DR2 (the pins are deasserted).
 *  - While a measurement runs MS reads 0x01 (0x08 in self-test); it reads
 *    0x00 again from the instant the measurement completed.
 *  - SLCT2 (MEN, ALPF) is sampled when the measurement starts.
 *  - DOR is set when a measurement completes while the previous sample is
 *    unread, i.e. ST2 has not been read since it completed. An accepted
 *    MS write clears DRDY but does not mark the data read (otherwise DOR
 *    could never be set: every measurement starts with an MS write).
 *  - MEN = 0: HST = 1 and the magnetometer registers read 0.
 *  - Self-test measures the magnetometer (ambient field plus the generator)
 *    and the temperature; the accelerometer registers keep their values.
 *  - The die temperature used for a sample is the one at its completion
 *    time; it is clamped to -50..150 degC, TMPS to 0..255.
 *  - Accelerometer axis with AxGA == 0, or any axis while REF3 is not
 *    0x18 | (EREF3 & 7): reads 2047 (reference circuit untrimmed).
 *    REF1, REF2 and OSC have no modelled effect.
 *  - The physics always uses the unit's EEPROM, also with eeprom_blank
 *    (that fault only changes what the bus reads).
 *  - Register addresses auto-increment modulo 256 (SPI: modulo 128); every
 *    byte of a burst behaves as a single access to its address, in order.
 *  - INT pins are push-pull outputs latched at measurement end; changing
 *    DRxEN afterwards does not move them.
 *  - Faults: no_drdy: the measurement never completes (MS stays non-zero
 *    until 0x00 is written); int1_open/int2_open: DRx is still set in
 *    INTxST but the pin stays low; stuck_x: accelerometer X always reads
 *    AS9888_MODEL_STUCK_X_VALUE; saturate_z: Z reads 2047; nak: the 50th,
 *    100th, ... transfer (counted from power-on, every transfer counts)
 *    fails; selftest_weak: the generator's Z is 150 LSB instead of 600;
 *    hofl: every magnetometer measurement reads X = 4095 and sets HOFL.
 *  - I2C failure = -EIO (NAK). SPI has no NAK: a failing SPI transfer
 *    reads 0xff bytes and drops written bytes, and returns 0. Both count
 *    in stats.naks.
 *  - The noise generator draws three Gaussians per accelerometer
 *    measurement (also for faulty axes), so the same seed and the same
 *    command sequence give the same samples. The magnetometer's noise
 *    (magn_noise, default 0: noiseless) and the tumble have generators of
 *    their own, seeded from the same seed: they leave the accelerometer's
 *    samples as they were.
 *  - The magnetic world (as9888_unit.h, as9888_magworld.h): every
 *    magnetometer measurement (also self-test) reads S (B + d) + h +
 *    noise, B the external field in the sensor frame at its completion, d
 *    the disturbance, S the soft iron, h the hard iron. The self-test
 *    generator is added after (it is inside the chip). The magnetometer
 *    has no temperature coefficient (the datasheet gives none).
 *  - Orientation: the accelerometer's up and the field's rotation come
 *    from one orientation. Given as "up" (+ "heading") the accelerometer
 *    uses "up" exactly as given; given as "orientation", or moved by the
 *    tumble, "up" is derived from it.
 *  - Tumble: every measurement (accelerometer or magnetometer) first turns
 *    the device by tumble degrees about an axis fixed in the sensor frame
 *    that itself wanders a little at every step (a random walk): smooth,
 *    seeded, natural motion, not a uniform sphere.
 *  - Disturbance: counts magnetometer measurements from the instant it is
 *    set (unit or setter); the k-th of n adds d sin(180 deg k / (n + 1)).
 */
#ifndef AS9888_MODEL_H
#define AS9888_MODEL_H

#include <linux/bits.h>
#include <linux/kernel.h>
#include <linux/types.h>

#include "as9888_magworld.h"
#include "as9888_unit.h"

#ifndef U64_MAX
#define U64_MAX			((u64)~0ULL)
#endif

/* Register map and timing shared with the driver and the daemon */
#include "as9888_regs.h"

/* Names the shared header does not carry */
#define AS9888_REG_HXH		0x12
#define AS9888_REG_HYL		0x13
#define AS9888_REG_HYH		0x14
#define AS9888_REG_HZL		0x15
#define AS9888_REG_HZH		0x16
#define AS9888_REG_A1XH		0x1a
#define AS9888_REG_A1YL		0x1b
#define AS9888_REG_A1YH		0x1c
#define AS9888_REG_A1ZL		0x1d
#define AS9888_REG_A1ZH		0x1e
#define AS9888_REG_AYGA		0x35
#define AS9888_REG_AZGA		0x36
#define AS9888_REG_AYDA		0x38
#define AS9888_WIA_FAULT_VAL	0x47

/* Timing in ns, the datasheet minimums exactly */
#define AS9888_T_RSTL_NS	(AS9888_T_RSTL_US * 1000ULL)
#define AS9888_T_BOOT_NS	(AS9888_T_BOOT_US * 1000ULL)
#define AS9888_T_EEP_NS		(AS9888_T_EEP_US * 1000ULL)
#define AS9888_T_PD_NS		(AS9888_T_PD_US * 1000ULL)
#define AS9888_T_ACC_NS		(AS9888_T_ACC_US * 1000ULL)
#define AS9888_T_ACC_LPF_NS	(AS9888_T_ACC_LPF_US * 1000ULL)
#define AS9888_T_MAG_NS		(AS9888_T_MAG_US * 1000ULL)

/* Fault behaviour constants */
#define AS9888_MODEL_NAK_PERIOD		50
#define AS9888_MODEL_STUCK_X_VALUE	1000
/* Self-test generator, LSB after sensitivity adjustment */
#define AS9888_MODEL_SELFTEST_X		(-20)
#define AS9888_MODEL_SELFTEST_Y		15
#define AS9888_MODEL_SELFTEST_Z		600
#define AS9888_MODEL_SELFTEST_WEAK_Z	150

enum as9888_bus {
	AS9888_BUS_I2C = 0,
	AS9888_BUS_SPI,
};

enum as9888_pin {
	AS9888_PIN_INT1 = 0,
	AS9888_PIN_INT2,
};

/**
 * struct as9888_model_stats - bus and chip counters since as9888_model_init()
 * @transfers:		bus transfers (reads + writes, also failed ones)
 * @reads:		read transfers
 * @writes:		write transfers
 * @naks:		failed transfers (boot, RSTN low, nak fault)
 * @bytes_read:		data bytes returned by successful reads
 * @bytes_written:	data bytes of successful writes
 * @measurements:	measurements completed
 * @magn_measurements: of these, the ones that measured the magnetometer
 *			(SLCT2.MEN set, or self-test)
 * @aborted:		measurements aborted (MS = 0 or reset)
 * @resets:		reset pulses that took effect
 * @power_offs:		supply switched off
 * @unpowered_transfers: transfers attempted while the supply was off
 * @backpowered:	times RSTN was driven high while the supply was off
 */
struct as9888_model_stats {
	u64 transfers;
	u64 reads;
	u64 writes;
	u64 naks;
	u64 bytes_read;
	u64 bytes_written;
	u64 measurements;
	u64 magn_measurements;
	u64 aborted;
	u64 resets;
	u64 power_offs;
	u64 unpowered_transfers;
	u64 backpowered;
};

/**
 * struct as9888_model - the chip state; treat as opaque, use the functions
 */
struct as9888_model {
	struct as9888_unit unit;	/* clamped copy */
	enum as9888_bus bus;
	u64 now_ns;			/* latest time seen */
	u64 init_ns;			/* power-on time (temperature drift) */
	u64 rng;			/* noise generator state */
	u64 mrng;			/* magnetometer noise generator */
	u64 trng;			/* tumble generator */
	s32 quat[AS9888_QUAT_LEN];	/* orientation, Q30, sensor to world */
	s32 omega[AS9888_UNIT_AXES];	/* tumble axis, Q30, sensor frame */
	u32 dist_done;			/* disturbance measurements so far */

	/* supply, reset pin and boot */
	bool powered;			/* supply on */
	bool rstn;			/* RSTN level the chip sees */
	bool rstn_pin;			/* RSTN level driven (also rstn_open) */
	bool reset_pending;		/* low, reset not yet taken effect */
	u64 rstn_fell_ns;
	u64 boot_end_ns;		/* accesses fail before this */

	/* mode */
	u8 ms;
	u64 pd_since_ns;		/* power-down entered */
	u64 mode_since_ns;		/* current mode entered */
	bool measuring;
	u64 meas_end_ns;
	bool meas_men;
	bool meas_alpf;

	/* registers */
	u8 int1en;
	u8 int2en;
	u8 slct1;
	u8 slct2;
	u8 st1;
	u8 st2;
	u8 tmps;
	s16 mag[AS9888_UNIT_AXES];
	s16 acc[AS9888_UNIT_AXES];
	u8 trim[10];			/* 0x30..0x39 */
	bool dr1;
	bool dr2;
	u32 dr1_rises;			/* INT1 low-to-high transitions */
	u32 dr2_rises;			/* INT2 low-to-high transitions */
	bool unread;			/* ST2 not read since last sample */

	u32 nak_count;			/* transfers modulo the NAK period */
	struct as9888_model_stats stats;
};

/* Power on at now_ns with @unit (NULL: as9888_unit_default()); I2C bus. */
void as9888_model_init(struct as9888_model *m, const struct as9888_unit *unit,
		       u64 now_ns);
/* Select the bus flavour (how failures look), default I2C. */
void as9888_model_set_bus(struct as9888_model *m, enum as9888_bus bus);

/*
 * One bus transfer starting at @reg with auto-increment. Returns 0 or
 * -EIO when the chip NAKs (I2C only). @len 0 is a valid (address-only)
 * transfer. Reads of a failed SPI transfer fill @buf with 0xff.
 */
int as9888_model_read(struct as9888_model *m, u64 now_ns, u8 reg, u8 *buf,
		      unsigned int len);
int as9888_model_write(struct as9888_model *m, u64 now_ns, u8 reg,
		       const u8 *buf, unsigned int len);

/* Switch the supply (true = on); on again starts t_BOOT. */
void as9888_model_set_power(struct as9888_model *m, u64 now_ns, bool on);

/*
 * Live changes of the unit's environment, as a test bench changes the
 * room around a chip: registers, a running measurement, the noise
 * generator and the counters stay. Events due before @now_ns happen
 * first with the old value; every measurement that completes from @now_ns
 * on uses the new one. Values are clamped as in as9888_model_init().
 */
/* Die temperature at @now_ns; a temperature_drift continues from there. */
void as9888_model_set_temperature(struct as9888_model *m, u64 now_ns,
				  s32 t_mdegc);
/* Posture: the sensor-frame direction pointing up, normalised to 1e6. */
void as9888_model_set_up(struct as9888_model *m, u64 now_ns,
			 const s32 up[AS9888_UNIT_AXES]);
/* Accelerometer noise, milli-LSB rms with ALPF = 0. */
void as9888_model_set_noise(struct as9888_model *m, u64 now_ns,
			    u32 noise_mlsb);

/*
 * The magnetic world, live (see as9888_unit.h for the units and ranges;
 * values are clamped as in as9888_model_init()). set_up() and
 * set_heading() give the orientation as (up, heading), set_orientation()
 * as a quaternion of any scale (a zero one is ignored). set_disturbance()
 * starts a passing magnet now.
 */
void as9888_model_set_heading(struct as9888_model *m, u64 now_ns,
			      s32 heading_mdeg);
void as9888_model_set_orientation(struct as9888_model *m, u64 now_ns,
				  const s32 q[AS9888_QUAT_LEN]);
void as9888_model_set_earth(struct as9888_model *m, u64 now_ns, s32 f_nt,
			    s32 incl_mdeg, s32 decl_mdeg);
void as9888_model_set_hard_iron(struct as9888_model *m, u64 now_ns,
				const s32 h_nt[AS9888_UNIT_AXES]);
void as9888_model_set_soft_iron(struct as9888_model *m, u64 now_ns,
				const s32 s_ppm[AS9888_UNIT_AXES *
						AS9888_UNIT_AXES]);
void as9888_model_set_magn_noise(struct as9888_model *m, u64 now_ns,
				 u32 noise_nt);
void as9888_model_set_disturbance(struct as9888_model *m, u64 now_ns,
				  const s32 d_nt[AS9888_UNIT_AXES], u32 n);
void as9888_model_set_tumble(struct as9888_model *m, u64 now_ns,
			     u32 tumble_mdeg);

/* The orientation now (Q30 unit quaternion, sensor to world). */
void as9888_model_orientation(const struct as9888_model *m,
			      s32 q[AS9888_QUAT_LEN]);

/*
 * The external field in the sensor frame now, nT: the Earth's turned by
 * the orientation (or the unit's fixed field), without disturbance, iron
 * or noise. The truth a calibration should recover. For tests and benches.
 */
void as9888_model_field_nt(const struct as9888_model *m,
			   s64 field[AS9888_UNIT_AXES]);

/* Drive RSTN (true = high). */
void as9888_model_set_rstn(struct as9888_model *m, u64 now_ns, bool level);

/* Level of INT1/INT2 at now_ns. */
bool as9888_model_pin(struct as9888_model *m, u64 now_ns,
		      enum as9888_pin pin);

/*
 * How often INT1/INT2 has risen since power-on, as of the last call that
 * took a time (an open pin never rises). A caller that samples the level
 * can miss a pulse: the pin falls on an MS write and rises again when
 * that measurement ends, both between two of its looks when the caller
 * is delayed. The count tells it that an edge happened all the same.
 */
u32 as9888_model_pin_rises(const struct as9888_model *m, enum as9888_pin pin);

/*
 * Time of the next internal event (measurement completion, reset taking
 * effect) as of the last call, or U64_MAX when none is pending.
 */
u64 as9888_model_next_event_ns(const struct as9888_model *m);

/* Process internal events up to now_ns (the other calls do this too). */
void as9888_model_advance(struct as9888_model *m, u64 now_ns);

/* Die temperature at now_ns, millidegrees Celsius (clamped). */
s32 as9888_model_temperature_mdegc(const struct as9888_model *m, u64 now_ns);

/*
 * Noise-free accelerometer value of @axis with the current registers at
 * temperature @t_mdegc, in nano-LSB (before rounding, clamping and
 * faults). For tests and benches.
 */
s64 as9888_model_accel_nlsb(const struct as9888_model *m, int axis,
			    s32 t_mdegc);

/*
 * Value of a configuration or trim register (INT1EN..MS, REF1..AZDA) as
 * the chip holds it, without the side effects or the counting of a bus
 * read; 0 for any other register. For tests and benches.
 */
u8 as9888_model_peek(const struct as9888_model *m, u8 reg);

static inline const struct as9888_model_stats *
as9888_model_stats(const struct as9888_model *m)
{
	return &m->stats;
}

#endif /* AS9888_MODEL_H */
