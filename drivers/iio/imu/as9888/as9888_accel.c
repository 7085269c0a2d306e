// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the accelerometer IIO device, "as9888-accel".
 *
 * Accelerometer X/Y/Z, compensated in the driver, and the die temperature
 * of the same measurements. Every accelerometer value, read or buffered, is
 * compensated with the offset Ot(t) and the sensitivity St(t) at the
 * temperature of its own sample (TMPS comes in the same burst), from the
 * factory EEPROM, the calibration userspace loads (caliboffset, calibtemp)
 * and the offset DAC value in use (calibbias). The values sit on one
 * constant scale, AS9888_ACC_OUT_PER_G per g: consumers need nothing but
 * raw and scale. The device never makes the chip measure the magnetometer.
 */

#include <linux/array_size.h>
#include <linux/bitops.h>
#include <linux/cleanup.h>
#include <linux/ctype.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/kstrtox.h>
#include <linux/math64.h>
#include <linux/mutex.h>
#include <linux/pm_runtime.h>
#include <linux/regmap.h>
#include <linux/slab.h>
#include <linux/string.h>
#include <linux/sysfs.h>
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

#define AS9888_MICRO			1000000
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
 * EEPROM, the calibration and the DAC value in use, which comes from the
 * register cache: the DAC changes only in the gap between two samples, so
 * it is the value the sample was measured with. A reading beyond the output
 * range is clamped to it.
 *
 * Return: 0 or a negative error number.
 */
static int as9888_accel_out(struct as9888_chip *chip,
			    const struct as9888_raw_sample *s, int axis,
			    s16 *out)
{
	s32 ot_q16, st_q16;
	unsigned int da;
	int ret;

	lockdep_assert_held(&chip->lock);

	ret = regmap_read(chip->regmap, AS9888_REG_ADA(axis), &da);
	if (ret)
		return ret;

	ret = as9888_accel_correction(&chip->ee, &chip->cal, axis, da,
				      as9888_tmps_to_mdegc(s->tmps),
				      &ot_q16, &st_q16);
	if (ret)
		return ret;

	ret = as9888_accel_compensate((s16)le16_to_cpu(s->accel[axis]),
				      ot_q16, st_q16, out);

	return ret == -ERANGE ? 0 : ret;
}

/* Offset DAC */

static int as9888_read_calibbias(struct as9888_chip *chip, int axis, int *val)
{
	unsigned int da;
	int ret;

	guard(mutex)(&chip->lock);

	/* Cached register: no bus access, also fine while suspended */
	ret = regmap_read(chip->regmap, AS9888_REG_ADA(axis), &da);
	if (ret)
		return ret;

	*val = as9888_dac2lin(chip->ee.axis[axis].ga, da);

	return IIO_VAL_INT;
}

/*
 * Also while a buffer runs on the data-ready trigger: the chip takes a trim
 * write in power-down only, so the value is written in the gap between two
 * samples (as9888_wait_gap()). The calibration is referred to the factory
 * DAC values, so it stays valid whatever the DAC holds, and every later
 * sample is compensated for the DAC in use. So a restore or a factory test
 * can change the DAC under a client that keeps the buffer enabled, such as
 * iio-sensor-proxy.
 */
static int as9888_write_calibbias(struct as9888_chip *chip, int axis, int lin)
{
	u8 da;
	int ret;

	if (lin < -AS9888_DAC_LIN_MAX || lin > AS9888_DAC_LIN_MAX)
		return -EINVAL;

	da = as9888_lin2dac(chip->ee.axis[axis].ga, lin);

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		ret = as9888_wait_gap(chip);
		if (!ret)
			ret = as9888_write_trim(chip, AS9888_REG_ADA(axis),
						&da, 1);
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
		ret = as9888_measure(chip, AS9888_ACCEL, AS9888_MS_SINGLE,
				     false, &s, &ts);
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
	-AS9888_DAC_LIN_MAX, 1, AS9888_DAC_LIN_MAX
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

/* Extended channel attributes */

static ssize_t as9888_caliboffset_read(struct iio_dev *indio_dev,
				       uintptr_t private,
				       const struct iio_chan_spec *chan,
				       char *buf)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	s64 micro;
	u64 abs_micro;
	u32 frac;

	scoped_guard(mutex, &chip->lock)
		micro = as9888_q16_to_micro(chip->cal.offset_q16[chan->address]);

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
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
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

	guard(mutex)(&chip->lock);
	chip->cal.offset_q16[chan->address] = q16;

	return len;
}

static ssize_t as9888_calibtemp_read(struct iio_dev *indio_dev,
				     uintptr_t private,
				     const struct iio_chan_spec *chan,
				     char *buf)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);

	guard(mutex)(&chip->lock);

	return sysfs_emit(buf, "%d\n", chip->cal.t_mdegc);
}

/* The valid TMPS range, -30..85 degC */
static ssize_t as9888_calibtemp_write(struct iio_dev *indio_dev,
				      uintptr_t private,
				      const struct iio_chan_spec *chan,
				      const char *buf, size_t len)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	int t_mdegc, ret;

	ret = kstrtoint(buf, 10, &t_mdegc);
	if (ret)
		return ret;

	if (t_mdegc < as9888_tmps_to_mdegc(AS9888_TMPS_MAX) ||
	    t_mdegc > as9888_tmps_to_mdegc(AS9888_TMPS_MIN))
		return -EINVAL;

	guard(mutex)(&chip->lock);
	chip->cal.t_mdegc = t_mdegc;

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
		ret = as9888_accel_out(chip, s, bit - AS9888_SCAN_ACCEL_X, chan);
		if (ret) {
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
