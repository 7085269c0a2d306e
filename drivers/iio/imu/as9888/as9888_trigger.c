// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the data-ready trigger, shared by the accelerometer and the
 * magnetometer IIO devices, and the buffer set-up both devices use.
 *
 * The chip has no output data rate: the trigger starts each measurement
 * itself, once per sampling period, and INT1 fires it when the sample is
 * ready. The sample is read once, by whichever device's handler runs first,
 * and each device takes its own channels from it. When the last handler is
 * done (the trigger's reenable op), the next measurement is started, with
 * the magnetometer on only while the magnetometer device's buffer runs on
 * the trigger.
 *
 * Everything else that needs the chip in power-down (a _raw read, the
 * self-test, a buffer on another trigger, an offset DAC write) waits for
 * the gap between two samples of the trigger: after the handlers are done
 * with one sample and before the next one starts. So a client of one
 * sensor neither stops the other sensor's buffer nor has to wait for it to
 * end, and every sample is compensated with the DAC value it was measured
 * with.
 */

#include <linux/bitfield.h>
#include <linux/bitops.h>
#include <linux/cleanup.h>
#include <linux/device.h>
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/jiffies.h>
#include <linux/ktime.h>
#include <linux/math64.h>
#include <linux/mutex.h>
#include <linux/pm_runtime.h>
#include <linux/regmap.h>
#include <linux/time64.h>
#include <linux/wait.h>

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>
#include <linux/iio/trigger.h>

#include "as9888_core.h"

/* Attempts to start the next measurement of the data-ready trigger */
#define AS9888_START_RETRIES		3
/*
 * How long a synchronous measurement waits for the data-ready trigger's
 * next gap between two samples, beyond two sampling periods
 */
#define AS9888_GAP_WAIT_SLACK_MS	2000

/* The trigger's sampling period in ns; with chip->lock held */
static u64 as9888_trig_period_ns(const struct as9888_chip *chip)
{
	return div_u64(NSEC_PER_SEC, chip->samp_freq);
}

/*
 * How long to wait for the data-ready trigger's gap: a sample may keep the
 * chip for a whole period, and the one after it too when a handler ran late
 */
static unsigned long as9888_trig_wait_jiffies(const struct as9888_chip *chip)
{
	unsigned int period_ms = DIV_ROUND_UP(MSEC_PER_SEC, chip->samp_freq);

	return msecs_to_jiffies(2 * period_ms + AS9888_GAP_WAIT_SLACK_MS);
}

/**
 * as9888_wait_gap() - wait for the gap between two samples of the trigger
 * @chip: chip state, with chip->lock held; the lock is dropped while
 *	  waiting
 *
 * Return: 0 with chip->lock held and no measurement of the data-ready
 * trigger in flight, or -ETIMEDOUT when the trigger's sample did not come
 * (also with chip->lock held).
 */
int as9888_wait_gap(struct as9888_chip *chip)
{
	unsigned long left;

	lockdep_assert_held(&chip->lock);

	left = as9888_trig_wait_jiffies(chip);
	while (chip->trig_busy) {
		mutex_unlock(&chip->lock);
		left = wait_event_timeout(chip->gap_wq,
					  !READ_ONCE(chip->trig_busy), left);
		mutex_lock(&chip->lock);
		if (!left && chip->trig_busy) {
			dev_err_ratelimited(chip->dev,
					    "data-ready trigger stalled\n");
			return -ETIMEDOUT;
		}
	}

	return 0;
}

/* The handlers are done with the sample, or it never comes: the gap */
static void as9888_trig_gap(struct as9888_chip *chip)
{
	lockdep_assert_held(&chip->lock);

	chip->trig_unread = false;
	WRITE_ONCE(chip->trig_busy, false);
	wake_up_all(&chip->gap_wq);
}

/* Start a measurement of the data-ready trigger; with chip->lock held */
static int as9888_trig_measure(struct as9888_chip *chip)
{
	int ret;

	lockdep_assert_held(&chip->lock);

	/* Before the MS write: INT1 must find it set */
	WRITE_ONCE(chip->trig_busy, true);
	chip->trig_unread = true;
	ret = as9888_start(chip, AS9888_MS_SINGLE,
			   chip->trig_users & BIT(AS9888_MAGN));
	if (ret)
		as9888_trig_gap(chip);

	return ret;
}

static int as9888_trig_start(struct as9888_chip *chip)
{
	int ret;

	lockdep_assert_held(&chip->lock);

	WRITE_ONCE(chip->trig_running, true);
	ret = as9888_trig_measure(chip);
	if (ret)
		WRITE_ONCE(chip->trig_running, false);
	chip->trig_slot = chip->last_start;

	return ret;
}

static int as9888_trig_stop(struct as9888_chip *chip)
{
	int ret;

	lockdep_assert_held(&chip->lock);

	WRITE_ONCE(chip->trig_running, false);
	wake_up(&chip->stop_wq);

	/* Abort a measurement in flight; a handler still to run finds none */
	ret = as9888_power_down(chip);
	chip->trig_err = -ENODATA;
	as9888_trig_gap(chip);

	return ret;
}

/**
 * as9888_trig_sample() - the sample of the data-ready trigger's last edge
 * @chip: chip state, with chip->lock held
 * @s: the sample
 *
 * The first handler to run after an INT1 edge reads the sample; the other
 * device's handler gets the same one.
 *
 * Return: 0 or the error of reading or checking the sample.
 */
int as9888_trig_sample(struct as9888_chip *chip,
		       const struct as9888_raw_sample **s)
{
	lockdep_assert_held(&chip->lock);

	if (chip->trig_unread) {
		chip->trig_err = as9888_read_sample(chip, &chip->trig_sample);
		if (!chip->trig_err)
			chip->trig_err = as9888_check_sample(chip,
							     &chip->trig_sample);
		chip->pd_since = chip->drdy_time;
		chip->trig_unread = false;
	}
	*s = &chip->trig_sample;

	return chip->trig_err;
}

/*
 * The trigger's reenable op: every device's handler is done with the
 * sample. Wait for the rest of the sampling period (the wait ends early
 * when the trigger stops), then start the next measurement, whose INT1
 * edge fires the trigger again. It runs in the last handler's thread or a
 * work item, never in interrupt context.
 */
static void as9888_trig_reenable(struct iio_trigger *trig)
{
	struct as9888_chip *chip = iio_trigger_get_drvdata(trig);
	ktime_t next, now;
	u64 period;
	s64 wait_ns;
	int i, ret = 0;

	scoped_guard(mutex, &chip->lock) {
		if (!chip->trig_running)
			return;
		as9888_trig_gap(chip);
		period = as9888_trig_period_ns(chip);
		next = ktime_add_ns(chip->trig_slot, period);
		now = ktime_get();
		/* a whole period behind: start a new schedule from now */
		if (ktime_before(ktime_add_ns(next, period), now))
			next = now;
		chip->trig_slot = next;
	}

	wait_ns = ktime_to_ns(ktime_sub(next, ktime_get()));
	if (wait_ns > 0)
		wait_event_hrtimeout(chip->stop_wq,
				     !READ_ONCE(chip->trig_running),
				     ns_to_ktime(wait_ns));

	guard(mutex)(&chip->lock);
	for (i = 0; i < AS9888_START_RETRIES && chip->trig_running; i++) {
		ret = as9888_trig_measure(chip);
		if (!ret)
			return;
	}
	if (ret)
		dev_err(chip->dev, "data-ready trigger stopped: %d\n", ret);
}

static const struct iio_trigger_ops as9888_trigger_ops = {
	/* Both devices of the chip share the bus device as parent */
	.validate_device = iio_trigger_validate_own_device,
	.reenable = as9888_trig_reenable,
};

/* True when @indio_dev's buffer runs on the chip's data-ready trigger */
bool as9888_on_drdy_trigger(struct iio_dev *indio_dev)
{
	struct as9888_chip *chip = as9888_iio_to_chip(indio_dev);

	return chip->trig && indio_dev->trig == chip->trig;
}

/* Buffers: the same set-up for both devices */

static int as9888_buffer_preenable(struct iio_dev *indio_dev)
{
	return pm_runtime_resume_and_get(as9888_iio_to_chip(indio_dev)->dev);
}

static int as9888_buffer_postenable(struct iio_dev *indio_dev)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	struct as9888_chip *chip = sensor->chip;
	int ret;

	if (!as9888_on_drdy_trigger(indio_dev))
		return 0;

	guard(mutex)(&chip->lock);

	/* A running trigger measures the magnetometer from its next sample */
	chip->trig_users |= BIT(sensor->id);
	if (chip->trig_running)
		return 0;

	ret = as9888_trig_start(chip);
	if (ret)
		chip->trig_users &= ~BIT(sensor->id);

	return ret;
}

static int as9888_buffer_predisable(struct iio_dev *indio_dev)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	struct as9888_chip *chip = sensor->chip;

	if (!as9888_on_drdy_trigger(indio_dev))
		return 0;

	guard(mutex)(&chip->lock);

	chip->trig_users &= ~BIT(sensor->id);
	if (chip->trig_users || !chip->trig_running)
		return 0;

	return as9888_trig_stop(chip);
}

static int as9888_buffer_postdisable(struct iio_dev *indio_dev)
{
	pm_runtime_put_autosuspend(as9888_iio_to_chip(indio_dev)->dev);

	return 0;
}

const struct iio_buffer_setup_ops as9888_buffer_ops = {
	.preenable = as9888_buffer_preenable,
	.postenable = as9888_buffer_postenable,
	.predisable = as9888_buffer_predisable,
	.postdisable = as9888_buffer_postdisable,
};

/* System sleep: a running data-ready trigger is stopped over it */

void as9888_trig_suspend(struct as9888_chip *chip)
{
	guard(mutex)(&chip->lock);

	chip->trig_resume = chip->trig_running;
	if (chip->trig_resume)
		as9888_trig_stop(chip);
}

int as9888_trig_resume(struct as9888_chip *chip)
{
	guard(mutex)(&chip->lock);

	if (!chip->trig_resume)
		return 0;

	chip->trig_resume = false;

	return as9888_trig_start(chip);
}

/*
 * INT1: a sample of the data-ready trigger fires the trigger; any other
 * measurement is waited for synchronously, with a timestamp for each
 * device (each may use its own clock).
 */
static irqreturn_t as9888_drdy_irq(int irq, void *private)
{
	struct as9888_chip *chip = private;
	enum as9888_sensor_id id;

	chip->drdy_time = ktime_get();

	if (READ_ONCE(chip->trig_busy)) {
		iio_trigger_poll(chip->trig);
		return IRQ_HANDLED;
	}

	for (id = 0; id < AS9888_SENSORS; id++)
		chip->drdy_ts[id] = iio_get_time_ns(chip->iio[id]);
	complete(&chip->drdy);

	return IRQ_HANDLED;
}

/**
 * as9888_trigger_setup() - INT1 and the data-ready trigger
 * @chip: chip state, with both IIO devices allocated
 * @irq: INT1
 *
 * The trigger is named after the accelerometer device, "as9888-dev<N>",
 * and is the default trigger of both devices.
 *
 * Return: 0 or a negative error number.
 */
int as9888_trigger_setup(struct as9888_chip *chip, int irq)
{
	struct device *dev = chip->dev;
	enum as9888_sensor_id id;
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

	chip->trig = devm_iio_trigger_alloc(dev, "as9888-dev%d",
					    iio_device_id(chip->iio[AS9888_ACCEL]));
	if (!chip->trig)
		return -ENOMEM;

	chip->trig->ops = &as9888_trigger_ops;
	iio_trigger_set_drvdata(chip->trig, chip);

	ret = devm_request_irq(dev, irq, as9888_drdy_irq, irq_type,
			       dev_name(dev), chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot request INT1\n");

	ret = devm_iio_trigger_register(dev, chip->trig);
	if (ret)
		return dev_err_probe(dev, ret, "cannot register trigger\n");

	for (id = 0; id < AS9888_SENSORS; id++)
		chip->iio[id]->trig = iio_trigger_get(chip->trig);

	ret = regmap_write(chip->regmap, AS9888_REG_INT1EN,
			   FIELD_PREP(AS9888_INTEN_DR_MSK, 1));
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable INT1\n");

	return 0;
}
