// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the magnetometer IIO device, "as9888-magn".
 *
 * Magnetometer X/Y/Z and the magnetometer self-test (step 2 of the
 * application note). Only this device makes the chip measure the
 * magnetometer (SLCT2.MEN, t_MAG instead of t_ACC per sample): a client of
 * the accelerometer never pays for it.
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

/*
 * 0.3 uT/LSB before adjustment, 1 G = 100 uT, and the adjustment
 * multiplies by (EHC + 128) / 256, so the scale in gauss is
 * 3 * (EHC + 128) / 256000.
 */
#define AS9888_MAGN_SCALE_NUM		3
#define AS9888_MAGN_SCALE_DEN		256000
#define AS9888_EHC_OFFSET		128

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
 * @scan:	buffer for one scan: up to three 16-bit channels, timestamp;
 *		used by the trigger handler only
 * @scan.chans: the channel values
 * @scan.timestamp: filled in by the IIO core
 */
struct as9888_magn {
	struct as9888_sensor sensor;
	struct as9888_selftest selftest;
	struct {
		s16 chans[AS9888_SCAN_MAGN_TIMESTAMP];
		aligned_s64 timestamp;
	} scan;
};

static int as9888_magn_read_channel(struct as9888_chip *chip,
				    const struct iio_chan_spec *chan,
				    int *val)
{
	struct as9888_raw_sample s;
	s64 ts;
	int ret;

	ret = pm_runtime_resume_and_get(chip->dev);
	if (ret)
		return ret;

	scoped_guard(mutex, &chip->lock)
		ret = as9888_measure(chip, AS9888_MAGN, AS9888_MS_SINGLE, true,
				     &s, &ts);

	pm_runtime_put_autosuspend(chip->dev);
	if (ret)
		return ret;

	ret = as9888_check_magn(&s);
	if (ret)
		return ret;

	*val = (s16)le16_to_cpu(s.magn[chan->address]);

	return IIO_VAL_INT;
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
		ret = as9888_magn_read_channel(chip, chan, val);
		iio_device_release_direct(indio_dev);
		return ret;
	case IIO_CHAN_INFO_SCALE:
		*val = AS9888_MAGN_SCALE_NUM *
		       (chip->ee.axis[chan->address].ehc + AS9888_EHC_OFFSET);
		*val2 = AS9888_MAGN_SCALE_DEN;
		return IIO_VAL_FRACTIONAL;
	case IIO_CHAN_INFO_SAMP_FREQ:
		return as9888_read_samp_freq(indio_dev, val);
	default:
		return -EINVAL;
	}
}

static int as9888_magn_read_avail(struct iio_dev *indio_dev,
				  const struct iio_chan_spec *chan,
				  const int **vals, int *type, int *length,
				  long mask)
{
	if (mask != IIO_CHAN_INFO_SAMP_FREQ)
		return -EINVAL;

	return as9888_read_samp_freq_avail(indio_dev, vals, type, length);
}

static int as9888_magn_write_raw(struct iio_dev *indio_dev,
				 const struct iio_chan_spec *chan, int val,
				 int val2, long mask)
{
	if (val2 || mask != IIO_CHAN_INFO_SAMP_FREQ)
		return -EINVAL;

	return as9888_write_samp_freq(indio_dev, val);
}

static int as9888_magn_write_raw_get_fmt(struct iio_dev *indio_dev,
					 const struct iio_chan_spec *chan,
					 long mask)
{
	if (mask != IIO_CHAN_INFO_SAMP_FREQ)
		return -EINVAL;

	return IIO_VAL_INT;
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

static const struct iio_chan_spec as9888_magn_channels[] = {
	AS9888_MAGN_CHANNEL(X),
	AS9888_MAGN_CHANNEL(Y),
	AS9888_MAGN_CHANNEL(Z),
	IIO_CHAN_SOFT_TIMESTAMP(AS9888_SCAN_MAGN_TIMESTAMP),
};

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
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);
	struct as9888_raw_sample s;
	bool pass;
	int axis, ret;
	s16 h;
	s64 ts;

	lockdep_assert_held(&chip->lock);

	ret = as9888_measure(chip, AS9888_MAGN, AS9888_MS_SINGLE, true, &s,
			     &ts);
	if (ret)
		return ret;

	pass = !as9888_check_magn(&s);
	for (axis = 0; axis < AS9888_AXES; axis++)
		pass &= !as9888_mag_overflow((s16)le16_to_cpu(s.magn[axis]));

	ret = as9888_measure(chip, AS9888_MAGN, AS9888_MS_SELF_TEST, true, &s,
			     &ts);
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
 * A saturated axis (HOFL) reads -4096 or 4095 and is pushed as it is.
 */
static bool as9888_magn_fill_scan(struct iio_dev *indio_dev,
				  const struct as9888_raw_sample *s)
{
	struct as9888_magn *magn = iio_priv(indio_dev);
	unsigned int bit, i = 0;

	if (FIELD_GET(AS9888_ST2_HST_MSK, s->st2))
		return false;

	iio_for_each_active_channel(indio_dev, bit) {
		if (bit == AS9888_SCAN_MAGN_TIMESTAMP)
			break;
		magn->scan.chans[i++] = le16_to_cpu(s->magn[bit]);
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
