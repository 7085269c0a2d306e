/* SPDX-License-Identifier: GPL-2.0 */
/*
 * ALSEN AS9888 6-axis sensor: 3-axis magnetometer, 3-axis accelerometer and
 * temperature sensor. The interface between the core and the bus drivers.
 */
#ifndef AS9888_H
#define AS9888_H

#include <linux/bits.h>
#include <linux/pm.h>

#include "as9888_regs.h"

struct device;
struct regmap;
struct regmap_config;

/* SPI, datasheet section 1: first byte bit 7 set to read, clear to write */
#define AS9888_SPI_READ_MSK		BIT(7)

extern const struct regmap_config as9888_i2c_regmap_config;
extern const struct regmap_config as9888_spi_regmap_config;
extern const struct dev_pm_ops as9888_pm_ops;

int as9888_core_probe(struct device *dev, struct regmap *regmap, int irq);

#endif /* AS9888_H */
