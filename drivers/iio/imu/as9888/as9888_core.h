/* SPDX-License-Identifier: GPL-2.0 */
/*
 * ALSEN AS9888 6-axis sensor: definitions shared by the files of the core
 * driver (chip access, the accelerometer and magnetometer IIO devices, the
 * data-ready trigger).
 *
 * The register map and the timing of the datasheet live in as9888_regs.h,
 * which the userspace daemon and the chip model share; this header adds
 * what only the kernel driver needs.
 */
#ifndef AS9888_CORE_H
#define AS9888_CORE_H

#include <linux/build_bug.h>
#include <linux/compiler.h>
#include <linux/completion.h>
#include <linux/ktime.h>
#include <linux/mutex.h>
#include <linux/regulator/consumer.h>
#include <linux/stddef.h>
#include <linux/types.h>
#include <linux/wait.h>

#include <linux/iio/iio.h>

#include "as9888.h"
#include "as9888_calib.h"

struct iio_trigger;

#define AS9888_MAX_REG			AS9888_REG_EEPROM_END
static_assert(AS9888_REG_EEPROM + AS9888_EEPROM_LEN - 1 ==
	      AS9888_REG_EEPROM_END);

/* vdd and vid */
#define AS9888_SUPPLIES			2

/**
 * struct as9888_raw_sample - one burst read of ST1..ST2 (0x10..0x1f)
 * @st1:	ST1: DRDY, DOR
 * @magn:	HXL..HZH, 13-bit two's complement sign-extended to 16 bit
 * @tmps:	temperature code
 * @empt:	reserved, 0x00 on a healthy device
 * @accel:	A1XL..A1ZH, 12-bit two's complement sign-extended to 16 bit
 * @st2:	ST2: HST, HOFL; reading it ends the data read
 */
struct as9888_raw_sample {
	u8 st1;
	__le16 magn[AS9888_AXES];
	u8 tmps;
	u8 empt;
	__le16 accel[AS9888_AXES];
	u8 st2;
} __packed;
static_assert(sizeof(struct as9888_raw_sample) == AS9888_SAMPLE_LEN);
static_assert(offsetof(struct as9888_raw_sample, magn) ==
	      AS9888_REG_HXL - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, tmps) ==
	      AS9888_REG_TMPS - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, empt) ==
	      AS9888_REG_EMPT - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, accel) ==
	      AS9888_REG_A1XL - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, st2) ==
	      AS9888_REG_ST2 - AS9888_REG_ST1);

/* Sensors of the chip, each an IIO device of its own */
enum as9888_sensor_id {
	AS9888_ACCEL,
	AS9888_MAGN,
	AS9888_SENSORS,
};

/**
 * struct as9888_chip - state of one chip, shared by its two IIO devices
 * @dev:	the bus device, parent of both IIO devices
 * @regmap:	register map; the trim and configuration registers are cached
 *		and rewritten by regcache_sync() after a power cycle
 * @iio:	the accelerometer and the magnetometer IIO devices
 * @trig:	data-ready trigger, NULL when INT1 is not wired
 * @supplies:	vdd and vid
 * @orientation: mount matrix from firmware
 * @ee:		the decoded factory EEPROM, read once at probe
 * @irq:	INT1, or 0 to poll ST1
 * @drdy:	completed by INT1 for measurements waited for synchronously
 * @stop_wq:	wakes the data-ready trigger's wait for its next sampling
 *		period when the trigger stops
 * @gap_wq:	wakes whoever waits for the gap between two samples of the
 *		data-ready trigger
 * @drdy_time:	ktime of the last INT1 edge (the chip entered power-down)
 * @drdy_ts:	IIO timestamp of the last INT1 edge, per device (each has
 *		its own clock), for measurements waited for synchronously
 * @trig_running: the data-ready trigger runs; written under @lock, read
 *		locklessly while waiting for the next sampling period
 * @trig_busy:	a sample of the data-ready trigger is in flight or its
 *		handlers are not done with it: the chip is not free for
 *		anything else. Written under @lock, read locklessly by the
 *		INT1 handler (which then polls the trigger instead of
 *		completing @drdy)
 * @lock:	serialises every register access sequence of the driver and
 *		protects the fields below. A measurement is a sequence (mode
 *		write, wait, burst read) that must not interleave with another
 *		one or with a trim write, which the chip accepts in power-down
 *		only. With @lock held and @trig_busy clear, the chip is in
 *		power-down. Taken after the IIO direct-mode claim and after a
 *		runtime PM reference, never before them.
 * @pd_since:	when the chip last entered power-down (t_PD reference)
 * @last_start:	when the last measurement was started
 * @trig_slot:	when the data-ready trigger's current sample was due; the
 *		next one is due a period later, so lateness does not add up
 * @trig_users:	sensors whose buffer runs on the data-ready trigger
 * @trig_resume: the data-ready trigger ran when the system suspended
 * @trig_unread: the data-ready trigger's sample in flight is not read yet
 * @trig_sample: the sample of the data-ready trigger's last INT1 edge,
 *		read once for both devices
 * @trig_err:	the result of reading and checking @trig_sample
 * @alpf:	accelerometer low-pass filter enabled
 * @samp_freq:	sampling frequency of the data-ready trigger, Hz
 * @cal:	accelerometer calibration (caliboffset, calibtemp) applied to
 *		every accelerometer reading
 */
struct as9888_chip {
	struct device *dev;
	struct regmap *regmap;
	struct iio_dev *iio[AS9888_SENSORS];
	struct iio_trigger *trig;
	struct regulator_bulk_data supplies[AS9888_SUPPLIES];
	struct iio_mount_matrix orientation;
	struct as9888_eeprom ee;
	int irq;
	struct completion drdy;
	wait_queue_head_t stop_wq;
	wait_queue_head_t gap_wq;
	ktime_t drdy_time;
	s64 drdy_ts[AS9888_SENSORS];
	bool trig_running;
	bool trig_busy;

	/* Serialises the register access sequences, see @lock above */
	struct mutex lock;
	ktime_t pd_since;
	ktime_t last_start;
	ktime_t trig_slot;
	unsigned long trig_users;
	bool trig_resume;
	bool trig_unread;
	struct as9888_raw_sample trig_sample;
	int trig_err;
	bool alpf;
	int samp_freq;
	struct as9888_accel_cal cal;
};

/**
 * struct as9888_sensor - what the IIO private data of each device starts with
 * @chip:	the chip
 * @id:		which sensor of the chip the device is
 */
struct as9888_sensor {
	struct as9888_chip *chip;
	enum as9888_sensor_id id;
};

static inline struct as9888_sensor *as9888_sensor(struct iio_dev *indio_dev)
{
	return iio_priv(indio_dev);
}

static inline struct as9888_chip *as9888_iio_to_chip(struct iio_dev *indio_dev)
{
	return as9888_sensor(indio_dev)->chip;
}

/* Chip access, as9888_chip.c; these run with chip->lock held */
int as9888_power_down(struct as9888_chip *chip);
int as9888_start(struct as9888_chip *chip, u8 mode, bool men);
int as9888_read_sample(struct as9888_chip *chip, struct as9888_raw_sample *s);
int as9888_check_sample(struct as9888_chip *chip,
			const struct as9888_raw_sample *s);
int as9888_check_magn(const struct as9888_raw_sample *s);
int as9888_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		   u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts);
int as9888_write_trim(struct as9888_chip *chip, unsigned int reg,
		      const u8 *val, size_t len);

/* What both IIO devices share, as9888_chip.c */
const struct iio_mount_matrix *
as9888_get_mount_matrix(const struct iio_dev *indio_dev,
			const struct iio_chan_spec *chan);
const struct iio_chan_spec *
as9888_channels_for(struct as9888_chip *chip, const struct iio_chan_spec *tmpl,
		    size_t n);
int as9888_debugfs_reg_access(struct iio_dev *indio_dev, unsigned int reg,
			      unsigned int writeval, unsigned int *readval);
int as9888_read_samp_freq(struct as9888_chip *chip, int *val);
int as9888_write_samp_freq(struct as9888_chip *chip, int freq);
int as9888_read_samp_freq_avail(const int **vals, int *type, int *length);

/* The accelerometer device, as9888_accel.c */
struct iio_dev *as9888_accel_alloc(struct as9888_chip *chip);

/* The magnetometer device, as9888_magn.c */
struct iio_dev *as9888_magn_alloc(struct as9888_chip *chip);
void as9888_magn_debugfs_init(struct iio_dev *indio_dev);

/* The data-ready trigger and the buffers, as9888_trigger.c */
extern const struct iio_buffer_setup_ops as9888_buffer_ops;
int as9888_trigger_setup(struct as9888_chip *chip, int irq);
bool as9888_on_drdy_trigger(struct iio_dev *indio_dev);
/* These two run with chip->lock held */
int as9888_wait_gap(struct as9888_chip *chip);
int as9888_trig_sample(struct as9888_chip *chip,
		       const struct as9888_raw_sample **s);
void as9888_trig_suspend(struct as9888_chip *chip);
int as9888_trig_resume(struct as9888_chip *chip);

#endif /* AS9888_CORE_H */
