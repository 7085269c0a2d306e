// SPDX-License-Identifier: GPL-2.0
/* A sensor's batch of held-back events (hal_queue.h) */
#include "hal_queue.h"

bool hal_queue_push(struct hal_queue *q, const struct as9888_event *e)
{
	if (hal_queue_full(q))
		return false;
	q->ev[(q->head + q->count) % HAL_QUEUE_EVENTS] = *e;
	q->count++;
	return true;
}

const struct as9888_event *hal_queue_oldest(const struct hal_queue *q)
{
	return q->count ? &q->ev[q->head] : NULL;
}

size_t hal_queue_take(struct hal_queue *q, struct as9888_event *out, size_t max)
{
	size_t n = 0;

	while (q->count && n < max) {
		out[n++] = q->ev[q->head];
		q->head = (q->head + 1) % HAL_QUEUE_EVENTS;
		q->count--;
	}
	return n;
}
