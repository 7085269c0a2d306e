/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Bounded logging: at most LOG_LIMIT_LINES routine lines in any
 * LOG_LIMIT_WINDOW_MS, the rest counted, so a flood of requests cannot
 * push the journal past its rate limit (which would then drop the lines
 * that matter, such as who changed the record).
 */
#ifndef AS9888_LOG_LIMIT_H
#define AS9888_LOG_LIMIT_H

#include <stdbool.h>
#include <stdint.h>

#define LOG_LIMIT_LINES		5
#define LOG_LIMIT_WINDOW_MS	1000

struct log_limit {
	uint64_t window_ms;	/* start of the current window */
	unsigned int lines;	/* logged in it */
	unsigned long suppressed;	/* not logged since the last report */
};

/*
 * May a routine line be logged at @now_ms? When it may and lines were
 * suppressed before it, *@suppressed gets their count (to say so) and the
 * count starts again; else *@suppressed is 0.
 */
bool log_limit_allow(struct log_limit *l, uint64_t now_ms, unsigned long *suppressed);

#endif
