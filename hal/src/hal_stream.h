/* SPDX-License-Identifier: GPL-2.0 */
/*
 * One IIO device's buffer, driven by the HAL: its scan elements, trigger,
 * rate and timestamp clock set with standard attributes, started and
 * stopped, its samples read from the character device.
 */
#ifndef AS9888_HAL_STREAM_H
#define AS9888_HAL_STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "hal_layout.h"

/* A read takes at most this many samples */
#define HAL_STREAM_BATCH	64
/* The kernel buffer's length in samples (buffer/length) */
#define HAL_STREAM_LENGTH	256

/**
 * struct hal_stream - one device
 * @dir:	its sysfs directory
 * @node:	its character device (/dev/iio:deviceN)
 * @type:	"accel" or "magn"
 * @unit:	IIO unit to Android's
 * @layout:	read when the buffer starts
 * @fd:		the character device while the buffer runs, else -1
 * @hz:		the rate set (0: the trigger's own)
 * @rates:	sampling_frequency_available, ascending; @nrates of them
 *		(0: the device has no sampling_frequency)
 */
struct hal_stream {
	char dir[256];
	char node[256];
	const char *type;
	double unit;
	struct hal_layout layout;
	int fd;
	long hz;
	long rates[32];
	unsigned int nrates;
};

/*
 * Set up @s for the device at @dir with its node @node; reads the rates
 * offered. 0 or -errno (why in @err).
 */
int hal_stream_init(struct hal_stream *s, const char *dir, const char *node,
		    const char *type, double unit, char *err, size_t errlen);

/*
 * sampling_frequency_available ("1 2 5 10 ..."): whole hertz ascending,
 * at most @max of them. The count, or -EINVAL
 */
int hal_parse_rates(const char *s, long *rates, unsigned int max);

/* The rate to ask of the device for @hz: the slowest offered >= @hz, else the fastest */
long hal_stream_pick_rate(const struct hal_stream *s, double hz);

/*
 * Start the buffer on @trigger (empty: leave the device's) at @hz: only
 * the axes and the timestamp in the scan, timestamps on CLOCK_BOOTTIME.
 * 0 or -errno; on failure the buffer is left off.
 */
int hal_stream_start(struct hal_stream *s, const char *trigger, long hz,
		     char *err, size_t errlen);

/* A new rate while running: 0 or -errno */
int hal_stream_set_rate(struct hal_stream *s, long hz, char *err, size_t errlen);

/* Stop the buffer and close the node (nothing when it is not running) */
void hal_stream_stop(struct hal_stream *s);

/*
 * Read the samples waiting (at most HAL_STREAM_BATCH) into @buf, which
 * holds HAL_STREAM_BATCH samples of any layout (HAL_STREAM_BATCH * 64
 * bytes). The number of samples, 0 when none waits, or -errno.
 */
int hal_stream_read(struct hal_stream *s, uint8_t *buf, size_t len);

#endif
