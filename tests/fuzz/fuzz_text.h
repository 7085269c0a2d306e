/* SPDX-License-Identifier: GPL-2.0 */
/* For the libFuzzer targets: an input as a NUL-terminated string. */
#ifndef AS9888_FUZZ_TEXT_H
#define AS9888_FUZZ_TEXT_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A heap copy of @data with a NUL after it (NULL when out of memory) */
static inline char *fuzz_text(const uint8_t *data, size_t size)
{
	char *s = malloc(size + 1);

	if (s) {
		memcpy(s, data, size);
		s[size] = '\0';
	}
	return s;
}

#endif
