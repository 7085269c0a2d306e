/* SPDX-License-Identifier: GPL-2.0 */
/*
 * One sysfs attribute of an IIO device, read or written whole, as text or
 * as a number. Every failure says which file and why in @err.
 */
#ifndef AS9888_HAL_ATTR_H
#define AS9888_HAL_ATTR_H

#include <stddef.h>

/* @dir/@name's text without the trailing newline: 0 or -errno */
int hal_attr_read(const char *dir, const char *name, char *buf, size_t len,
		  char *err, size_t errlen);

/* Write @value to @dir/@name in one write(): 0 or -errno */
int hal_attr_write(const char *dir, const char *name, const char *value,
		   char *err, size_t errlen);

/* A decimal number, the whole text, finite: 0, -EINVAL or -errno */
int hal_attr_double(const char *dir, const char *name, double *out,
		    char *err, size_t errlen);

/* A decimal integer, the whole text: 0, -EINVAL or -errno */
int hal_attr_long(const char *dir, const char *name, long *out,
		  char *err, size_t errlen);

/* Parsers of the same, for text already read: 0 or -EINVAL */
int hal_parse_double(const char *s, double *out);
int hal_parse_long(const char *s, long *out);

#endif
