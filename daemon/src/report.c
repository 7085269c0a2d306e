// SPDX-License-Identifier: GPL-2.0
/* The judgments of a factory test run, and their text and JSON forms. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "json.h"
#include "report.h"

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
	snprintf(j->step, sizeof(j->step), "%s", step);
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

		fprintf(out, "%-6s %-4s %s: %s", j->step,
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
		fputs("\"step\": ", out);
		json_string(out, j->step);
		fputs(", \"name\": ", out);
		json_string(out, j->name);
		fputs(", \"measured\": ", out);
		json_string(out, j->measured);
		fputs(", \"limits\": ", out);
		json_string(out, j->limits);
		fputs(", \"result\": ", out);
		json_string(out, judgment_result_str(j->result));
		fputc('}', out);
	}
	fputs(r->count ? "\n  ]" : "]", out);
}
