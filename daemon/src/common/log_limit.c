// SPDX-License-Identifier: GPL-2.0
/* Bounded logging (log_limit.h). */
#include "common/log_limit.h"

bool log_limit_allow(struct log_limit *l, uint64_t now_ms, unsigned long *suppressed)
{
	*suppressed = 0;
	if (!l->window_ms || now_ms >= l->window_ms + LOG_LIMIT_WINDOW_MS) {
		l->window_ms = now_ms ? now_ms : 1;
		l->lines = 0;
	}
	if (l->lines >= LOG_LIMIT_LINES) {
		l->suppressed++;
		return false;
	}
	l->lines++;
	*suppressed = l->suppressed;
	l->suppressed = 0;

	return true;
}
