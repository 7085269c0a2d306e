// SPDX-License-Identifier: GPL-2.0
/*
 * Built without libgpiod (meson -Dlibgpiod=disabled): the raw backend talks
 * I2C only; naming a pin (--gpiochip with a line option) fails and says so.
 */
#include <errno.h>
#include <stdio.h>

#include "chip/gpio.h"

static int no_gpiod(char *err, size_t errlen)
{
	snprintf(err, errlen,
		 "this as9888-calibd is built without libgpiod (meson -Dlibgpiod=disabled): leave out --gpiochip and the line options, the pin checks are then skipped");
	return -EOPNOTSUPP;
}

int gpio_open_output(const char *chip, unsigned int offset, int value,
		     struct gpio_line **out, char *err, size_t errlen)
{
	return no_gpiod(err, errlen);
}

int gpio_open_rising(const char *chip, unsigned int offset,
		     struct gpio_line **out, char *err, size_t errlen)
{
	return no_gpiod(err, errlen);
}

int gpio_set(struct gpio_line *line, int value)
{
	return -EOPNOTSUPP;
}

int gpio_get(struct gpio_line *line)
{
	return -EOPNOTSUPP;
}

int gpio_wait_rising(struct gpio_line *line, uint64_t timeout_ns)
{
	return -EOPNOTSUPP;
}

void gpio_close(struct gpio_line *line)
{
}

const char *gpio_library_version(void)
{
	return "none";
}
