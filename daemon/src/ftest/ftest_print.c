// SPDX-License-Identifier: GPL-2.0
/* The factory test's report as text or JSON. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ftest/ftest_print.h"
#include "common/json.h"

static void print_axes_q16(FILE *out, const int32_t v[AS9888_AXES])
{
	fprintf(out, "[%.6f, %.6f, %.6f]", v[0] / 65536.0, v[1] / 65536.0,
		v[2] / 65536.0);
}

/* ISO 8601 UTC, e.g. "2026-11-23T20:45:00Z"; null before the test started */
static void print_utc(FILE *out, int64_t t)
{
	time_t tt = (time_t)t;
	struct tm tm;
	char buf[32];

	if (!t || !gmtime_r(&tt, &tm) ||
	    !strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm)) {
		fputs("null", out);
		return;
	}
	json_string(out, buf);
}

/* The chip's identity: its EEPROM fingerprint and bytes, once read */
static void print_chip(FILE *out, const struct ftest_result *res)
{
	char hex[3 * AS9888_EEPROM_LEN];
	int i;

	if (!res->have_eeprom) {
		fputs("null", out);
		return;
	}
	for (i = 0; i < AS9888_EEPROM_LEN; i++)
		snprintf(hex + 3 * i, sizeof(hex) - 3 * (size_t)i, "%02x%s",
			 res->ee.raw[i], i < AS9888_EEPROM_LEN - 1 ? " " : "");
	fprintf(out, "{\"fingerprint\": \"%016llx\", \"eeprom\": ",
		(unsigned long long)record_fingerprint(res->ee.raw));
	json_string(out, hex);
	fputc('}', out);
}

/* What the operator chose */
static void print_options(FILE *out, const struct ftest_opts *o)
{
	static const char axes[] = "xyz";
	char g[3] = "";
	int axis;

	for (axis = 0; axis < AS9888_AXES && o->gravity_given; axis++)
		if (o->gravity[axis]) {
			g[0] = axes[axis];
			g[1] = o->gravity[axis] > 0 ? '+' : '-';
		}
	fprintf(out, "{\"samples\": %u, \"permissible_error\": ", o->samples);
	json_number(out, o->permissible_error_q16 ?
		    o->permissible_error_q16 / 65536.0 : NAN);
	fputs(", \"confidence\": ", out);
	json_number(out, o->confidence_1e4 ? o->confidence_1e4 / 1e4 : NAN);
	fprintf(out, ", \"fluctuation\": %u, \"lpf\": %s, \"gravity\": ",
		o->fluctuation, o->lpf ? "true" : "false");
	json_string(out, g[0] ? g : NULL);
	fprintf(out, ", \"keep_going\": %s, \"stable_timeout_ms\": %u, \"sequence\": \"%s\"}",
		o->keep_going ? "true" : "false", o->stable_timeout_ms,
		o->note_order ? "note" : "datasheet");
}

/*
 * What the stored level means promise (docs/DECISIONS.md, "What E means"):
 * the bound's kind, E and P, the quantile z, and per axis the standard
 * error the stored run achieved and mean +- z * that standard error
 */
static void print_error_bound(FILE *out, const struct ftest_result *res)
{
	const struct ftest_opts *o = &res->opts;
	const char *mode = !o->permissible_error_q16 ? "fixed_n" :
			   o->confidence_1e4 ? "probability" : "one_sigma";
	int axis;

	if (!res->have_calibration) {
		fputs("null", out);
		return;
	}
	fputs("{\n    \"mode\": ", out);
	json_string(out, mode);
	fputs(",\n    \"permissible_error\": ", out);
	json_number(out, o->permissible_error_q16 ?
		    o->permissible_error_q16 / 65536.0 : NAN);
	fputs(",\n    \"probability\": ", out);
	/* one sigma: P(|Z| <= 1) */
	json_number(out, !o->permissible_error_q16 ? NAN :
		    o->confidence_1e4 ? o->confidence_1e4 / 1e4 : erf(M_SQRT1_2));
	fprintf(out, ",\n    \"z\": %.6f,\n    \"standard_error\": [%.6f, %.6f, %.6f],\n"
		"    \"interval\": [", res->bound_z, res->level_se[0],
		res->level_se[1], res->level_se[2]);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		double m = res->rec.level_mean_q16[axis] / 65536.0;
		double h = res->bound_z * res->level_se[axis];

		fprintf(out, "%s[%.6f, %.6f]", axis ? ", " : "", m - h, m + h);
	}
	fputs("]\n  }", out);
}

void ftest_print_json(FILE *out, const struct ftest_result *res,
			       const char *record_path, bool stored)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;
	uint32_t w;
	bool first = true;

	fprintf(out, "{\n  \"schema\": \"%s\",\n  \"schema_version\": %d,\n"
		"  \"tool\": \"as9888-calibd\",\n  \"tool_version\": ",
		FTEST_REPORT_SCHEMA, FTEST_REPORT_VERSION);
	json_string(out, AS9888_VERSION);
	fputs(",\n  \"timestamp\": ", out);
	print_utc(out, res->started);
	fputs(",\n  \"result\": ", out);
	json_string(out, failed ? "fail" : "pass");
	fputs(",\n  \"backend\": ", out);
	json_string(out, res->backend);
	fputs(",\n  \"chip\": ", out);
	print_chip(out, res);
	fputs(",\n  \"options\": ", out);
	print_options(out, &res->opts);
	fputs(",\n  \"failed_step\": ", out);
	json_string(out, failed ? failed->step : NULL);
	fputs(",\n  \"failed_id\": ", out);
	json_string(out, failed ? failed->id : NULL);
	fputs(",\n  \"steps\": ", out);
	report_print_json_steps(out, &res->report);
	fputs(",\n  \"warnings\": [", out);
	for (w = res->warnings; w; w &= w - 1, first = false) {
		fputs(first ? "" : ", ", out);
		json_string(out, as9888_ee_warning_str(w & -w));
	}
	fputs("],\n  \"calibration\": ", out);
	if (!res->have_calibration) {
		fputs("null", out);
	} else {
		fprintf(out, "{\n    \"dac\": [%u, %u, %u],\n    \"level_mean\": ",
			rec->dac[0], rec->dac[1], rec->dac[2]);
		print_axes_q16(out, rec->level_mean_q16);
		fputs(",\n    \"offset\": ", out);
		print_axes_q16(out, res->offset_q16);
		fprintf(out, ",\n    \"t_level\": %.3f,\n    \"gravity\": [%d, %d, %d],\n"
			"    \"samples\": %u,\n    \"lpf\": %s\n  }",
			rec->t_level_mdegc / 1000.0, rec->gravity[0],
			rec->gravity[1], rec->gravity[2], rec->samples,
			rec->lpf ? "true" : "false");
	}
	fputs(",\n  \"error_bound\": ", out);
	print_error_bound(out, res);
	fprintf(out, ",\n  \"duration_ms\": %.3f", res->duration_ns / 1e6);
	fprintf(out, ",\n  \"overlap_lost\": %u", res->overlap_lost);
	fputs(",\n  \"record\": ", out);
	json_string(out, stored ? record_path : NULL);
	fputs("\n}\n", out);
}

void ftest_print_text(FILE *out, const struct ftest_result *res)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;

	if (res->backend)
		fprintf(out, "Backend: %s%s\n\n", res->backend,
			!strcmp(res->backend, "sim") ?
			" (the SIMULATED chip, not a unit: its record is marked so)" : "");
	report_print_text(out, &res->report);
	if (res->have_calibration) {
		fprintf(out, "\nCalibration\n");
		fprintf(out, "  DAC          0x%02x 0x%02x 0x%02x\n", rec->dac[0],
			rec->dac[1], rec->dac[2]);
		fprintf(out, "  level mean   %.3f %.3f %.3f LSB\n",
			rec->level_mean_q16[0] / 65536.0,
			rec->level_mean_q16[1] / 65536.0,
			rec->level_mean_q16[2] / 65536.0);
		fprintf(out, "  offset Ot_L  %.3f %.3f %.3f LSB\n",
			res->offset_q16[0] / 65536.0, res->offset_q16[1] / 65536.0,
			res->offset_q16[2] / 65536.0);
		fprintf(out, "  t_L          %.3f degC\n", rec->t_level_mdegc / 1000.0);
		fprintf(out, "  gravity      %d %d %d\n", rec->gravity[0],
			rec->gravity[1], rec->gravity[2]);
		fprintf(out, "  samples      %u%s\n", rec->samples,
			rec->lpf ? " (low-pass filter on)" : "");
	}
	fprintf(out, "\nSteps 1-3 took %.1f ms\n", res->duration_ns / 1e6);
	if (failed)
		fprintf(out, "\nResult: FAIL at step %s (%s: %s)\n", failed->step,
			failed->name, failed->measured);
	else
		fprintf(out, "\nResult: PASS\n");
}


/* A failure's type (the Ant schema wants one): a judgment outside its limits */
#define JUNIT_FAILURE_TYPE	"as9888.judgment"

/* @s as XML character data or attribute value */
static void xml_text(FILE *out, const char *s)
{
	for (; s && *s; s++) {
		unsigned char c = (unsigned char)*s;

		switch (c) {
		case '<':
			fputs("&lt;", out);
			break;
		case '>':
			fputs("&gt;", out);
			break;
		case '&':
			fputs("&amp;", out);
			break;
		case '"':
			fputs("&quot;", out);
			break;
		default:
			if (c < 0x20 && c != '\n' && c != '\t')
				fputc('?', out);
			else
				fputc(c, out);
		}
	}
}

static void xml_property(FILE *out, const char *name, const char *value)
{
	fprintf(out, "      <property name=\"%s\" value=\"", name);
	xml_text(out, value ? value : "");
	fputs("\"/>\n", out);
}

void ftest_print_junit(FILE *out, const struct ftest_result *res)
{
	const struct report *r = &res->report;
	size_t i, failures = 0, skipped = 0;
	char chip[20] = "", stamp[32] = "", host[HOST_NAME_MAX + 1];
	time_t t = (time_t)res->started;
	struct tm tm;

	for (i = 0; i < r->count; i++) {
		failures += r->items[i].result == JUDGMENT_FAIL;
		skipped += r->items[i].result == JUDGMENT_SKIP;
	}
	if (res->have_eeprom)
		snprintf(chip, sizeof(chip), "%016llx",
			 (unsigned long long)record_fingerprint(res->ee.raw));
	if (res->started && gmtime_r(&t, &tm))
		strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%S", &tm);

	if (gethostname(host, sizeof(host)))
		snprintf(host, sizeof(host), "localhost");
	host[sizeof(host) - 1] = '\0';

	/* Jenkins' junit-10.xsd: no "skipped" on <testsuites>, only on <testsuite> */
	fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", out);
	fprintf(out, "<testsuites name=\"as9888-calibd factory-test\" tests=\"%zu\" failures=\"%zu\" errors=\"0\" time=\"%.6f\">\n",
		r->count, failures, res->duration_ns / 1e9);
	fprintf(out, "  <testsuite name=\"%s\" tests=\"%zu\" failures=\"%zu\" skipped=\"%zu\" errors=\"0\" time=\"%.6f\" timestamp=\"%s\" hostname=\"",
		FTEST_REPORT_SCHEMA, r->count, failures, skipped,
		res->duration_ns / 1e9, stamp);
	xml_text(out, host);
	fputs("\" id=\"0\" package=\"as9888-calibd\">\n", out);
	fputs("    <properties>\n", out);
	xml_property(out, "tool_version", AS9888_VERSION);
	xml_property(out, "backend", res->backend);
	xml_property(out, "chip", chip);
	fputs("    </properties>\n", out);
	for (i = 0; i < r->count; i++) {
		const struct judgment *j = &r->items[i];

		fputs("    <testcase classname=\"step ", out);
		xml_text(out, j->step);
		fputs("\" name=\"", out);
		xml_text(out, j->id);
		fputc(' ', out);
		xml_text(out, j->name);
		fputs("\" time=\"0\">", out);
		if (j->result != JUDGMENT_PASS) {
			fputs(j->result == JUDGMENT_FAIL ?
			      "\n      <failure type=\"" JUNIT_FAILURE_TYPE "\" message=\"" :
			      "\n      <skipped message=\"", out);
			xml_text(out, j->measured);
			if (j->limits[0]) {
				fputs(" (limits: ", out);
				xml_text(out, j->limits);
				fputc(')', out);
			}
			fputs("\"/>\n    ", out);
		}
		fputs("<system-out>", out);
		xml_text(out, j->measured);
		fputs("</system-out></testcase>\n", out);
	}
	fputs("    <system-out></system-out>\n    <system-err></system-err>\n", out);
	fputs("  </testsuite>\n</testsuites>\n", out);
}
