/* SPDX-License-Identifier: GPL-2.0 */
/* The factory test's report as text or JSON. */
#ifndef AS9888_FTEST_PRINT_H
#define AS9888_FTEST_PRINT_H

#include <stdbool.h>
#include <stdio.h>

#include "ftest.h"

/* @record_path is printed when @stored */
void ftest_print_json(FILE *out, const struct ftest_result *res,
		      const char *record_path, bool stored);
void ftest_print_text(FILE *out, const struct ftest_result *res);

#endif
