/* SPDX-License-Identifier: GPL-2.0 */
/* Minimal JSON output helpers. */
#ifndef AS9888_JSON_H
#define AS9888_JSON_H

#include <stdio.h>

/* Print @s as a JSON string literal, escaped; NULL prints null. */
void json_string(FILE *out, const char *s);
/* Print @v as a JSON number; NAN (and infinities) print null. */
void json_number(FILE *out, double v);

#endif
