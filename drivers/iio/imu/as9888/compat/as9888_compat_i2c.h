/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 out-of-tree builds on kernels before 6.3, as9888_i2c.c only (see
 * Kbuild): there the one-argument I2C probe callback is .probe_new, and
 * .probe still takes the i2c_device_id. Every header the file includes is
 * read first, so the rename reaches nothing but the driver's initializer.
 *
 * Not part of the upstream series.
 */
#ifndef AS9888_COMPAT_I2C_H
#define AS9888_COMPAT_I2C_H

#include <linux/bits.h>
#include <linux/build_bug.h>
#include <linux/compiler.h>
#include <linux/err.h>
#include <linux/i2c.h>
#include <linux/mod_devicetable.h>
#include <linux/module.h>
#include <linux/pm.h>
#include <linux/regmap.h>
#include <linux/stddef.h>
#include <linux/types.h>

#define probe				probe_new

#endif /* AS9888_COMPAT_I2C_H */
