// SPDX-License-Identifier: GPL-2.0
/* How often requests through the socket may change the record (record_budget.h). */
#include "store/record_budget.h"

void record_budget_init(struct record_budget *b, uint64_t now_ms)
{
	b->left = RECORD_BUDGET_BURST;
	b->refilled_ms = now_ms;
}

static void refill(struct record_budget *b, uint64_t now_ms)
{
	uint64_t back;

	if (b->left >= RECORD_BUDGET_BURST) {
		b->refilled_ms = now_ms;
		return;
	}
	back = (now_ms - b->refilled_ms) / RECORD_BUDGET_REFILL_MS;
	if (back >= RECORD_BUDGET_BURST - b->left) {
		b->left = RECORD_BUDGET_BURST;
		b->refilled_ms = now_ms;
		return;
	}
	b->left += (unsigned int)back;
	b->refilled_ms += back * RECORD_BUDGET_REFILL_MS;
}

uint64_t record_budget_take(struct record_budget *b, uint64_t now_ms)
{
	refill(b, now_ms);
	if (!b->left)
		return b->refilled_ms + RECORD_BUDGET_REFILL_MS - now_ms;
	b->left--;

	return 0;
}

void record_budget_refund(struct record_budget *b)
{
	if (b->left < RECORD_BUDGET_BURST)
		b->left++;
}
