// SPDX-License-Identifier: GPL-2.0
/*
 * Smoke test of daemon/src/chip/gpio.c built against libgpiod 2.x
 * (scripts/libgpiod2-check.sh): prints the library version, then checks
 * that opening a line on a chip that does not exist fails with a message
 * naming the chip, by name and by path. Needs no GPIO hardware.
 *
 * Output: "version <x.y.z>" on stdout; exit 0 when every check passed.
 */
#include <stdio.h>
#include <string.h>

#include "chip/gpio.h"

static int expect_open_fails(const char *chip)
{
	struct gpio_line *line = NULL;
	char err[256] = "";
	int ret;

	ret = gpio_open_output(chip, 0, 1, &line, err, sizeof(err));
	if (ret == 0) {
		fprintf(stderr, "FAIL: gpio_open_output(\"%s\") succeeded\n", chip);
		gpio_close(line);
		return 1;
	}
	if (ret > 0) {
		fprintf(stderr, "FAIL: gpio_open_output(\"%s\") returned %d, not -errno\n",
			chip, ret);
		return 1;
	}
	if (line) {
		fprintf(stderr, "FAIL: gpio_open_output(\"%s\") failed but set *out\n", chip);
		return 1;
	}
	if (!strstr(err, chip)) {
		fprintf(stderr, "FAIL: error for \"%s\" does not name the chip: \"%s\"\n",
			chip, err);
		return 1;
	}
	printf("ok: %s -> %d: %s\n", chip, ret, err);
	return 0;
}

int main(void)
{
	const char *version = gpio_library_version();
	int failed = 0;

	if (!version || !*version) {
		fprintf(stderr, "FAIL: gpio_library_version() is empty\n");
		return 1;
	}
	printf("version %s\n", version);
	failed |= expect_open_fails("as9888-no-such-gpiochip");
	failed |= expect_open_fails("/dev/as9888-no-such-gpiochip");
	return failed;
}
