// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: 3-axis magnetometer, 3-axis accelerometer and
 * temperature sensor. Chip access, shared by both sensors.
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
 * (as9888_trigger.c), which decides when the chip is free for a
 * measurement of their own (as9888_gap_measure()).
 *
 * Probe and power management are in as9888_probe.c.
 */

#include <linux/array_size.h>
#include <linux/atomic.h>
#include <linux/bitfield.h>
#include <linux/bug.h>
#include <linux/cleanup.h>
#include <linux/completion.h>
#include <linux/delay.h>
#include <linux/device.h>
#include <linux/jiffies.h>
#include <linux/ktime.h>
#include <linux/math.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/regmap.h>
#include <linux/time64.h>
#include <linux/types.h>

#include <linux/iio/iio.h>

#include "as9888_core.h"

/* A measurement that has not completed by 1.5 t + margin has failed */
#define AS9888_MEAS_MARGIN_US		2000
#define AS9888_MEAS_TIMEOUT_US(t)	((t) * 3 / 2 + AS9888_MEAS_MARGIN_US)
/*
 * How much longer a data-ready edge is waited for when the sample is
 * already ready: far beyond the latency of a handler on a busy system
 */
#define AS9888_LATE_EDGE_MS		100
/* ST1 polling interval when no interrupt is wired */
#define AS9888_POLL_US			100

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

/*
 * Modes and measurements; all of these run with chip->lock held, or in
 * probe before the IIO devices are registered, when nothing else can
 * reach the chip
 */

/* Wait until t_PD has passed since the chip entered power-down */
void as9888_wait_pd(struct as9888_chip *chip)
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
	/* Counted first: the edge may come before regmap_write() returns */
	scoped_guard(mutex, &chip->int_lock) {
		WRITE_ONCE(chip->meas_seq, chip->meas_seq + 1);
		ret = regmap_write(chip->regmap, AS9888_REG_MS, mode);
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

		*ts = READ_ONCE(chip->drdy_ts[id]);
		chip->pd_since = READ_ONCE(chip->drdy_time);

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
 * EMPT. A data overrun (ST1.DOR) only means an earlier sample was lost,
 * and is not worth a word when the driver left that sample unread itself.
 */
int as9888_check_sample(struct as9888_chip *chip,
			const struct as9888_raw_sample *s)
{
	if (!FIELD_GET(AS9888_ST1_DRDY_MSK, s->st1)) {
		dev_err_ratelimited(chip->dev, "no data ready (ST1 0x%02x)\n",
				    s->st1);
		return -EIO;
	}

	if (FIELD_GET(AS9888_ST1_DOR_MSK, s->st1) && !chip->sample_skipped)
		dev_warn_ratelimited(chip->dev, "data overrun, a sample was lost\n");
	chip->sample_skipped = false;

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
 * With chip->lock held and the chip in power-down: the data-ready
 * trigger in its gap, which only as9888_gap_measure() waits for, so the
 * devices measure through that. Here, a sample of the trigger in flight
 * (a caller that did not wait) is refused with a warning, and so is a
 * measurement during system sleep, when the supplies are, or are about
 * to be, off. One MS write and one burst read of ST1..ST2 on the bus
 * (plus ST1 polls in the unusual case that the sample is late without
 * INT1). On any error the measurement is aborted, leaving the chip in
 * power-down.
 *
 * Return: 0, -EBUSY during system sleep or outside the trigger's gap, or
 * a negative error number.
 */
int as9888_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		   u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts)
{
	bool self_test = mode == AS9888_MS_SELF_TEST;
	unsigned int t_us = as9888_meas_time_us(chip, men || self_test);
	int ret;

	lockdep_assert_held(&chip->lock);

	if (WARN_ON_ONCE(atomic_read(&chip->trig_state) != AS9888_TRIG_IDLE))
		return -EBUSY;
	if (chip->suspended)
		return -EBUSY;

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
 * The chip ignores trim writes outside power-down. With chip->lock held
 * and the data-ready trigger in its gap, the chip is in power-down, so no
 * MS read here: a measurement of as9888_measure() ends, or is aborted by
 * a power-down write, before it lets go of the lock; one of the trigger
 * ends before its gap, or is aborted (a failed start, the watchdog, a
 * stop); probe writes the trim after leaving EEPROM access mode. Wait for
 * t_PD, write, and check the write with an uncached read.
 *
 * Return: 0, -EIO when a register does not read back what was written, or
 * another negative error number.
 */
int as9888_write_trim(struct as9888_chip *chip, unsigned int reg,
		      const u8 *val, size_t len)
{
	u8 readback[AS9888_TRIM_LEN];
	size_t i;
	int ret;

	lockdep_assert_held(&chip->lock);

	if (len > sizeof(readback))
		return -EINVAL;

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
			dev_err_ratelimited(chip->dev,
					    "register 0x%02zx reads 0x%02x, 0x%02x written\n",
					    reg + i, readback[i], val[i]);
			return -EIO;
		}
	}

	return 0;
}

/* The mount matrix from firmware, the same for both sensors */
const struct iio_mount_matrix *
as9888_get_mount_matrix(const struct iio_dev *indio_dev,
			const struct iio_chan_spec *chan)
{
	const struct as9888_sensor *sensor = iio_priv(indio_dev);

	return &sensor->chip->orientation;
}
