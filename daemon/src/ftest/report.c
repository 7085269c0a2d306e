// SPDX-License-Identifier: GPL-2.0
/* The judgments of a factory test run, and their text and JSON forms. */
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "common/json.h"
#include "ftest/report.h"

static bool id_taken(const struct report *r, const struct judgment *j,
		     const char *id)
{
	const struct judgment *i;

	for (i = r->items; i < j; i++)
		if (!strcmp(i->id, id))
			return true;

	return false;
}

static void set_id(const struct report *r, struct judgment *j, const char *step)
{
	size_t len = strcspn(step, ".");
	unsigned int n;

	snprintf(j->step, sizeof(j->step), "%.*s", (int)len, step);
	snprintf(j->id, sizeof(j->id), "%s", step);
	for (n = 2; id_taken(r, j, j->id); n++)
		snprintf(j->id, sizeof(j->id), "%.20s.%u", step, n);
}

void report_set_value(struct report *r, double value, double low, double high,
		      const char *unit)
{
	struct judgment *j;

	if (!r->count)
		return;
	j = &r->items[r->count - 1];
	j->value = value;
	j->low = low;
	j->high = high;
	snprintf(j->unit, sizeof(j->unit), "%s", unit ? unit : "");
}

enum judgment_result report_add(struct report *r, const char *step,
				const char *name, enum judgment_result result,
				const char *limits, const char *measured, ...)
{
	struct judgment *j;
	va_list ap;

	if (r->count == r->cap) {
		size_t cap = r->cap ? r->cap * 2 : 32;
		struct judgment *items = realloc(r->items, cap * sizeof(*items));

		if (!items) {
			/* keep the verdict even when the entry is lost */
			r->oom = true;
			return result;
		}
		r->items = items;
		r->cap = cap;
	}

	j = &r->items[r->count++];
	set_id(r, j, step);
	j->value = j->low = j->high = NAN;
	j->unit[0] = '\0';
	snprintf(j->name, sizeof(j->name), "%s", name);
	snprintf(j->limits, sizeof(j->limits), "%s", limits ? limits : "");
	va_start(ap, measured);
	vsnprintf(j->measured, sizeof(j->measured), measured, ap);
	va_end(ap);
	j->result = result;

	return result;
}

const struct judgment *report_first_failure(const struct report *r)
{
	size_t i;

	for (i = 0; i < r->count; i++)
		if (r->items[i].result == JUDGMENT_FAIL)
			return &r->items[i];

	return NULL;
}

void report_free(struct report *r)
{
	free(r->items);
	memset(r, 0, sizeof(*r));
}

const char *judgment_result_str(enum judgment_result result)
{
	switch (result) {
	case JUDGMENT_PASS:
		return "pass";
	case JUDGMENT_FAIL:
		return "fail";
	default:
		return "skip";
	}
}

void report_print_text(FILE *out, const struct report *r)
{
	size_t i;

	for (i = 0; i < r->count; i++) {
		const struct judgment *j = &r->items[i];

		fprintf(out, "%-6s %-4s %s: %s", j->id,
			judgment_result_str(j->result), j->name, j->measured);
		if (j->limits[0])
			fprintf(out, " (limits: %s)", j->limits);
		fputc('\n', out);
	}
}

void report_print_json_steps(FILE *out, const struct report *r)
{
	size_t i;

	fputc('[', out);
	for (i = 0; i < r->count; i++) {
		const struct judgment *j = &r->items[i];

		fputs(i ? ",\n    {" : "\n    {", out);
		fputs("\"id\": ", out);
		json_string(out, j->id);
		fputs(", \"step\": ", out);
		json_string(out, j->step);
		fputs(", \"name\": ", out);
		json_string(out, j->name);
		fputs(", \"measured\": ", out);
		json_string(out, j->measured);
		fputs(", \"limits\": ", out);
		json_string(out, j->limits);
		fputs(", \"result\": ", out);
		json_string(out, judgment_result_str(j->result));
		fputs(", \"value\": ", out);
		json_number(out, j->value);
		fputs(", \"low\": ", out);
		json_number(out, j->low);
		fputs(", \"high\": ", out);
		json_number(out, j->high);
		fputs(", \"unit\": ", out);
		json_string(out, j->unit[0] ? j->unit : NULL);
		fputc('}', out);
	}
	fputs(r->count ? "\n  ]" : "]", out);
}
