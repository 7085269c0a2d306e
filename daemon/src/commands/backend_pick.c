// SPDX-License-Identifier: GPL-2.0
/*
 * Which backend a command uses when --backend is not given: the bound
 * driver, else the chip on the raw bus, else none. Never the simulator: a
 * station without the driver or the bus must fail, not test a simulated
 * chip.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "as9888_regs.h"
#include "chip/backend_raw.h"
#include "commands/cli.h"
#include "chip/iio.h"
#include "chip/transport.h"

/* 0 when a chip answers with the AS9888's WIA at @raw's bus and address */
static int probe_raw(const struct backend_raw_opts *raw, char *why, size_t len)
{
	struct backend_raw_opts probe = *raw;
	struct transport *t;
	uint8_t wia = 0;
	int ret;

	/* the pins are not needed to see whether the chip is there */
	probe.gpiochip = NULL;
	probe.rstn = probe.int1 = probe.int2 = RAW_LINE_NONE;
	ret = backend_raw_open(&probe, &t, why, len);
	if (ret)
		return ret;
	ret = transport_read_reg(t, AS9888_REG_WIA, &wia);
	transport_destroy(t);
	if (ret) {
		snprintf(why, len, "%s: nothing answers at 0x%02x (%s)", raw->i2c_dev,
			 raw->address, strerror(-ret));
		return ret;
	}
	if (wia != AS9888_WIA_VAL) {
		snprintf(why, len, "%s: the device at 0x%02x is not an AS9888 (WIA 0x%02x)",
			 raw->i2c_dev, raw->address, wia);
		return -ENODEV;
	}

	return 0;
}

void cli_pick_backend(struct cli_opts *o)
{
	char dir[IIO_PATH_MAX], raw_why[200];

	o->backend_auto = true;
	if (!iio_find_device(NULL, dir, sizeof(dir))) {
		o->backend = CLI_BACKEND_IIO;
		return;
	}
	if (!probe_raw(&o->raw, raw_why, sizeof(raw_why))) {
		o->backend = CLI_BACKEND_RAW;
		return;
	}
	o->backend = CLI_BACKEND_NONE;
	snprintf(o->backend_why, sizeof(o->backend_why),
		 "no AS9888 found, nothing done: no %s IIO device is bound (the driver is not bound: load as9888_i2c or as9888_spi with modprobe; if modprobe does not find them, install the driver: dkms install, see README \"Kernel side\"), and no chip answers on the raw bus (%s; load i2c-dev with \"modprobe i2c-dev\", name the bus with --i2c-dev and --i2c-address, and for the pin checks --gpiochip with the line options, libgpiod installed). The simulator runs only when named: --backend sim",
		 IIO_ACCEL_NAME, raw_why);
}
