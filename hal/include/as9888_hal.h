/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The AS9888 sensors HAL core: the driver's two IIO devices as Android
 * sensors, with no Android dependency (plain C, POSIX threads).
 *
 * An adapter (hal/android/: a multihal ISensorsSubHal 2.1) opens the core
 * once, lists its sensors and forwards the framework's calls:
 *
 *	struct as9888_hal *h;
 *	char err[256];
 *
 *	if (as9888_hal_open(&cfg, post, ctx, &h, err, sizeof(err)))
 *		... no AS9888 here: why is in err
 *	as9888_hal_sensors(h, &list);			getSensorsList
 *	as9888_hal_batch(h, handle, period_ns, latency_ns);	batch
 *	as9888_hal_activate(h, handle, true);		activate
 *	as9888_hal_flush(h, handle);			flush
 *	as9888_hal_close(h);
 *
 * The core runs one reader thread: it poll()s both devices' character
 * devices and calls @post with the events, in Android's units (m/s^2, uT)
 * and Android's device frame (the driver's mount matrix applied), stamped
 * with the driver's timestamps on CLOCK_BOOTTIME. @post is called from
 * that thread only, never with the core's lock held, and must not call
 * back into the core. A second thread hands one magnetometer sample a
 * second to as9888-calibd (the field mode's magn-feed) so that a slow
 * daemon never holds the events up.
 */
#ifndef AS9888_HAL_H
#define AS9888_HAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Android's sensor types (hardware/sensors-base.h), the values the adapter passes on */
enum as9888_sensor_type {
	AS9888_TYPE_META_DATA = 0,
	AS9888_TYPE_ACCELEROMETER = 1,
	AS9888_TYPE_MAGNETIC_FIELD = 2,
	AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED = 14,
};

/* The core's sensor handles: 1.. (the multihal keeps the upper byte) */
enum as9888_sensor_handle {
	AS9888_HANDLE_ACCEL = 1,
	AS9888_HANDLE_MAGN = 2,
	AS9888_HANDLE_MAGN_UNCAL = 3,
	AS9888_SENSOR_COUNT = 3,
};

/* SensorStatus: the accuracy Android shows with the field */
enum as9888_status {
	AS9888_STATUS_UNRELIABLE = 0,
	AS9888_STATUS_ACCURACY_LOW = 1,
	AS9888_STATUS_ACCURACY_MEDIUM = 2,
	AS9888_STATUS_ACCURACY_HIGH = 3,
};

/**
 * struct as9888_sensor_info - one sensor, as SensorInfo 2.1 wants it
 * @handle:	enum as9888_sensor_handle
 * @type:	enum as9888_sensor_type
 * @name:	shown to users
 * @vendor:	ditto
 * @type_name:	Android's string type ("android.sensor.accelerometer")
 * @max_range:	in the sensor's units
 * @resolution:	ditto, one LSB
 * @power_ma:	supply current while active
 * @min_delay_us: shortest period: 1e6 / the fastest sampling_frequency
 * @max_delay_us: longest period: 1e6 / the slowest
 * @fifo_max:	the software queue's events (batching)
 */
struct as9888_sensor_info {
	int handle;
	int type;
	const char *name;
	const char *vendor;
	const char *type_name;
	float max_range;
	float resolution;
	float power_ma;
	int32_t min_delay_us;
	int32_t max_delay_us;
	uint32_t fifo_max;
};

/**
 * struct as9888_event - one event
 * @handle:	the sensor's
 * @type:	its type, or AS9888_TYPE_META_DATA for a flush-complete
 * @timestamp_ns: CLOCK_BOOTTIME, the driver's timestamp of the sample
 * @v:		x, y, z (m/s^2 or uT, Android's frame); for the
 *		uncalibrated field also the bias in v[3..5]
 * @status:	enum as9888_status
 */
struct as9888_event {
	int handle;
	int type;
	int64_t timestamp_ns;
	float v[6];
	int status;
};

/**
 * struct as9888_hal_config - where to look (as9888_hal_config_defaults())
 * @sysfs:	sysfs's mount point ("/sys")
 * @dev:	where the IIO character devices are ("/dev")
 * @parent:	on a board with two AS9888, the bus device of the one to
 *		use, as its directory is named in sysfs ("1-000c",
 *		"spi1.0"); empty: the first found
 * @trigger:	the trigger to run the buffers on; empty: the chip's
 *		data-ready trigger (as9888-devN), else the one the devices
 *		already have
 * @record:	as9888-calibd's record (the residual soft iron); empty: none
 * @socket:	as9888-calibd's request socket (magn-feed); empty: no feed
 * @feed_interval_ms: how often to feed (1000)
 */
struct as9888_hal_config {
	char sysfs[128];
	char dev[128];
	char parent[64];
	char trigger[64];
	char record[256];
	char socket[108];
	unsigned int feed_interval_ms;
};

/* The defaults of Android (the paths of contrib/android/) */
void as9888_hal_config_defaults(struct as9888_hal_config *cfg);

/*
 * Read "key value" lines (the keys are the fields' names; '#' starts a
 * comment) from @text into @cfg. 0, or -EINVAL with the line and why in
 * @err; @cfg is then left as it was.
 */
int as9888_hal_config_parse(const char *text, struct as9888_hal_config *cfg,
			    char *err, size_t errlen);

/* The same from the file @path; -errno when it cannot be read */
int as9888_hal_config_load(const char *path, struct as9888_hal_config *cfg,
			   char *err, size_t errlen);

struct as9888_hal;

typedef void (*as9888_hal_post_fn)(void *ctx, const struct as9888_event *ev,
				   size_t n);

/*
 * Find the chip's two IIO devices, read their channels and start the
 * threads. 0, or -errno with what failed and why in @err.
 */
int as9888_hal_open(const struct as9888_hal_config *cfg, as9888_hal_post_fn post,
		    void *ctx, struct as9888_hal **out, char *err, size_t errlen);

/* Stop both buffers, the threads, and free @h (NULL is fine) */
void as9888_hal_close(struct as9888_hal *h);

/* The sensors: *@list gets an array of the returned count */
size_t as9888_hal_sensors(const struct as9888_hal *h,
			  const struct as9888_sensor_info **list);

/*
 * The framework's calls, from any thread but @post's. 0; -EINVAL for an
 * unknown handle or a bad argument (flush of an inactive sensor too); -EIO
 * (or another -errno) when the driver refused, the reason in
 * as9888_hal_error(). activate() and batch() make the sysfs writes that
 * start, change or stop a device's buffer on the caller's thread and
 * return when they are done (one call at a time; the other device's events
 * keep flowing meanwhile); flush() does not block.
 */
int as9888_hal_activate(struct as9888_hal *h, int handle, bool enable);
int as9888_hal_batch(struct as9888_hal *h, int handle, int64_t period_ns,
		     int64_t max_latency_ns);
int as9888_hal_flush(struct as9888_hal *h, int handle);

/* The last error the core met, for the adapter's log (copied into @buf) */
void as9888_hal_error(struct as9888_hal *h, char *buf, size_t len);

#ifdef __cplusplus
}
#endif

#endif
