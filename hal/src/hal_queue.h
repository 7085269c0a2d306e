/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A sensor's batch: the events held back for its max report latency,
 * oldest first, in a ring of fixed size (the FIFO the HAL reports).
 */
#ifndef AS9888_HAL_QUEUE_H
#define AS9888_HAL_QUEUE_H

#include <stdbool.h>
#include <stddef.h>

#include "as9888_hal.h"

#define HAL_QUEUE_EVENTS	1024

struct hal_queue {
	struct as9888_event ev[HAL_QUEUE_EVENTS];
	size_t head;
	size_t count;
};

static inline bool hal_queue_full(const struct hal_queue *q)
{
	return q->count == HAL_QUEUE_EVENTS;
}

/* Append @e; false when full (the caller delivers the queue first) */
bool hal_queue_push(struct hal_queue *q, const struct as9888_event *e);

/* The oldest event, or NULL */
const struct as9888_event *hal_queue_oldest(const struct hal_queue *q);

/* Move up to @max events, oldest first, to @out: how many */
size_t hal_queue_take(struct hal_queue *q, struct as9888_event *out, size_t max);

#endif
