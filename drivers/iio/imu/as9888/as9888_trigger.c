// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888: the data-ready trigger, shared by the accelerometer and the
 * magnetometer IIO devices, and what both devices share around it: their
 * allocation with a triggered buffer, the buffer set-up, the trigger
 * handler, each device's sampling frequency, and the gap between two of
 * the trigger's samples, in which their own measurements and register
 * writes run.
 *
 * The chip has no output data rate: the trigger starts each measurement
 * itself, when the next sample of one of its devices is due, and INT1
 * fires it when the sample is ready. The sample is read once, by the first
 * handler of a device whose sample it is, and each such device takes its
 * own channels from it; the other device's handler does not touch it.
 * Each device has its own sampling_frequency; the trigger measures at the
 * union of their schedules, the magnetometer only in the samples of the
 * magnetometer device. Two devices, one interrupt and one trigger that
 * both may use, so that a sample both want is one measurement (kmx61,
 * also two devices on one interrupt, gives each device a trigger of its
 * own instead). For both to buffer on it at once the kernel needs
 * CONFIG_IIO_CONSUMERS_PER_TRIGGER >= 2 (the default).
 *
 * A sample goes IDLE -> MEASURING (the MS write) -> FIRED (the INT1 edge,
 * the trigger is polled) -> IDLE (the trigger's reenable op: every handler
 * is done). The reenable op only re-arms: an hrtimer wakes the trigger when
 * the next sample is due, or at once when it is due already, and a work
 * item starts it; the reenable op itself neither writes the chip nor
 * sleeps. A reenable that finds no FIRED sample (one left over from before
 * the trigger stopped and started again) changes nothing.
 *
 * Everything else that needs the chip in power-down (a _raw read, the
 * self-test, a buffer on another trigger, an offset DAC write) waits for
 * the gap between two samples of the trigger (as9888_wait_gap(), and
 * as9888_gap_measure() for a measurement): IDLE. So a client of one
 * sensor neither stops the other sensor's buffer nor has to wait for it
 * to end, and every sample is compensated with the DAC value it was
 * measured with.
 */

#include <linux/array_size.h>
#include <linux/atomic.h>
#include <linux/bitfield.h>
#include <linux/bitops.h>
#include <linux/cleanup.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/hrtimer.h>
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/jiffies.h>
#include <linux/ktime.h>
#include <linux/limits.h>
#include <linux/math64.h>
#include <linux/minmax.h>
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
/*
 * How long a synchronous measurement waits for the data-ready trigger's
 * gap between two samples: one sample and its handlers, or the trigger's
 * watchdog (1 s) when its edge never comes, and far beyond the latency of
 * a handler on a busy system
 */
#define AS9888_GAP_WAIT_MS		3000

/*
 * Sampling frequencies. A rate is offered when its period leaves room for
 * the sample, t_PD and the sample's bus transfers (a mode write and a
 * 16-byte burst read take about 0.5 ms on I2C at 400 kHz): t_MAG for the
 * magnetometer, and for the accelerometer too while the magnetometer
 * device buffers on the trigger (its samples include the magnetometer);
 * otherwise t_ACC, with the low-pass filter or without. So every rate
 * offered is delivered: 100 Hz with the magnetometer, 125 Hz for the
 * accelerometer alone with the filter, 400 Hz without.
 */
#define AS9888_BUS_BUDGET_US		1000
#define AS9888_PERIOD_MIN_US(t)		((t) + AS9888_T_PD_US + \
					 AS9888_BUS_BUDGET_US)

/* The rate each device starts with, Hz */
#define AS9888_SAMP_FREQ_DEFAULT	100

static void as9888_trig_kick(struct as9888_chip *chip);

static const int as9888_samp_freq_avail[] = {
	1, 2, 5, 10, 20, 25, 50, 100, 125, 200, 250, 400,
};

static_assert(USEC_PER_SEC / 100 >= AS9888_PERIOD_MIN_US(AS9888_T_MAG_US));
static_assert(USEC_PER_SEC / 125 >= AS9888_PERIOD_MIN_US(AS9888_T_ACC_LPF_US));
static_assert(USEC_PER_SEC / 400 >= AS9888_PERIOD_MIN_US(AS9888_T_ACC_US));

/* How many of the rates @id can have now; with chip->lock held */
static unsigned int as9888_samp_freq_count(const struct as9888_chip *chip,
					   enum as9888_sensor_id id)
{
	unsigned int t_us, n = 0;

	if (id == AS9888_MAGN || chip->trig_users & BIT(AS9888_MAGN))
		t_us = AS9888_T_MAG_US;
	else
		t_us = chip->alpf ? AS9888_T_ACC_LPF_US : AS9888_T_ACC_US;

	while (n < ARRAY_SIZE(as9888_samp_freq_avail) &&
	       USEC_PER_SEC / as9888_samp_freq_avail[n] >=
	       AS9888_PERIOD_MIN_US(t_us))
		n++;

	return n;
}

/*
 * The rate @sensor gets: the one written, or the fastest the chip allows
 * now when that is less (the filter was turned on, the magnetometer joined
 * the trigger); with chip->lock held
 */
static int as9888_samp_freq_of(const struct as9888_sensor *sensor)
{
	const struct as9888_chip *chip = sensor->chip;
	unsigned int n = as9888_samp_freq_count(chip, sensor->desc->id);

	return min(sensor->samp_freq, as9888_samp_freq_avail[n - 1]);
}

/* A device's sampling period on the trigger in ns; with chip->lock held */
static u64 as9888_trig_period_ns(const struct as9888_chip *chip,
				 enum as9888_sensor_id id)
{
	return div_u64(NSEC_PER_SEC,
		       as9888_samp_freq_of(as9888_sensor(chip->iio[id])));
}

int as9888_read_samp_freq_avail(struct iio_dev *indio_dev, const int **vals,
				int *type, int *length)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);

	guard(mutex)(&sensor->chip->lock);
	*vals = as9888_samp_freq_avail;
	*length = as9888_samp_freq_count(sensor->chip, sensor->desc->id);
	*type = IIO_VAL_INT;

	return IIO_AVAIL_LIST;
}

int as9888_read_samp_freq(struct iio_dev *indio_dev, int *val)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);

	guard(mutex)(&sensor->chip->lock);
	*val = as9888_samp_freq_of(sensor);

	return IIO_VAL_INT;
}

/*
 * A new rate counts from the device's next sample on; one due later than
 * a new, shorter period from now comes sooner. The other device keeps its
 * rate. A buffer running on another trigger runs at that trigger's rate:
 * a write there would change nothing, and fails.
 */
int as9888_write_samp_freq(struct iio_dev *indio_dev, int freq)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	struct as9888_chip *chip = sensor->chip;
	enum as9888_sensor_id id = sensor->desc->id;
	unsigned int i, n;
	ktime_t soonest;

	if (iio_buffer_enabled(indio_dev) && !as9888_on_drdy_trigger(indio_dev))
		return -EBUSY;

	guard(mutex)(&chip->lock);

	n = as9888_samp_freq_count(chip, id);
	for (i = 0; i < n; i++)
		if (as9888_samp_freq_avail[i] == freq)
			break;
	if (i == n)
		return -EINVAL;

	sensor->samp_freq = freq;
	if (chip->trig_users & BIT(id)) {
		soonest = ktime_add_ns(ktime_get(),
				       as9888_trig_period_ns(chip, id));
		if (ktime_after(chip->trig_due[id], soonest))
			chip->trig_due[id] = soonest;
		as9888_trig_kick(chip);
	}

	return 0;
}

/* The handlers are done with the sample, or it never comes: the gap */
static void as9888_trig_gap(struct as9888_chip *chip)
{
	lockdep_assert_held(&chip->lock);

	/* A sample that came and that no device wanted: the next has DOR */
	if (chip->trig_unread &&
	    atomic_read(&chip->trig_state) == AS9888_TRIG_FIRED)
		chip->sample_skipped = true;
	chip->trig_unread = false;
	chip->trig_take = 0;
	atomic_set(&chip->trig_state, AS9888_TRIG_IDLE);
	wake_up_all(&chip->gap_wq);
}

/*
 * Start the sample due at @slot, for every device whose next sample is due
 * by then, or by now when the sample is late; a device no faster than one
 * of those joins it when its own sample is due within half that device's
 * period, so that the two schedules fall into step instead of each taking
 * the chip on its own. A faster device is never taken early: half a
 * slower device's period would be most of its own. Each device's next
 * sample is due a period after this one was due, not after @slot: taking
 * a sample early or late moves it, not the device's rate. With chip->lock
 * held and the trigger IDLE.
 */
static int as9888_trig_measure(struct as9888_chip *chip, ktime_t slot)
{
	ktime_t by = max(slot, ktime_get());
	u64 period, shortest = U64_MAX;
	unsigned long take = 0;
	unsigned int id;
	ktime_t now;
	int ret;

	lockdep_assert_held(&chip->lock);

	/* The devices due, and the shortest period among them */
	for_each_set_bit(id, &chip->trig_users, AS9888_SENSORS) {
		if (ktime_after(chip->trig_due[id], by))
			continue;
		take |= BIT(id);
		shortest = min(shortest, as9888_trig_period_ns(chip, id));
	}
	if (!take)
		return 0;

	for_each_set_bit(id, &chip->trig_users, AS9888_SENSORS)
		if (as9888_trig_period_ns(chip, id) >= shortest &&
		    ktime_before(chip->trig_due[id],
				 ktime_add_ns(by, shortest / 2)))
			take |= BIT(id);

	/* Before the MS write: INT1 must find the sample MEASURING */
	atomic_set(&chip->trig_state, AS9888_TRIG_MEASURING);
	chip->trig_take = take;
	chip->trig_unread = true;
	ret = as9888_start(chip, AS9888_MS_SINGLE, take & BIT(AS9888_MAGN));
	if (ret) {
		/* The MS write may have reached the chip: IDLE is power-down */
		as9888_power_down(chip);
		as9888_trig_gap(chip);
		return ret;
	}

	mod_delayed_work(system_power_efficient_wq, &chip->trig_wd,
			 msecs_to_jiffies(AS9888_TRIG_WD_MS));

	/*
	 * The next ones: a period after this one was due; more than a whole
	 * period behind (the trigger was held up), from now
	 */
	now = ktime_get();
	for_each_set_bit(id, &take, AS9888_SENSORS) {
		period = as9888_trig_period_ns(chip, id);
		chip->trig_due[id] = ktime_add_ns(chip->trig_due[id], period);
		if (ktime_before(ktime_add_ns(chip->trig_due[id], period), now))
			chip->trig_due[id] = now;
	}

	return 0;
}

/* When the trigger's next sample is due; with chip->lock held, users set */
static ktime_t as9888_trig_slot(const struct as9888_chip *chip)
{
	ktime_t slot = KTIME_MAX;
	enum as9888_sensor_id id;

	for (id = 0; id < AS9888_SENSORS; id++)
		if (chip->trig_users & BIT(id) &&
		    ktime_before(chip->trig_due[id], slot))
			slot = chip->trig_due[id];

	return slot;
}

/*
 * When the trigger's next sample is not due yet, set the hrtimer for it
 * and return true; false when it is due now (@slot says when it was due).
 * With chip->lock held and the trigger's users set.
 */
static bool as9888_trig_arm(struct as9888_chip *chip, ktime_t *slot)
{
	*slot = as9888_trig_slot(chip);
	if (!ktime_after(*slot, ktime_get()))
		return false;

	hrtimer_start(&chip->trig_timer, *slot, HRTIMER_MODE_ABS);

	return true;
}

/*
 * The trigger may start its next sample: it runs for a device, in the gap,
 * the system awake and nobody waiting for the chip; with chip->lock held
 */
static bool as9888_trig_may_start(const struct as9888_chip *chip)
{
	return chip->trig && chip->trig_running && !chip->suspended &&
	       chip->trig_users && !chip->gap_waiters &&
	       atomic_read(&chip->trig_state) == AS9888_TRIG_IDLE;
}

/**
 * as9888_trig_next() - start the data-ready trigger's next sample
 * @chip: chip state, with chip->lock held
 *
 * When the trigger may start a sample: start it if it is due, else wake
 * up when it is. A start that fails is tried a few times; when every
 * attempt fails the watchdog tries again later, so the buffer gets samples
 * again once the bus recovers.
 *
 * This writes the chip and may sleep for t_PD: process context only (the
 * work item, the watchdog, a buffer's postenable, system resume). The
 * reenable op only re-arms (as9888_trig_kick()).
 *
 * Return: 0, or the error of the last attempt to start the sample.
 */
static int as9888_trig_next(struct as9888_chip *chip)
{
	ktime_t slot;
	int i, ret;

	lockdep_assert_held(&chip->lock);

	chip->trig_retry = false;
	if (!as9888_trig_may_start(chip) || as9888_trig_arm(chip, &slot))
		return 0;

	for (i = 0; i < AS9888_START_RETRIES; i++) {
		ret = as9888_trig_measure(chip, slot);
		if (!ret)
			return 0;
	}

	dev_err_ratelimited(chip->dev,
			    "data-ready trigger cannot start a sample (%d), retrying in %u ms\n",
			    ret, AS9888_TRIG_WD_MS);
	chip->trig_retry = true;
	mod_delayed_work(system_power_efficient_wq, &chip->trig_wd,
			 msecs_to_jiffies(AS9888_TRIG_WD_MS));

	return ret;
}

/**
 * as9888_trig_kick() - arm the data-ready trigger for its next sample
 * @chip: chip state, with chip->lock held
 *
 * After a sample's handlers are done (the reenable op), a change of the
 * trigger's devices or their rates, or the end of a wait for the gap:
 * when the trigger may start a sample, the hrtimer is set for the time it
 * is due, or the work item queued when it is due already; the work item
 * starts it (as9888_trig_next()) once the lock is free. Neither the bus
 * nor a sleep: this is all the reenable op does.
 */
static void as9888_trig_kick(struct as9888_chip *chip)
{
	ktime_t slot;

	lockdep_assert_held(&chip->lock);

	if (as9888_trig_may_start(chip) && !as9888_trig_arm(chip, &slot))
		queue_work(system_highpri_wq, &chip->trig_work);
}

/* No sample of the data-ready trigger in flight or in its handlers */
static bool as9888_trig_idle(struct as9888_chip *chip)
{
	return atomic_read(&chip->trig_state) == AS9888_TRIG_IDLE;
}

/**
 * as9888_wait_gap() - wait for the gap between two samples of the trigger
 * @chip: chip state, with chip->lock held; the lock is dropped while
 *	  waiting
 *
 * A waiter is counted in chip->gap_waiters, and the trigger does not start
 * its next sample while one is counted: the gap is handed over. Without
 * that, a trigger whose next sample is due at once would take the chip
 * back before the woken waiter ever ran. The last waiter to leave has the
 * trigger look at its schedule again (it starts once the lock is free).
 *
 * Return: 0 with chip->lock held and no measurement of the data-ready
 * trigger in flight, or -ETIMEDOUT when the trigger's sample did not come
 * (also with chip->lock held).
 */
int as9888_wait_gap(struct as9888_chip *chip)
{
	unsigned long left;
	int ret = 0;

	lockdep_assert_held(&chip->lock);

	if (as9888_trig_idle(chip))
		return 0;

	left = msecs_to_jiffies(AS9888_GAP_WAIT_MS);
	chip->gap_waiters++;
	while (!as9888_trig_idle(chip)) {
		mutex_unlock(&chip->lock);
		left = wait_event_timeout(chip->gap_wq, as9888_trig_idle(chip),
					  left);
		mutex_lock(&chip->lock);
		if (!left && !as9888_trig_idle(chip)) {
			dev_err_ratelimited(chip->dev,
					    "data-ready trigger stalled\n");
			ret = -ETIMEDOUT;
			break;
		}
	}
	if (!--chip->gap_waiters)
		as9888_trig_kick(chip);

	return ret;
}

/**
 * as9888_gap_measure() - a device's own measurement, in the trigger's gap
 * @chip: chip state, with chip->lock held; the lock is dropped while
 *	  waiting for the gap
 * @id: the device that asks for it
 * @mode: AS9888_MS_SINGLE or AS9888_MS_SELF_TEST
 * @men: measure the magnetometer too (always done in self-test)
 * @s: the sample
 * @ts: timestamp of the sample
 *
 * A _raw read, the self-test and a buffer on another trigger measure
 * here. While the data-ready trigger runs for a buffer, wait for the gap
 * between two of its samples (as9888_wait_gap()), then run the
 * measurement (as9888_measure(), which refuses one during system sleep:
 * checked after the wait, which drops the lock, as a halted trigger is
 * idle).
 *
 * Return: 0, -EBUSY during system sleep, or a negative error number.
 */
int as9888_gap_measure(struct as9888_chip *chip, enum as9888_sensor_id id,
		       u8 mode, bool men, struct as9888_raw_sample *s, s64 *ts)
{
	int ret;

	ret = as9888_wait_gap(chip);
	if (ret)
		return ret;

	return as9888_measure(chip, id, mode, men, s, ts);
}

/*
 * Register access for debugging (iio/iio:deviceX/direct_reg_access); it
 * also makes the IIO core create the devices' debugfs directories (the
 * magnetometer's holds selftest_readings). Under chip->lock, like every
 * register access sequence of the driver; a write waits for the gap
 * between two samples of the data-ready trigger, as a trim write does.
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
		if (readval) {
			ret = regmap_read(chip->regmap, reg, readval);
		} else {
			ret = as9888_wait_gap(chip);
			if (!ret)
				ret = regmap_write(chip->regmap, reg, writeval);
		}
	}

	pm_runtime_put_autosuspend(chip->dev);

	return ret;
}

static void as9888_trig_work(struct work_struct *work)
{
	struct as9888_chip *chip = container_of(work, struct as9888_chip,
						trig_work);

	guard(mutex)(&chip->lock);
	as9888_trig_next(chip);
}

/* The next sample is due: start it from process context */
static enum hrtimer_restart as9888_trig_timer(struct hrtimer *timer)
{
	struct as9888_chip *chip = container_of(timer, struct as9888_chip,
						trig_timer);

	queue_work(system_highpri_wq, &chip->trig_work);

	return HRTIMER_NORESTART;
}

/*
 * The watchdog of the data-ready trigger. A sample whose INT1 edge never
 * came (a glitch on the line, an edge lost by the interrupt controller)
 * would leave the trigger waiting for good, the buffer enabled and empty:
 * abort it and go on with the next one. A start that failed is tried
 * again.
 */
static void as9888_trig_watchdog(struct work_struct *work)
{
	struct as9888_chip *chip = container_of(to_delayed_work(work),
						struct as9888_chip, trig_wd);
	s64 left_ms;

	guard(mutex)(&chip->lock);

	if (!chip->trig_running)
		return;

	if (atomic_read(&chip->trig_state) == AS9888_TRIG_MEASURING) {
		/* A sample started after the timer was due re-armed it */
		left_ms = AS9888_TRIG_WD_MS -
			  ktime_ms_delta(ktime_get(), chip->last_start);
		if (left_ms > 0) {
			mod_delayed_work(system_power_efficient_wq,
					 &chip->trig_wd, msecs_to_jiffies(left_ms));
			return;
		}
		/* Unless the edge comes right now */
		if (atomic_cmpxchg(&chip->trig_state, AS9888_TRIG_MEASURING,
				   AS9888_TRIG_IDLE) != AS9888_TRIG_MEASURING)
			return;
		dev_warn_ratelimited(chip->dev,
				     "data-ready trigger: no %s edge %u ms after a sample started, restarting\n",
				     chip->int_pin->name, AS9888_TRIG_WD_MS);
		/* Only the edge may be lost: the next sample may have DOR */
		chip->sample_skipped = true;
		as9888_power_down(chip);
		as9888_trig_gap(chip);
	} else if (!chip->trig_retry) {
		/* The handlers have the sample, or the next one is on its way */
		return;
	}

	as9888_trig_next(chip);
}

/* Stop sampling: abort a measurement in flight; with chip->lock held */
static int as9888_trig_halt(struct as9888_chip *chip)
{
	int ret;

	lockdep_assert_held(&chip->lock);

	chip->trig_retry = false;
	hrtimer_try_to_cancel(&chip->trig_timer);
	if (atomic_read(&chip->trig_state) == AS9888_TRIG_IDLE)
		return 0;

	/* A handler still to run finds no sample (as9888_trig_sample()) */
	ret = as9888_power_down(chip);
	as9888_trig_gap(chip);

	return ret;
}

/*
 * The IIO core enables the trigger with its first consumer and disables it
 * with its last; which devices' samples it takes, the buffers say
 * (as9888_buffer_postenable()).
 */
static int as9888_trig_set_state(struct iio_trigger *trig, bool state)
{
	struct as9888_chip *chip = iio_trigger_get_drvdata(trig);

	guard(mutex)(&chip->lock);

	chip->trig_running = state;
	if (state)
		return 0;

	return as9888_trig_halt(chip);
}

/**
 * as9888_trig_sample() - the sample of the data-ready trigger's last edge
 * @chip: chip state, with chip->lock held
 * @s: the sample
 *
 * Called by the handlers of the devices whose sample it is (chip->trig_take)
 * only: the first to run after the INT1 edge reads the sample, the other
 * gets the same one. A handler that runs for no FIRED sample (the trigger
 * stopped meanwhile) gets none.
 *
 * Return: 0, -ENODATA, or the error of reading or checking the sample.
 */
int as9888_trig_sample(struct as9888_chip *chip,
		       const struct as9888_raw_sample **s)
{
	lockdep_assert_held(&chip->lock);

	if (atomic_read(&chip->trig_state) != AS9888_TRIG_FIRED)
		return -ENODATA;

	if (chip->trig_unread) {
		chip->trig_err = as9888_read_sample(chip, &chip->trig_sample);
		if (!chip->trig_err)
			chip->trig_err = as9888_check_sample(chip,
							     &chip->trig_sample);
		chip->pd_since = READ_ONCE(chip->drdy_time);
		chip->trig_unread = false;
	}
	*s = &chip->trig_sample;

	return chip->trig_err;
}

/*
 * The trigger's reenable op: every device's handler is done with the
 * sample. It only re-arms: the gap begins, and the hrtimer or the work
 * item is set for the next sample (as9888_trig_kick()), which the work
 * item starts; no bus access and no sleep here. It runs in the last
 * handler's thread, or from system_wq when the last to finish was a
 * consumer slot without a handler; one left over from before the trigger
 * stopped and started again finds no FIRED sample and does nothing.
 */
static void as9888_trig_reenable(struct iio_trigger *trig)
{
	struct as9888_chip *chip = iio_trigger_get_drvdata(trig);

	guard(mutex)(&chip->lock);

	if (atomic_read(&chip->trig_state) != AS9888_TRIG_FIRED)
		return;

	as9888_trig_gap(chip);
	as9888_trig_kick(chip);
}

static const struct iio_trigger_ops as9888_trigger_ops = {
	/* Both devices of the chip share the bus device as parent */
	.validate_device = iio_trigger_validate_own_device,
	.set_trigger_state = as9888_trig_set_state,
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

/*
 * The trigger runs (as9888_trig_set_state()); from now on it takes this
 * device's samples too: with the other device's next one when that is
 * overdue or comes within a period, else at once, so that the two are in
 * step from the start. The first sample starts here, in the process enabling
 * the buffer, so that a failure to start it fails the enable.
 */
static int as9888_buffer_postenable(struct iio_dev *indio_dev)
{
	struct as9888_sensor *sensor = as9888_sensor(indio_dev);
	enum as9888_sensor_id id = sensor->desc->id;
	struct as9888_chip *chip = sensor->chip;
	ktime_t now, due;
	u64 period;
	int ret;

	if (!as9888_on_drdy_trigger(indio_dev))
		return 0;

	guard(mutex)(&chip->lock);

	/*
	 * The other device's next sample, if any, also when it is overdue:
	 * the two share it, and from then on their schedules are one
	 */
	due = as9888_trig_slot(chip);
	now = ktime_get();
	period = as9888_trig_period_ns(chip, id);
	if (ktime_after(due, ktime_add_ns(now, period)))
		due = now;
	chip->trig_users |= BIT(id);
	chip->trig_due[id] = due;
	ret = as9888_trig_next(chip);
	if (ret)
		chip->trig_users &= ~BIT(id);

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

	return 0;
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
 * trigger's edge, when it is one of this device's, or one measured for
 * this device alone on another trigger, goes to the device's buffer.
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
		if (!as9888_on_drdy_trigger(indio_dev)) {
			s = &own;
			ret = as9888_gap_measure(chip, desc->id,
						 AS9888_MS_SINGLE, desc->men,
						 &own, &ts);
		} else if (chip->trig_take & BIT(desc->id)) {
			ret = as9888_trig_sample(chip, &s);
		} else {
			/* Not this device's sample (or none): not read here */
			ret = -ENODATA;
		}

		if (!ret)
			desc->push(indio_dev, s, ts);
	}

	/* The last device done with the sample re-arms the trigger */
	iio_trigger_notify_done(indio_dev->trig);

	return IRQ_HANDLED;
}

/*
 * sampling_frequency is the device's rate on the data-ready trigger:
 * without INT1 the buffer runs on another trigger, which sets the rate, so
 * the channels go without it.
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
	sensor->samp_freq = AS9888_SAMP_FREQ_DEFAULT;

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
 * System sleep: a running data-ready trigger pauses over it, and no
 * measurement starts until resume (chip->suspended). Once the lock is
 * dropped here, no handler is in a register access sequence and none will
 * start one; the watchdog and the work item have nothing to start.
 */
void as9888_trig_suspend(struct as9888_chip *chip)
{
	scoped_guard(mutex, &chip->lock) {
		chip->suspended = true;
		if (chip->trig_running)
			as9888_trig_halt(chip);
	}

	if (chip->trig) {
		hrtimer_cancel(&chip->trig_timer);
		cancel_work_sync(&chip->trig_work);
		cancel_delayed_work_sync(&chip->trig_wd);
	}
}

/* Each device's next sample is due at once */
int as9888_trig_resume(struct as9888_chip *chip)
{
	enum as9888_sensor_id id;
	ktime_t now = ktime_get();

	guard(mutex)(&chip->lock);

	chip->suspended = false;
	for (id = 0; id < AS9888_SENSORS; id++)
		chip->trig_due[id] = now;

	return as9888_trig_next(chip);
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
	unsigned long seq = READ_ONCE(chip->meas_seq);
	enum as9888_sensor_id id;

	/*
	 * No measurement since the last edge: not the chip's data ready (its
	 * pin while runtime suspend has cut the supplies, a glitch), so that
	 * a storm of them is caught as spurious
	 */
	if (seq == READ_ONCE(chip->irq_seq))
		return IRQ_NONE;

	WRITE_ONCE(chip->drdy_time, ktime_get());
	WRITE_ONCE(chip->irq_seq, seq);

	if (atomic_cmpxchg(&chip->trig_state, AS9888_TRIG_MEASURING,
			   AS9888_TRIG_FIRED) == AS9888_TRIG_MEASURING) {
		iio_trigger_poll(chip->trig);
		return IRQ_HANDLED;
	}

	for (id = 0; id < AS9888_SENSORS; id++)
		WRITE_ONCE(chip->drdy_ts[id], iio_get_time_ns(chip->iio[id]));
	complete(&chip->drdy);

	return IRQ_HANDLED;
}

/* Level-triggered: the same, then the thread deasserts the pin */
static irqreturn_t as9888_drdy_irq_level(int irq, void *private)
{
	if (as9888_drdy_irq(irq, private) == IRQ_NONE)
		return IRQ_NONE;

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

	if (chip->meas_seq == READ_ONCE(chip->irq_seq))
		regmap_read(chip->regmap, chip->int_pin->st_reg, &st);

	return IRQ_HANDLED;
}

/*
 * Removal: the trigger is stopped (no timer, work item or watchdog arms
 * another), but they may still be pending
 */
static void as9888_trig_cancel(void *arg)
{
	struct as9888_chip *chip = arg;

	hrtimer_cancel(&chip->trig_timer);
	cancel_work_sync(&chip->trig_work);
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
	INIT_WORK(&chip->trig_work, as9888_trig_work);
	hrtimer_setup(&chip->trig_timer, as9888_trig_timer, CLOCK_MONOTONIC,
		      HRTIMER_MODE_ABS);
	ret = devm_add_action_or_reset(dev, as9888_trig_cancel, chip);
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
