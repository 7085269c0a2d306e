// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: I2C driver.
 *
 * 7-bit address 0x0c..0x0f (CAD1, CAD0), up to 400 kHz; the register
 * address auto-increments on bursts.
 */

#include <linux/err.h>
#include <linux/i2c.h>
#include <linux/mod_devicetable.h>
#include <linux/module.h>
#include <linux/pm.h>
#include <linux/regmap.h>

#include "as9888.h"

static int as9888_i2c_probe(struct i2c_client *client)
{
	struct regmap *regmap;

	regmap = devm_regmap_init_i2c(client, &as9888_i2c_regmap_config);
	if (IS_ERR(regmap))
		return dev_err_probe(&client->dev, PTR_ERR(regmap),
				     "cannot initialize regmap\n");

	return as9888_core_probe(&client->dev, regmap, client->irq);
}

static const struct i2c_device_id as9888_i2c_id[] = {
	{ "as9888" },
	{ }
};
MODULE_DEVICE_TABLE(i2c, as9888_i2c_id);

static const struct of_device_id as9888_i2c_of_match[] = {
	{ .compatible = "alsen,as9888" },
	{ }
};
MODULE_DEVICE_TABLE(of, as9888_i2c_of_match);

static struct i2c_driver as9888_i2c_driver = {
	.driver = {
		.name = "as9888_i2c",
		.of_match_table = as9888_i2c_of_match,
		.pm = pm_ptr(&as9888_pm_ops),
	},
	.probe = as9888_i2c_probe,
	.id_table = as9888_i2c_id,
};
module_i2c_driver(as9888_i2c_driver);

MODULE_DESCRIPTION("ALSEN AS9888 accelerometer/magnetometer I2C driver");
MODULE_LICENSE("GPL");
MODULE_IMPORT_NS("IIO_AS9888");
