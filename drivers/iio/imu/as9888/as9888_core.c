// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: 3-axis magnetometer, 3-axis accelerometer and
 * temperature sensor. Bus-independent core.
 *
 * The chip has no continuous mode: every sample is one single measurement
 * (MS = 0x01) that ends with data ready (ST1.DRDY, and INT1 when DR1EN is
 * set), after which the chip is back in power-down. The magnetometer is only
 * measured when SLCT2.MEN is set, which makes a sample take t_MAG instead of
 * t_ACC, so MEN is set only when a magnetometer channel is read.
 *
 * Factory trim comes from an EEPROM that is readable only in EEPROM access
 * mode; it is read once at probe and decoded with the shared calibration
 * arithmetic of as9888_calib.c. Every accelerometer reading is compensated
 * with that arithmetic at the temperature of its own sample, so that it
 * sits on one constant scale: consumers need nothing but raw and scale.
 */

#include <linux/array_size.h>
#include <linux/bitfield.h>
#include <linux/bitmap.h>
#include <linux/bits.h>
#include <linux/cleanup.h>
#include <linux/completion.h>
#include <linux/ctype.h>
#include <linux/debugfs.h>
#include <linux/delay.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/gpio/consumer.h>
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/kstrtox.h>
#include <linux/ktime.h>
#include <linux/math64.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/nvmem-provider.h>
#include <linux/pm.h>
#include <linux/pm_runtime.h>
#include <linux/property.h>
#include <linux/regmap.h>
#include <linux/regulator/consumer.h>
#include <linux/seq_file.h>
#include <linux/slab.h>
#include <linux/string.h>
#include <linux/sysfs.h>
#include <linux/time64.h>
#include <linux/types.h>
#include <linux/wait.h>

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>
#include <linux/iio/sysfs.h>
#include <linux/iio/trigger.h>
#include <linux/iio/trigger_consumer.h>
#include <linux/iio/triggered_buffer.h>

#include <asm/byteorder.h>

#include "as9888.h"

#define AS9888_DRV_NAME			"as9888"

/* A measurement that has not completed by 1.5 t + margin has failed */
#define AS9888_MEAS_MARGIN_US		2000
#define AS9888_MEAS_TIMEOUT_US(t)	((t) * 3 / 2 + AS9888_MEAS_MARGIN_US)
/*
 * RSTN low time: twice t_RSTL, so that a delay that ends a little early
 * (udelay() is calibrated, not measured) still makes a valid pulse
 */
#define AS9888_RSTL_US			(2 * AS9888_T_RSTL_US)
/* ST1 polling interval when no interrupt is wired */
#define AS9888_POLL_US			100

#define AS9888_AUTOSUSPEND_MS		2000
/* Attempts to start the next measurement of a data-ready triggered buffer */
#define AS9888_START_RETRIES		3
/*
 * How long an offset DAC write waits for the data-ready triggered buffer's
 * next gap between samples, beyond two sampling periods
 */
#define AS9888_DAC_WAIT_SLACK_MS	2000

#define AS9888_SAMP_FREQ_DEFAULT	100

/*
 * Magnetometer: 0.3 uT/LSB before adjustment, 1 G = 100 uT, and the
 * adjustment multiplies by (EHC + 128) / 256, so the scale in gauss is
 * 3 * (EHC + 128) / 256000.
 */
#define AS9888_MAGN_SCALE_NUM		3
#define AS9888_MAGN_SCALE_DEN		256000
#define AS9888_EHC_OFFSET		128

/*
 * Accelerometer: compensated readings are on AS9888_ACC_OUT_PER_G LSB per
 * g, so the scale is standard gravity, 9.80665 m/s^2, divided by that.
 */
#define AS9888_G_NUM			980665
#define AS9888_G_DEN			100000
#define AS9888_ACC_SCALE_DEN		(AS9888_G_DEN * AS9888_ACC_OUT_PER_G)

#define AS9888_NANO			1000000000LL
#define AS9888_MICRO			1000000
#define AS9888_MILLI			1000
/* Decimal places of in_accel_*_caliboffset */
#define AS9888_CALIBOFFSET_PLACES	6

/* ALPF quadruples the conversion time and halves the noise */
#define AS9888_OSR_ALPF_OFF		1
#define AS9888_OSR_ALPF_ON		4

/*
 * Temperature, datasheet section 5: T = (176 - TMPS) / 1.6 degC, i.e.
 * T [mdegC] = (TMPS - 176) * -625. IIO computes (raw + offset) * scale,
 * so raw = TMPS, offset = -176 and scale = -625 mdegC give it exactly.
 */
#define AS9888_TEMP_OFFSET		(-AS9888_TMPS_ZERO_DEGC)
#define AS9888_TEMP_SCALE_MDEGC		(-AS9888_MDEGC_PER_TMPS)

enum as9888_scan {
	AS9888_SCAN_ACCEL_X,
	AS9888_SCAN_ACCEL_Y,
	AS9888_SCAN_ACCEL_Z,
	AS9888_SCAN_MAGN_X,
	AS9888_SCAN_MAGN_Y,
	AS9888_SCAN_MAGN_Z,
	AS9888_SCAN_TEMP,
	AS9888_SCAN_TIMESTAMP,
};

#define AS9888_SCAN_MAGN_MSK	GENMASK(AS9888_SCAN_MAGN_Z, AS9888_SCAN_MAGN_X)

static const char * const as9888_supply_names[] = { "vdd", "vid" };

/**
 * struct as9888_selftest - result of the last magnetometer self-test
 * @done:	a self-test has run
 * @pass:	every judgment of step 2 of the application note passed
 * @adj_q8:	self-test reading per axis after sensitivity adjustment,
 *		1/256 LSB
 */
struct as9888_selftest {
	bool done;
	bool pass;
	s32 adj_q8[AS9888_AXES];
};

/**
 * struct as9888_data - driver state
 * @dev:	the bus device
 * @regmap:	register map; the trim and configuration registers are cached
 *		and rewritten by regcache_sync() after a power cycle
 * @trig:	data-ready trigger, NULL when INT1 is not wired
 * @supplies:	vdd and vid
 * @orientation: mount matrix from firmware
 * @ee:		the decoded factory EEPROM, read once at probe
 * @irq:	INT1, or 0 to poll ST1
 * @drdy:	completed by INT1 for measurements waited for synchronously
 * @stop_wq:	wakes a data-ready triggered buffer that waits for its next
 *		sampling period when the buffer stops
 * @dac_wq:	wakes offset DAC writers when their pending value is written
 * @drdy_time:	ktime of the last INT1 edge (the chip entered power-down)
 * @drdy_ts:	IIO timestamp of the last INT1 edge
 * @trig_running: the data-ready triggered buffer is running; written under
 *		@lock, read locklessly by the interrupt handler
 * @lock:	serialises every register access sequence of the driver and
 *		protects the fields below. A measurement is a sequence (mode
 *		write, wait, burst read) that must not interleave with another
 *		one or with a trim write, which the chip accepts in power-down
 *		only. With @lock held and no data-ready triggered buffer
 *		running, the chip is in power-down. Taken after the IIO
 *		direct-mode claim and after a runtime PM reference, never
 *		before them.
 * @pd_since:	when the chip last entered power-down (t_PD reference)
 * @last_start:	when the last measurement was started
 * @trig_slot:	when the data-ready trigger's current sample was due; the
 *		next one is due a period later, so lateness does not add up
 * @trig_resume: @trig_running was set when the system suspended
 * @dac_pending: axes whose offset DAC value waits in @dac_val for the
 *		data-ready triggered buffer's next gap between two samples
 * @dac_val:	those DAC register values
 * @dac_err:	per axis, the result of writing the last pending value
 * @dac_flushes: how many times the pending values were written
 * @scan_mask:	channels of the buffer's scan
 * @buf_men:	the buffer's scan includes a magnetometer channel
 * @alpf:	accelerometer low-pass filter enabled
 * @samp_freq:	sampling frequency of the data-ready triggered buffer, Hz
 * @cal:	accelerometer calibration (caliboffset, calibtemp) applied to
 *		every accelerometer reading
 * @selftest:	result of the last self-test
 * @scan:	buffer for one scan: up to seven 16-bit channels, timestamp
 * @scan.chans: the channel values
 * @scan.timestamp: filled in by the IIO core
 */
struct as9888_data {
	struct device *dev;
	struct regmap *regmap;
	struct iio_trigger *trig;
	struct regulator_bulk_data supplies[ARRAY_SIZE(as9888_supply_names)];
	struct iio_mount_matrix orientation;
	struct as9888_eeprom ee;
	int irq;
	struct completion drdy;
	wait_queue_head_t stop_wq;
	wait_queue_head_t dac_wq;
	ktime_t drdy_time;
	s64 drdy_ts;
	bool trig_running;

	/* Serialises the register access sequences, see @lock above */
	struct mutex lock;
	ktime_t pd_since;
	ktime_t last_start;
	ktime_t trig_slot;
	bool trig_resume;
	unsigned long dac_pending;
	u8 dac_val[AS9888_AXES];
	int dac_err[AS9888_AXES];
	unsigned int dac_flushes;
	unsigned long scan_mask;
	bool buf_men;
	bool alpf;
	int samp_freq;
	struct as9888_accel_cal cal;
	struct as9888_selftest selftest;

	struct {
		s16 chans[AS9888_SCAN_TIMESTAMP];
		aligned_s64 timestamp;
	} scan;
};

/* Register map */

static const struct regmap_range as9888_readable_ranges[] = {
	regmap_reg_range(AS9888_REG_WIA, AS9888_REG_WIA),
	regmap_reg_range(AS9888_REG_INT1EN, AS9888_REG_MS),
	regmap_reg_range(AS9888_REG_ST1, AS9888_REG_ST2),
	regmap_reg_range(AS9888_REG_REF1, AS9888_REG_AZDA),
	regmap_reg_range(AS9888_REG_EEPROM, AS9888_REG_EEPROM_END),
};

static const struct regmap_access_table as9888_readable_table = {
	.yes_ranges = as9888_readable_ranges,
	.n_yes_ranges = ARRAY_SIZE(as9888_readable_ranges),
};

static const struct regmap_range as9888_writeable_ranges[] = {
	regmap_reg_range(AS9888_REG_INT1EN, AS9888_REG_INT2EN),
	regmap_reg_range(AS9888_REG_SLCT1, AS9888_REG_MS),
	regmap_reg_range(AS9888_REG_REF1, AS9888_REG_AZDA),
};

static const struct regmap_access_table as9888_writeable_table = {
	.yes_ranges = as9888_writeable_ranges,
	.n_yes_ranges = ARRAY_SIZE(as9888_writeable_ranges),
};

/*
 * MS returns to power-down by itself, status and data change with every
 * measurement, and the EEPROM window reads 0x00 outside EEPROM access mode:
 * none of them can be cached. The driver keeps its own copy of the EEPROM.
 */
static const struct regmap_range as9888_volatile_ranges[] = {
	regmap_reg_range(AS9888_REG_WIA, AS9888_REG_WIA),
	regmap_reg_range(AS9888_REG_INT1ST, AS9888_REG_INT2ST),
	regmap_reg_range(AS9888_REG_MS, AS9888_REG_MS),
	regmap_reg_range(AS9888_REG_ST1, AS9888_REG_ST2),
	regmap_reg_range(AS9888_REG_EEPROM, AS9888_REG_EEPROM_END),
};

static const struct regmap_access_table as9888_volatile_table = {
	.yes_ranges = as9888_volatile_ranges,
	.n_yes_ranges = ARRAY_SIZE(as9888_volatile_ranges),
};

/* Reading INT1ST/INT2ST deasserts the pin, reading ST2 clears DRDY and DOR */
static const struct regmap_range as9888_precious_ranges[] = {
	regmap_reg_range(AS9888_REG_INT1ST, AS9888_REG_INT2ST),
	regmap_reg_range(AS9888_REG_ST2, AS9888_REG_ST2),
};

static const struct regmap_access_table as9888_precious_table = {
	.yes_ranges = as9888_precious_ranges,
	.n_yes_ranges = ARRAY_SIZE(as9888_precious_ranges),
};

static const struct reg_default as9888_reg_defaults[] = {
	{ AS9888_REG_INT1EN, 0x00 },
	{ AS9888_REG_INT2EN, 0x00 },
	{ AS9888_REG_SLCT1, 0x00 },
	{ AS9888_REG_SLCT2, 0x00 },
	{ AS9888_REG_REF1, 0x00 },
	{ AS9888_REG_REF2, 0x00 },
	{ AS9888_REG_REF3, 0x00 },
	{ AS9888_REG_OSC, 0x00 },
	{ AS9888_REG_AGA(0), 0x00 },
	{ AS9888_REG_AGA(1), 0x00 },
	{ AS9888_REG_AGA(2), 0x00 },
	{ AS9888_REG_ADA(0), AS9888_DAC_ZERO },
	{ AS9888_REG_ADA(1), AS9888_DAC_ZERO },
	{ AS9888_REG_ADA(2), AS9888_DAC_ZERO },
};

#define AS9888_REGMAP_CONFIG_COMMON					\
	.reg_bits = 8,							\
	.val_bits = 8,							\
	.max_register = AS9888_MAX_REG,					\
	.rd_table = &as9888_readable_table,				\
	.wr_table = &as9888_writeable_table,				\
	.volatile_table = &as9888_volatile_table,			\
	.precious_table = &as9888_precious_table,			\
	.reg_defaults = as9888_reg_defaults,				\
	.num_reg_defaults = ARRAY_SIZE(as9888_reg_defaults),		\
	.cache_type = REGCACHE_MAPLE

const struct regmap_config as9888_i2c_regmap_config = {
	AS9888_REGMAP_CONFIG_COMMON,
};
EXPORT_SYMBOL_NS_GPL(as9888_i2c_regmap_config, "IIO_AS9888");

/* SPI, datasheet section 1: bit 7 of the first byte set to read */
const struct regmap_config as9888_spi_regmap_config = {
	AS9888_REGMAP_CONFIG_COMMON,
	.read_flag_mask = AS9888_SPI_READ_MSK,
	.write_flag_mask = 0,
};
EXPORT_SYMBOL_NS_GPL(as9888_spi_regmap_config, "IIO_AS9888");

/* Modes and measurements; all of these run with data->lock held */

/* Wait until t_PD has passed since the chip entered power-down */
static void as9888_wait_pd(struct as9888_data *data)
{
	s64 left_us = ktime_us_delta(ktime_add_us(data->pd_since,
						  AS9888_T_PD_US),
				     ktime_get());

	if (left_us > 0)
		fsleep(left_us);
}

static int as9888_power_down(struct as9888_data *data)
{
	int ret;

	ret = regmap_write(data->regmap, AS9888_REG_MS, AS9888_MS_POWER_DOWN);
	data->pd_since = ktime_get();

	return ret;
}

/**
 * as9888_start() - start a measurement
 * @data: driver data
 * @mode: AS9888_MS_SINGLE or AS9888_MS_SELF_TEST
 * @men: measure the magnetometer too
 *
 * A mode is entered from power-down only, and not before t_PD has passed:
 * a write that breaks this rule is ignored by the chip, so wait for it.
 * The accepted MS write also deasserts INT1, so INT1ST never needs reading.
 *
 * Return: 0 or a negative error number.
 */
static int as9888_start(struct as9888_data *data, u8 mode, bool men)
{
	unsigned int slct2 = FIELD_PREP(AS9888_SLCT2_MEN_MSK, men) |
			     FIELD_PREP(AS9888_SLCT2_ALPF_MSK, data->alpf);
	int ret;

	lockdep_assert_held(&data->lock);

	/* Cached: no bus access unless the setting changes */
	ret = regmap_update_bits(data->regmap, AS9888_REG_SLCT2,
				 AS9888_SLCT2_MEN_MSK | AS9888_SLCT2_ALPF_MSK,
				 slct2);
	if (ret)
		return ret;

	if (data->irq)
		reinit_completion(&data->drdy);

	as9888_wait_pd(data);
	ret = regmap_write(data->regmap, AS9888_REG_MS, mode);
	data->last_start = ktime_get();

	return ret;
}

static unsigned int as9888_meas_time_us(const struct as9888_data *data,
					bool men)
{
	if (men)
		return AS9888_T_MAG_US;

	return data->alpf ? AS9888_T_ACC_LPF_US : AS9888_T_ACC_US;
}

static int as9888_read_sample(struct as9888_data *data,
			      struct as9888_raw_sample *s)
{
	return regmap_bulk_read(data->regmap, AS9888_REG_ST1, s, sizeof(*s));
}

/**
 * as9888_wait_sample() - wait for a started measurement and read it
 * @indio_dev: the IIO device
 * @t_us: duration of the measurement
 * @s: the sample
 * @ts: timestamp of the end of the measurement
 *
 * With INT1 wired, wait for its edge. Without it, sleep for the duration
 * of the measurement and read the sample: a sample that is not ready yet
 * (ST1.DRDY clear) sends the driver polling ST1 until the timeout.
 *
 * Return: 0 or a negative error number, -ETIMEDOUT when the measurement
 * did not complete in time.
 */
static int as9888_wait_sample(struct iio_dev *indio_dev, unsigned int t_us,
			      struct as9888_raw_sample *s, s64 *ts)
{
	struct as9888_data *data = iio_priv(indio_dev);
	unsigned int timeout_us = AS9888_MEAS_TIMEOUT_US(t_us);
	unsigned int st1;
	int ret;

	if (data->irq) {
		if (!wait_for_completion_timeout(&data->drdy,
						 usecs_to_jiffies(timeout_us)))
			return -ETIMEDOUT;

		*ts = data->drdy_ts;
		data->pd_since = data->drdy_time;

		return as9888_read_sample(data, s);
	}

	fsleep(t_us);
	ret = as9888_read_sample(data, s);
	if (ret)
		return ret;

	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, s->st1)) {
		ret = regmap_read_poll_timeout(data->regmap, AS9888_REG_ST1,
					       st1,
					       FIELD_GET(AS9888_ST1_DRDY_MSK, st1),
					       AS9888_POLL_US,
					       timeout_us - t_us);
		if (ret)
			return ret;

		ret = as9888_read_sample(data, s);
		if (ret)
			return ret;
	}

	*ts = iio_get_time_ns(indio_dev);
	/* The chip entered power-down before we saw DRDY */
	data->pd_since = ktime_get();

	return 0;
}

/*
 * Checks that apply to every sample: data ready (ST1.DRDY) and a healthy
 * EMPT. A data overrun (ST1.DOR) only means an earlier sample was lost.
 */
static int as9888_check_sample(struct as9888_data *data,
			       const struct as9888_raw_sample *s)
{
	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, s->st1)) {
		dev_err_ratelimited(data->dev, "no data ready (ST1 0x%02x)\n",
				    s->st1);
		return -EIO;
	}

	if (FIELD_GET(AS9888_ST1_DOR_MSK, s->st1))
		dev_warn_ratelimited(data->dev, "data overrun, a sample was lost\n");

	if (s->empt) {
		dev_err_ratelimited(data->dev, "EMPT reads 0x%02x, device fault\n",
				    s->empt);
		return -EIO;
	}

	return 0;
}

/*
 * Magnetometer checks: HST set means the magnetometer was not measured,
 * HOFL that an axis saturated.
 */
static int as9888_check_magn(const struct as9888_raw_sample *s)
{
	if (FIELD_GET(AS9888_ST2_HST_MSK, s->st2))
		return -EIO;

	if (FIELD_GET(AS9888_ST2_HOFL_MSK, s->st2))
		return -ERANGE;

	return 0;
}

/**
 * as9888_measure() - run one measurement and read the sample
 * @indio_dev: the IIO device
 * @mode: AS9888_MS_SINGLE or AS9888_MS_SELF_TEST
 * @men: measure the magnetometer too (always done in self-test)
 * @s: the sample
 * @ts: timestamp of the sample
 *
 * One MS write and one burst read of ST1..ST2 on the bus (plus ST1 polls
 * in the unusual case that the sample is late without INT1). On any error
 * the measurement is aborted, leaving the chip in power-down.
 *
 * Return: 0 or a negative error number.
 */
static int as9888_measure(struct iio_dev *indio_dev, u8 mode, bool men,
			  struct as9888_raw_sample *s, s64 *ts)
{
	struct as9888_data *data = iio_priv(indio_dev);
	bool self_test = mode == AS9888_MS_SELF_TEST;
	unsigned int t_us = as9888_meas_time_us(data, men || self_test);
	int ret;

	lockdep_assert_held(&data->lock);

	ret = as9888_start(data, mode, men || self_test);
	if (!ret)
		ret = as9888_wait_sample(indio_dev, t_us, s, ts);
	if (ret) {
		if (ret == -ETIMEDOUT)
			dev_err_ratelimited(data->dev,
					    "measurement not done after %u us\n",
					    AS9888_MEAS_TIMEOUT_US(t_us));
		/* Abort whatever may still run; the first error is reported */
		as9888_power_down(data);
		return ret;
	}

	return as9888_check_sample(data, s);
}

/**
 * as9888_write_trim() - write a trim register and read it back
 * @data: driver data
 * @reg: first register
 * @val: values
 * @len: number of registers
 *
 * The chip ignores trim writes outside power-down, so make sure it is in
 * power-down (and t_PD has passed, step 1-29) first, then check the write
 * with an uncached read (D10).
 *
 * Return: 0, -EIO when a register does not read back what was written, or
 * another negative error number.
 */
static int as9888_write_trim(struct as9888_data *data, unsigned int reg,
			     const u8 *val, size_t len)
{
	u8 readback[AS9888_TRIM_LEN];
	unsigned int ms;
	size_t i;
	int ret;

	lockdep_assert_held(&data->lock);

	if (len > sizeof(readback))
		return -EINVAL;

	ret = regmap_read(data->regmap, AS9888_REG_MS, &ms);
	if (ret)
		return ret;

	if (ms != AS9888_MS_POWER_DOWN) {
		ret = as9888_power_down(data);
		if (ret)
			return ret;
	}
	as9888_wait_pd(data);

	ret = regmap_bulk_write(data->regmap, reg, val, len);
	if (ret)
		return ret;

	regcache_cache_bypass(data->regmap, true);
	ret = regmap_raw_read(data->regmap, reg, readback, len);
	regcache_cache_bypass(data->regmap, false);
	if (ret)
		return ret;

	for (i = 0; i < len; i++) {
		if (readback[i] != val[i]) {
			dev_err(data->dev,
				"register 0x%02zx reads 0x%02x, 0x%02x written\n",
				reg + i, readback[i], val[i]);
			return -EIO;
		}
	}

	return 0;
}

/* Accelerometer compensation */

/**
 * as9888_accel_out() - one axis of a sample, compensated
 * @data: driver data
 * @s: a checked sample
 * @axis: 0..2 for X..Z
 * @out: the reading on the constant scale, AS9888_ACC_OUT_PER_G per g
 *
 * Offset Ot(t) and sensitivity St(t) (datasheet 6.4, 6.5) are those at the
 * temperature of the sample itself (TMPS is in the same burst), from the
 * EEPROM, the calibration and the DAC value in use, which comes from the
 * register cache. A reading beyond the output range is clamped to it.
 *
 * Return: 0 or a negative error number.
 */
static int as9888_accel_out(struct as9888_data *data,
			    const struct as9888_raw_sample *s, int axis,
			    s16 *out)
{
	s32 ot_q16, st_q16;
	unsigned int da;
	int ret;

	lockdep_assert_held(&data->lock);

	ret = regmap_read(data->regmap, AS9888_REG_ADA(axis), &da);
	if (ret)
		return ret;

	ret = as9888_accel_correction(&data->ee, &data->cal, axis, da,
				      as9888_tmps_to_mdegc(s->tmps),
				      &ot_q16, &st_q16);
	if (ret)
		return ret;

	ret = as9888_accel_compensate((s16)le16_to_cpu(s->accel[axis]),
				      ot_q16, st_q16, out);

	return ret == -ERANGE ? 0 : ret;
}

/* Offset DAC */

static int as9888_read_calibbias(struct as9888_data *data, int axis, int *val)
{
	unsigned int da;
	int ret;

	guard(mutex)(&data->lock);

	/* Cached register: no bus access, also fine while suspended */
	ret = regmap_read(data->regmap, AS9888_REG_ADA(axis), &da);
	if (ret)
		return ret;

	*val = as9888_dac2lin(data->ee.axis[axis].ga, da);

	return IIO_VAL_INT;
}

/* Write the DAC values that wait for a gap between two samples */
static void as9888_flush_dac(struct as9888_data *data)
{
	unsigned long axis;

	lockdep_assert_held(&data->lock);

	if (!data->dac_pending)
		return;

	for_each_set_bit(axis, &data->dac_pending, AS9888_AXES)
		data->dac_err[axis] = as9888_write_trim(data,
							AS9888_REG_ADA(axis),
							&data->dac_val[axis], 1);
	data->dac_pending = 0;
	WRITE_ONCE(data->dac_flushes, data->dac_flushes + 1);
	wake_up_all(&data->dac_wq);
}

/*
 * While the data-ready triggered buffer runs, a measurement is nearly
 * always in flight, and a trim write would abort it (the chip takes one in
 * power-down only) and with it the next INT1 edge. The value waits instead
 * for the gap between two samples (as9888_next_sample()) or for the buffer
 * to stop. The calibration is referred to the factory DAC values, so it
 * stays valid whatever the DAC holds: as9888_accel_out() compensates every
 * later sample for the DAC in use. So a restore or a factory test can
 * change the DAC under a client that keeps the buffer enabled, such as
 * iio-sensor-proxy.
 */
static int as9888_queue_calibbias(struct as9888_data *data, int axis, u8 da)
{
	unsigned int period_ms, flushes;

	scoped_guard(mutex, &data->lock) {
		if (!data->trig_running)
			return as9888_write_trim(data, AS9888_REG_ADA(axis),
						 &da, 1);
		data->dac_val[axis] = da;
		data->dac_pending |= BIT(axis);
		flushes = data->dac_flushes;
		period_ms = DIV_ROUND_UP(MSEC_PER_SEC, data->samp_freq);
	}

	wait_event_timeout(data->dac_wq, READ_ONCE(data->dac_flushes) != flushes,
			   msecs_to_jiffies(2 * period_ms +
					    AS9888_DAC_WAIT_SLACK_MS));

	guard(mutex)(&data->lock);
	if (data->dac_flushes == flushes) {
		/* The trigger stalled: take the value back */
		data->dac_pending &= ~BIT(axis);
		return -ETIMEDOUT;
	}

	return data->dac_err[axis];
}

static int as9888_write_calibbias(struct iio_dev *indio_dev, int axis,
				  int lin)
{
	struct as9888_data *data = iio_priv(indio_dev);
	int ret;

	if (lin < -AS9888_DAC_LIN_MAX || lin > AS9888_DAC_LIN_MAX)
		return -EINVAL;

	ret = pm_runtime_resume_and_get(data->dev);
	if (ret)
		return ret;

	ret = as9888_queue_calibbias(data, axis,
				     as9888_lin2dac(data->ee.axis[axis].ga, lin));

	pm_runtime_put_autosuspend(data->dev);

	return ret;
}

/* Single reads */

static int as9888_read_channel(struct iio_dev *indio_dev,
			       const struct iio_chan_spec *chan, int *val)
{
	struct as9888_data *data = iio_priv(indio_dev);
	bool men = chan->type == IIO_MAGN;
	struct as9888_raw_sample s;
	s16 accel;
	s64 ts;
	int ret;

	ret = pm_runtime_resume_and_get(data->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &data->lock) {
		ret = as9888_measure(indio_dev, AS9888_MS_SINGLE, men, &s, &ts);
		if (!ret && chan->type == IIO_ACCEL)
			ret = as9888_accel_out(data, &s, chan->address, &accel);
	}

	pm_runtime_put_autosuspend(data->dev);
	if (ret)
		return ret;

	switch (chan->type) {
	case IIO_ACCEL:
		*val = accel;
		return IIO_VAL_INT;
	case IIO_MAGN:
		ret = as9888_check_magn(&s);
		if (ret)
			return ret;
		*val = (s16)le16_to_cpu(s.magn[chan->address]);
		return IIO_VAL_INT;
	case IIO_TEMP:
		*val = s.tmps;
		return IIO_VAL_INT;
	default:
		return -EINVAL;
	}
}

static int as9888_read_samp_freq(struct as9888_data *data, int *val)
{
	guard(mutex)(&data->lock);
	*val = data->samp_freq;

	return IIO_VAL_INT;
}

static int as9888_read_oversampling(struct as9888_data *data, int *val)
{
	guard(mutex)(&data->lock);
	*val = data->alpf ? AS9888_OSR_ALPF_ON : AS9888_OSR_ALPF_OFF;

	return IIO_VAL_INT;
}

static int as9888_write_oversampling(struct as9888_data *data, int ratio)
{
	if (ratio != AS9888_OSR_ALPF_OFF && ratio != AS9888_OSR_ALPF_ON)
		return -EINVAL;

	guard(mutex)(&data->lock);
	data->alpf = ratio == AS9888_OSR_ALPF_ON;

	return 0;
}

static int as9888_read_raw(struct iio_dev *indio_dev,
			   const struct iio_chan_spec *chan, int *val,
			   int *val2, long mask)
{
	struct as9888_data *data = iio_priv(indio_dev);
	int ret;

	switch (mask) {
	case IIO_CHAN_INFO_RAW:
		if (!iio_device_claim_direct(indio_dev))
			return -EBUSY;
		ret = as9888_read_channel(indio_dev, chan, val);
		iio_device_release_direct(indio_dev);
		return ret;
	case IIO_CHAN_INFO_SCALE:
		switch (chan->type) {
		case IIO_ACCEL:
			*val = AS9888_G_NUM;
			*val2 = AS9888_ACC_SCALE_DEN;
			return IIO_VAL_FRACTIONAL;
		case IIO_MAGN:
			*val = AS9888_MAGN_SCALE_NUM *
			       (data->ee.axis[chan->address].ehc +
				AS9888_EHC_OFFSET);
			*val2 = AS9888_MAGN_SCALE_DEN;
			return IIO_VAL_FRACTIONAL;
		case IIO_TEMP:
			*val = AS9888_TEMP_SCALE_MDEGC;
			return IIO_VAL_INT;
		default:
			return -EINVAL;
		}
	case IIO_CHAN_INFO_OFFSET:
		if (chan->type != IIO_TEMP)
			return -EINVAL;
		*val = AS9888_TEMP_OFFSET;
		return IIO_VAL_INT;
	case IIO_CHAN_INFO_CALIBBIAS:
		return as9888_read_calibbias(data, chan->address, val);
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		return as9888_read_oversampling(data, val);
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_read_samp_freq(data, val);
	default:
		return -EINVAL;
	}
}

static const int as9888_calibbias_range[] = {
	-AS9888_DAC_LIN_MAX, 1, AS9888_DAC_LIN_MAX
};

static const int as9888_oversampling_avail[] = {
	AS9888_OSR_ALPF_OFF, AS9888_OSR_ALPF_ON
};

/*
 * Rates of the data-ready triggered buffer: those whose period leaves room
 * for the longest sample, t_MAG with the magnetometer in the scan, plus
 * t_PD and the sample's bus transfers (a mode write and a 16-byte burst
 * read take about 0.5 ms on I2C at 400 kHz), so that every rate offered is
 * the rate delivered whatever the scan and the filter.
 */
#define AS9888_BUS_BUDGET_US		1000
#define AS9888_SAMP_FREQ_MAX		100
static_assert(USEC_PER_SEC / AS9888_SAMP_FREQ_MAX >=
	      AS9888_T_MAG_US + AS9888_T_PD_US + AS9888_BUS_BUDGET_US);

static const int as9888_samp_freq_avail[] = {
	1, 2, 5, 10, 20, 25, 50, AS9888_SAMP_FREQ_MAX,
};

static int as9888_read_avail(struct iio_dev *indio_dev,
			     const struct iio_chan_spec *chan,
			     const int **vals, int *type, int *length,
			     long mask)
{
	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
		*vals = as9888_calibbias_range;
		*type = IIO_VAL_INT;
		return IIO_AVAIL_RANGE;
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		*vals = as9888_oversampling_avail;
		*length = ARRAY_SIZE(as9888_oversampling_avail);
		*type = IIO_VAL_INT;
		return IIO_AVAIL_LIST;
	case IIO_CHAN_INFO_SAMP_FREQ:
		*vals = as9888_samp_freq_avail;
		*length = ARRAY_SIZE(as9888_samp_freq_avail);
		*type = IIO_VAL_INT;
		return IIO_AVAIL_LIST;
	default:
		return -EINVAL;
	}
}

static int as9888_write_samp_freq(struct as9888_data *data, int freq)
{
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(as9888_samp_freq_avail); i++) {
		if (as9888_samp_freq_avail[i] == freq) {
			guard(mutex)(&data->lock);
			data->samp_freq = freq;
			return 0;
		}
	}

	return -EINVAL;
}

static int as9888_write_raw(struct iio_dev *indio_dev,
			    const struct iio_chan_spec *chan, int val, int val2,
			    long mask)
{
	struct as9888_data *data = iio_priv(indio_dev);
	int ret;

	if (val2)
		return -EINVAL;

	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
		/* Also while buffering: see as9888_queue_calibbias() */
		return as9888_write_calibbias(indio_dev, chan->address, val);
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_write_samp_freq(data, val);
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		/* The sample time changes: not while the buffer runs */
		if (!iio_device_claim_direct(indio_dev))
			return -EBUSY;
		ret = as9888_write_oversampling(data, val);
		iio_device_release_direct(indio_dev);
		return ret;
	default:
		return -EINVAL;
	}
}

static int as9888_write_raw_get_fmt(struct iio_dev *indio_dev,
				    const struct iio_chan_spec *chan,
				    long mask)
{
	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
	case IIO_CHAN_INFO_SAMP_FREQ:
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		return IIO_VAL_INT;
	default:
		return -EINVAL;
	}
}

/* Extended channel attributes */

static const struct iio_mount_matrix *
as9888_get_mount_matrix(const struct iio_dev *indio_dev,
			const struct iio_chan_spec *chan)
{
	struct as9888_data *data = iio_priv(indio_dev);

	return &data->orientation;
}

static ssize_t as9888_caliboffset_read(struct iio_dev *indio_dev,
				       uintptr_t private,
				       const struct iio_chan_spec *chan,
				       char *buf)
{
	struct as9888_data *data = iio_priv(indio_dev);
	s64 micro;
	u64 abs_micro;
	u32 frac;

	scoped_guard(mutex, &data->lock)
		micro = as9888_q16_to_micro(data->cal.offset_q16[chan->address]);

	abs_micro = micro < 0 ? -micro : micro;
	abs_micro = div_u64_rem(abs_micro, AS9888_MICRO, &frac);

	return sysfs_emit(buf, "%s%llu.%0*u\n", micro < 0 ? "-" : "",
			  abs_micro, AS9888_CALIBOFFSET_PLACES, frac);
}

/**
 * as9888_parse_micro() - parse a decimal with up to six places
 * @buf: "[-]I[.F]", optionally followed by a newline; not NUL-terminated
 * @len: length of @buf
 * @micro: the value in millionths
 *
 * Unlike iio_str_to_fixpoint(), the integer part may not wrap around.
 *
 * Return: 0, -EINVAL when @buf is no such number, or -ENOMEM.
 */
static int as9888_parse_micro(const char *buf, size_t len, s64 *micro)
{
	char *str __free(kfree) = kstrndup(buf, len, GFP_KERNEL);
	unsigned int whole, frac = 0;
	char *num, *dot;
	size_t places = 0;
	bool neg;

	if (!str)
		return -ENOMEM;

	num = strim(str);
	neg = *num == '-';
	if (neg)
		num++;

	dot = strchr(num, '.');
	if (dot) {
		*dot++ = '\0';
		for (; dot[places]; places++) {
			if (!isdigit(dot[places]) ||
			    places == AS9888_CALIBOFFSET_PLACES)
				return -EINVAL;
			frac = frac * 10 + dot[places] - '0';
		}
		if (!places)
			return -EINVAL;
	}

	/* kstrtouint() would take a sign, which has been dealt with */
	if (!isdigit(*num) || kstrtouint(num, 10, &whole))
		return -EINVAL;

	for (; places < AS9888_CALIBOFFSET_PLACES; places++)
		frac *= 10;

	*micro = (s64)whole * AS9888_MICRO + frac;
	if (neg)
		*micro = -*micro;

	return 0;
}

static ssize_t as9888_caliboffset_write(struct iio_dev *indio_dev,
					uintptr_t private,
					const struct iio_chan_spec *chan,
					const char *buf, size_t len)
{
	struct as9888_data *data = iio_priv(indio_dev);
	s32 q16;
	s64 micro;
	int ret;

	ret = as9888_parse_micro(buf, len, &micro);
	if (ret)
		return ret;

	if (micro < -(s64)AS9888_CAL_OFFSET_MAX_LSB * AS9888_MICRO ||
	    micro > (s64)AS9888_CAL_OFFSET_MAX_LSB * AS9888_MICRO ||
	    as9888_micro_to_q16(micro, &q16))
		return -EINVAL;

	guard(mutex)(&data->lock);
	data->cal.offset_q16[chan->address] = q16;

	return len;
}

static ssize_t as9888_calibtemp_read(struct iio_dev *indio_dev,
				     uintptr_t private,
				     const struct iio_chan_spec *chan,
				     char *buf)
{
	struct as9888_data *data = iio_priv(indio_dev);

	guard(mutex)(&data->lock);

	return sysfs_emit(buf, "%d\n", data->cal.t_mdegc);
}

/* The valid TMPS range, -30..85 degC */
static ssize_t as9888_calibtemp_write(struct iio_dev *indio_dev,
				      uintptr_t private,
				      const struct iio_chan_spec *chan,
				      const char *buf, size_t len)
{
	struct as9888_data *data = iio_priv(indio_dev);
	int t_mdegc, ret;

	ret = kstrtoint(buf, 10, &t_mdegc);
	if (ret)
		return ret;

	if (t_mdegc < as9888_tmps_to_mdegc(AS9888_TMPS_MAX) ||
	    t_mdegc > as9888_tmps_to_mdegc(AS9888_TMPS_MIN))
		return -EINVAL;

	guard(mutex)(&data->lock);
	data->cal.t_mdegc = t_mdegc;

	return len;
}

static const struct iio_chan_spec_ext_info as9888_accel_ext_info[] = {
	IIO_MOUNT_MATRIX(IIO_SHARED_BY_TYPE, as9888_get_mount_matrix),
	{
		.name = "caliboffset",
		.shared = IIO_SEPARATE,
		.read = as9888_caliboffset_read,
		.write = as9888_caliboffset_write,
	},
	{
		.name = "calibtemp",
		.shared = IIO_SHARED_BY_TYPE,
		.read = as9888_calibtemp_read,
		.write = as9888_calibtemp_write,
	},
	{ }
};

static const struct iio_chan_spec_ext_info as9888_magn_ext_info[] = {
	IIO_MOUNT_MATRIX(IIO_SHARED_BY_TYPE, as9888_get_mount_matrix),
	{ }
};

#define AS9888_ACCEL_CHANNEL(_axis) {					\
	.type = IIO_ACCEL,						\
	.modified = 1,							\
	.channel2 = IIO_MOD_##_axis,					\
	.address = AS9888_SCAN_ACCEL_##_axis - AS9888_SCAN_ACCEL_X,	\
	.info_mask_separate = BIT(IIO_CHAN_INFO_RAW) |			\
			      BIT(IIO_CHAN_INFO_CALIBBIAS),		\
	.info_mask_separate_available = BIT(IIO_CHAN_INFO_CALIBBIAS),	\
	.info_mask_shared_by_type = BIT(IIO_CHAN_INFO_SCALE) |		\
				    BIT(IIO_CHAN_INFO_OVERSAMPLING_RATIO), \
	.info_mask_shared_by_type_available =				\
		BIT(IIO_CHAN_INFO_OVERSAMPLING_RATIO),			\
	.info_mask_shared_by_all = BIT(IIO_CHAN_INFO_SAMP_FREQ),	\
	.info_mask_shared_by_all_available = BIT(IIO_CHAN_INFO_SAMP_FREQ), \
	.scan_index = AS9888_SCAN_ACCEL_##_axis,			\
	.scan_type = {							\
		.sign = 's',						\
		.realbits = 16,						\
		.storagebits = 16,					\
		.endianness = IIO_CPU,					\
	},								\
	.ext_info = as9888_accel_ext_info,				\
}

#define AS9888_MAGN_CHANNEL(_axis) {					\
	.type = IIO_MAGN,						\
	.modified = 1,							\
	.channel2 = IIO_MOD_##_axis,					\
	.address = AS9888_SCAN_MAGN_##_axis - AS9888_SCAN_MAGN_X,	\
	.info_mask_separate = BIT(IIO_CHAN_INFO_RAW) |			\
			      BIT(IIO_CHAN_INFO_SCALE),			\
	.info_mask_shared_by_all = BIT(IIO_CHAN_INFO_SAMP_FREQ),	\
	.info_mask_shared_by_all_available = BIT(IIO_CHAN_INFO_SAMP_FREQ), \
	.scan_index = AS9888_SCAN_MAGN_##_axis,				\
	.scan_type = {							\
		.sign = 's',						\
		.realbits = 13,						\
		.storagebits = 16,					\
		.endianness = IIO_CPU,					\
	},								\
	.ext_info = as9888_magn_ext_info,				\
}

static const struct iio_chan_spec as9888_channels[] = {
	AS9888_ACCEL_CHANNEL(X),
	AS9888_ACCEL_CHANNEL(Y),
	AS9888_ACCEL_CHANNEL(Z),
	AS9888_MAGN_CHANNEL(X),
	AS9888_MAGN_CHANNEL(Y),
	AS9888_MAGN_CHANNEL(Z),
	{
		.type = IIO_TEMP,
		.info_mask_separate = BIT(IIO_CHAN_INFO_RAW) |
				      BIT(IIO_CHAN_INFO_OFFSET) |
				      BIT(IIO_CHAN_INFO_SCALE),
		.info_mask_shared_by_all = BIT(IIO_CHAN_INFO_SAMP_FREQ),
		.info_mask_shared_by_all_available =
			BIT(IIO_CHAN_INFO_SAMP_FREQ),
		.scan_index = AS9888_SCAN_TEMP,
		.scan_type = {
			.sign = 'u',
			.realbits = 8,
			.storagebits = 16,
			.endianness = IIO_CPU,
		},
	},
	IIO_CHAN_SOFT_TIMESTAMP(AS9888_SCAN_TIMESTAMP),
};

/*
 * sampling_frequency is that of the data-ready trigger: without INT1 the
 * buffer runs on another trigger, which sets the rate, so the channels go
 * without it.
 */
static int as9888_channels_init(struct iio_dev *indio_dev, bool drdy)
{
	struct as9888_data *data = iio_priv(indio_dev);
	struct iio_chan_spec *chans;
	unsigned int i;

	indio_dev->num_channels = ARRAY_SIZE(as9888_channels);
	if (drdy) {
		indio_dev->channels = as9888_channels;
		return 0;
	}

	chans = devm_kmemdup(data->dev, as9888_channels,
			     sizeof(as9888_channels), GFP_KERNEL);
	if (!chans)
		return -ENOMEM;

	for (i = 0; i < ARRAY_SIZE(as9888_channels); i++) {
		chans[i].info_mask_shared_by_all = 0;
		chans[i].info_mask_shared_by_all_available = 0;
	}
	indio_dev->channels = chans;

	return 0;
}

/* Self-test, step 2 of the application note */

/**
 * as9888_run_selftest() - magnetometer function test
 * @indio_dev: the IIO device
 * @res: the result
 *
 * A normal measurement with the magnetometer on must complete without
 * overflow (steps 2-2..2-13), then a self-test measurement must complete
 * with every axis, after sensitivity adjustment, within its window
 * (steps 2-14..2-23).
 *
 * Return: 0 when both measurements completed (@res says whether the
 * judgments passed) or a negative error number.
 */
static int as9888_run_selftest(struct iio_dev *indio_dev,
			       struct as9888_selftest *res)
{
	struct as9888_data *data = iio_priv(indio_dev);
	struct as9888_raw_sample s;
	bool pass;
	int axis, ret;
	s16 h;
	s64 ts;

	lockdep_assert_held(&data->lock);

	ret = as9888_measure(indio_dev, AS9888_MS_SINGLE, true, &s, &ts);
	if (ret)
		return ret;

	pass = !as9888_check_magn(&s);
	for (axis = 0; axis < AS9888_AXES; axis++)
		pass &= !as9888_mag_overflow((s16)le16_to_cpu(s.magn[axis]));

	ret = as9888_measure(indio_dev, AS9888_MS_SELF_TEST, true, &s, &ts);
	if (ret)
		return ret;

	pass &= !as9888_check_magn(&s);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		u8 ehc = data->ee.axis[axis].ehc;

		h = (s16)le16_to_cpu(s.magn[axis]);
		res->adj_q8[axis] = as9888_mag_adjust_q8(h, ehc);
		pass &= as9888_selftest_ok(axis, h, ehc);
	}
	res->pass = pass;
	res->done = true;

	return 0;
}

static int as9888_selftest(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);
	struct as9888_selftest res = { };
	int ret;

	ret = pm_runtime_resume_and_get(data->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &data->lock) {
		ret = as9888_run_selftest(indio_dev, &res);
		data->selftest = res;
	}

	pm_runtime_put_autosuspend(data->dev);

	return ret;
}

static ssize_t selftest_store(struct device *dev, struct device_attribute *attr,
			      const char *buf, size_t len)
{
	struct iio_dev *indio_dev = dev_to_iio_dev(dev);
	bool run;
	int ret;

	ret = kstrtobool(buf, &run);
	if (ret)
		return ret;
	if (!run)
		return -EINVAL;

	if (!iio_device_claim_direct(indio_dev))
		return -EBUSY;

	ret = as9888_selftest(indio_dev);
	iio_device_release_direct(indio_dev);

	return ret ?: len;
}

static ssize_t selftest_show(struct device *dev, struct device_attribute *attr,
			     char *buf)
{
	struct as9888_data *data = iio_priv(dev_to_iio_dev(dev));
	const struct as9888_selftest *res = &data->selftest;

	guard(mutex)(&data->lock);

	if (!res->done)
		return sysfs_emit(buf, "none\n");

	return sysfs_emit(buf, "%s\n", res->pass ? "pass" : "fail");
}

static IIO_DEVICE_ATTR_RW(selftest, 0);

static struct attribute *as9888_attrs[] = {
	&iio_dev_attr_selftest.dev_attr.attr,
	NULL
};

static const struct attribute_group as9888_attrs_group = {
	.attrs = as9888_attrs,
};

/*
 * debugfs iio/iio:deviceX/selftest_readings: the adjusted self-test
 * readings of the last test, "X Y Z" in LSB rounded to 1/1000.
 */
static int as9888_selftest_readings_show(struct seq_file *m, void *unused)
{
	struct as9888_data *data = iio_priv(m->private);
	const struct as9888_selftest *res = &data->selftest;
	int axis;

	guard(mutex)(&data->lock);

	if (!res->done) {
		seq_puts(m, "none\n");
		return 0;
	}

	for (axis = 0; axis < AS9888_AXES; axis++) {
		s64 milli = as9888_div_round_s64((s64)res->adj_q8[axis] *
						 AS9888_MILLI, AS9888_Q8_ONE);
		u64 abs_milli = milli < 0 ? -milli : milli;
		u32 frac;
		u64 whole = div_u64_rem(abs_milli, AS9888_MILLI, &frac);

		seq_printf(m, "%s%s%llu.%03u", axis ? " " : "",
			   milli < 0 ? "-" : "", whole, frac);
	}
	seq_putc(m, '\n');

	return 0;
}
DEFINE_SHOW_ATTRIBUTE(as9888_selftest_readings);

/* Removed with the IIO device's debugfs directory when it unregisters */
static void as9888_debugfs_init(struct iio_dev *indio_dev)
{
	struct dentry *dir = iio_get_debugfs_dentry(indio_dev);

	if (IS_ERR_OR_NULL(dir))
		return;

	debugfs_create_file("selftest_readings", 0400, dir, indio_dev,
			    &as9888_selftest_readings_fops);
}

/* Buffer and trigger */

static int as9888_update_scan_mode(struct iio_dev *indio_dev,
				   const unsigned long *scan_mask)
{
	struct as9888_data *data = iio_priv(indio_dev);

	guard(mutex)(&data->lock);
	data->scan_mask = *scan_mask;
	data->buf_men = *scan_mask & AS9888_SCAN_MAGN_MSK;

	return 0;
}

/*
 * Register access for debugging (iio/iio:deviceX/direct_reg_access); it
 * also makes the IIO core create the device's debugfs directory, which
 * holds selftest_readings. Serialised with the driver's own sequences.
 */
static int as9888_debugfs_reg_access(struct iio_dev *indio_dev,
				     unsigned int reg, unsigned int writeval,
				     unsigned int *readval)
{
	struct as9888_data *data = iio_priv(indio_dev);
	int ret;

	ret = pm_runtime_resume_and_get(data->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &data->lock) {
		if (readval)
			ret = regmap_read(data->regmap, reg, readval);
		else
			ret = regmap_write(data->regmap, reg, writeval);
	}

	pm_runtime_put_autosuspend(data->dev);

	return ret;
}

static const struct iio_info as9888_info = {
	.read_raw = as9888_read_raw,
	.read_avail = as9888_read_avail,
	.write_raw = as9888_write_raw,
	.write_raw_get_fmt = as9888_write_raw_get_fmt,
	.update_scan_mode = as9888_update_scan_mode,
	.debugfs_reg_access = as9888_debugfs_reg_access,
	.attrs = &as9888_attrs_group,
};

/* Fill data->scan from a checked sample, false if it is no good */
static bool as9888_fill_scan(struct as9888_data *data,
			     const struct as9888_raw_sample *s)
{
	unsigned int bit, i = 0;
	s16 *chan;
	int ret;

	lockdep_assert_held(&data->lock);

	/* A saturated axis (HOFL) reads -4096 or 4095: pushed as it is */
	if (data->buf_men && FIELD_GET(AS9888_ST2_HST_MSK, s->st2)) {
		dev_err_ratelimited(data->dev, "magnetometer not measured\n");
		return false;
	}

	/* The timestamp is placed by the IIO core */
	for_each_set_bit(bit, &data->scan_mask, AS9888_SCAN_TIMESTAMP) {
		chan = &data->scan.chans[i++];
		switch (bit) {
		case AS9888_SCAN_ACCEL_X ... AS9888_SCAN_ACCEL_Z:
			ret = as9888_accel_out(data, s,
					       bit - AS9888_SCAN_ACCEL_X, chan);
			if (ret) {
				dev_err_ratelimited(data->dev,
						    "cannot compensate a sample: %d\n",
						    ret);
				return false;
			}
			break;
		case AS9888_SCAN_MAGN_X ... AS9888_SCAN_MAGN_Z:
			*chan = le16_to_cpu(s->magn[bit - AS9888_SCAN_MAGN_X]);
			break;
		case AS9888_SCAN_TEMP:
			*chan = s->tmps;
			break;
		}
	}

	return true;
}

/* Read the sample whose INT1 edge fired the data-ready trigger */
static int as9888_collect_sample(struct as9888_data *data,
				 struct as9888_raw_sample *s)
{
	int ret;

	ret = as9888_read_sample(data, s);
	if (ret)
		return ret;

	data->pd_since = data->drdy_time;

	return as9888_check_sample(data, s);
}

/**
 * as9888_next_sample() - start the next sample of the data-ready trigger
 * @data: driver data
 *
 * Waits for the rest of the sampling period (the wait ends early when the
 * buffer stops), then starts the next measurement, whose INT1 edge fires
 * the trigger again.
 */
static void as9888_next_sample(struct as9888_data *data)
{
	ktime_t next, now;
	u64 period;
	s64 wait_ns;
	int i, ret = 0;

	scoped_guard(mutex, &data->lock) {
		period = div_u64(AS9888_NANO, data->samp_freq);
		next = ktime_add_ns(data->trig_slot, period);
		now = ktime_get();
		/* a whole period behind: start a new schedule from now */
		if (ktime_before(ktime_add_ns(next, period), now))
			next = now;
		data->trig_slot = next;
	}

	wait_ns = ktime_to_ns(ktime_sub(next, ktime_get()));
	if (wait_ns > 0)
		wait_event_hrtimeout(data->stop_wq,
				     !READ_ONCE(data->trig_running),
				     ns_to_ktime(wait_ns));

	guard(mutex)(&data->lock);
	/* The chip is in power-down between two samples: the DAC's turn */
	as9888_flush_dac(data);
	for (i = 0; i < AS9888_START_RETRIES && data->trig_running; i++) {
		ret = as9888_start(data, AS9888_MS_SINGLE, data->buf_men);
		if (!ret)
			return;
	}
	if (ret)
		dev_err(data->dev, "data-ready trigger stopped: %d\n", ret);
}

static irqreturn_t as9888_trigger_handler(int irq, void *p)
{
	struct iio_poll_func *pf = p;
	struct iio_dev *indio_dev = pf->indio_dev;
	struct as9888_data *data = iio_priv(indio_dev);
	bool own = iio_trigger_using_own(indio_dev);
	struct as9888_raw_sample s;
	s64 ts = pf->timestamp;
	int ret;

	scoped_guard(mutex, &data->lock) {
		if (own)
			ret = as9888_collect_sample(data, &s);
		else
			ret = as9888_measure(indio_dev, AS9888_MS_SINGLE,
					     data->buf_men, &s, &ts);

		if (!ret && as9888_fill_scan(data, &s))
			iio_push_to_buffers_with_ts(indio_dev, &data->scan,
						    sizeof(data->scan), ts);
	}

	/* Before the next sample, whose INT1 edge must find it done */
	iio_trigger_notify_done(indio_dev->trig);

	if (own)
		as9888_next_sample(data);

	return IRQ_HANDLED;
}

static int as9888_buffer_preenable(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);

	return pm_runtime_resume_and_get(data->dev);
}

/* Start the data-ready trigger; both run with the buffer lock held */
static int as9888_trig_start(struct as9888_data *data)
{
	int ret;

	lockdep_assert_held(&data->lock);

	WRITE_ONCE(data->trig_running, true);
	ret = as9888_start(data, AS9888_MS_SINGLE, data->buf_men);
	if (ret)
		WRITE_ONCE(data->trig_running, false);
	data->trig_slot = data->last_start;

	return ret;
}

static int as9888_trig_stop(struct as9888_data *data)
{
	int ret;

	lockdep_assert_held(&data->lock);

	WRITE_ONCE(data->trig_running, false);
	wake_up(&data->stop_wq);

	/* Abort a measurement in flight */
	ret = as9888_power_down(data);
	as9888_flush_dac(data);

	return ret;
}

static int as9888_buffer_postenable(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);

	if (!iio_trigger_using_own(indio_dev))
		return 0;

	guard(mutex)(&data->lock);

	return as9888_trig_start(data);
}

static int as9888_buffer_predisable(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);

	if (!iio_trigger_using_own(indio_dev))
		return 0;

	guard(mutex)(&data->lock);

	return as9888_trig_stop(data);
}

static int as9888_buffer_postdisable(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);

	pm_runtime_put_autosuspend(data->dev);

	return 0;
}

static const struct iio_buffer_setup_ops as9888_buffer_ops = {
	.preenable = as9888_buffer_preenable,
	.postenable = as9888_buffer_postenable,
	.predisable = as9888_buffer_predisable,
	.postdisable = as9888_buffer_postdisable,
};

static const struct iio_trigger_ops as9888_trigger_ops = {
	.validate_device = iio_trigger_validate_own_device,
};

static irqreturn_t as9888_irq_handler(int irq, void *private)
{
	struct iio_dev *indio_dev = private;
	struct as9888_data *data = iio_priv(indio_dev);

	data->drdy_time = ktime_get();
	data->drdy_ts = iio_get_time_ns(indio_dev);

	if (READ_ONCE(data->trig_running))
		iio_trigger_poll(data->trig);
	else
		complete(&data->drdy);

	return IRQ_HANDLED;
}

/*
 * INT1 is the data-ready interrupt. With interrupt names it must be the
 * one named "INT1" (INT2 is not used); without names the first interrupt
 * is taken to be INT1. No interrupt: ST1 is polled.
 */
static int as9888_get_irq(struct device *dev, int bus_irq)
{
	struct fwnode_handle *fwnode = dev_fwnode(dev);
	int irq;

	if (!fwnode || !fwnode_property_present(fwnode, "interrupt-names"))
		return bus_irq > 0 ? bus_irq : 0;

	irq = fwnode_irq_get_byname(fwnode, "INT1");
	if (irq == -EPROBE_DEFER)
		return irq;

	return irq > 0 ? irq : 0;
}

static int as9888_setup_irq(struct iio_dev *indio_dev, int irq)
{
	struct as9888_data *data = iio_priv(indio_dev);
	struct device *dev = data->dev;
	u32 irq_type;
	int ret;

	/* INT1 rises at the end of a measurement, falls on the next MS write */
	irq_type = irq_get_trigger_type(irq);
	if (irq_type == IRQF_TRIGGER_NONE)
		irq_type = IRQF_TRIGGER_RISING;
	if (irq_type != IRQF_TRIGGER_RISING)
		return dev_err_probe(dev, -EINVAL,
				     "INT1 must be rising edge, not 0x%x\n",
				     irq_type);

	data->irq = irq;

	data->trig = devm_iio_trigger_alloc(dev, "%s-dev%d", indio_dev->name,
					    iio_device_id(indio_dev));
	if (!data->trig)
		return -ENOMEM;

	data->trig->ops = &as9888_trigger_ops;
	iio_trigger_set_drvdata(data->trig, indio_dev);

	ret = devm_request_irq(dev, irq, as9888_irq_handler, irq_type,
			       indio_dev->name, indio_dev);
	if (ret)
		return dev_err_probe(dev, ret, "cannot request INT1\n");

	ret = devm_iio_trigger_register(dev, data->trig);
	if (ret)
		return dev_err_probe(dev, ret, "cannot register trigger\n");

	indio_dev->trig = iio_trigger_get(data->trig);

	ret = regmap_write(data->regmap, AS9888_REG_INT1EN,
			   FIELD_PREP(AS9888_INTEN_DR_MSK, 1));
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable INT1\n");

	return 0;
}

/* Power, reset and the factory trim: step 1 of the application note */

static int as9888_power_on(struct as9888_data *data)
{
	int ret;

	ret = regulator_bulk_enable(ARRAY_SIZE(data->supplies), data->supplies);
	if (ret)
		return ret;

	/* The chip NAKs (I2C) or reads 0xff (SPI) until it has booted */
	fsleep(AS9888_T_BOOT_US);
	/* It boots into power-down */
	data->pd_since = ktime_get();

	return 0;
}

static void as9888_power_off(void *arg)
{
	struct as9888_data *data = arg;

	if (pm_runtime_status_suspended(data->dev))
		return;

	regulator_bulk_disable(ARRAY_SIZE(data->supplies), data->supplies);
	pm_runtime_set_suspended(data->dev);
}

static int as9888_power_init(struct as9888_data *data)
{
	struct device *dev = data->dev;
	unsigned int i;
	int ret;

	for (i = 0; i < ARRAY_SIZE(data->supplies); i++)
		data->supplies[i].supply = as9888_supply_names[i];

	ret = devm_regulator_bulk_get(dev, ARRAY_SIZE(data->supplies),
				      data->supplies);
	if (ret)
		return dev_err_probe(dev, ret, "cannot get regulators\n");

	ret = as9888_power_on(data);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable regulators\n");

	/* Runtime PM status tells as9888_power_off() whether power is on */
	ret = pm_runtime_set_active(dev);
	if (ret) {
		regulator_bulk_disable(ARRAY_SIZE(data->supplies),
				       data->supplies);
		return dev_err_probe(dev, ret, "cannot set runtime PM status\n");
	}

	return devm_add_action_or_reset(dev, as9888_power_off, data);
}

static int as9888_reset(struct as9888_data *data)
{
	struct gpio_desc *reset;

	/* Asserted (RSTN low) when requested */
	reset = devm_gpiod_get_optional(data->dev, "reset", GPIOD_OUT_HIGH);
	if (IS_ERR(reset))
		return dev_err_probe(data->dev, PTR_ERR(reset),
				     "cannot get reset GPIO\n");
	if (!reset)
		return 0;

	fsleep(AS9888_RSTL_US);
	gpiod_set_value_cansleep(reset, 0);
	fsleep(AS9888_T_BOOT_US);
	data->pd_since = ktime_get();

	return 0;
}

/* Steps 1-5..1-29: the whole EEPROM in one burst in EEPROM access mode */
static int as9888_read_eeprom(struct as9888_data *data,
			      u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = data->dev;
	int ret, ret_pd;

	as9888_wait_pd(data);
	ret = regmap_write(data->regmap, AS9888_REG_MS, AS9888_MS_EEPROM);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enter EEPROM mode\n");

	fsleep(AS9888_T_EEP_US);
	ret = regmap_bulk_read(data->regmap, AS9888_REG_EEPROM, raw,
			       AS9888_EEPROM_LEN);

	/* EEPROM access mode is left only by writing power-down */
	ret_pd = as9888_power_down(data);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read EEPROM\n");
	if (ret_pd)
		return dev_err_probe(dev, ret_pd,
				     "cannot leave EEPROM mode\n");

	return 0;
}

static int as9888_decode_eeprom(struct as9888_data *data,
				const u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = data->dev;
	unsigned long bits;
	unsigned int bit;
	int ret;

	ret = as9888_eeprom_decode(raw, &data->ee);

	bits = data->ee.errors;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(data->ee.errors))
		dev_err(dev, "%s\n", as9888_ee_error_str(BIT(bit)));
	if (ret)
		return dev_err_probe(dev, ret, "unusable factory EEPROM %*ph\n",
				     AS9888_EEPROM_LEN, raw);

	bits = data->ee.warnings;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(data->ee.warnings))
		dev_warn(dev, "%s\n", as9888_ee_warning_str(BIT(bit)));

	return 0;
}

/* Steps 1-30..1-39 and the read-back check of D10 */
static int as9888_load_trim(struct as9888_data *data)
{
	const struct as9888_eeprom *ee = &data->ee;
	u8 trim[AS9888_TRIM_LEN] = {
		[AS9888_REG_REF1 - AS9888_REG_REF1] = ee->ref1,
		[AS9888_REG_REF2 - AS9888_REG_REF1] = ee->ref2,
		[AS9888_REG_REF3 - AS9888_REG_REF1] = ee->ref3,
		[AS9888_REG_OSC - AS9888_REG_REF1] = ee->osc,
	};
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		trim[AS9888_REG_AGA(axis) - AS9888_REG_REF1] = ee->axis[axis].ga;
		trim[AS9888_REG_ADA(axis) - AS9888_REG_REF1] = ee->axis[axis].da;
	}

	guard(mutex)(&data->lock);

	ret = as9888_write_trim(data, AS9888_REG_REF1, trim, sizeof(trim));
	if (ret)
		return dev_err_probe(data->dev, ret, "cannot load trim\n");

	return 0;
}

static int as9888_chip_init(struct as9888_data *data)
{
	u8 raw[AS9888_EEPROM_LEN];
	unsigned int wia;
	int ret;

	ret = as9888_reset(data);
	if (ret)
		return ret;

	ret = regmap_read(data->regmap, AS9888_REG_WIA, &wia);
	if (ret)
		return dev_err_probe(data->dev, ret, "cannot read WIA\n");
	if (wia != AS9888_WIA_VAL)
		return dev_err_probe(data->dev, -ENODEV,
				     "WIA reads 0x%02x, not an AS9888 (0x%02x)\n",
				     wia, AS9888_WIA_VAL);

	ret = as9888_read_eeprom(data, raw);
	if (ret)
		return ret;

	ret = as9888_decode_eeprom(data, raw);
	if (ret)
		return ret;

	/* Until userspace loads a level test: the factory's state */
	data->cal.t_mdegc = data->ee.t_rt_mdegc;

	return as9888_load_trim(data);
}

/*
 * The EEPROM as an NVMEM device "as9888-eeprom<N>", N the number of the
 * IIO device; reads are served from the copy taken at probe.
 */
static int as9888_nvmem_read(void *priv, unsigned int offset, void *val,
			     size_t bytes)
{
	struct as9888_data *data = priv;

	if (offset >= AS9888_EEPROM_LEN || bytes > AS9888_EEPROM_LEN - offset)
		return -EINVAL;

	memcpy(val, &data->ee.raw[offset], bytes);

	return 0;
}

static int as9888_nvmem_register(struct iio_dev *indio_dev)
{
	struct as9888_data *data = iio_priv(indio_dev);
	struct nvmem_config config = {
		.dev = data->dev,
		.name = AS9888_DRV_NAME "-eeprom",
		.id = iio_device_id(indio_dev),
		.owner = THIS_MODULE,
		.type = NVMEM_TYPE_EEPROM,
		.read_only = true,
		.ignore_wp = true,
		.word_size = 1,
		.stride = 1,
		.size = AS9888_EEPROM_LEN,
		.reg_read = as9888_nvmem_read,
		.priv = data,
	};
	struct nvmem_device *nvmem;

	if (!IS_ENABLED(CONFIG_NVMEM))
		return 0;

	nvmem = devm_nvmem_register(data->dev, &config);
	if (IS_ERR(nvmem))
		return dev_err_probe(data->dev, PTR_ERR(nvmem),
				     "cannot register EEPROM\n");

	return 0;
}

int as9888_core_probe(struct device *dev, struct regmap *regmap, int irq)
{
	struct iio_dev *indio_dev;
	struct as9888_data *data;
	int ret;

	indio_dev = devm_iio_device_alloc(dev, sizeof(*data));
	if (!indio_dev)
		return -ENOMEM;

	data = iio_priv(indio_dev);
	data->dev = dev;
	data->regmap = regmap;
	data->samp_freq = AS9888_SAMP_FREQ_DEFAULT;
	init_completion(&data->drdy);
	init_waitqueue_head(&data->stop_wq);
	init_waitqueue_head(&data->dac_wq);
	dev_set_drvdata(dev, indio_dev);

	ret = devm_mutex_init(dev, &data->lock);
	if (ret)
		return ret;

	ret = iio_read_mount_matrix(dev, &data->orientation);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read mount matrix\n");

	indio_dev->name = AS9888_DRV_NAME;
	indio_dev->info = &as9888_info;
	indio_dev->modes = INDIO_DIRECT_MODE;

	ret = as9888_power_init(data);
	if (ret)
		return ret;

	ret = as9888_chip_init(data);
	if (ret)
		return ret;

	irq = as9888_get_irq(dev, irq);
	if (irq < 0)
		return dev_err_probe(dev, irq, "cannot get INT1\n");
	if (irq) {
		ret = as9888_setup_irq(indio_dev, irq);
		if (ret)
			return ret;
	}

	ret = as9888_channels_init(indio_dev, irq);
	if (ret)
		return ret;

	ret = devm_iio_triggered_buffer_setup(dev, indio_dev,
					      iio_pollfunc_store_time,
					      as9888_trigger_handler,
					      &as9888_buffer_ops);
	if (ret)
		return dev_err_probe(dev, ret, "cannot set up buffer\n");

	ret = as9888_nvmem_register(indio_dev);
	if (ret)
		return ret;

	pm_runtime_set_autosuspend_delay(dev, AS9888_AUTOSUSPEND_MS);
	pm_runtime_use_autosuspend(dev);
	ret = devm_pm_runtime_enable(dev);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable runtime PM\n");

	ret = devm_iio_device_register(dev, indio_dev);
	if (ret)
		return ret;

	as9888_debugfs_init(indio_dev);

	return 0;
}
EXPORT_SYMBOL_NS_GPL(as9888_core_probe, "IIO_AS9888");

/* Power management */

static int as9888_runtime_suspend(struct device *dev)
{
	struct as9888_data *data = iio_priv(dev_get_drvdata(dev));
	int ret;

	regcache_cache_only(data->regmap, true);
	regcache_mark_dirty(data->regmap);

	ret = regulator_bulk_disable(ARRAY_SIZE(data->supplies),
				     data->supplies);
	if (ret)
		regcache_cache_only(data->regmap, false);

	return ret;
}

/*
 * Power returns, so the chip has lost its trim, DAC and interrupt setup:
 * after t_BOOT, rewrite them from the register cache, in power-down.
 */
static int as9888_runtime_resume(struct device *dev)
{
	struct as9888_data *data = iio_priv(dev_get_drvdata(dev));
	int ret;

	guard(mutex)(&data->lock);

	ret = as9888_power_on(data);
	if (ret)
		return ret;

	regcache_cache_only(data->regmap, false);
	as9888_wait_pd(data);
	ret = regcache_sync(data->regmap);
	if (ret) {
		regcache_cache_only(data->regmap, true);
		regulator_bulk_disable(ARRAY_SIZE(data->supplies),
				       data->supplies);
	}

	return ret;
}

/* A running data-ready trigger is stopped over system sleep */
static int as9888_suspend(struct device *dev)
{
	struct as9888_data *data = iio_priv(dev_get_drvdata(dev));

	scoped_guard(mutex, &data->lock) {
		data->trig_resume = data->trig_running;
		if (data->trig_resume)
			as9888_trig_stop(data);
	}

	return pm_runtime_force_suspend(dev);
}

static int as9888_resume(struct device *dev)
{
	struct as9888_data *data = iio_priv(dev_get_drvdata(dev));
	int ret;

	ret = pm_runtime_force_resume(dev);
	if (ret)
		return ret;

	guard(mutex)(&data->lock);

	if (!data->trig_resume)
		return 0;

	data->trig_resume = false;

	return as9888_trig_start(data);
}

EXPORT_NS_GPL_DEV_PM_OPS(as9888_pm_ops, IIO_AS9888) = {
	SYSTEM_SLEEP_PM_OPS(as9888_suspend, as9888_resume)
	RUNTIME_PM_OPS(as9888_runtime_suspend, as9888_runtime_resume, NULL)
};

MODULE_DESCRIPTION("ALSEN AS9888 accelerometer/magnetometer core driver");
MODULE_LICENSE("GPL");
MODULE_IMPORT_NS("IIO_AS9888");
