/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The raw backend: the chip on an I2C bus through i2c-dev (the kernel
 * driver unbound), RSTN and INT1/INT2 through libgpiod.
 */
#ifndef AS9888_BACKEND_RAW_H
#define AS9888_BACKEND_RAW_H

#include <stddef.h>

#include "chip/transport.h"

#define RAW_LINE_NONE	(-1)

/**
 * struct backend_raw_opts - where the chip is
 * @i2c_dev:	i2c-dev node, e.g. /dev/i2c-1
 * @address:	7-bit address, 0x0c..0x0f
 * @gpiochip:	GPIO chip of the lines below (name or path), may be NULL
 *		when no line is given
 * @rstn:	RSTN line offset, or RAW_LINE_NONE
 * @int1:	INT1 line offset, or RAW_LINE_NONE (then DRDY is polled)
 * @int2:	INT2 line offset, or RAW_LINE_NONE
 */
struct backend_raw_opts {
	const char *i2c_dev;
	unsigned int address;
	const char *gpiochip;
	int rstn;
	int int1;
	int int2;
};

int backend_raw_open(const struct backend_raw_opts *opts,
		     struct transport **out, char *err, size_t errlen);

#endif
