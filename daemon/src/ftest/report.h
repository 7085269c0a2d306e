/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The judgments of a factory test run: one entry per judgment, named by
 * the application note's step number, with what was measured, the limits
 * and the result; printed as text or JSON.
 */
#ifndef AS9888_REPORT_H
#define AS9888_REPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

enum judgment_result {
	JUDGMENT_PASS = 0,
	JUDGMENT_FAIL,
	JUDGMENT_SKIP,
};

#define JUDGMENT_STEP_LEN	16
#define JUDGMENT_ID_LEN		32
#define JUDGMENT_UNIT_LEN	16
#define JUDGMENT_TEXT_LEN	160

/**
 * struct judgment - one judgment of the report
 * @id:		unique within the report: the application note's step, and
 *		".what" when one step holds several judgments ("3-5.stable")
 * @step:	the application note's step number ("3-5")
 * @name:	what is judged
 * @measured:	what was found, for people
 * @limits:	the limits, for people
 * @result:	pass, fail or skip
 * @value:	what was found as a number, NAN when there is none
 * @low:	the lowest passing @value (inclusive), NAN: no lower limit
 * @high:	the highest passing @value (inclusive), NAN: no upper limit
 * @unit:	@value's unit ("LSB", "code", "bool" for 1 = true, ...)
 */
struct judgment {
	char id[JUDGMENT_ID_LEN];
	char step[JUDGMENT_STEP_LEN];
	char name[JUDGMENT_TEXT_LEN];
	char measured[JUDGMENT_TEXT_LEN];
	char limits[JUDGMENT_TEXT_LEN];
	enum judgment_result result;
	double value;
	double low;
	double high;
	char unit[JUDGMENT_UNIT_LEN];
};

struct report {
	struct judgment *items;
	size_t count;
	size_t cap;
	bool oom;
};

/*
 * Add a judgment; @measured is a printf format. @step is the application
 * note's step, optionally followed by ".what" to tell apart several
 * judgments of one step; the whole is the judgment's ID, made unique with
 * a ".2", ".3"... suffix if it is taken. Returns the result, so a
 * caller can write: if (report_add(...) == JUDGMENT_FAIL) ...
 */
enum judgment_result report_add(struct report *r, const char *step,
				 const char *name, enum judgment_result result,
				 const char *limits, const char *measured, ...)
	__attribute__((format(printf, 6, 7)));
/* The last judgment's number: @value within @low..@high (NAN: none) */
void report_set_value(struct report *r, double value, double low, double high,
		      const char *unit);
/* The first failed judgment, or NULL */
const struct judgment *report_first_failure(const struct report *r);
void report_free(struct report *r);
const char *judgment_result_str(enum judgment_result result);

void report_print_text(FILE *out, const struct report *r);
/* The "steps" array of the JSON report */
void report_print_json_steps(FILE *out, const struct report *r);

#endif
