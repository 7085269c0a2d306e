// SPDX-License-Identifier: GPL-2.0
/*
 * ALSEN AS9888 6-axis sensor: probe and power management of the core
 * driver, shared by the I2C and SPI drivers.
 *
 * Probe powers the chip up with a reset pulse, loads its factory trim and
 * makes the accelerometer and magnetometer IIO devices (as9888_accel.c,
 * as9888_magn.c) and the data-ready trigger (as9888_trigger.c), then
 * registers both devices. Runtime PM switches the supplies off while the
 * chip is unused and restores its registers at power-up.
 *
 * Factory trim comes from an EEPROM that is readable only in EEPROM access
 * mode; it is read once at probe and decoded with the shared calibration
 * arithmetic of as9888_calib.c.
 */

#include <linux/array_size.h>
#include <linux/bitmap.h>
#include <linux/bits.h>
#include <linux/cleanup.h>
#include <linux/completion.h>
#include <linux/delay.h>
#include <linux/device.h>
#include <linux/err.h>
#include <linux/gpio/consumer.h>
#include <linux/interrupt.h>
#include <linux/ktime.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/nvmem-provider.h>
#include <linux/pm.h>
#include <linux/pm_runtime.h>
#include <linux/property.h>
#include <linux/regmap.h>
#include <linux/regulator/consumer.h>
#include <linux/string.h>
#include <linux/types.h>
#include <linux/wait.h>

#include <linux/iio/iio.h>

#include "as9888_core.h"

#define AS9888_DRV_NAME			"as9888"

/*
 * RSTN low time: twice t_RSTL, so that a delay that ends a little early
 * (udelay() is calibrated, not measured) still makes a valid pulse
 */
#define AS9888_RSTL_US			(2 * AS9888_T_RSTL_US)

#define AS9888_AUTOSUSPEND_MS		2000

static const char * const as9888_supply_names[AS9888_SUPPLIES] = {
	"vdd", "vid",
};

/* Power, reset and the factory trim */

/*
 * Supplies on, then RSTN released: RSTN is held low while the supplies are
 * off (as9888_power_cut()), so every power-up is also a reset pulse of at
 * least t_RSTL. The chip answers t_BOOT after RSTN rises (or after
 * power-on, without a reset GPIO), in power-down.
 */
static int as9888_power_on(struct as9888_chip *chip)
{
	int ret;

	ret = regulator_bulk_enable(ARRAY_SIZE(chip->supplies), chip->supplies);
	if (ret)
		return ret;

	if (chip->reset) {
		fsleep(AS9888_RSTL_US);
		gpiod_set_value_cansleep(chip->reset, 0);
	}

	/* The chip NAKs (I2C) or reads 0xff (SPI) until it has booted */
	fsleep(AS9888_T_BOOT_US);
	/* It boots into power-down */
	chip->pd_since = ktime_get();

	return 0;
}

/*
 * RSTN low, then the supplies off: a logic-high RSTN would feed the
 * unpowered chip through its input protection (as ak8975_power_off()).
 * When the supplies cannot be switched off, RSTN is released again: the
 * chip then needs a register restore (its registers are at their reset
 * values after the pulse).
 */
static int as9888_power_cut(struct as9888_chip *chip)
{
	int ret;

	gpiod_set_value_cansleep(chip->reset, 1);

	ret = regulator_bulk_disable(ARRAY_SIZE(chip->supplies),
				     chip->supplies);
	if (ret && chip->reset) {
		fsleep(AS9888_RSTL_US);
		gpiod_set_value_cansleep(chip->reset, 0);
		fsleep(AS9888_T_BOOT_US);
		chip->pd_since = ktime_get();
	}

	return ret;
}

static void as9888_power_off(void *arg)
{
	struct as9888_chip *chip = arg;

	if (pm_runtime_status_suspended(chip->dev))
		return;

	as9888_power_cut(chip);
	pm_runtime_set_suspended(chip->dev);
}

/*
 * RSTN is taken asserted before the supplies are switched on, and released
 * by as9888_power_on(): probe starts with a reset pulse, whatever state the
 * chip was left in.
 */
static int as9888_power_init(struct as9888_chip *chip)
{
	struct device *dev = chip->dev;
	unsigned int i;
	int ret;

	chip->reset = devm_gpiod_get_optional(dev, "reset", GPIOD_OUT_HIGH);
	if (IS_ERR(chip->reset))
		return dev_err_probe(dev, PTR_ERR(chip->reset),
				     "cannot get reset GPIO\n");

	for (i = 0; i < ARRAY_SIZE(chip->supplies); i++)
		chip->supplies[i].supply = as9888_supply_names[i];

	ret = devm_regulator_bulk_get(dev, ARRAY_SIZE(chip->supplies),
				      chip->supplies);
	if (ret)
		return dev_err_probe(dev, ret, "cannot get regulators\n");

	ret = as9888_power_on(chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable regulators\n");

	/* Runtime PM status tells as9888_power_off() whether power is on */
	ret = pm_runtime_set_active(dev);
	if (ret) {
		as9888_power_cut(chip);
		return dev_err_probe(dev, ret, "cannot set runtime PM status\n");
	}

	return devm_add_action_or_reset(dev, as9888_power_off, chip);
}

/* The whole EEPROM in one burst, in EEPROM access mode */
static int as9888_read_eeprom(struct as9888_chip *chip,
			      u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = chip->dev;
	int ret, ret_pd;

	as9888_wait_pd(chip);
	ret = regmap_write(chip->regmap, AS9888_REG_MS, AS9888_MS_EEPROM);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enter EEPROM mode\n");

	fsleep(AS9888_T_EEP_US);
	ret = regmap_bulk_read(chip->regmap, AS9888_REG_EEPROM, raw,
			       AS9888_EEPROM_LEN);

	/* EEPROM access mode is left only by writing power-down */
	ret_pd = as9888_power_down(chip);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read EEPROM\n");
	if (ret_pd)
		return dev_err_probe(dev, ret_pd,
				     "cannot leave EEPROM mode\n");

	return 0;
}

static int as9888_decode_eeprom(struct as9888_chip *chip,
				const u8 raw[AS9888_EEPROM_LEN])
{
	struct device *dev = chip->dev;
	unsigned long bits;
	unsigned int bit;
	int ret;

	ret = as9888_eeprom_decode(raw, &chip->ee);

	bits = chip->ee.errors;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(chip->ee.errors))
		dev_err(dev, "%s\n", as9888_ee_error_str(BIT(bit)));
	if (ret)
		return dev_err_probe(dev, ret, "unusable factory EEPROM %*ph\n",
				     AS9888_EEPROM_LEN, raw);

	bits = chip->ee.warnings;
	for_each_set_bit(bit, &bits, BITS_PER_TYPE(chip->ee.warnings))
		dev_warn(dev, "%s\n", as9888_ee_warning_str(BIT(bit)));

	return 0;
}

/*
 * The trim registers from the EEPROM, in one write checked by an uncached
 * read-back (as9888_write_trim())
 */
static int as9888_load_trim(struct as9888_chip *chip)
{
	const struct as9888_eeprom *ee = &chip->ee;
	u8 trim[AS9888_TRIM_LEN] = {
		[AS9888_REG_REF1 - AS9888_REG_REF1] = ee->ref1,
		[AS9888_REG_REF2 - AS9888_REG_REF1] = ee->ref2,
		[AS9888_REG_REF3 - AS9888_REG_REF1] = ee->ref3,
		[AS9888_REG_OSC - AS9888_REG_REF1] = ee->osc,
	};
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		trim[AS9888_REG_AGA(axis) - AS9888_REG_REF1] = ee->axis[axis].ga;
		trim[AS9888_REG_ADA(axis) - AS9888_REG_REF1] = ee->axis[axis].da;
	}

	guard(mutex)(&chip->lock);

	ret = as9888_write_trim(chip, AS9888_REG_REF1, trim, sizeof(trim));
	if (ret)
		return dev_err_probe(chip->dev, ret, "cannot load trim\n");

	return 0;
}

static int as9888_chip_init(struct as9888_chip *chip)
{
	u8 raw[AS9888_EEPROM_LEN];
	unsigned int wia;
	int ret;

	ret = regmap_read(chip->regmap, AS9888_REG_WIA, &wia);
	if (ret)
		return dev_err_probe(chip->dev, ret, "cannot read WIA\n");
	/*
	 * An unknown ID is not an error: a compatible part whose firmware
	 * node names "alsen,as9888" as its fallback compatible is to probe
	 */
	if (wia != AS9888_WIA_VAL)
		dev_info(chip->dev, "WIA reads 0x%02x, expected 0x%02x\n",
			 wia, AS9888_WIA_VAL);

	ret = as9888_read_eeprom(chip, raw);
	if (ret)
		return ret;

	ret = as9888_decode_eeprom(chip, raw);
	if (ret)
		return ret;

	return as9888_load_trim(chip);
}

/*
 * The EEPROM as a read-only NVMEM device, a child of the bus device; reads
 * are served from the copy taken at probe
 */
static int as9888_nvmem_read(void *priv, unsigned int offset, void *val,
			     size_t bytes)
{
	struct as9888_chip *chip = priv;

	if (offset >= AS9888_EEPROM_LEN || bytes > AS9888_EEPROM_LEN - offset)
		return -EINVAL;

	memcpy(val, &chip->ee.raw[offset], bytes);

	return 0;
}

static int as9888_nvmem_register(struct as9888_chip *chip)
{
	struct nvmem_config config = {
		.dev = chip->dev,
		.name = AS9888_DRV_NAME "-eeprom",
		.id = NVMEM_DEVID_AUTO,
		.owner = THIS_MODULE,
		.type = NVMEM_TYPE_EEPROM,
		.read_only = true,
		.ignore_wp = true,
		.word_size = 1,
		.stride = 1,
		.size = AS9888_EEPROM_LEN,
		.reg_read = as9888_nvmem_read,
		.priv = chip,
	};
	struct nvmem_device *nvmem;

	if (!IS_ENABLED(CONFIG_NVMEM))
		return 0;

	nvmem = devm_nvmem_register(chip->dev, &config);
	if (IS_ERR(nvmem))
		return dev_err_probe(chip->dev, PTR_ERR(nvmem),
				     "cannot register EEPROM\n");

	return 0;
}

static const struct as9888_int_pin as9888_int_pins[] = {
	{ "INT1", AS9888_REG_INT1EN, AS9888_REG_INT1ST },
	{ "INT2", AS9888_REG_INT2EN, AS9888_REG_INT2ST },
};

/*
 * The data-ready interrupt. Without interrupt-names, the device's (first)
 * interrupt is INT1, and no interrupt means ST1 is polled. With
 * interrupt-names, INT1 is taken when it is named, else INT2 (a board that
 * wires INT2 only, as bmi323 and kx022a allow); a named interrupt that
 * cannot be got is a firmware error that fails probe, never a silent fall
 * back to polling. fwnode_irq_get_byname() returns -ENODATA for a name
 * that interrupt-names does not list.
 */
static int as9888_get_irq(struct as9888_chip *chip, int bus_irq)
{
	struct device *dev = chip->dev;
	struct fwnode_handle *fwnode = dev_fwnode(dev);
	const struct as9888_int_pin *pin;
	unsigned int i;
	int irq;

	chip->int_pin = &as9888_int_pins[0];
	if (!fwnode || !fwnode_property_present(fwnode, "interrupt-names"))
		return bus_irq > 0 ? bus_irq : 0;

	for (i = 0; i < ARRAY_SIZE(as9888_int_pins); i++) {
		pin = &as9888_int_pins[i];
		irq = fwnode_irq_get_byname(fwnode, pin->name);
		if (irq == -ENODATA)
			continue;
		if (irq < 0)
			return dev_err_probe(dev, irq, "cannot get interrupt %s\n",
					     pin->name);

		chip->int_pin = pin;
		return irq;
	}

	return dev_err_probe(dev, -EINVAL,
			     "interrupt-names names neither INT1 nor INT2\n");
}

/* Both IIO devices appear only when the whole chip is set up */
static int as9888_register(struct as9888_chip *chip)
{
	enum as9888_sensor_id id;
	int ret;

	for (id = 0; id < AS9888_SENSORS; id++) {
		ret = devm_iio_device_register(chip->dev, chip->iio[id]);
		if (ret)
			return dev_err_probe(chip->dev, ret,
					     "cannot register IIO device\n");
	}

	as9888_magn_debugfs_init(chip->iio[AS9888_MAGN]);

	return 0;
}

int as9888_core_probe(struct device *dev, struct regmap *regmap, int irq)
{
	struct as9888_chip *chip;
	int ret;

	chip = devm_kzalloc(dev, sizeof(*chip), GFP_KERNEL);
	if (!chip)
		return -ENOMEM;

	chip->dev = dev;
	chip->regmap = regmap;
	init_completion(&chip->drdy);
	init_waitqueue_head(&chip->gap_wq);
	dev_set_drvdata(dev, chip);

	ret = devm_mutex_init(dev, &chip->lock);
	if (ret)
		return ret;

	ret = devm_mutex_init(dev, &chip->int_lock);
	if (ret)
		return ret;

	ret = iio_read_mount_matrix(dev, &chip->orientation);
	if (ret)
		return dev_err_probe(dev, ret, "cannot read mount matrix\n");

	ret = as9888_power_init(chip);
	if (ret)
		return ret;

	ret = as9888_chip_init(chip);
	if (ret)
		return ret;

	irq = as9888_get_irq(chip, irq);
	if (irq < 0)
		return irq;
	/* Known before the channels are: sampling_frequency needs it */
	chip->irq = irq;

	chip->iio[AS9888_ACCEL] = as9888_sensor_alloc(chip, &as9888_accel_desc);
	if (IS_ERR(chip->iio[AS9888_ACCEL]))
		return PTR_ERR(chip->iio[AS9888_ACCEL]);

	chip->iio[AS9888_MAGN] = as9888_sensor_alloc(chip, &as9888_magn_desc);
	if (IS_ERR(chip->iio[AS9888_MAGN]))
		return PTR_ERR(chip->iio[AS9888_MAGN]);
	as9888_magn_init(chip->iio[AS9888_MAGN]);

	if (irq) {
		ret = as9888_trigger_setup(chip);
		if (ret)
			return ret;
	}

	ret = as9888_nvmem_register(chip);
	if (ret)
		return ret;

	pm_runtime_set_autosuspend_delay(dev, AS9888_AUTOSUSPEND_MS);
	pm_runtime_use_autosuspend(dev);
	ret = devm_pm_runtime_enable(dev);
	if (ret)
		return dev_err_probe(dev, ret, "cannot enable runtime PM\n");

	return as9888_register(chip);
}
EXPORT_SYMBOL_NS_GPL(as9888_core_probe, "IIO_AS9888");

/* Power management */

/*
 * Under the chip's lock, so that no register access sequence is cut in the
 * middle: after this, the registers are served from the cache (the trim,
 * the DAC and the interrupt set-up, rewritten on resume) and every other
 * access fails without reaching the bus.
 *
 * When the supplies cannot be switched off, the chip stays powered, but
 * RSTN was pulsed (see as9888_power_cut()) and its registers are at their
 * reset values: they are restored and the device stays active. That is
 * -EAGAIN for the PM core: the device is fine, suspend may be tried again.
 * Any other error would be kept as the device's runtime PM error, and every
 * later runtime resume would fail until the driver is bound again.
 */
static int as9888_runtime_suspend(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	guard(mutex)(&chip->lock);

	regcache_cache_only(chip->regmap, true);
	regcache_mark_dirty(chip->regmap);

	ret = as9888_power_cut(chip);
	if (!ret)
		return 0;

	regcache_cache_only(chip->regmap, false);
	as9888_wait_pd(chip);
	ret = regcache_sync(chip->regmap);
	if (ret) {
		dev_err(dev, "cannot restore the registers after a failed power-off: %d\n",
			ret);
		return ret;
	}

	return -EAGAIN;
}

/*
 * Power returns (with a reset pulse, see as9888_power_on()), so the chip
 * has lost its trim, DAC and interrupt setup: after t_BOOT, rewrite them
 * from the register cache, in power-down.
 */
static int as9888_runtime_resume(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	guard(mutex)(&chip->lock);

	ret = as9888_power_on(chip);
	if (ret)
		return ret;

	regcache_cache_only(chip->regmap, false);
	as9888_wait_pd(chip);
	ret = regcache_sync(chip->regmap);
	if (ret) {
		regcache_cache_only(chip->regmap, true);
		as9888_power_cut(chip);
	}

	return ret;
}

/*
 * System sleep: as9888_trig_suspend() stops a running data-ready trigger
 * and makes every measurement fail with -EBUSY until resume, so a buffer
 * on another trigger (whose handler may still run until the interrupts
 * are suspended) touches no register; the data-ready interrupt is
 * disabled, which also waits for a handler in flight; then the supplies
 * go off.
 */
static int as9888_suspend(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	as9888_trig_suspend(chip);
	if (chip->irq)
		disable_irq(chip->irq);

	ret = pm_runtime_force_suspend(dev);
	if (ret) {
		if (chip->irq)
			enable_irq(chip->irq);
		as9888_trig_resume(chip);
	}

	return ret;
}

/*
 * Measurements are allowed again even when the power-up failed: the device
 * is then left runtime suspended (see pm_runtime_force_resume()), so the
 * next runtime resume, on the next access, tries again. A data-ready
 * trigger that ran is not restarted on the unpowered chip; its buffer gets
 * samples again once it is disabled and enabled.
 */
static int as9888_resume(struct device *dev)
{
	struct as9888_chip *chip = dev_get_drvdata(dev);
	int ret;

	ret = pm_runtime_force_resume(dev);
	if (chip->irq)
		enable_irq(chip->irq);
	if (ret) {
		scoped_guard(mutex, &chip->lock)
			chip->suspended = false;
		return ret;
	}

	return as9888_trig_resume(chip);
}

EXPORT_NS_GPL_DEV_PM_OPS(as9888_pm_ops, IIO_AS9888) = {
	SYSTEM_SLEEP_PM_OPS(as9888_suspend, as9888_resume)
	RUNTIME_PM_OPS(as9888_runtime_suspend, as9888_runtime_resume, NULL)
};

MODULE_DESCRIPTION("ALSEN AS9888 accelerometer/magnetometer core driver");
MODULE_LICENSE("GPL");
