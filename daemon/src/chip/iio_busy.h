/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Another program capturing from the IIO device: who holds its character
 * device, and a bounded wait for its buffer to be free. The factory test
 * and the field commands need the buffer to themselves; a client such as
 * iio-sensor-proxy or iio_readdev that holds it gets its turn first, and a
 * client that never lets go is named in the error.
 */
#ifndef AS9888_IIO_BUSY_H
#define AS9888_IIO_BUSY_H

#include <stddef.h>
#include <stdint.h>

#include "iio_attr.h"

/* How often the wait looks at the buffer again */
#define IIO_BUSY_POLL_MS	100

/*
 * The programs that have @chardev open, as "name (pid N), ..." in @out
 * (cut short with "..." when it does not fit), found under @proc ("/proc"
 * on a system). Processes this user may not look into are left out.
 * Returns how many were found, or -errno when @proc cannot be read.
 */
int iio_chardev_holders(const char *proc, const char *chardev, char *out,
			size_t size);

/*
 * Wait until the buffer of the IIO device at @dir is off (buffer/enable
 * reads 0), looking every @poll_ms for at most @timeout_ms on the monotonic
 * clock. Returns 0 once it is off, -EBUSY when it is still on at the end,
 * or the -errno of reading buffer/enable.
 */
int iio_wait_buffer_free(const char *dir, uint32_t timeout_ms,
			 uint32_t poll_ms);

/* The same on buffer/enable kept open (iio_attr.h) */
int iio_wait_enable_off(const struct iio_attr *enable, uint32_t timeout_ms,
			uint32_t poll_ms);

#endif /* AS9888_IIO_BUSY_H */
