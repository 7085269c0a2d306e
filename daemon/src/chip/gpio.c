// SPDX-License-Identifier: GPL-2.0
/*
 * GPIO lines through libgpiod, for both of its APIs: 1.x (line handles
 * requested one by one) and 2.x (line requests built from settings). The
 * rest of the program sees only gpio.h.
 */
#include <errno.h>
#include <gpiod.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "chip/gpio.h"

#define CONSUMER	"as9888-calibd"
#define NS_PER_SEC	1000000000ULL

static int gpio_fail(char *err, size_t errlen, const char *what,
		     const char *chip, unsigned int offset)
{
	int e = errno ? errno : EIO;

	snprintf(err, errlen, "%s %s line %u: %s", what, chip, offset,
		 strerror(e));
	return -e;
}

#ifdef AS9888_GPIOD_V2

struct gpio_line {
	struct gpiod_chip *chip;
	struct gpiod_line_request *req;
	struct gpiod_edge_event_buffer *events;
	unsigned int offset;
};

static struct gpiod_chip *chip_open(const char *name)
{
	char path[64];

	if (strchr(name, '/'))
		return gpiod_chip_open(name);
	snprintf(path, sizeof(path), "/dev/%s", name);
	return gpiod_chip_open(path);
}

static int request(const char *chip, unsigned int offset, bool output,
		   int value, struct gpio_line **out, char *err, size_t errlen)
{
	struct gpiod_line_settings *settings = NULL;
	struct gpiod_line_config *config = NULL;
	struct gpiod_request_config *rconfig = NULL;
	struct gpio_line *line;
	int ret = 0;

	line = calloc(1, sizeof(*line));
	if (!line)
		return -ENOMEM;
	line->offset = offset;
	errno = 0;
	line->chip = chip_open(chip);
	if (!line->chip) {
		ret = gpio_fail(err, errlen, "cannot open", chip, offset);
		goto out;
	}
	settings = gpiod_line_settings_new();
	config = gpiod_line_config_new();
	rconfig = gpiod_request_config_new();
	if (!settings || !config || !rconfig) {
		ret = -ENOMEM;
		goto out;
	}
	if (output) {
		gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_OUTPUT);
		gpiod_line_settings_set_output_value(settings, value ?
				GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE);
	} else {
		gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_INPUT);
		gpiod_line_settings_set_edge_detection(settings, GPIOD_LINE_EDGE_RISING);
		line->events = gpiod_edge_event_buffer_new(1);
		if (!line->events) {
			ret = -ENOMEM;
			goto out;
		}
	}
	gpiod_request_config_set_consumer(rconfig, CONSUMER);
	if (gpiod_line_config_add_line_settings(config, &offset, 1, settings)) {
		ret = gpio_fail(err, errlen, "cannot configure", chip, offset);
		goto out;
	}
	line->req = gpiod_chip_request_lines(line->chip, rconfig, config);
	if (!line->req)
		ret = gpio_fail(err, errlen, "cannot request", chip, offset);
out:
	gpiod_line_settings_free(settings);
	gpiod_line_config_free(config);
	gpiod_request_config_free(rconfig);
	if (ret)
		gpio_close(line);
	else
		*out = line;
	return ret;
}

int gpio_set(struct gpio_line *line, int value)
{
	return gpiod_line_request_set_value(line->req, line->offset, value ?
			GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE) ?
	       -errno : 0;
}

int gpio_get(struct gpio_line *line)
{
	enum gpiod_line_value v = gpiod_line_request_get_value(line->req,
							       line->offset);

	return v == GPIOD_LINE_VALUE_ERROR ? -errno : v == GPIOD_LINE_VALUE_ACTIVE;
}

int gpio_wait_rising(struct gpio_line *line, uint64_t timeout_ns)
{
	int ret = gpiod_line_request_wait_edge_events(line->req,
						      (int64_t)timeout_ns);

	if (ret <= 0)
		return ret < 0 ? -errno : 0;
	if (gpiod_line_request_read_edge_events(line->req, line->events, 1) < 0)
		return -errno;
	return 1;
}

void gpio_close(struct gpio_line *line)
{
	if (!line)
		return;
	if (line->req)
		gpiod_line_request_release(line->req);
	if (line->events)
		gpiod_edge_event_buffer_free(line->events);
	if (line->chip)
		gpiod_chip_close(line->chip);
	free(line);
}

const char *gpio_library_version(void)
{
	return gpiod_api_version();
}

#else /* libgpiod 1.x */

struct gpio_line {
	struct gpiod_chip *chip;
	struct gpiod_line *line;
};

static int request(const char *chip, unsigned int offset, bool output,
		   int value, struct gpio_line **out, char *err, size_t errlen)
{
	struct gpio_line *line;
	int ret = 0;

	line = calloc(1, sizeof(*line));
	if (!line)
		return -ENOMEM;
	errno = 0;
	line->chip = gpiod_chip_open_lookup(chip);
	if (!line->chip) {
		ret = gpio_fail(err, errlen, "cannot open", chip, offset);
		goto out;
	}
	line->line = gpiod_chip_get_line(line->chip, offset);
	if (!line->line) {
		ret = gpio_fail(err, errlen, "no such line on", chip, offset);
		goto out;
	}
	if (output ? gpiod_line_request_output(line->line, CONSUMER, value) :
		     gpiod_line_request_rising_edge_events(line->line, CONSUMER))
		ret = gpio_fail(err, errlen, "cannot request", chip, offset);
out:
	if (ret)
		gpio_close(line);
	else
		*out = line;
	return ret;
}

int gpio_set(struct gpio_line *line, int value)
{
	return gpiod_line_set_value(line->line, value) ? -errno : 0;
}

int gpio_get(struct gpio_line *line)
{
	int v = gpiod_line_get_value(line->line);

	return v < 0 ? -errno : v;
}

int gpio_wait_rising(struct gpio_line *line, uint64_t timeout_ns)
{
	struct timespec ts = {
		.tv_sec = (time_t)(timeout_ns / NS_PER_SEC),
		.tv_nsec = (long)(timeout_ns % NS_PER_SEC),
	};
	struct gpiod_line_event event;
	int ret = gpiod_line_event_wait(line->line, &ts);

	if (ret <= 0)
		return ret < 0 ? -errno : 0;
	if (gpiod_line_event_read(line->line, &event))
		return -errno;
	return 1;
}

void gpio_close(struct gpio_line *line)
{
	if (!line)
		return;
	if (line->line)
		gpiod_line_release(line->line);
	if (line->chip)
		gpiod_chip_close(line->chip);
	free(line);
}

const char *gpio_library_version(void)
{
	return gpiod_version_string();
}

#endif

int gpio_open_output(const char *chip, unsigned int offset, int value,
		     struct gpio_line **out, char *err, size_t errlen)
{
	return request(chip, offset, true, value, out, err, errlen);
}

int gpio_open_rising(const char *chip, unsigned int offset,
		     struct gpio_line **out, char *err, size_t errlen)
{
	return request(chip, offset, false, 0, out, err, errlen);
}
