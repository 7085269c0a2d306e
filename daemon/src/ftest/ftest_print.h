/* SPDX-License-Identifier: GPL-2.0 */
/* The factory test's report as text or JSON. */
#ifndef AS9888_FTEST_PRINT_H
#define AS9888_FTEST_PRINT_H

#include <stdbool.h>
#include <stdio.h>

#include "ftest/ftest.h"

/*
 * The JSON report's format: daemon/report.schema.json, whose "$id" ends in
 * FTEST_REPORT_SCHEMA and whose schema_version is FTEST_REPORT_VERSION
 * (raised when a field changes meaning or goes away; new fields keep it).
 */
#define FTEST_REPORT_SCHEMA	"as9888-factory-test-report"
/* 2: options.permissible_error with options.confidence bounds the error itself */
#define FTEST_REPORT_VERSION	2
#ifndef AS9888_VERSION
#define AS9888_VERSION		"unknown"
#endif

/* @record_path is printed when @stored */
void ftest_print_json(FILE *out, const struct ftest_result *res,
		      const char *record_path, bool stored);
void ftest_print_text(FILE *out, const struct ftest_result *res);
/*
 * The same judgments as JUnit XML for line dashboards and CI: one
 * testsuite, one testcase per judgment (name: its ID and what it judges,
 * classname: the step), failure or skipped as judged; backend, chip and
 * versions as properties
 */
void ftest_print_junit(FILE *out, const struct ftest_result *res);

#endif
