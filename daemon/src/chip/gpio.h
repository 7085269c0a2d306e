/* SPDX-License-Identifier: GPL-2.0 */
/*
 * GPIO lines through libgpiod, the same calls for libgpiod 1.6 (Debian 12)
 * and 2.x: an output for RSTN, rising-edge inputs for INT1/INT2.
 */
#ifndef AS9888_GPIO_H
#define AS9888_GPIO_H

#include <stddef.h>
#include <stdint.h>

struct gpio_line;

/* @chip: a name ("gpiochip0") or a path ("/dev/gpiochip0") */
int gpio_open_output(const char *chip, unsigned int offset, int value,
		     struct gpio_line **out, char *err, size_t errlen);
int gpio_open_rising(const char *chip, unsigned int offset,
		     struct gpio_line **out, char *err, size_t errlen);
int gpio_set(struct gpio_line *line, int value);
/* 0 or 1, or -errno */
int gpio_get(struct gpio_line *line);
/* Wait for a rising edge: 1 seen, 0 timeout, -errno */
int gpio_wait_rising(struct gpio_line *line, uint64_t timeout_ns);
void gpio_close(struct gpio_line *line);
/* "1.6.3", "2.2.1": the library the program runs with */
const char *gpio_library_version(void);

#endif
