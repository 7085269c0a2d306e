// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the accelerometer IIO device, "as9888-accel".
 *
 * Accelerometer X/Y/Z, compensated in the driver, and the die temperature
 * of the same measurements. Every accelerometer value, read or buffered, is
 * compensated with the offset Ot(t) and the sensitivity St(t) at the
 * temperature of its own sample (TMPS comes in the same burst), from the
 * factory EEPROM, the calibration (calibbias) and the offset DAC value in
 * use, which the driver chooses from the calibbias. The values sit on one
 * constant scale, AS9888_ACC_OUT_PER_G per g: consumers need nothing but
 * raw and scale. The device never makes the chip measure the magnetometer.
 */

#include <linux/array_size.h>
#include <linux/bitops.h>
#include <linux/cleanup.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/mutex.h>
#include <linux/pm_runtime.h>
#include <linux/regmap.h>
#include <linux/types.h>

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>

#include <asm/byteorder.h>

#include "as9888_core.h"

/*
 * Compensated readings are on AS9888_ACC_OUT_PER_G LSB per g, so the scale
 * is standard gravity, 9.80665 m/s^2, divided by that.
 */
#define AS9888_G_NUM			980665
#define AS9888_G_DEN			100000
#define AS9888_ACC_SCALE_DEN		(AS9888_G_DEN * AS9888_ACC_OUT_PER_G)

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

enum as9888_accel_scan {
	AS9888_SCAN_ACCEL_X,
	AS9888_SCAN_ACCEL_Y,
	AS9888_SCAN_ACCEL_Z,
	AS9888_SCAN_TEMP,
	AS9888_SCAN_ACCEL_TIMESTAMP,
};

/**
 * struct as9888_accel - IIO private data of the accelerometer device
 * @sensor:	the chip, and which sensor this is
 * @scan:	buffer for one scan: up to four 16-bit channels, timestamp;
 *		used by the trigger handler only
 * @scan.chans: the channel values
 * @scan.timestamp: filled in by the IIO core
 */
struct as9888_accel {
	struct as9888_sensor sensor;
	struct {
		s16 chans[AS9888_SCAN_ACCEL_TIMESTAMP];
		aligned_s64 timestamp;
	} scan;
};

/**
 * as9888_accel_out() - one axis of a sample, compensated
 * @chip: chip state, with chip->lock held
 * @s: a checked sample
 * @axis: 0..2 for X..Z
 * @out: the reading on the constant scale, AS9888_ACC_OUT_PER_G per g
 *
 * Offset Ot(t) and sensitivity St(t) (datasheet 6.4, 6.5) are those at the
 * temperature of the sample itself (TMPS is in the same burst), from the
 * EEPROM, the calibbias and the DAC value in use, which comes from the
 * register cache: the DAC changes only in the gap between two samples, so
 * it is the value the sample was measured with.
 *
 * Return: 0, -ERANGE when the chip's reading is at its rail (saturated) or
 * the result is beyond the output range: @out then holds the output
 * limit of that sign; or another negative error number.
 */
static int as9888_accel_out(struct as9888_chip *chip,
			    const struct as9888_raw_sample *s, int axis,
			    s16 *out)
{
	s16 raw = (s16)le16_to_cpu(s->accel[axis]);
	s32 ot_q16, st_q16;
	unsigned int da;
	int ret;

	lockdep_assert_held(&chip->lock);

	if (as9888_acc_saturated(raw)) {
		*out = raw < 0 ? AS9888_ACC_OUT_MIN : AS9888_ACC_OUT_MAX;
		return -ERANGE;
	}

	ret = regmap_read(chip->regmap, AS9888_REG_ADA(axis), &da);
	if (ret)
		return ret;

	ret = as9888_accel_correction(&chip->ee, &chip->cal, axis, da,
				      as9888_tmps_to_mdegc(s->tmps),
				      &ot_q16, &st_q16);
	if (ret)
		return ret;

	return as9888_accel_compensate(raw, ot_q16, st_q16, out);
}

/* Calibration */

static int as9888_read_calibbias(struct as9888_chip *chip, int axis, int *val)
{
	guard(mutex)(&chip->lock);
	*val = chip->cal.bias[axis];

	return IIO_VAL_INT;
}

/*
 * Write an axis' offset DAC; with chip->lock held, in the gap. regmap
 * takes a value into its cache before the bus write, keeps it when it
 * reads back wrong and drops the register from the cache when the bus
 * write fails. Either way the old value is then written back, so that the
 * cache (which compensates every later sample, and which runtime resume
 * writes to the chip) and the chip hold the DAC value of the calibbias
 * kept. When that write fails too, the old value goes into the cache
 * alone, and the chip may run with the new one until it is powered again:
 * that is logged.
 */
static int as9888_write_dac(struct as9888_chip *chip, int axis, u8 da)
{
	unsigned int reg = AS9888_REG_ADA(axis), old;
	u8 prev;
	int ret;

	lockdep_assert_held(&chip->lock);

	/* From the cache: probe wrote the trim */
	ret = regmap_read(chip->regmap, reg, &old);
	if (ret)
		return ret;

	ret = as9888_write_trim(chip, reg, &da, 1);
	if (!ret)
		return 0;

	prev = old;
	if (as9888_write_trim(chip, reg, &prev, 1)) {
		/*
		 * A write that fails on the bus drops the register from the
		 * cache. Under int_lock: the interrupt thread's INTxST read
		 * would fail while the map is cache-only.
		 */
		scoped_guard(mutex, &chip->int_lock) {
			regcache_cache_only(chip->regmap, true);
			regmap_write(chip->regmap, reg, old);
			regcache_cache_only(chip->regmap, false);
		}
		dev_err_ratelimited(chip->dev,
				    "offset DAC 0x%02x may hold 0x%02x until the chip is powered again (0x%02x kept)\n",
				    reg, da, prev);
	}

	return ret;
}

/*
 * The calibbias is realised as the offset DAC value that centres the chip's
 * output (as9888_bias_dac()) and the compensation of the rest; both change
 * together under chip->lock, so every sample is compensated for the DAC it
 * was measured with. Also while a buffer runs on the data-ready trigger:
 * the chip takes a trim write in power-down only, so the DAC is written in
 * the gap between two samples (as9888_wait_gap()). So a restore can change
 * the calibration under a client that keeps the buffer enabled, such as
 * iio-sensor-proxy.
 */
static int as9888_write_calibbias(struct as9888_chip *chip, int axis, int bias)
{
	u8 da;
	int ret;

	if (as9888_bias_dac(&chip->ee.axis[axis], bias, &da))
		return -EINVAL;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		ret = as9888_wait_gap(chip);
		if (!ret)
			ret = as9888_write_dac(chip, axis, da);
		if (!ret)
			chip->cal.bias[axis] = bias;
	}

	pm_runtime_put_autosuspend(chip->dev);

	return ret;
}

/* Single reads: accelerometer and temperature, without the magnetometer */
static int as9888_accel_read_channel(struct as9888_chip *chip,
				     const struct iio_chan_spec *chan,
				     int *val)
{
	struct as9888_raw_sample s;
	s16 accel;
	s64 ts;
	int ret;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		ret = as9888_gap_measure(chip, AS9888_ACCEL,
					 AS9888_MS_SINGLE, false, &s, &ts);
		if (!ret && chan->type == IIO_ACCEL)
			ret = as9888_accel_out(chip, &s, chan->address, &accel);
	}

	pm_runtime_put_autosuspend(chip->dev);
	if (ret)
		return ret;

	*val = chan->type == IIO_ACCEL ? accel : s.tmps;

	return IIO_VAL_INT;
}

static int as9888_read_oversampling(struct as9888_chip *chip, int *val)
{
	guard(mutex)(&chip->lock);
	*val = chip->alpf ? AS9888_OSR_ALPF_ON : AS9888_OSR_ALPF_OFF;

	return IIO_VAL_INT;
}

static int as9888_write_oversampling(struct as9888_chip *chip, int ratio)
{
	if (ratio != AS9888_OSR_ALPF_OFF && ratio != AS9888_OSR_ALPF_ON)
		return -EINVAL;

	guard(mutex)(&chip->lock);
	chip->alpf = ratio == AS9888_OSR_ALPF_ON;

	return 0;
}

static int as9888_accel_read_raw(struct iio_dev *indio_dev,
				 const struct iio_chan_spec *chan, int *val,
				 int *val2, long mask)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	int ret;

	switch (mask) {
	case IIO_CHAN_INFO_RAW:
		if (!iio_device_claim_direct(indio_dev))
			return -EBUSY;
		ret = as9888_accel_read_channel(chip, chan, val);
		iio_device_release_direct(indio_dev);
		return ret;
	case IIO_CHAN_INFO_SCALE:
		switch (chan->type) {
		case IIO_ACCEL:
			*val = AS9888_G_NUM;
			*val2 = AS9888_ACC_SCALE_DEN;
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
		return as9888_read_calibbias(chip, chan->address, val);
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		return as9888_read_oversampling(chip, val);
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_read_samp_freq(indio_dev, val);
	default:
		return -EINVAL;
	}
}

static const int as9888_calibbias_range[] = {
	-AS9888_CALIBBIAS_MAX, 1, AS9888_CALIBBIAS_MAX
};

static const int as9888_oversampling_avail[] = {
	AS9888_OSR_ALPF_OFF, AS9888_OSR_ALPF_ON
};

static int as9888_accel_read_avail(struct iio_dev *indio_dev,
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
		return as9888_read_samp_freq_avail(indio_dev, vals, type,
						   length);
	default:
		return -EINVAL;
	}
}

static int as9888_accel_write_raw(struct iio_dev *indio_dev,
				  const struct iio_chan_spec *chan, int val,
				  int val2, long mask)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	int ret;

	if (val2)
		return -EINVAL;

	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
		/* Also while buffering: see as9888_write_calibbias() */
		return as9888_write_calibbias(chip, chan->address, val);
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_write_samp_freq(indio_dev, val);
	case IIO_CHAN_INFO_OVERSAMPLING_RATIO:
		/* The sample time changes: not while the buffer runs */
		if (!iio_device_claim_direct(indio_dev))
			return -EBUSY;
		ret = as9888_write_oversampling(chip, val);
		iio_device_release_direct(indio_dev);
		return ret;
	default:
		return -EINVAL;
	}
}

static int as9888_accel_write_raw_get_fmt(struct iio_dev *indio_dev,
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

static const struct iio_chan_spec_ext_info as9888_accel_ext_info[] = {
	IIO_MOUNT_MATRIX(IIO_SHARED_BY_TYPE, as9888_get_mount_matrix),
	{ }
};

/*
 * realbits 16: the compensated values span s16, but one chip LSB is about
 * four of them, so the resolution is the chip's 12 bits.
 */
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

static const struct iio_chan_spec as9888_accel_channels[] = {
	AS9888_ACCEL_CHANNEL(X),
	AS9888_ACCEL_CHANNEL(Y),
	AS9888_ACCEL_CHANNEL(Z),
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
	IIO_CHAN_SOFT_TIMESTAMP(AS9888_SCAN_ACCEL_TIMESTAMP),
};

static const struct iio_info as9888_accel_info = {
	.read_raw = as9888_accel_read_raw,
	.read_avail = as9888_accel_read_avail,
	.write_raw = as9888_accel_write_raw,
	.write_raw_get_fmt = as9888_accel_write_raw_get_fmt,
	.debugfs_reg_access = as9888_debugfs_reg_access,
};

/* Fill the scan from a checked sample, false if it is no good */
static bool as9888_accel_fill_scan(struct iio_dev *indio_dev,
				   const struct as9888_raw_sample *s)
{
	struct as9888_accel *accel = iio_priv(indio_dev);
	struct as9888_chip *chip = accel->sensor.chip;
	unsigned int bit, i = 0;
	s16 *chan;
	int ret;

	lockdep_assert_held(&chip->lock);

	/* The timestamp is placed by the IIO core */
	iio_for_each_active_channel(indio_dev, bit) {
		if (bit == AS9888_SCAN_ACCEL_TIMESTAMP)
			break;
		chan = &accel->scan.chans[i++];
		if (bit == AS9888_SCAN_TEMP) {
			*chan = s->tmps;
			continue;
		}
		/* Saturated or beyond the output range: the limit is pushed */
		ret = as9888_accel_out(chip, s, bit - AS9888_SCAN_ACCEL_X, chan);
		if (ret && ret != -ERANGE) {
			dev_err_ratelimited(chip->dev,
					    "cannot compensate a sample: %d\n",
					    ret);
			return false;
		}
	}

	return true;
}

static void as9888_accel_push(struct iio_dev *indio_dev,
			      const struct as9888_raw_sample *s, s64 ts)
{
	struct as9888_accel *accel = iio_priv(indio_dev);

	if (as9888_accel_fill_scan(indio_dev, s))
		iio_push_to_buffers_with_ts(indio_dev, &accel->scan,
					    sizeof(accel->scan), ts);
}

const struct as9888_sensor_desc as9888_accel_desc = {
	.id = AS9888_ACCEL,
	.name = "as9888-accel",
	.priv_size = sizeof(struct as9888_accel),
	.info = &as9888_accel_info,
	.channels = as9888_accel_channels,
	.num_channels = ARRAY_SIZE(as9888_accel_channels),
	.men = false,
	.push = as9888_accel_push,
};
