// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 test bench: an IIO device that has nothing to do with the AS9888,
 * "as9888-sim-other" (one voltage channel that reads 0, a timestamp, a
 * triggered buffer), so that the guest tests can check that the chip's
 * data-ready trigger refuses a device of another chip, and that such a
 * device takes a trigger that is free for all (an hrtimer trigger). Its
 * parent is a platform device of the same name without a driver. Loaded
 * and removed by the tests that need it (73-split.sh).
 */

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>
#include <linux/iio/trigger.h>
#include <linux/iio/trigger_consumer.h>
#include <linux/iio/triggered_buffer.h>
#include <linux/module.h>
#include <linux/platform_device.h>

#define AS9888_SIM_OTHER_NAME "as9888-sim-other"

static struct platform_device *as9888_sim_other_pdev;
static struct iio_dev *as9888_sim_other_iio;

static const struct iio_chan_spec as9888_sim_other_channels[] = {
	{
		.type = IIO_VOLTAGE,
		.indexed = 1,
		.channel = 0,
		.info_mask_separate = BIT(IIO_CHAN_INFO_RAW),
		.scan_index = 0,
		.scan_type = {
			.sign = 's',
			.realbits = 16,
			.storagebits = 16,
			.endianness = IIO_CPU,
		},
	},
	IIO_CHAN_SOFT_TIMESTAMP(1),
};

static int as9888_sim_other_read_raw(struct iio_dev *indio_dev,
				     struct iio_chan_spec const *chan,
				     int *val, int *val2, long mask)
{
	if (mask != IIO_CHAN_INFO_RAW)
		return -EINVAL;
	*val = 0;
	return IIO_VAL_INT;
}

static const struct iio_info as9888_sim_other_info = {
	.read_raw = as9888_sim_other_read_raw,
};

static irqreturn_t as9888_sim_other_handler(int irq, void *p)
{
	struct iio_poll_func *pf = p;
	struct iio_dev *indio_dev = pf->indio_dev;
	/* the channel (0) in the first 8 bytes, the timestamp in the last */
	s64 scan[2] = { };

	iio_push_to_buffers_with_timestamp(indio_dev, scan,
					   iio_get_time_ns(indio_dev));
	iio_trigger_notify_done(indio_dev->trig);
	return IRQ_HANDLED;
}

static int __init as9888_sim_other_init(void)
{
	struct iio_dev *indio_dev;
	int ret;

	as9888_sim_other_pdev =
		platform_device_register_simple(AS9888_SIM_OTHER_NAME,
						PLATFORM_DEVID_NONE, NULL, 0);
	if (IS_ERR(as9888_sim_other_pdev))
		return PTR_ERR(as9888_sim_other_pdev);

	indio_dev = iio_device_alloc(&as9888_sim_other_pdev->dev, 0);
	if (!indio_dev) {
		ret = -ENOMEM;
		goto err_pdev;
	}
	indio_dev->name = AS9888_SIM_OTHER_NAME;
	indio_dev->info = &as9888_sim_other_info;
	indio_dev->modes = INDIO_DIRECT_MODE;
	indio_dev->channels = as9888_sim_other_channels;
	indio_dev->num_channels = ARRAY_SIZE(as9888_sim_other_channels);

	ret = iio_triggered_buffer_setup(indio_dev, NULL,
					 as9888_sim_other_handler, NULL);
	if (ret)
		goto err_free;
	ret = iio_device_register(indio_dev);
	if (ret)
		goto err_buffer;
	as9888_sim_other_iio = indio_dev;
	return 0;

err_buffer:
	iio_triggered_buffer_cleanup(indio_dev);
err_free:
	iio_device_free(indio_dev);
err_pdev:
	platform_device_unregister(as9888_sim_other_pdev);
	return ret;
}
module_init(as9888_sim_other_init);

static void __exit as9888_sim_other_exit(void)
{
	iio_device_unregister(as9888_sim_other_iio);
	iio_triggered_buffer_cleanup(as9888_sim_other_iio);
	iio_device_free(as9888_sim_other_iio);
	platform_device_unregister(as9888_sim_other_pdev);
}
module_exit(as9888_sim_other_exit);

MODULE_DESCRIPTION("AS9888 test bench: an IIO device unrelated to the AS9888");
MODULE_LICENSE("GPL");
