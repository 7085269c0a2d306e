// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the data-ready trigger, shared by the accelerometer and the
 * magnetometer IIO devices, and what both devices share around it: their
 * allocation with a triggered buffer, the buffer set-up and the trigger
 * handler.
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
 * the gap between two samples of the trigger (as9888_wait_gap(), in
 * as9888_chip.c): after the handlers are done with one sample and before
 * the next one starts. So a client of one sensor neither stops the other
 * sensor's buffer nor has to wait for it to end, and every sample is
 * compensated with the DAC value it was measured with.
 */

#include <linux/bitfield.h>
#include <linux/bitops.h>
#include <linux/cleanup.h>
#include <linux/device.h>
#include <linux/err.h>
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
#include <linux/workqueue.h>

#include <linux/iio/buffer.h>
#include <linux/iio/iio.h>
#include <linux/iio/trigger.h>
#include <linux/iio/trigger_consumer.h>
#include <linux/iio/triggered_buffer.h>

#include "as9888_core.h"

/* Attempts to start the next measurement of the data-ready trigger */
#define AS9888_START_RETRIES		3
/*
 * The data-ready trigger's watchdog: an INT1 edge that has not come this
 * long after its sample started (a sample takes t_MAG = 7.3 ms at most) is
 * taken as lost, and a start that failed is tried again after as long
 */
#define AS9888_TRIG_WD_MS		1000

/* The trigger's sampling period in ns; with chip->lock held */
static u64 as9888_trig_period_ns(const struct as9888_chip *chip)
{
	return div_u64(NSEC_PER_SEC, chip->samp_freq);
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

	/* Before the MS write: INT1 must find them set */
	WRITE_ONCE(chip->trig_fired, false);
	WRITE_ONCE(chip->trig_busy, true);
	chip->trig_unread = true;
	ret = as9888_start(chip, AS9888_MS_SINGLE,
			   chip->trig_users & BIT(AS9888_MAGN));
	if (ret) {
		as9888_trig_gap(chip);
		return ret;
	}

	mod_delayed_work(system_power_efficient_wq, &chip->trig_wd,
			 msecs_to_jiffies(AS9888_TRIG_WD_MS));

	return 0;
}

/*
 * Start the next sample of the running trigger, trying a few times; when
 * every attempt fails the watchdog tries again later, so the buffer gets
 * samples again once the bus recovers. With chip->lock held.
 */
static void as9888_trig_next(struct as9888_chip *chip)
{
	int i, ret = 0;

	lockdep_assert_held(&chip->lock);

	chip->trig_retry = false;
	for (i = 0; i < AS9888_START_RETRIES && chip->trig_running; i++) {
		ret = as9888_trig_measure(chip);
		if (!ret)
			return;
	}
	if (!chip->trig_running)
		return;

	dev_err_ratelimited(chip->dev,
			    "data-ready trigger cannot start a sample (%d), retrying in %u ms\n",
			    ret, AS9888_TRIG_WD_MS);
	chip->trig_retry = true;
	mod_delayed_work(system_power_efficient_wq, &chip->trig_wd,
			 msecs_to_jiffies(AS9888_TRIG_WD_MS));
}

/*
 * The watchdog of the data-ready trigger. A sample whose INT1 edge never
 * came (a glitch on the line, an edge lost by the interrupt controller)
 * would leave the trigger waiting for good, the buffer enabled and empty:
 * abort it and start the next one. A start that failed is tried again.
 */
static void as9888_trig_watchdog(struct work_struct *work)
{
	struct as9888_chip *chip = container_of(to_delayed_work(work),
						struct as9888_chip, trig_wd);
	s64 left_ms;

	guard(mutex)(&chip->lock);

	if (!chip->trig_running)
		return;

	if (chip->trig_busy) {
		/* The edge came: the handlers have the sample */
		if (READ_ONCE(chip->trig_fired))
			return;
		/* A sample started after the timer was due re-armed it */
		left_ms = AS9888_TRIG_WD_MS -
			  ktime_ms_delta(ktime_get(), chip->last_start);
		if (left_ms > 0) {
			mod_delayed_work(system_power_efficient_wq,
					 &chip->trig_wd, msecs_to_jiffies(left_ms));
			return;
		}
		dev_warn_ratelimited(chip->dev,
				     "data-ready trigger: no %s edge %u ms after a sample started, restarting\n",
				     chip->int_pin->name, AS9888_TRIG_WD_MS);
		as9888_power_down(chip);
		as9888_trig_gap(chip);
	} else if (!chip->trig_retry) {
		/* Between two samples: the next one is on its way */
		return;
	}

	as9888_trig_next(chip);
	chip->trig_slot = chip->last_start;
}

static int as9888_trig_start(struct as9888_chip *chip)
{
	int ret;

	lockdep_assert_held(&chip->lock);

	WRITE_ONCE(chip->trig_running, true);
	chip->trig_gen++;
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
	chip->trig_retry = false;
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
 * work item, never in interrupt context. A trigger stopped and started
 * again meanwhile (a new generation) has its own first sample under way.
 */
static void as9888_trig_reenable(struct iio_trigger *trig)
{
	struct as9888_chip *chip = iio_trigger_get_drvdata(trig);
	unsigned int gen;
	ktime_t next, now;
	u64 period;
	s64 wait_ns;

	scoped_guard(mutex, &chip->lock) {
		if (!chip->trig_running)
			return;
		gen = chip->trig_gen;
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

	/*
	 * The gap is handed over to whoever waits for it, see
	 * as9888_wait_gap(). Bounded: every waiter leaves within its own
	 * deadline (two periods and the slack, then one measurement).
	 */
	wait_event(chip->gap_wq, !READ_ONCE(chip->gap_waiters));

	guard(mutex)(&chip->lock);
	if (chip->trig_gen == gen)
		as9888_trig_next(chip);
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
	chip->trig_users |= BIT(sensor->desc->id);
	if (chip->trig_running)
		return 0;

	ret = as9888_trig_start(chip);
	if (ret)
		chip->trig_users &= ~BIT(sensor->desc->id);

	return ret;
}

static int as9888_buffer_predisable(struct iio_dev *indio_dev)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	struct as9888_chip *chip = sensor->chip;

	if (!as9888_on_drdy_trigger(indio_dev))
		return 0;

	guard(mutex)(&chip->lock);

	chip->trig_users &= ~BIT(sensor->desc->id);
	if (chip->trig_users || !chip->trig_running)
		return 0;

	return as9888_trig_stop(chip);
}

static int as9888_buffer_postdisable(struct iio_dev *indio_dev)
{
	pm_runtime_put_autosuspend(as9888_iio_to_chip(indio_dev)->dev);

	return 0;
}

static const struct iio_buffer_setup_ops as9888_buffer_ops = {
	.preenable = as9888_buffer_preenable,
	.postenable = as9888_buffer_postenable,
	.predisable = as9888_buffer_predisable,
	.postdisable = as9888_buffer_postdisable,
};

/*
 * The trigger handler of both devices: the sample of the data-ready
 * trigger's edge, or one measured for this device alone on another
 * trigger, goes to the device's buffer.
 */
static irqreturn_t as9888_trigger_handler(int irq, void *p)
{
	struct iio_poll_func *pf = p;
	struct iio_dev *indio_dev = pf->indio_dev;
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	const struct as9888_sensor_desc *desc = sensor->desc;
	struct as9888_chip *chip = sensor->chip;
	const struct as9888_raw_sample *s;
	struct as9888_raw_sample own;
	s64 ts = pf->timestamp;
	int ret;

	scoped_guard(mutex, &chip->lock) {
		if (as9888_on_drdy_trigger(indio_dev)) {
			ret = as9888_trig_sample(chip, &s);
		} else {
			s = &own;
			ret = as9888_measure(chip, desc->id, AS9888_MS_SINGLE,
					     desc->men, &own, &ts);
		}

		if (!ret)
			desc->push(indio_dev, s, ts);
	}

	/* The last device done with the sample starts the next one */
	iio_trigger_notify_done(indio_dev->trig);

	return IRQ_HANDLED;
}

/*
 * sampling_frequency is that of the data-ready trigger: without INT1 the
 * buffer runs on another trigger, which sets the rate, so the channels go
 * without it.
 */
static const struct iio_chan_spec *
as9888_channels_for(struct as9888_chip *chip, const struct iio_chan_spec *tmpl,
		    size_t n)
{
	struct iio_chan_spec *chans;
	size_t i;

	if (chip->irq)
		return tmpl;

	chans = devm_kmemdup(chip->dev, tmpl, n * sizeof(*tmpl), GFP_KERNEL);
	if (!chans)
		return NULL;

	for (i = 0; i < n; i++) {
		chans[i].info_mask_shared_by_all = 0;
		chans[i].info_mask_shared_by_all_available = 0;
	}

	return chans;
}

/**
 * as9888_sensor_alloc() - the IIO device of a sensor, ready to register
 * @chip: chip state
 * @desc: the sensor
 *
 * Return: the device or an ERR_PTR().
 */
struct iio_dev *as9888_sensor_alloc(struct as9888_chip *chip,
				    const struct as9888_sensor_desc *desc)
{
	struct device *dev = chip->dev;
	struct as9888_sensor *sensor;
	struct iio_dev *indio_dev;
	int ret;

	indio_dev = devm_iio_device_alloc(dev, desc->priv_size);
	if (!indio_dev)
		return ERR_PTR(-ENOMEM);

	sensor = iio_priv(indio_dev);
	sensor->chip = chip;
	sensor->desc = desc;

	indio_dev->name = desc->name;
	indio_dev->info = desc->info;
	indio_dev->modes = INDIO_DIRECT_MODE;
	indio_dev->num_channels = desc->num_channels;
	indio_dev->channels = as9888_channels_for(chip, desc->channels,
						  desc->num_channels);
	if (!indio_dev->channels)
		return ERR_PTR(-ENOMEM);

	ret = devm_iio_triggered_buffer_setup(dev, indio_dev,
					      iio_pollfunc_store_time,
					      as9888_trigger_handler,
					      &as9888_buffer_ops);
	if (ret)
		return ERR_PTR(dev_err_probe(dev, ret,
					     "cannot set up the %s buffer\n",
					     desc->name));

	return indio_dev;
}

/*
 * System sleep: a running data-ready trigger is stopped over it, and no
 * measurement starts until resume (chip->suspended). Once the lock is
 * dropped here, no handler is in a register access sequence and none will
 * start one; the watchdog has nothing to restart.
 */
void as9888_trig_suspend(struct as9888_chip *chip)
{
	scoped_guard(mutex, &chip->lock) {
		chip->suspended = true;
		chip->trig_resume = chip->trig_running;
		if (chip->trig_resume)
			as9888_trig_stop(chip);
	}

	if (chip->trig)
		cancel_delayed_work_sync(&chip->trig_wd);
}

int as9888_trig_resume(struct as9888_chip *chip)
{
	guard(mutex)(&chip->lock);

	chip->suspended = false;
	if (!chip->trig_resume)
		return 0;

	chip->trig_resume = false;

	return as9888_trig_start(chip);
}

/*
 * The data-ready interrupt (INT1, or INT2): a sample of the data-ready
 * trigger fires the trigger; any other measurement is waited for
 * synchronously, with a timestamp for each device (each may use its own
 * clock).
 */
static irqreturn_t as9888_drdy_irq(int irq, void *private)
{
	struct as9888_chip *chip = private;
	enum as9888_sensor_id id;

	chip->drdy_time = ktime_get();
	chip->irq_seq = READ_ONCE(chip->meas_seq);

	if (READ_ONCE(chip->trig_busy)) {
		WRITE_ONCE(chip->trig_fired, true);
		iio_trigger_poll(chip->trig);
		return IRQ_HANDLED;
	}

	for (id = 0; id < AS9888_SENSORS; id++)
		chip->drdy_ts[id] = iio_get_time_ns(chip->iio[id]);
	complete(&chip->drdy);

	return IRQ_HANDLED;
}

/* Level-triggered: the same, then the thread deasserts the pin */
static irqreturn_t as9888_drdy_irq_level(int irq, void *private)
{
	as9888_drdy_irq(irq, private);

	return IRQ_WAKE_THREAD;
}

/*
 * The interrupt stays masked (IRQF_ONESHOT) until this returns: deassert
 * the pin by reading INTxST, unless a measurement started since the
 * interrupt fired: its MS write deasserted the pin, and reading INTxST now
 * could clear the data ready of that new measurement.
 */
static irqreturn_t as9888_drdy_thread(int irq, void *private)
{
	struct as9888_chip *chip = private;
	unsigned int st;

	guard(mutex)(&chip->int_lock);

	if (chip->meas_seq == chip->irq_seq)
		regmap_read(chip->regmap, chip->int_pin->st_reg, &st);

	return IRQ_HANDLED;
}

/* Removal: the trigger is stopped, its watchdog may still be pending */
static void as9888_trig_wd_cancel(void *arg)
{
	struct as9888_chip *chip = arg;

	cancel_delayed_work_sync(&chip->trig_wd);
}

/**
 * as9888_trigger_setup() - the data-ready interrupt and trigger
 * @chip: chip state, with both IIO devices allocated, chip->irq and
 *	  chip->int_pin set
 *
 * The pin rises at the end of a measurement and falls on the next accepted
 * MS write or when INTxST is read: a rising edge (the default) or a high
 * level. The trigger is named after the accelerometer device,
 * "as9888-dev<N>", and is the default trigger of both devices.
 *
 * Return: 0 or a negative error number.
 */
int as9888_trigger_setup(struct as9888_chip *chip)
{
	const struct as9888_int_pin *pin = chip->int_pin;
	struct device *dev = chip->dev;
	irq_handler_t handler, thread;
	enum as9888_sensor_id id;
	unsigned long flags;
	u32 irq_type;
	int ret;

	irq_type = irq_get_trigger_type(chip->irq);
	if (irq_type == IRQF_TRIGGER_NONE)
		irq_type = IRQF_TRIGGER_RISING;
	switch (irq_type) {
	case IRQF_TRIGGER_RISING:
		handler = as9888_drdy_irq;
		thread = NULL;
		flags = irq_type;
		break;
	case IRQF_TRIGGER_HIGH:
		handler = as9888_drdy_irq_level;
		thread = as9888_drdy_thread;
		flags = irq_type | IRQF_ONESHOT;
		break;
	default:
		return dev_err_probe(dev, -EINVAL,
				     "%s must be rising edge or level high, not 0x%x\n",
				     pin->name, irq_type);
	}

	chip->trig = devm_iio_trigger_alloc(dev, "as9888-dev%d",
					    iio_device_id(chip->iio[AS9888_ACCEL]));
	if (!chip->trig)
		return -ENOMEM;

	chip->trig->ops = &as9888_trigger_ops;
	iio_trigger_set_drvdata(chip->trig, chip);

	INIT_DELAYED_WORK(&chip->trig_wd, as9888_trig_watchdog);
	ret = devm_add_action_or_reset(dev, as9888_trig_wd_cancel, chip);
	if (ret)
		return ret;

	ret = devm_request_threaded_irq(dev, chip->irq, handler, thread, flags,
					dev_name(dev), chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot request %s\n", pin->name);

	ret = devm_iio_trigger_register(dev, chip->trig);
	if (ret)
		return dev_err_probe(dev, ret, "cannot register trigger\n");

	for (id = 0; id < AS9888_SENSORS; id++)
		chip->iio[id]->trig = iio_trigger_get(chip->trig);

	ret = regmap_write(chip->regmap, pin->en_reg,
			   FIELD_PREP(AS9888_INTEN_DR_MSK, 1));
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable %s\n", pin->name);

	return 0;
}
