/* SPDX-License-Identifier: GPL-2.0 */
/*
 * How often requests through the daemon's socket may change the record: a
 * bucket of RECORD_BUDGET_BURST changes that refills one every
 * RECORD_BUDGET_REFILL_MS, so that no client, however often it asks,
 * rewrites the flash more than the documented budget (docs/DECISIONS.md,
 * "Who may ask for what").
 */
#ifndef AS9888_RECORD_BUDGET_H
#define AS9888_RECORD_BUDGET_H

#include <stdint.h>

/* Changes allowed at once, and the time that gives one back (6 hours) */
#define RECORD_BUDGET_BURST	8
#define RECORD_BUDGET_REFILL_MS	(6ull * 3600 * 1000)

struct record_budget {
	unsigned int left;
	uint64_t refilled_ms;	/* when the last change was given back */
};

void record_budget_init(struct record_budget *b, uint64_t now_ms);

/* 0 when a change is taken from the budget, else the ms until one is back */
uint64_t record_budget_take(struct record_budget *b, uint64_t now_ms);

/* A change taken but not made (the request failed): given back */
void record_budget_refund(struct record_budget *b);

#endif
