// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: 3-axis magnetometer, 3-axis accelerometer and
 * temperature sensor. Chip access and probe, shared by both sensors.
 *
 * The chip has no continuous mode: every sample is one single measurement
 * (MS = 0x01) that ends with data ready (ST1.DRDY, and INT1 when DR1EN is
 * set), after which the chip is back in power-down. The magnetometer is only
 * measured when SLCT2.MEN is set, which makes a sample take t_MAG instead of
 * t_ACC.
 *
 * Each sensor is an IIO device of its own (as9888_accel.c, as9888_magn.c),
 * so that a client of one never makes the chip measure the other: the
 * magnetometer is measured only for the magnetometer device. Both devices
 * share this chip state, its lock and the data-ready trigger
 * (as9888_trigger.c).
 *
 * Factory trim comes from an EEPROM that is readable only in EEPROM access
 * mode; it is read once at probe and decoded with the shared calibration
 * arithmetic of as9888_calib.c.
 */

#include <linux/array_size.h>
#include <linux/bitfield.h>
#include <linux/bitmap.h>
#include <linux/bits.h>
#include <linux/cleanup.h>
#include <linux/completion.h>
#include <linux/delay.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/gpio/consumer.h>
#include <linux/interrupt.h>
#include <linux/ktime.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/nvmem-provider.h>
#include <linux/pm.h>
#include <linux/pm_runtime.h>
#include <linux/property.h>
#include <linux/regmap.h>
#include <linux/regulator/consumer.h>
#include <linux/string.h>
#include <linux/time64.h>
#include <linux/types.h>
#include <linux/wait.h>

#include <linux/iio/iio.h>

#include <asm/byteorder.h>

#include "as9888_core.h"

#define AS9888_DRV_NAME			"as9888"

/* A measurement that has not completed by 1.5 t + margin has failed */
#define AS9888_MEAS_MARGIN_US		2000
#define AS9888_MEAS_TIMEOUT_US(t)	((t) * 3 / 2 + AS9888_MEAS_MARGIN_US)
/*
 * How much longer a data-ready edge is waited for when the sample is
 * already ready: far beyond the latency of a handler on a busy system
 */
#define AS9888_LATE_EDGE_MS		100
/*
 * RSTN low time: twice t_RSTL, so that a delay that ends a little early
 * (udelay() is calibrated, not measured) still makes a valid pulse
 */
#define AS9888_RSTL_US			(2 * AS9888_T_RSTL_US)
/* ST1 polling interval when no interrupt is wired */
#define AS9888_POLL_US			100

#define AS9888_AUTOSUSPEND_MS		2000

#define AS9888_SAMP_FREQ_DEFAULT	100

static const char * const as9888_supply_names[AS9888_SUPPLIES] = {
	"vdd", "vid",
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

/* Modes and measurements; all of these run with chip->lock held */

/* Wait until t_PD has passed since the chip entered power-down */
static void as9888_wait_pd(struct as9888_chip *chip)
{
	s64 left_us = ktime_us_delta(ktime_add_us(chip->pd_since,
						  AS9888_T_PD_US),
				     ktime_get());

	if (left_us > 0)
		fsleep(left_us);
}

int as9888_power_down(struct as9888_chip *chip)
{
	int ret;

	ret = regmap_write(chip->regmap, AS9888_REG_MS, AS9888_MS_POWER_DOWN);
	chip->pd_since = ktime_get();

	return ret;
}

/**
 * as9888_start() - start a measurement
 * @chip: chip state
 * @mode: AS9888_MS_SINGLE or AS9888_MS_SELF_TEST
 * @men: measure the magnetometer too
 *
 * A mode is entered from power-down only, and not before t_PD has passed:
 * a write that breaks this rule is ignored by the chip, so wait for it.
 * The accepted MS write also deasserts the data-ready pin, so with an
 * edge-triggered interrupt INTxST never needs reading.
 *
 * Return: 0 or a negative error number.
 */
int as9888_start(struct as9888_chip *chip, u8 mode, bool men)
{
	unsigned int slct2 = FIELD_PREP(AS9888_SLCT2_MEN_MSK, men) |
			     FIELD_PREP(AS9888_SLCT2_ALPF_MSK, chip->alpf);
	int ret;

	lockdep_assert_held(&chip->lock);

	/* Cached: no bus access unless the setting changes */
	ret = regmap_update_bits(chip->regmap, AS9888_REG_SLCT2,
				 AS9888_SLCT2_MEN_MSK | AS9888_SLCT2_ALPF_MSK,
				 slct2);
	if (ret)
		return ret;

	if (chip->irq)
		reinit_completion(&chip->drdy);

	as9888_wait_pd(chip);
	scoped_guard(mutex, &chip->int_lock) {
		ret = regmap_write(chip->regmap, AS9888_REG_MS, mode);
		WRITE_ONCE(chip->meas_seq, chip->meas_seq + 1);
	}
	chip->last_start = ktime_get();

	return ret;
}

static unsigned int as9888_meas_time_us(const struct as9888_chip *chip,
					bool men)
{
	if (men)
		return AS9888_T_MAG_US;

	return chip->alpf ? AS9888_T_ACC_LPF_US : AS9888_T_ACC_US;
}

int as9888_read_sample(struct as9888_chip *chip, struct as9888_raw_sample *s)
{
	return regmap_bulk_read(chip->regmap, AS9888_REG_ST1, s, sizeof(*s));
}

/*
 * Wait for the data-ready edge of a started measurement. When none came by
 * @timeout_us but ST1.DRDY says the sample is ready, the handler may just
 * be late on a busy system: give the edge AS9888_LATE_EDGE_MS more. A
 * ready sample whose edge never comes is a pin fault (an open INT1 line).
 */
static int as9888_wait_edge(struct as9888_chip *chip, unsigned int timeout_us)
{
	const char *pin = chip->int_pin->name;
	unsigned int st1;
	int ret;

	if (wait_for_completion_timeout(&chip->drdy,
					usecs_to_jiffies(timeout_us)))
		return 0;

	ret = regmap_read(chip->regmap, AS9888_REG_ST1, &st1);
	if (ret)
		return ret;
	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, st1))
		return -ETIMEDOUT;

	if (wait_for_completion_timeout(&chip->drdy,
					msecs_to_jiffies(AS9888_LATE_EDGE_MS)))
		return 0;

	dev_err_ratelimited(chip->dev,
			    "sample ready but no %s edge: check the %s line\n",
			    pin, pin);
	return -EIO;
}

/**
 * as9888_wait_sample() - wait for a started measurement and read it
 * @chip: chip state
 * @id: the device that asked for the measurement, for its timestamp
 * @t_us: duration of the measurement
 * @s: the sample
 * @ts: timestamp of the end of the measurement
 *
 * With the data-ready interrupt wired, wait for its edge
 * (as9888_wait_edge()). Without it, sleep for the duration of the
 * measurement and read the sample: a sample that is not ready yet
 * (ST1.DRDY clear) sends the driver polling ST1 until the timeout.
 *
 * Return: 0 or a negative error number: -ETIMEDOUT when the measurement
 * did not complete in time, -EIO when it did but its edge never came.
 */
static int as9888_wait_sample(struct as9888_chip *chip,
			      enum as9888_sensor_id id, unsigned int t_us,
			      struct as9888_raw_sample *s, s64 *ts)
{
	unsigned int timeout_us = AS9888_MEAS_TIMEOUT_US(t_us);
	unsigned int st1;
	int ret;

	if (chip->irq) {
		ret = as9888_wait_edge(chip, timeout_us);
		if (ret)
			return ret;

		*ts = chip->drdy_ts[id];
		chip->pd_since = chip->drdy_time;

		return as9888_read_sample(chip, s);
	}

	fsleep(t_us);
	ret = as9888_read_sample(chip, s);
	if (ret)
		return ret;

	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, s->st1)) {
		ret = regmap_read_poll_timeout(chip->regmap, AS9888_REG_ST1,
					       st1,
					       FIELD_GET(AS9888_ST1_DRDY_MSK, st1),
					       AS9888_POLL_US,
					       timeout_us - t_us);
		if (ret)
			return ret;

		ret = as9888_read_sample(chip, s);
		if (ret)
			return ret;
	}

	*ts = iio_get_time_ns(chip->iio[id]);
	/* The chip entered power-down before we saw DRDY */
	chip->pd_since = ktime_get();

	return 0;
}

/*
 * Checks that apply to every sample: data ready (ST1.DRDY) and a healthy
 * EMPT. A data overrun (ST1.DOR) only means an earlier sample was lost.
 */
int as9888_check_sample(struct as9888_chip *chip,
			const struct as9888_raw_sample *s)
{
	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, s->st1)) {
		dev_err_ratelimited(chip->dev, "no data ready (ST1 0x%02x)\n",
				    s->st1);
		return -EIO;
	}

	if (FIELD_GET(AS9888_ST1_DOR_MSK, s->st1))
		dev_warn_ratelimited(chip->dev, "data overrun, a sample was lost\n");

	if (s->empt) {
		dev_err_ratelimited(chip->dev, "EMPT reads 0x%02x, device fault\n",
				    s->empt);
		return -EIO;
	}

	return 0;
}

/*
 * Magnetometer checks: HST set means the magnetometer was not measured,
 * HOFL that an axis saturated.
 */
int as9888_check_magn(const struct as9888_raw_sample *s)
{
	if (FIELD_GET(AS9888_ST2_HST_MSK, s->st2))
		return -EIO;

	if (FIELD_GET(AS9888_ST2_HOFL_MSK, s->st2))
		return -ERANGE;

	return 0;
}

/**
 * as9888_measure() - run one measurement and read the sample
 * @chip: chip state
 * @id: the device that asks for it
 * @mode: AS9888_MS_SINGLE or AS9888_MS_SELF_TEST
 * @men: measure the magnetometer too (always done in self-test)
 * @s: the sample
 * @ts: timestamp of the sample
 *
 * During system sleep nothing is measured. While the data-ready trigger
 * runs for a buffer, wait for the gap between two of its samples first.
 * Then one MS write and one burst read of ST1..ST2 on the bus (plus ST1
 * polls in the unusual case that the sample is late without INT1). On any
 * error the measurement is aborted, leaving the chip in power-down.
 *
 * Return: 0, -EBUSY during system sleep, or a negative error number.
 */
int as9888_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		   u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts)
{
	bool self_test = mode == AS9888_MS_SELF_TEST;
	unsigned int t_us = as9888_meas_time_us(chip, men || self_test);
	int ret;

	lockdep_assert_held(&chip->lock);

	/* System sleep: the supplies are, or are about to be, off */
	if (chip->suspended)
		return -EBUSY;

	ret = as9888_wait_gap(chip);
	if (ret)
		return ret;

	ret = as9888_start(chip, mode, men || self_test);
	if (!ret)
		ret = as9888_wait_sample(chip, id, t_us, s, ts);
	if (ret) {
		if (ret == -ETIMEDOUT)
			dev_err_ratelimited(chip->dev,
					    "measurement not done after %u us\n",
					    AS9888_MEAS_TIMEOUT_US(t_us));
		/* Abort whatever may still run; the first error is reported */
		as9888_power_down(chip);
		return ret;
	}

	return as9888_check_sample(chip, s);
}

/**
 * as9888_write_trim() - write a trim register and read it back
 * @chip: chip state
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
int as9888_write_trim(struct as9888_chip *chip, unsigned int reg,
		      const u8 *val, size_t len)
{
	u8 readback[AS9888_TRIM_LEN];
	unsigned int ms;
	size_t i;
	int ret;

	lockdep_assert_held(&chip->lock);

	if (len > sizeof(readback))
		return -EINVAL;

	ret = regmap_read(chip->regmap, AS9888_REG_MS, &ms);
	if (ret)
		return ret;

	if (ms != AS9888_MS_POWER_DOWN) {
		ret = as9888_power_down(chip);
		if (ret)
			return ret;
	}
	as9888_wait_pd(chip);

	ret = regmap_bulk_write(chip->regmap, reg, val, len);
	if (ret)
		return ret;

	regcache_cache_bypass(chip->regmap, true);
	ret = regmap_raw_read(chip->regmap, reg, readback, len);
	regcache_cache_bypass(chip->regmap, false);
	if (ret)
		return ret;

	for (i = 0; i < len; i++) {
		if (readback[i] != val[i]) {
			dev_err(chip->dev,
				"register 0x%02zx reads 0x%02x, 0x%02x written\n",
				reg + i, readback[i], val[i]);
			return -EIO;
		}
	}

	return 0;
}

/* Sampling frequency of the data-ready trigger, shared by both devices */

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

int as9888_read_samp_freq_avail(const int **vals, int *type, int *length)
{
	*vals = as9888_samp_freq_avail;
	*length = ARRAY_SIZE(as9888_samp_freq_avail);
	*type = IIO_VAL_INT;

	return IIO_AVAIL_LIST;
}

int as9888_read_samp_freq(struct as9888_chip *chip, int *val)
{
	guard(mutex)(&chip->lock);
	*val = chip->samp_freq;

	return IIO_VAL_INT;
}

int as9888_write_samp_freq(struct as9888_chip *chip, int freq)
{
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(as9888_samp_freq_avail); i++) {
		if (as9888_samp_freq_avail[i] == freq) {
			guard(mutex)(&chip->lock);
			chip->samp_freq = freq;
			return 0;
		}
	}

	return -EINVAL;
}

/* The mount matrix from firmware, the same for both sensors */
const struct iio_mount_matrix *
as9888_get_mount_matrix(const struct iio_dev *indio_dev,
			const struct iio_chan_spec *chan)
{
	const struct as9888_sensor *sensor = iio_priv(indio_dev);

	return &sensor->chip->orientation;
}

/*
 * Register access for debugging (iio/iio:deviceX/direct_reg_access); it
 * also makes the IIO core create the devices' debugfs directories, the
 * magnetometer's holding selftest_readings. Serialised with the driver's own sequences.
 */
int as9888_debugfs_reg_access(struct iio_dev *indio_dev, unsigned int reg,
			      unsigned int writeval, unsigned int *readval)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	int ret;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		if (readval)
			ret = regmap_read(chip->regmap, reg, readval);
		else
			ret = regmap_write(chip->regmap, reg, writeval);
	}

	pm_runtime_put_autosuspend(chip->dev);

	return ret;
}

/* Power, reset and the factory trim: step 1 of the application note */

/*
 * Supplies on, then RSTN released: RSTN is held low while the supplies are
 * off (as9888_power_cut()), so every power-up is also a reset pulse of at
 * least t_RSTL. The chip answers t_BOOT after RSTN rises (or after
 * power-on, without a reset GPIO), in power-down.
 */
static int as9888_power_on(struct as9888_chip *chip)
{
	int ret;

	ret = regulator_bulk_enable(ARRAY_SIZE(chip->supplies), chip->supplies);
	if (ret)
		return ret;

	if (chip->reset) {
		fsleep(AS9888_RSTL_US);
		gpiod_set_value_cansleep(chip->reset, 0);
	}

	/* The chip NAKs (I2C) or reads 0xff (SPI) until it has booted */
	fsleep(AS9888_T_BOOT_US);
	/* It boots into power-down */
	chip->pd_since = ktime_get();

	return 0;
}

/*
 * RSTN low, then the supplies off: a logic-high RSTN would feed the
 * unpowered chip through its input protection (as ak8975_power_off()).
 * When the supplies cannot be switched off, RSTN is released again: the
 * chip then needs a register restore (its registers are at their reset
 * values after the pulse).
 */
static int as9888_power_cut(struct as9888_chip *chip)
{
	int ret;

	gpiod_set_value_cansleep(chip->reset, 1);

	ret = regulator_bulk_disable(ARRAY_SIZE(chip->supplies),
				     chip->supplies);
	if (ret && chip->reset) {
		fsleep(AS9888_RSTL_US);
		gpiod_set_value_cansleep(chip->reset, 0);
		fsleep(AS9888_T_BOOT_US);
		chip->pd_since = ktime_get();
	}

	return ret;
}

static void as9888_power_off(void *arg)
{
	struct as9888_chip *chip = arg;

	if (pm_runtime_status_suspended(chip->dev))
		return;

	as9888_power_cut(chip);
	pm_runtime_set_suspended(chip->dev);
}

/*
 * RSTN is taken asserted before the supplies are switched on, and released
 * by as9888_power_on(): probe starts with a reset pulse, whatever state the
 * chip was left in.
 */
static int as9888_power_init(struct as9888_chip *chip)
{
	struct device *dev = chip->dev;
	unsigned int i;
	int ret;

	chip->reset = devm_gpiod_get_optional(dev, "reset", GPIOD_OUT_HIGH);
	if (IS_ERR(chip->reset))
		return dev_err_probe(dev, PTR_ERR(chip->reset),
				     "cannot get reset GPIO\n");

	for (i = 0; i < ARRAY_SIZE(chip->supplies); i++)
		chip->supplies[i].supply = as9888_supply_names[i];

	ret = devm_regulator_bulk_get(dev, ARRAY_SIZE(chip->supplies),
				      chip->supplies);
	if (ret)
		return dev_err_probe(dev, ret, "cannot get regulators\n");

	ret = as9888_power_on(chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable regulators\n");

	/* Runtime PM status tells as9888_power_off() whether power is on */
	ret = pm_runtime_set_active(dev);
	if (ret) {
		as9888_power_cut(chip);
		return dev_err_probe(dev, ret, "cannot set runtime PM status\n");
	}

	return devm_add_action_or_reset(dev, as9888_power_off, chip);
}

/* Steps 1-5..1-29: the whole EEPROM in one burst in EEPROM access mode */
static int as9888_read_eeprom(struct as9888_chip *chip,
			      u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = chip->dev;
	int ret, ret_pd;

	as9888_wait_pd(chip);
	ret = regmap_write(chip->regmap, AS9888_REG_MS, AS9888_MS_EEPROM);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enter EEPROM mode\n");

	fsleep(AS9888_T_EEP_US);
	ret = regmap_bulk_read(chip->regmap, AS9888_REG_EEPROM, raw,
			       AS9888_EEPROM_LEN);

	/* EEPROM access mode is left only by writing power-down */
	ret_pd = as9888_power_down(chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read EEPROM\n");
	if (ret_pd)
		return dev_err_probe(dev, ret_pd,
				     "cannot leave EEPROM mode\n");

	return 0;
}

static int as9888_decode_eeprom(struct as9888_chip *chip,
				const u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = chip->dev;
	unsigned long bits;
	unsigned int bit;
	int ret;

	ret = as9888_eeprom_decode(raw, &chip->ee);

	bits = chip->ee.errors;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(chip->ee.errors))
		dev_err(dev, "%s\n", as9888_ee_error_str(BIT(bit)));
	if (ret)
		return dev_err_probe(dev, ret, "unusable factory EEPROM %*ph\n",
				     AS9888_EEPROM_LEN, raw);

	bits = chip->ee.warnings;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(chip->ee.warnings))
		dev_warn(dev, "%s\n", as9888_ee_warning_str(BIT(bit)));

	return 0;
}

/* Steps 1-30..1-39 and the read-back check of D10 */
static int as9888_load_trim(struct as9888_chip *chip)
{
	const struct as9888_eeprom *ee = &chip->ee;
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

	guard(mutex)(&chip->lock);

	ret = as9888_write_trim(chip, AS9888_REG_REF1, trim, sizeof(trim));
	if (ret)
		return dev_err_probe(chip->dev, ret, "cannot load trim\n");

	return 0;
}

static int as9888_chip_init(struct as9888_chip *chip)
{
	u8 raw[AS9888_EEPROM_LEN];
	unsigned int wia;
	int ret;

	ret = regmap_read(chip->regmap, AS9888_REG_WIA, &wia);
	if (ret)
		return dev_err_probe(chip->dev, ret, "cannot read WIA\n");
	if (wia != AS9888_WIA_VAL)
		return dev_err_probe(chip->dev, -ENODEV,
				     "WIA reads 0x%02x, not an AS9888 (0x%02x)\n",
				     wia, AS9888_WIA_VAL);

	ret = as9888_read_eeprom(chip, raw);
	if (ret)
		return ret;

	ret = as9888_decode_eeprom(chip, raw);
	if (ret)
		return ret;

	/* Until userspace loads a level test: the factory's state */
	chip->cal.t_mdegc = chip->ee.t_rt_mdegc;

	return as9888_load_trim(chip);
}

/*
 * The EEPROM as an NVMEM device "as9888-eeprom<N>", N the number of the
 * accelerometer's IIO device; reads are served from the copy taken at
 * probe.
 */
static int as9888_nvmem_read(void *priv, unsigned int offset, void *val,
			     size_t bytes)
{
	struct as9888_chip *chip = priv;

	if (offset >= AS9888_EEPROM_LEN || bytes > AS9888_EEPROM_LEN - offset)
		return -EINVAL;

	memcpy(val, &chip->ee.raw[offset], bytes);

	return 0;
}

static int as9888_nvmem_register(struct as9888_chip *chip)
{
	struct nvmem_config config = {
		.dev = chip->dev,
		.name = AS9888_DRV_NAME "-eeprom",
		.id = iio_device_id(chip->iio[AS9888_ACCEL]),
		.owner = THIS_MODULE,
		.type = NVMEM_TYPE_EEPROM,
		.read_only = true,
		.ignore_wp = true,
		.word_size = 1,
		.stride = 1,
		.size = AS9888_EEPROM_LEN,
		.reg_read = as9888_nvmem_read,
		.priv = chip,
	};
	struct nvmem_device *nvmem;

	if (!IS_ENABLED(CONFIG_NVMEM))
		return 0;

	nvmem = devm_nvmem_register(chip->dev, &config);
	if (IS_ERR(nvmem))
		return dev_err_probe(chip->dev, PTR_ERR(nvmem),
				     "cannot register EEPROM\n");

	return 0;
}

static const struct as9888_int_pin as9888_int_pins[] = {
	{ "INT1", AS9888_REG_INT1EN, AS9888_REG_INT1ST },
	{ "INT2", AS9888_REG_INT2EN, AS9888_REG_INT2ST },
};

/*
 * The data-ready interrupt. Without interrupt-names, the device's (first)
 * interrupt is INT1, and no interrupt means ST1 is polled. With
 * interrupt-names, INT1 is taken when it is named, else INT2 (a board that
 * wires INT2 only, as bmi323 does); a named interrupt that cannot be got
 * is a firmware error that fails probe, never a silent fall back to
 * polling.
 */
static int as9888_get_irq(struct as9888_chip *chip, int bus_irq)
{
	struct device *dev = chip->dev;
	struct fwnode_handle *fwnode = dev_fwnode(dev);
	const struct as9888_int_pin *pin;
	unsigned int i;
	int index, irq;

	chip->int_pin = &as9888_int_pins[0];
	if (!fwnode || !fwnode_property_present(fwnode, "interrupt-names"))
		return bus_irq > 0 ? bus_irq : 0;

	for (i = 0; i < ARRAY_SIZE(as9888_int_pins); i++) {
		pin = &as9888_int_pins[i];
		index = fwnode_property_match_string(fwnode, "interrupt-names",
						     pin->name);
		if (index < 0)
			continue;

		irq = fwnode_irq_get(fwnode, index);
		if (irq < 0)
			return dev_err_probe(dev, irq,
					     "cannot get interrupt %s (interrupt-names entry %d)\n",
					     pin->name, index);

		chip->int_pin = pin;
		return irq;
	}

	return dev_err_probe(dev, -EINVAL,
			     "interrupt-names names neither INT1 nor INT2\n");
}

/* Both IIO devices appear only when the whole chip is set up */
static int as9888_register(struct as9888_chip *chip)
{
	enum as9888_sensor_id id;
	int ret;

	for (id = 0; id < AS9888_SENSORS; id++) {
		ret = devm_iio_device_register(chip->dev, chip->iio[id]);
		if (ret)
			return dev_err_probe(chip->dev, ret,
					     "cannot register IIO device\n");
	}

	as9888_magn_debugfs_init(chip->iio[AS9888_MAGN]);

	return 0;
}

int as9888_core_probe(struct device *dev, struct regmap *regmap, int irq)
{
	struct as9888_chip *chip;
	int ret;

	chip = devm_kzalloc(dev, sizeof(*chip), GFP_KERNEL);
	if (!chip)
		return -ENOMEM;

	chip->dev = dev;
	chip->regmap = regmap;
	chip->samp_freq = AS9888_SAMP_FREQ_DEFAULT;
	init_completion(&chip->drdy);
	init_waitqueue_head(&chip->stop_wq);
	init_waitqueue_head(&chip->gap_wq);
	dev_set_drvdata(dev, chip);

	ret = devm_mutex_init(dev, &chip->lock);
	if (ret)
		return ret;

	ret = devm_mutex_init(dev, &chip->int_lock);
	if (ret)
		return ret;

	ret = iio_read_mount_matrix(dev, &chip->orientation);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read mount matrix\n");

	ret = as9888_power_init(chip);
	if (ret)
		return ret;

	ret = as9888_chip_init(chip);
	if (ret)
		return ret;

	irq = as9888_get_irq(chip, irq);
	if (irq < 0)
		return irq;
	/* Known before the channels are: sampling_frequency needs it */
	chip->irq = irq;

	chip->iio[AS9888_ACCEL] = as9888_sensor_alloc(chip, &as9888_accel_desc);
	if (IS_ERR(chip->iio[AS9888_ACCEL]))
		return PTR_ERR(chip->iio[AS9888_ACCEL]);

	chip->iio[AS9888_MAGN] = as9888_sensor_alloc(chip, &as9888_magn_desc);
	if (IS_ERR(chip->iio[AS9888_MAGN]))
		return PTR_ERR(chip->iio[AS9888_MAGN]);

	if (irq) {
		ret = as9888_trigger_setup(chip);
		if (ret)
			return ret;
	}

	ret = as9888_nvmem_register(chip);
	if (ret)
		return ret;

	pm_runtime_set_autosuspend_delay(dev, AS9888_AUTOSUSPEND_MS);
	pm_runtime_use_autosuspend(dev);
	ret = devm_pm_runtime_enable(dev);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable runtime PM\n");

	return as9888_register(chip);
}
EXPORT_SYMBOL_NS_GPL(as9888_core_probe, "IIO_AS9888");

/* Power management */

/*
 * Under the chip's lock, so that no register access sequence is cut in the
 * middle: after this, the registers are served from the cache (the trim,
 * the DAC and the interrupt set-up, rewritten on resume) and every other
 * access fails without reaching the bus.
 */
static int as9888_runtime_suspend(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	guard(mutex)(&chip->lock);

	regcache_cache_only(chip->regmap, true);
	regcache_mark_dirty(chip->regmap);

	ret = as9888_power_cut(chip);
	if (ret) {
		regcache_cache_only(chip->regmap, false);
		/* RSTN was pulsed: the chip lost its registers */
		regcache_sync(chip->regmap);
	}

	return ret;
}

/*
 * Power returns (with a reset pulse, see as9888_power_on()), so the chip
 * has lost its trim, DAC and interrupt setup: after t_BOOT, rewrite them
 * from the register cache, in power-down.
 */
static int as9888_runtime_resume(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	guard(mutex)(&chip->lock);

	ret = as9888_power_on(chip);
	if (ret)
		return ret;

	regcache_cache_only(chip->regmap, false);
	as9888_wait_pd(chip);
	ret = regcache_sync(chip->regmap);
	if (ret) {
		regcache_cache_only(chip->regmap, true);
		as9888_power_cut(chip);
	}

	return ret;
}

/*
 * System sleep: as9888_trig_suspend() stops a running data-ready trigger
 * and makes every measurement fail with -EBUSY until resume, so a buffer
 * on another trigger (whose handler may still run until the interrupts
 * are suspended) touches no register; INT1 is disabled, which also waits
 * for a handler in flight; then the supplies go off.
 */
static int as9888_suspend(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	as9888_trig_suspend(chip);
	if (chip->irq)
		disable_irq(chip->irq);

	ret = pm_runtime_force_suspend(dev);
	if (ret) {
		if (chip->irq)
			enable_irq(chip->irq);
		as9888_trig_resume(chip);
	}

	return ret;
}

static int as9888_resume(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	ret = pm_runtime_force_resume(dev);
	if (chip->irq)
		enable_irq(chip->irq);
	if (ret)
		return ret;

	return as9888_trig_resume(chip);
}

EXPORT_NS_GPL_DEV_PM_OPS(as9888_pm_ops, IIO_AS9888) = {
	SYSTEM_SLEEP_PM_OPS(as9888_suspend, as9888_resume)
	RUNTIME_PM_OPS(as9888_runtime_suspend, as9888_runtime_resume, NULL)
};

MODULE_DESCRIPTION("ALSEN AS9888 accelerometer/magnetometer core driver");
MODULE_LICENSE("GPL");
MODULE_IMPORT_NS("IIO_AS9888");
