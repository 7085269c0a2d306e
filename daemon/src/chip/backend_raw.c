// SPDX-License-Identifier: GPL-2.0
/*
 * The raw backend: i2c-dev for the registers (one I2C_RDWR transaction with
 * a repeated start per burst read, one write() per burst write) and
 * libgpiod for RSTN and the interrupt pins.
 */
#include <errno.h>
#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "chip/backend_raw.h"
#include "chip/gpio.h"

#define NS_PER_SEC	1000000000ULL
/* Largest burst the daemon makes: the EEPROM window */
#define RAW_MAX_BURST	32

struct raw_transport {
	struct transport base;
	int fd;
	unsigned int address;
	struct gpio_line *rstn;
	struct gpio_line *pin[2];
};

static struct raw_transport *to_raw(struct transport *t)
{
	return (struct raw_transport *)t;
}

static int raw_read(struct transport *t, uint8_t reg, uint8_t *buf, size_t len)
{
	struct raw_transport *r = to_raw(t);
	struct i2c_msg msgs[2] = {
		{ .addr = (uint16_t)r->address, .flags = 0, .len = 1, .buf = &reg },
		{ .addr = (uint16_t)r->address, .flags = I2C_M_RD,
		  .len = (uint16_t)len, .buf = buf },
	};
	struct i2c_rdwr_ioctl_data xfer = { .msgs = msgs, .nmsgs = 2 };

	if (len > RAW_MAX_BURST)
		return -EINVAL;
	return ioctl(r->fd, I2C_RDWR, &xfer) < 0 ? -errno : 0;
}

static int raw_write(struct transport *t, uint8_t reg, const uint8_t *buf,
		     size_t len)
{
	struct raw_transport *r = to_raw(t);
	uint8_t msg[RAW_MAX_BURST + 1];
	ssize_t n;

	if (len > RAW_MAX_BURST)
		return -EINVAL;
	msg[0] = reg;
	memcpy(msg + 1, buf, len);
	n = write(r->fd, msg, len + 1);
	if (n < 0)
		return -errno;
	return (size_t)n == len + 1 ? 0 : -EIO;
}

static int raw_set_rstn(struct transport *t, bool level)
{
	struct raw_transport *r = to_raw(t);

	return r->rstn ? gpio_set(r->rstn, level) : -EOPNOTSUPP;
}

static bool raw_pin_monitored(struct transport *t, enum transport_pin pin)
{
	return to_raw(t)->pin[pin] != NULL;
}

static uint64_t raw_now_ns(struct transport *t)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * NS_PER_SEC + (uint64_t)ts.tv_nsec;
}

/*
 * Wait until the pin is high. An edge event may be left over from an
 * earlier measurement whose pin was deasserted since: an event only counts
 * when the pin reads high afterwards. At the deadline the level decides:
 * on a busy machine the edge's event can reach us after the pin rose (the
 * kernel queues it from a thread), and a pin that reads high has risen.
 */
static int raw_wait_pin(struct transport *t, enum transport_pin pin,
			uint64_t timeout_ns)
{
	struct gpio_line *line = to_raw(t)->pin[pin];
	uint64_t deadline = raw_now_ns(t) + timeout_ns, now;
	int ret;

	for (;;) {
		ret = gpio_get(line);
		if (ret != 0)
			return ret;
		now = raw_now_ns(t);

		if (now >= deadline)
			return 0;
		ret = gpio_wait_rising(line, deadline - now);
		if (ret < 0)
			return ret;
		if (ret == 0)
			return gpio_get(line);
	}
}

static void raw_sleep_ns(struct transport *t, uint64_t ns)
{
	struct timespec ts = {
		.tv_sec = (time_t)(ns / NS_PER_SEC),
		.tv_nsec = (long)(ns % NS_PER_SEC),
	};

	while (nanosleep(&ts, &ts) && errno == EINTR)
		;
}

static void raw_destroy(struct transport *t)
{
	struct raw_transport *r = to_raw(t);

	gpio_close(r->rstn);
	gpio_close(r->pin[0]);
	gpio_close(r->pin[1]);
	if (r->fd >= 0)
		close(r->fd);
	free(r);
}

static const struct transport_ops raw_ops = {
	.read = raw_read,
	.write = raw_write,
	.set_rstn = raw_set_rstn,
	.pin_monitored = raw_pin_monitored,
	.wait_pin = raw_wait_pin,
	.now_ns = raw_now_ns,
	.sleep_ns = raw_sleep_ns,
	.destroy = raw_destroy,
};

int backend_raw_open(const struct backend_raw_opts *opts,
		     struct transport **out, char *err, size_t errlen)
{
	struct raw_transport *r;
	int ret = 0;

	if (opts->address < 0x0c || opts->address > 0x0f) {
		snprintf(err, errlen, "I2C address 0x%02x is not 0x0c..0x0f",
			 opts->address);
		return -EINVAL;
	}
	if ((opts->rstn >= 0 || opts->int1 >= 0 || opts->int2 >= 0) &&
	    !opts->gpiochip) {
		snprintf(err, errlen, "GPIO lines given without a GPIO chip");
		return -EINVAL;
	}

	r = calloc(1, sizeof(*r));
	if (!r) {
		snprintf(err, errlen, "raw backend: out of memory");
		return -ENOMEM;
	}
	r->base.ops = &raw_ops;
	r->base.name = "raw";
	r->address = opts->address;
	r->fd = open(opts->i2c_dev, O_RDWR | O_CLOEXEC);
	if (r->fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "cannot open %s: %s", opts->i2c_dev,
			 strerror(errno));
		goto fail;
	}
	if (ioctl(r->fd, I2C_SLAVE, (unsigned long)opts->address) < 0) {
		ret = -errno;
		snprintf(err, errlen, "%s: cannot address 0x%02x: %s%s",
			 opts->i2c_dev, opts->address, strerror(errno),
			 errno == EBUSY ? " (is the as9888 driver bound? unbind it)" : "");
		goto fail;
	}
	if (opts->rstn >= 0)
		ret = gpio_open_output(opts->gpiochip, (unsigned int)opts->rstn, 1,
				       &r->rstn, err, errlen);
	if (!ret && opts->int1 >= 0)
		ret = gpio_open_rising(opts->gpiochip, (unsigned int)opts->int1,
				       &r->pin[TRANSPORT_INT1], err, errlen);
	if (!ret && opts->int2 >= 0)
		ret = gpio_open_rising(opts->gpiochip, (unsigned int)opts->int2,
				       &r->pin[TRANSPORT_INT2], err, errlen);
	if (ret)
		goto fail;

	*out = &r->base;
	return 0;
fail:
	raw_destroy(&r->base);
	return ret;
}
