// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: SPI driver.
 *
 * Mode 3, up to 5 MHz, 4-wire: the mode and the clock are the firmware's to
 * describe (spi-cpol, spi-cpha, spi-max-frequency, which the binding caps
 * at 5 MHz). The first byte carries the register address in bits 6:0 and
 * the direction in bit 7 (set: read, clear: write); the address
 * auto-increments on bursts.
 */

#include <linux/err.h>
#include <linux/mod_devicetable.h>
#include <linux/module.h>
#include <linux/pm.h>
#include <linux/regmap.h>
#include <linux/spi/spi.h>

#include "as9888.h"

static int as9888_spi_probe(struct spi_device *spi)
{
	struct regmap *regmap;

	regmap = devm_regmap_init_spi(spi, &as9888_spi_regmap_config);
	if (IS_ERR(regmap))
		return dev_err_probe(&spi->dev, PTR_ERR(regmap),
				     "cannot initialize regmap\n");

	return as9888_core_probe(&spi->dev, regmap, spi->irq);
}

static const struct spi_device_id as9888_spi_id[] = {
	{ "as9888" },
	{ }
};
MODULE_DEVICE_TABLE(spi, as9888_spi_id);

static const struct of_device_id as9888_spi_of_match[] = {
	{ .compatible = "alsen,as9888" },
	{ }
};
MODULE_DEVICE_TABLE(of, as9888_spi_of_match);

static struct spi_driver as9888_spi_driver = {
	.driver = {
		.name = "as9888_spi",
		.of_match_table = as9888_spi_of_match,
		.pm = pm_ptr(&as9888_pm_ops),
	},
	.probe = as9888_spi_probe,
	.id_table = as9888_spi_id,
};
module_spi_driver(as9888_spi_driver);

MODULE_DESCRIPTION("ALSEN AS9888 accelerometer/magnetometer SPI driver");
MODULE_LICENSE("GPL");
MODULE_IMPORT_NS("IIO_AS9888");
