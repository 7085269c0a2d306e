/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The calibration daemon's field mode, fed: one magnetometer sample and
 * the accelerometer's reading of the same moment, about once a second,
 * handed to as9888-calibd ("magn-feed", as9888_magn_feed()) by a thread
 * of its own, so that a slow or absent daemon never holds the sensor
 * events up. A sample offered while the last is still on its way
 * replaces the one waiting.
 */
#ifndef AS9888_HAL_FEED_H
#define AS9888_HAL_FEED_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct hal_feed;

/*
 * Start feeding @socket every @interval_ms; @accel_dir is read for the
 * accelerometer (in_accel_<axis>_raw) when a sample comes without one.
 * 0 or -errno (why in @err).
 */
int hal_feed_start(const char *socket, const char *accel_dir,
		   unsigned int interval_ms, struct hal_feed **out,
		   char *err, size_t errlen);

/*
 * A magnetometer sample at @now_ns (any monotonic clock): @y the
 * driver's output in uT in the sensor frame, @accel the accelerometer's
 * raw reading or NULL. Taken when @interval_ms passed since the last
 * one taken; cheap otherwise.
 */
void hal_feed_offer(struct hal_feed *f, const double y[3], const int32_t *accel,
		    int64_t now_ns);

/* Samples handed over and refused so far; the last refusal's reason */
void hal_feed_stats(struct hal_feed *f, unsigned long *fed, unsigned long *failed,
		    char *last_err, size_t len);

/* Stop the thread (waits for a feed under way) and free @f (NULL is fine) */
void hal_feed_stop(struct hal_feed *f);

#endif
