// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the simulated unit description (--unit FILE), parsed by
 * the chip model: never a crash or an out-of-bounds read, and an error
 * always names a line within the input.
 */
#include <linux/types.h>
#include <stdint.h>
#include <stdlib.h>

#include "as9888_unit.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct as9888_unit_error err = { 0 };
	struct as9888_unit u;
	unsigned int lines = 1;
	size_t i;

	if (size > 65536)
		return 0;
	for (i = 0; i < size; i++)
		lines += data[i] == '\n';
	if (as9888_unit_parse((const char *)data, (unsigned int)size, &u, &err) &&
	    (err.line > lines || !err.msg[0]))
		abort();

	return 0;
}
