/* SPDX-License-Identifier: GPL-2.0 */
/*
 * ALSEN AS9888 6-axis sensor: 3-axis magnetometer, 3-axis accelerometer and
 * temperature sensor. Definitions shared by the core and the bus drivers.
 *
 * The register map and the timing of the datasheet live in as9888_regs.h,
 * which the userspace daemon and the chip model share; this header adds
 * what only the kernel driver needs.
 */
#ifndef AS9888_H
#define AS9888_H

#include <linux/bits.h>
#include <linux/build_bug.h>
#include <linux/compiler.h>
#include <linux/stddef.h>
#include <linux/types.h>

#include "as9888_calib.h"
#include "as9888_regs.h"

struct device;
struct regmap;

#define AS9888_MAX_REG			AS9888_REG_EEPROM_END
static_assert(AS9888_REG_EEPROM + AS9888_EEPROM_LEN - 1 ==
	      AS9888_REG_EEPROM_END);

/* SPI, datasheet section 1: first byte bit 7 set to read, clear to write */
#define AS9888_SPI_READ_MSK		BIT(7)
#define AS9888_SPI_MAX_HZ		5000000

/**
 * struct as9888_raw_sample - one burst read of ST1..ST2 (0x10..0x1f)
 * @st1:	ST1: DRDY, DOR
 * @magn:	HXL..HZH, 13-bit two's complement sign-extended to 16 bit
 * @tmps:	temperature code
 * @empt:	reserved, 0x00 on a healthy device
 * @accel:	A1XL..A1ZH, 12-bit two's complement sign-extended to 16 bit
 * @st2:	ST2: HST, HOFL; reading it ends the data read
 */
struct as9888_raw_sample {
	u8 st1;
	__le16 magn[AS9888_AXES];
	u8 tmps;
	u8 empt;
	__le16 accel[AS9888_AXES];
	u8 st2;
} __packed;
static_assert(sizeof(struct as9888_raw_sample) == AS9888_SAMPLE_LEN);
static_assert(offsetof(struct as9888_raw_sample, magn) ==
	      AS9888_REG_HXL - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, tmps) ==
	      AS9888_REG_TMPS - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, empt) ==
	      AS9888_REG_EMPT - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, accel) ==
	      AS9888_REG_A1XL - AS9888_REG_ST1);
static_assert(offsetof(struct as9888_raw_sample, st2) ==
	      AS9888_REG_ST2 - AS9888_REG_ST1);

extern const struct regmap_config as9888_i2c_regmap_config;
extern const struct regmap_config as9888_spi_regmap_config;
extern const struct dev_pm_ops as9888_pm_ops;

int as9888_core_probe(struct device *dev, struct regmap *regmap, int irq);

#endif /* AS9888_H */
