/* SPDX-License-Identifier: GPL-2.0 */
/*
 * ALSEN AS9888 6-axis sensor: definitions shared by the files of the core
 * driver (chip access, probe and power management, the accelerometer and
 * magnetometer IIO devices, the data-ready trigger).
 *
 * The register map and the timing of the datasheet live in as9888_regs.h;
 * this header adds what only the core driver needs.
 */
#ifndef AS9888_CORE_H
#define AS9888_CORE_H

#include <linux/atomic.h>
#include <linux/build_bug.h>
#include <linux/compiler.h>
#include <linux/completion.h>
#include <linux/hrtimer.h>
#include <linux/ktime.h>
#include <linux/mutex.h>
#include <linux/regulator/consumer.h>
#include <linux/stddef.h>
#include <linux/types.h>
#include <linux/wait.h>
#include <linux/workqueue.h>

#include <linux/iio/iio.h>

#include "as9888.h"
#include "as9888_calib.h"

struct gpio_desc;
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

/**
 * struct as9888_int_pin - a data-ready output of the chip
 * @name:	its name in interrupt-names
 * @en_reg:	INTxEN, bit DRxEN drives the pin on data ready
 * @st_reg:	INTxST, reading it deasserts the pin
 */
struct as9888_int_pin {
	const char *name;
	unsigned int en_reg;
	unsigned int st_reg;
};

/*
 * Where the data-ready trigger's current sample is (chip->trig_state):
 * the gap between two samples (the chip is free for anything else), a
 * measurement in flight, or the trigger fired on its edge and its
 * handlers hold the sample until the reenable op
 */
enum as9888_trig_state {
	AS9888_TRIG_IDLE,
	AS9888_TRIG_MEASURING,
	AS9888_TRIG_FIRED,
};

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
 * @trig:	data-ready trigger, NULL without a data-ready interrupt
 * @supplies:	vdd and vid
 * @reset:	RSTN, or NULL; asserted (low) whenever the supplies are off, so
 *		that the pin never feeds a chip without power
 * @orientation: mount matrix from firmware
 * @ee:		the decoded factory EEPROM, read once at probe
 * @irq:	the data-ready interrupt (INT1, or INT2 when only INT2 is
 *		wired), or 0 to poll ST1
 * @int_pin:	the pin @irq is wired to, INT1 or INT2; "INT1" below stands
 *		for whichever it is
 * @int_lock:	makes the start of a measurement (its MS write, which
 *		deasserts the pin, and @meas_seq) atomic with respect to the
 *		deassertion of a level-triggered pin by reading INTxST, as
 *		is a DAC write back's moment in cache-only mode, in which
 *		that read would fail; taken inside @lock, and alone by the
 *		interrupt thread
 * @meas_seq:	measurements started, under @int_lock; counted before the
 *		MS write, so that its edge always finds it
 * @irq_seq:	@meas_seq when the interrupt last fired: an edge that finds
 *		the two equal belongs to no measurement (the pin of a chip
 *		without power, a glitch) and is not handled
 * @drdy:	completed by INT1 for measurements waited for synchronously
 * @trig_wd:	the data-ready trigger's watchdog: armed with each sample it
 *		starts, it restarts a sample whose INT1 edge never came and
 *		retries a start that failed, so that the trigger never stalls
 * @trig_timer:	wakes the data-ready trigger when its next sample is due
 * @trig_work:	starts the data-ready trigger's next sample (bus access:
 *		process context, queued by @trig_timer, or by
 *		as9888_trig_kick() when the sample is due already)
 * @trig_state:	enum as9888_trig_state. Set under @lock, but for the step
 *		from MEASURING to FIRED, which the INT1 handler takes
 *		locklessly (atomic_cmpxchg() against the watchdog's abort)
 * @gap_wq:	wakes whoever waits for the gap between two samples of the
 *		data-ready trigger
 * @drdy_time:	ktime of the last INT1 edge (the chip entered power-down)
 * @drdy_ts:	IIO timestamp of the last INT1 edge, per device (each has
 *		its own clock), for measurements waited for synchronously.
 *		The INT1 handler writes @drdy_time and @drdy_ts once per
 *		measurement (see @irq_seq), and they are read under @lock
 *		after the edge: the next write needs a new measurement, which
 *		only a holder of @lock starts, so a 64-bit value never tears
 *		on a 32-bit machine
 * @trig_running: the data-ready trigger is enabled (a buffer is attached
 *		to it), under @lock
 * @gap_waiters: how many wait for the gap between two samples of the
 *		data-ready trigger; the trigger starts no sample while one
 *		is counted, under @lock
 * @lock:	serialises every register access sequence of the driver and
 *		protects the fields below. A measurement is a sequence (mode
 *		write, wait, burst read) that must not interleave with another
 *		one or with a trim write, which the chip accepts in power-down
 *		only. With @lock held and @trig_state IDLE, the chip is in
 *		power-down. Taken after the IIO direct-mode claim and after a
 *		runtime PM reference, never before them.
 * @pd_since:	when the chip last entered power-down (t_PD reference)
 * @last_start:	when the last measurement was started
 * @trig_due:	when each sensor's next sample of the data-ready trigger is
 *		due: a period after the last one was due, so lateness does
 *		not add up
 * @trig_users:	sensors whose buffer runs on the data-ready trigger
 * @trig_take:	sensors whose sample the trigger's current one is; only
 *		their handlers read it; 0 in the gap
 * @trig_retry:	the data-ready trigger could not start its next sample: the
 *		watchdog tries again
 * @suspended:	the system is suspending or asleep: no measurement starts
 *		(a buffer on another trigger gets no samples until resume)
 * @trig_unread: the data-ready trigger's sample in flight is not read yet
 * @sample_skipped: the data-ready trigger left a sample that came unread
 *		(no device wanted it, or the trigger stopped): the next
 *		sample's ST1.DOR says so, and is no lost sample of a client
 * @trig_sample: the sample of the data-ready trigger's last INT1 edge,
 *		read once for both devices
 * @trig_err:	the result of reading and checking @trig_sample
 * @alpf:	accelerometer low-pass filter enabled
 * @cal:	accelerometer calibration (calibbias) applied to every
 *		accelerometer reading; zero after probe
 */
struct as9888_chip {
	struct device *dev;
	struct regmap *regmap;
	struct iio_dev *iio[AS9888_SENSORS];
	struct iio_trigger *trig;
	struct regulator_bulk_data supplies[AS9888_SUPPLIES];
	struct gpio_desc *reset;
	struct iio_mount_matrix orientation;
	struct as9888_eeprom ee;
	int irq;
	const struct as9888_int_pin *int_pin;
	struct mutex int_lock;	/* see @int_lock above */
	unsigned long meas_seq;
	unsigned long irq_seq;
	struct completion drdy;
	struct delayed_work trig_wd;
	struct hrtimer trig_timer;
	struct work_struct trig_work;
	atomic_t trig_state;
	wait_queue_head_t gap_wq;
	ktime_t drdy_time;
	s64 drdy_ts[AS9888_SENSORS];
	bool trig_running;
	unsigned int gap_waiters;

	/* Serialises the register access sequences, see @lock above */
	struct mutex lock;
	ktime_t pd_since;
	ktime_t last_start;
	ktime_t trig_due[AS9888_SENSORS];
	unsigned long trig_users;
	unsigned long trig_take;
	bool trig_retry;
	bool suspended;
	bool trig_unread;
	bool sample_skipped;
	struct as9888_raw_sample trig_sample;
	int trig_err;
	bool alpf;
	struct as9888_accel_cal cal;
};

struct as9888_sensor_desc;

/**
 * struct as9888_sensor - what the IIO private data of each device starts with
 * @chip:	the chip
 * @desc:	which sensor of the chip the device is
 * @samp_freq:	the device's sampling frequency on the data-ready trigger,
 *		Hz, under chip->lock
 */
struct as9888_sensor {
	struct as9888_chip *chip;
	const struct as9888_sensor_desc *desc;
	int samp_freq;
};

/**
 * struct as9888_sensor_desc - what makes the IIO device of a sensor
 * @id:		which sensor
 * @name:	the IIO device's name
 * @priv_size:	size of its IIO private data, which starts with a
 *		struct as9888_sensor
 * @info:	its IIO info
 * @channels:	its channels, with sampling_frequency (dropped without a
 *		data-ready interrupt)
 * @num_channels: how many
 * @men:	its own measurements include the magnetometer
 * @push:	push the device's channels of a checked sample to its buffer,
 *		with the chip's lock held
 */
struct as9888_sensor_desc {
	enum as9888_sensor_id id;
	const char *name;
	size_t priv_size;
	const struct iio_info *info;
	const struct iio_chan_spec *channels;
	unsigned int num_channels;
	bool men;
	void (*push)(struct iio_dev *indio_dev,
		     const struct as9888_raw_sample *s, s64 ts);
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
void as9888_wait_pd(struct as9888_chip *chip);
int as9888_power_down(struct as9888_chip *chip);
int as9888_start(struct as9888_chip *chip, u8 mode, bool men);
int as9888_read_sample(struct as9888_chip *chip, struct as9888_raw_sample *s);
int as9888_check_sample(struct as9888_chip *chip,
			const struct as9888_raw_sample *s);
int as9888_check_magn(const struct as9888_raw_sample *s);
/* In the trigger's gap only: the devices call as9888_gap_measure() */
int as9888_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		   u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts);
int as9888_write_trim(struct as9888_chip *chip, unsigned int reg,
		      const u8 *val, size_t len);

/* What both IIO devices share, as9888_chip.c */
const struct iio_mount_matrix *
as9888_get_mount_matrix(const struct iio_dev *indio_dev,
			const struct iio_chan_spec *chan);

/* The accelerometer device, as9888_accel.c */
extern const struct as9888_sensor_desc as9888_accel_desc;

/* The magnetometer device, as9888_magn.c */
extern const struct as9888_sensor_desc as9888_magn_desc;
void as9888_magn_init(struct iio_dev *indio_dev);
void as9888_magn_debugfs_init(struct iio_dev *indio_dev);

/* The data-ready trigger and the buffers, as9888_trigger.c */
struct iio_dev *as9888_sensor_alloc(struct as9888_chip *chip,
				    const struct as9888_sensor_desc *desc);
int as9888_trigger_setup(struct as9888_chip *chip);
bool as9888_on_drdy_trigger(struct iio_dev *indio_dev);
/* These run with chip->lock held */
int as9888_trig_sample(struct as9888_chip *chip,
		       const struct as9888_raw_sample **s);
int as9888_wait_gap(struct as9888_chip *chip);
int as9888_gap_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		       u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts);
/* Register access for debugging, in the trigger's gap */
int as9888_debugfs_reg_access(struct iio_dev *indio_dev, unsigned int reg,
			      unsigned int writeval, unsigned int *readval);
/* Each device's sampling_frequency on the data-ready trigger */
int as9888_read_samp_freq(struct iio_dev *indio_dev, int *val);
int as9888_write_samp_freq(struct iio_dev *indio_dev, int freq);
int as9888_read_samp_freq_avail(struct iio_dev *indio_dev, const int **vals,
				int *type, int *length);
void as9888_trig_suspend(struct as9888_chip *chip);
int as9888_trig_resume(struct as9888_chip *chip);

#endif /* AS9888_CORE_H */
