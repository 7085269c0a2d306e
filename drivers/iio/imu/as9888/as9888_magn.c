// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the magnetometer IIO device, "as9888-magn".
 *
 * Magnetometer X/Y/Z and the magnetometer self-test (the magnetometer
 * part of the vendor's function test). Only this device makes the chip
 * measure the magnetometer (SLCT2.MEN, t_MAG instead of t_ACC per
 * sample): a client of the accelerometer never pays for it.
 *
 * Every reading, read or buffered, carries the calibration userspace
 * writes (calibbias, calibscale: the hard iron and the diagonal of the
 * soft-iron correction), applied here with as9888_magn_calibrate(). It is
 * driver state, not the chip's, so it survives runtime suspend and system
 * sleep; the self-test judges the chip's own readings, without it.
 */

#include <linux/array_size.h>
#include <linux/bitfield.h>
#include <linux/bits.h>
#include <linux/cleanup.h>
#include <linux/debugfs.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/kstrtox.h>
#include <linux/math64.h>
#include <linux/mutex.h>
#include <linux/pm_runtime.h>
#include <linux/seq_file.h>
#include <linux/sysfs.h>
#include <linux/types.h>

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>
#include <linux/iio/sysfs.h>

#include <asm/byteorder.h>

#include "as9888_core.h"

/**
 * struct as9888_selftest - result of the last magnetometer self-test
 * @done:	a self-test has run
 * @pass:	every judgment of the magnetometer self-test passed
 * @adj_q8:	self-test reading per axis after sensitivity adjustment,
 *		1/256 LSB
 */
struct as9888_selftest {
	bool done;
	bool pass;
	s32 adj_q8[AS9888_AXES];
};

enum as9888_magn_scan {
	AS9888_SCAN_MAGN_X,
	AS9888_SCAN_MAGN_Y,
	AS9888_SCAN_MAGN_Z,
	AS9888_SCAN_MAGN_TIMESTAMP,
};

/**
 * struct as9888_magn - IIO private data of the magnetometer device
 * @sensor:	the chip, and which sensor this is
 * @selftest:	result of the last self-test, under the chip's lock
 * @cal:	the calibration applied to every reading, under the chip's
 *		lock (the buffer's push runs with it held, so a sample never
 *		sees half of a change); bias 0 and scale 1 after probe
 * @scan:	buffer for one scan: up to three 16-bit channels, timestamp;
 *		used by the trigger handler only
 * @scan.chans: the channel values
 * @scan.timestamp: filled in by the IIO core
 */
struct as9888_magn {
	struct as9888_sensor sensor;
	struct as9888_selftest selftest;
	struct as9888_magn_cal cal;
	struct {
		s16 chans[AS9888_SCAN_MAGN_TIMESTAMP];
		aligned_s64 timestamp;
	} scan;
};

/**
 * as9888_magn_out() - one axis of a sample, calibrated
 * @magn: the device's private data, with the chip's lock held
 * @s: a sample with magnetometer data
 * @axis: 0..2 for X..Z
 * @out: the calibrated reading, or the rail of its sign (-4096 or 4095)
 *
 * Return: 0, or -ERANGE when the chip's count is at its rail or the
 * calibrated value is beyond the output range (see as9888_magn_calibrate()).
 */
static int as9888_magn_out(struct as9888_magn *magn,
			   const struct as9888_raw_sample *s, int axis,
			   s16 *out)
{
	lockdep_assert_held(&magn->sensor.chip->lock);

	return as9888_magn_calibrate((s16)le16_to_cpu(s->magn[axis]),
				     magn->cal.bias[axis],
				     magn->cal.scale_micro[axis], out);
}

static int as9888_magn_read_channel(struct iio_dev *indio_dev,
				    const struct iio_chan_spec *chan,
				    int *val)
{
	struct as9888_magn *magn = iio_priv(indio_dev);
	struct as9888_chip *chip = magn->sensor.chip;
	struct as9888_raw_sample s;
	s16 h;
	s64 ts;
	int ret;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		ret = as9888_gap_measure(chip, AS9888_MAGN, AS9888_MS_SINGLE,
					 true, &s, &ts);
		/* HOFL: -ERANGE for every axis, as the chip does not say which */
		if (!ret)
			ret = as9888_check_magn(&s);
		if (!ret)
			ret = as9888_magn_out(magn, &s, chan->address, &h);
	}

	pm_runtime_put_autosuspend(chip->dev);
	if (ret)
		return ret;

	*val = h;

	return IIO_VAL_INT;
}

/* Calibration: driver state only, so also while the buffer runs */

static int as9888_magn_read_cal(struct as9888_magn *magn,
				const struct iio_chan_spec *chan, int *val,
				int *val2, long mask)
{
	guard(mutex)(&magn->sensor.chip->lock);

	if (mask == IIO_CHAN_INFO_CALIBBIAS) {
		*val = magn->cal.bias[chan->address];
		return IIO_VAL_INT;
	}

	*val = magn->cal.scale_micro[chan->address] /
	       AS9888_MAGN_CALIBSCALE_ONE;
	*val2 = magn->cal.scale_micro[chan->address] %
		AS9888_MAGN_CALIBSCALE_ONE;

	return IIO_VAL_INT_PLUS_MICRO;
}

/*
 * A new value takes effect with the next sample read or pushed: samples
 * before it carry the old calibration, samples after it the new one.
 */
static int as9888_magn_write_cal(struct as9888_magn *magn,
				 const struct iio_chan_spec *chan, int val,
				 int val2, long mask)
{
	s32 micro;
	int ret;

	if (mask == IIO_CHAN_INFO_CALIBBIAS) {
		if (val2 || !as9888_magn_calibbias_valid(val))
			return -EINVAL;
		guard(mutex)(&magn->sensor.chip->lock);
		magn->cal.bias[chan->address] = val;
		return 0;
	}

	ret = as9888_magn_calibscale_micro(val, val2, &micro);
	if (ret)
		return ret;

	guard(mutex)(&magn->sensor.chip->lock);
	magn->cal.scale_micro[chan->address] = micro;

	return 0;
}

static int as9888_magn_read_raw(struct iio_dev *indio_dev,
				const struct iio_chan_spec *chan, int *val,
				int *val2, long mask)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	int ret;

	switch (mask) {
	case IIO_CHAN_INFO_RAW:
		if (!iio_device_claim_direct(indio_dev))
			return -EBUSY;
		ret = as9888_magn_read_channel(indio_dev, chan, val);
		iio_device_release_direct(indio_dev);
		return ret;
	case IIO_CHAN_INFO_SCALE:
		*val = as9888_mag_scale_num(chip->ee.axis[chan->address].ehc);
		*val2 = AS9888_MAGN_SCALE_DEN;
		return IIO_VAL_FRACTIONAL;
	case IIO_CHAN_INFO_CALIBBIAS:
	case IIO_CHAN_INFO_CALIBSCALE:
		return as9888_magn_read_cal(iio_priv(indio_dev), chan, val,
					    val2, mask);
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_read_samp_freq(indio_dev, val);
	default:
		return -EINVAL;
	}
}

static const int as9888_magn_calibbias_range[] = {
	-AS9888_MAGN_CALIBBIAS_MAX, 1, AS9888_MAGN_CALIBBIAS_MAX
};

/* 0.500000 to 2.000000 in steps of 0.000001, IIO_VAL_INT_PLUS_MICRO pairs */
static const int as9888_magn_calibscale_range[] = {
	AS9888_MAGN_CALIBSCALE_MIN / AS9888_MAGN_CALIBSCALE_ONE,
	AS9888_MAGN_CALIBSCALE_MIN % AS9888_MAGN_CALIBSCALE_ONE,
	0, 1,
	AS9888_MAGN_CALIBSCALE_MAX / AS9888_MAGN_CALIBSCALE_ONE,
	AS9888_MAGN_CALIBSCALE_MAX % AS9888_MAGN_CALIBSCALE_ONE,
};

static int as9888_magn_read_avail(struct iio_dev *indio_dev,
				  const struct iio_chan_spec *chan,
				  const int **vals, int *type, int *length,
				  long mask)
{
	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
		*vals = as9888_magn_calibbias_range;
		*type = IIO_VAL_INT;
		return IIO_AVAIL_RANGE;
	case IIO_CHAN_INFO_CALIBSCALE:
		*vals = as9888_magn_calibscale_range;
		*type = IIO_VAL_INT_PLUS_MICRO;
		return IIO_AVAIL_RANGE;
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_read_samp_freq_avail(indio_dev, vals, type,
						   length);
	default:
		return -EINVAL;
	}
}

static int as9888_magn_write_raw(struct iio_dev *indio_dev,
				 const struct iio_chan_spec *chan, int val,
				 int val2, long mask)
{
	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
	case IIO_CHAN_INFO_CALIBSCALE:
		/* Also while buffering: a restore under a running client */
		return as9888_magn_write_cal(iio_priv(indio_dev), chan, val,
					     val2, mask);
	case IIO_CHAN_INFO_SAMP_FREQ:
		if (val2)
			return -EINVAL;
		return as9888_write_samp_freq(indio_dev, val);
	default:
		return -EINVAL;
	}
}

static int as9888_magn_write_raw_get_fmt(struct iio_dev *indio_dev,
					 const struct iio_chan_spec *chan,
					 long mask)
{
	switch (mask) {
	case IIO_CHAN_INFO_CALIBBIAS:
	case IIO_CHAN_INFO_SAMP_FREQ:
		return IIO_VAL_INT;
	case IIO_CHAN_INFO_CALIBSCALE:
		return IIO_VAL_INT_PLUS_MICRO;
	default:
		return -EINVAL;
	}
}

static const struct iio_chan_spec_ext_info as9888_magn_ext_info[] = {
	IIO_MOUNT_MATRIX(IIO_SHARED_BY_TYPE, as9888_get_mount_matrix),
	{ }
};

#define AS9888_MAGN_CHANNEL(_axis) {					\
	.type = IIO_MAGN,						\
	.modified = 1,							\
	.channel2 = IIO_MOD_##_axis,					\
	.address = AS9888_SCAN_MAGN_##_axis - AS9888_SCAN_MAGN_X,	\
	.info_mask_separate = BIT(IIO_CHAN_INFO_RAW) |			\
			      BIT(IIO_CHAN_INFO_SCALE) |		\
			      BIT(IIO_CHAN_INFO_CALIBBIAS) |		\
			      BIT(IIO_CHAN_INFO_CALIBSCALE),		\
	.info_mask_separate_available = BIT(IIO_CHAN_INFO_CALIBBIAS) |	\
					BIT(IIO_CHAN_INFO_CALIBSCALE),	\
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

static const struct iio_chan_spec as9888_magn_channels[] = {
	AS9888_MAGN_CHANNEL(X),
	AS9888_MAGN_CHANNEL(Y),
	AS9888_MAGN_CHANNEL(Z),
	IIO_CHAN_SOFT_TIMESTAMP(AS9888_SCAN_MAGN_TIMESTAMP),
};

/* Self-test: the vendor's function test, magnetometer part */

/**
 * as9888_run_selftest() - magnetometer function test
 * @indio_dev: the IIO device
 * @res: the result
 *
 * A normal measurement with the magnetometer on must complete without
 * overflow, then a self-test measurement must complete with every axis,
 * after sensitivity adjustment, within its window.
 *
 * Return: 0 when both measurements completed (@res says whether the
 * judgments passed) or a negative error number.
 */
static int as9888_run_selftest(struct iio_dev *indio_dev,
			       struct as9888_selftest *res)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	struct as9888_raw_sample s;
	bool pass;
	int axis, ret;
	s16 h;
	s64 ts;

	lockdep_assert_held(&chip->lock);

	ret = as9888_gap_measure(chip, AS9888_MAGN, AS9888_MS_SINGLE, true,
				 &s, &ts);
	if (ret)
		return ret;

	pass = !as9888_check_magn(&s);
	for (axis = 0; axis < AS9888_AXES; axis++)
		pass &= !as9888_mag_overflow((s16)le16_to_cpu(s.magn[axis]));

	ret = as9888_gap_measure(chip, AS9888_MAGN, AS9888_MS_SELF_TEST,
				 true, &s, &ts);
	if (ret)
		return ret;

	pass &= !as9888_check_magn(&s);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		u8 ehc = chip->ee.axis[axis].ehc;

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
	struct as9888_magn *magn = iio_priv(indio_dev);
	struct as9888_chip *chip = magn->sensor.chip;
	struct as9888_selftest res = { };
	int ret;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock) {
		ret = as9888_run_selftest(indio_dev, &res);
		magn->selftest = res;
	}

	pm_runtime_put_autosuspend(chip->dev);

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
	struct as9888_magn *magn = iio_priv(dev_to_iio_dev(dev));
	struct as9888_chip *chip = magn->sensor.chip;
	const struct as9888_selftest *res = &magn->selftest;

	guard(mutex)(&chip->lock);

	if (!res->done)
		return sysfs_emit(buf, "none\n");

	return sysfs_emit(buf, "%s\n", res->pass ? "pass" : "fail");
}

static IIO_DEVICE_ATTR_RW(selftest, 0);

static struct attribute *as9888_magn_attrs[] = {
	&iio_dev_attr_selftest.dev_attr.attr,
	NULL
};

static const struct attribute_group as9888_magn_attrs_group = {
	.attrs = as9888_magn_attrs,
};

/*
 * debugfs iio/iio:deviceX/selftest_readings: the adjusted self-test
 * readings of the last test, "X Y Z" in LSB rounded to 1/1000.
 */
static int as9888_selftest_readings_show(struct seq_file *m, void *unused)
{
	struct as9888_magn *magn = iio_priv(m->private);
	struct as9888_chip *chip = magn->sensor.chip;
	const struct as9888_selftest *res = &magn->selftest;
	int axis;

	guard(mutex)(&chip->lock);

	if (!res->done) {
		seq_puts(m, "none\n");
		return 0;
	}

	for (axis = 0; axis < AS9888_AXES; axis++) {
		s64 milli = as9888_q8_to_milli(res->adj_q8[axis]);
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

/* The device's state before it registers: the calibration's defaults */
void as9888_magn_init(struct iio_dev *indio_dev)
{
	struct as9888_magn *magn = iio_priv(indio_dev);

	as9888_magn_cal_init(&magn->cal);
}

/* Removed with the IIO device's debugfs directory when it unregisters */
void as9888_magn_debugfs_init(struct iio_dev *indio_dev)
{
	struct dentry *dir = iio_get_debugfs_dentry(indio_dev);

	if (IS_ERR_OR_NULL(dir))
		return;

	debugfs_create_file("selftest_readings", 0400, dir, indio_dev,
			    &as9888_selftest_readings_fops);
}

static const struct iio_info as9888_magn_info = {
	.read_raw = as9888_magn_read_raw,
	.read_avail = as9888_magn_read_avail,
	.write_raw = as9888_magn_write_raw,
	.write_raw_get_fmt = as9888_magn_write_raw_get_fmt,
	.debugfs_reg_access = as9888_debugfs_reg_access,
	.attrs = &as9888_magn_attrs_group,
};

/*
 * Fill the scan from a checked sample, false if it has no magnetometer
 * data (HST: the chip did not measure it; the data-ready trigger gives
 * this device only the samples it started with the magnetometer on).
 * Each axis is calibrated; a saturated one (its count at the rail, HOFL)
 * or one calibrated beyond the output range is pushed as the rail of its
 * sign, -4096 or 4095, which no calibrated value takes.
 */
static bool as9888_magn_fill_scan(struct iio_dev *indio_dev,
				  const struct as9888_raw_sample *s)
{
	struct as9888_magn *magn = iio_priv(indio_dev);
	unsigned int bit, i = 0;

	lockdep_assert_held(&magn->sensor.chip->lock);

	if (FIELD_GET(AS9888_ST2_HST_MSK, s->st2))
		return false;

	iio_for_each_active_channel(indio_dev, bit) {
		if (bit == AS9888_SCAN_MAGN_TIMESTAMP)
			break;
		/* -ERANGE leaves the rail in the scan, as said above */
		as9888_magn_out(magn, s, bit - AS9888_SCAN_MAGN_X,
				&magn->scan.chans[i++]);
	}

	return true;
}

static void as9888_magn_push(struct iio_dev *indio_dev,
			     const struct as9888_raw_sample *s, s64 ts)
{
	struct as9888_magn *magn = iio_priv(indio_dev);

	if (as9888_magn_fill_scan(indio_dev, s))
		iio_push_to_buffers_with_ts(indio_dev, &magn->scan,
					    sizeof(magn->scan), ts);
}

const struct as9888_sensor_desc as9888_magn_desc = {
	.id = AS9888_MAGN,
	.name = "as9888-magn",
	.priv_size = sizeof(struct as9888_magn),
	.info = &as9888_magn_info,
	.channels = as9888_magn_channels,
	.num_channels = ARRAY_SIZE(as9888_magn_channels),
	.men = true,
	.push = as9888_magn_push,
};
