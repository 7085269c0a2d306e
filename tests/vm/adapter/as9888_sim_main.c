// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 test adapter: the shared chip model (tests/model) on a simulated
 * board, for the real-kernel test bench.
 *
 * The module presents one AS9888 the way a board would:
 *  - an I2C adapter "as9888-sim-i2c" on which the chip answers at 0x0c;
 *    a write message [reg, data...] is one model write, a write of the
 *    register followed by a read (repeated start) is one model read, a
 *    lone read continues at the auto-incremented address. A transfer the
 *    model NAKs (boot time, RSTN low, the "nak" fault) fails with -ENXIO.
 *  - a GPIO chip "as9888-sim-gpio" with the lines AS9888_RSTN (the chip's
 *    reset input: a consumer drives it), AS9888_INT1 and AS9888_INT2 (the
 *    chip's outputs, with interrupts from the kernel's interrupt
 *    simulator, edge triggered).
 *  - with the module parameter spi=1, an SPI controller (mode 3): a message is one chip
 *    select; its first byte is R/W + register, the rest the data. The
 *    model is then in SPI mode (a failed transfer reads 0xff).
 *  - a regulator "as9888-sim-supply" that is the chip's vdd and vid: when
 *    its last consumer disables it the chip loses power (registers to
 *    reset values, no answer on the bus) and boots again when it is
 *    enabled, as on a board that switches the sensor's supply.
 *  - the device "as9888" at 0x0c (or on SPI chip select 0 with the module
 *    parameter spi=1) with INT1 as its interrupt, RSTN as its
 *    reset-gpios (software node reference where gpiolib supports it, a GPIO
 *    lookup table otherwise) and a mount matrix.
 * The model runs in real time: an hrtimer is armed at the model's next
 * internal event, advances the model and raises INT1/INT2 on their edges.
 *
 * Control and measurement in debugfs, directory as9888_sim/:
 *  unit	write a unit description (datasheet section 8): parsed, the
 *		device removed, the chip powered on as that unit and the
 *		device instantiated again; read: the description in use
 *  present	"1": instantiate the device (after a power cycle of the
 *		chip), "0": remove it; read: 0/1
 *  stats	bus and chip counters; any write zeroes the bus counters
 *  regs	the chip's configuration and trim registers as it holds them
 *		("0xRR 0xVV" per line), read without a bus transfer
 *  bus		"i2c-N" of the adapter, and the client name
 *  drop_int1	write N: the next N INT1 edges are not delivered (a glitch,
 *		an edge lost by the interrupt controller); counted in stats
 *		as irqs_dropped; read: how many are still to be dropped
 *  wiring	how the chip's interrupt reaches the driver; writing one
 *		re-instantiates the device (after a power cycle of the
 *		chip): "int1" (the default) INT1 as the device's interrupt,
 *		rising edge; "int1-level" INT1 as a level-high interrupt of
 *		the adapter's own interrupt controller, which raises it again
 *		when it is unmasked while INT1 is still high, as a level
 *		interrupt does (the interrupt simulator has edges only);
 *		"bad" as "int1" plus interrupt-names = "INT1" on the software
 *		node, whose interrupts no one can get (a malformed
 *		specifier); "int2" INT2 only, rising edge, named "INT2" in
 *		interrupt-names, as a board that wires INT2 alone describes
 *		it (INT1 goes nowhere); read: the wiring in use
 *  fail_next	write N: the next N bus transfers fail (I2C NAK, SPI error)
 *		without reaching the chip; read: how many are left
 *  fail_supply_on, fail_supply_off
 *		write N: the next N times the supply is to be switched on
 *		(off), the regulator fails with -EIO and the chip keeps its
 *		power state; read: how many are left
 *  delay_int1_us write N: every INT1 edge from now on reaches the interrupt
 *		controller N microseconds after the pin rose (a slow
 *		interrupt path, a host that deschedules the guest); 0 (the
 *		default) delivers them at once. An edge that comes while an
 *		earlier one is still held is delivered with it, as a
 *		controller that latches one pending edge does; counted in
 *		stats as irqs_delayed. Read: the delay in use
 *  glitch_int1	write anything: one INT1 edge now, whatever the chip does (a
 *		glitch on the line, the pin of a chip without power)
 * Live environment, without re-creating the chip or the device (registers,
 * a running measurement and the counters stay; every measurement that
 * completes after the write uses the new value; it also holds for a chip
 * powered on again through "present" or the supply, until the next "unit"):
 *  temperature	die temperature, degC, as the unit file's "temperature"
 *		value (up to 3 decimals, -50..150); read: the temperature now
 *		(with the unit's drift, which continues from a written value)
 *  up		posture, as the unit file's "up" value (three numbers, any
 *		scale, normalised); read: the normalised vector, 6 decimals
 *  noise	accelerometer noise, LSB rms, as the unit file's "noise"
 * and the magnetic world, each as the unit file's key of the same name
 * (tests/model/as9888_unit.h):
 *  heading	deg, the turn about the world's up after the tilt of "up"
 *  orientation	w x y z, the sensor-to-world quaternion (replaces up and
 *		heading); read: the orientation now (it moves with tumble)
 *  earth	F I D: the Earth's field, uT, inclination and declination
 *		in deg; the field then turns with the orientation
 *  hard_iron	x y z, uT; soft_iron 9 values, row major
 *  magn_noise	uT rms per axis
 *  disturbance	x y z n: a magnet passing by over the next n magnetometer
 *		measurements, starting now (n = 0: a constant field)
 *  tumble	deg per measurement of seeded random motion (0 stops it)
 * "up" reads the posture now (it moves with tumble and orientation).
 */

#include <linux/debugfs.h>
#include <linux/gpio/driver.h>
#include <linux/gpio/machine.h>
#include <linux/hrtimer.h>
#include <linux/i2c.h>
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/irq_sim.h>
#include <linux/irq_work.h>
#include <linux/irqdomain.h>
#include <linux/ktime.h>
#include <linux/math64.h>
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/platform_device.h>
#include <linux/property.h>
#include <linux/regulator/driver.h>
#include <linux/regulator/machine.h>
#include <linux/slab.h>
#include <linux/spi/spi.h>
#include <linux/spinlock.h>
#include <linux/uaccess.h>
#include <linux/version.h>

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 2, 0)
#include <linux/gpio/property.h>
#define AS9888_SIM_SWNODE_GPIO	1
#endif

#include "as9888_model.h"
#include "as9888_unit.h"

#define AS9888_SIM_ADDR		0x0c
#define AS9888_SIM_UNIT_MAX	4096

/* The debugfs files that change the environment live */
enum as9888_sim_knob_id {
	AS9888_SIM_KNOB_TEMPERATURE = 0,
	AS9888_SIM_KNOB_UP,
	AS9888_SIM_KNOB_NOISE,
	AS9888_SIM_KNOB_HEADING,
	AS9888_SIM_KNOB_ORIENTATION,
	AS9888_SIM_KNOB_EARTH,
	AS9888_SIM_KNOB_HARD_IRON,
	AS9888_SIM_KNOB_SOFT_IRON,
	AS9888_SIM_KNOB_MAGN_NOISE,
	AS9888_SIM_KNOB_DISTURBANCE,
	AS9888_SIM_KNOB_TUMBLE,
	AS9888_SIM_NKNOBS,
};

static const char *const as9888_sim_knob_keys[AS9888_SIM_NKNOBS] = {
	"temperature", "up", "noise", "heading", "orientation", "earth",
	"hard_iron", "soft_iron", "magn_noise", "disturbance", "tumble",
};

enum as9888_sim_wiring {
	AS9888_SIM_WIRING_INT1 = 0,
	AS9888_SIM_WIRING_INT1_LEVEL,
	AS9888_SIM_WIRING_BAD,
	AS9888_SIM_WIRING_INT2,
	AS9888_SIM_NWIRINGS,
};

static const char *const as9888_sim_wiring_names[AS9888_SIM_NWIRINGS] = {
	"int1", "int1-level", "bad", "int2",
};

/* Longest value accepted by a knob (soft_iron: nine numbers) */
#define AS9888_SIM_KNOB_MAX	160

struct as9888_sim;

/**
 * struct as9888_sim_knob - one live environment file
 * @s:		the board
 * @id:		which one
 */
struct as9888_sim_knob {
	struct as9888_sim *s;
	enum as9888_sim_knob_id id;
};

enum as9888_sim_line {
	AS9888_SIM_RSTN = 0,
	AS9888_SIM_INT1,
	AS9888_SIM_INT2,
	AS9888_SIM_NLINES,
};

static const char *const as9888_sim_line_names[AS9888_SIM_NLINES] = {
	"AS9888_RSTN", "AS9888_INT1", "AS9888_INT2",
};

/**
 * struct as9888_sim - the simulated board
 * @lock:	protects @model, @pin, @rises, @rstn, @ptr and the bus counters;
 *		taken in the hrtimer (hard irq) and in process context
 * @model:	the chip
 * @pin:	INT1/INT2 levels last seen (edge detection)
 * @rises:	INT1/INT2 rise counts of the model last seen: a pulse that
 *		fell and rose again between two looks is an edge too
 * @rstn:	RSTN level driven by the consumer
 * @ptr:	register address for a read without a preceding write
 * @xfers:	master_xfer calls and SPI messages
 * @msgs:	I2C messages
 * @model_xfers: model transfers (reads + writes) since the last zeroing
 * @model_naks:	failed model transfers since the last zeroing
 * @irqs:	INT edges delivered to the interrupt simulator
 * @irqs_dropped: INT1 edges not delivered (drop_int1)
 * @drop_int1:	INT1 edges still to drop
 * @fail_next:	bus transfers still to fail
 * @fail_supply_on: switch-ons of the supply still to fail
 * @fail_supply_off: switch-offs of the supply still to fail
 * @delay_int1_us: how late INT1 edges are delivered (delay_int1_us)
 * @irqs_delayed: INT1 edges delivered late
 * @held:	INT1 edges found and not delivered yet (bit 0), under @lock
 * @timer:	wakes up at the model's next event
 * @delay_timer: delivers the INT1 edge held back by @delay_int1_us
 * @cfg_lock:	serialises unit/present changes
 * @unit:	the unit in use
 * @unit_text:	its description (NUL-terminated)
 * @pdev:	parent device of the adapter and the GPIO chip
 * @adap:	the I2C adapter
 * @gc:		the GPIO chip
 * @domain:	the interrupt simulator's domain, one hwirq per line
 * @ctlr:	the SPI controller
 * @client:	the AS9888 on I2C, or NULL
 * @spi:	the AS9888 on SPI, or NULL
 * @dir:	debugfs directory
 * @rdev:	the chip's supply
 * @knobs:	the live environment files of debugfs
 * @wiring:	how INT1 reaches the driver, under @cfg_lock
 * @fwnode:	the firmware node of the device in use
 * @board_fwnode: the firmware node of wiring=int2 (see as9888_sim_board_ops)
 * @lvl_domain:	the level-triggered interrupt controller (one line, INT1)
 * @lvl_work:	raises its interrupt from hard interrupt context
 * @lvl_masked:	its line is masked
 */
struct as9888_sim {
	spinlock_t lock;		/* see @lock above */
	struct as9888_model model;
	bool pin[2];
	u32 rises[2];
	bool rstn;
	u8 ptr;
	u64 xfers;
	u64 msgs;
	u64 model_xfers;
	u64 model_naks;
	u64 irqs;
	u64 irqs_dropped;
	u32 drop_int1;
	u32 fail_next;
	u32 fail_supply_on;
	u32 fail_supply_off;
	u32 delay_int1_us;
	u64 irqs_delayed;
	unsigned int held;
	struct hrtimer timer;
	struct hrtimer delay_timer;

	struct mutex cfg_lock;		/* see @cfg_lock above */
	struct as9888_unit unit;
	char *unit_text;

	struct platform_device *pdev;
	struct i2c_adapter adap;
	struct gpio_chip gc;
	struct irq_domain *domain;
	struct spi_controller *ctlr;
	struct i2c_client *client;
	struct spi_device *spi;
	struct dentry *dir;
	struct regulator_dev *rdev;
	struct as9888_sim_knob knobs[AS9888_SIM_NKNOBS];
	enum as9888_sim_wiring wiring;
	struct fwnode_handle *fwnode;
	struct fwnode_handle board_fwnode;
	struct irq_domain *lvl_domain;
	struct irq_work lvl_work;
	bool lvl_masked;
};

static struct as9888_sim *sim;

static bool spi;
module_param(spi, bool, 0444);
MODULE_PARM_DESC(spi, "put the chip on the SPI controller instead of I2C");

static const struct software_node as9888_sim_gpio_node = {
	.name = "as9888-sim-gpio",
};

static const char * const as9888_sim_mount_matrix[] = {
	"0", "1", "0",
	"-1", "0", "0",
	"0", "0", "1",
};

static const struct property_entry as9888_sim_props[] = {
	PROPERTY_ENTRY_STRING("compatible", "alsen,as9888"),
	PROPERTY_ENTRY_STRING_ARRAY("mount-matrix", as9888_sim_mount_matrix),
#ifdef AS9888_SIM_SWNODE_GPIO
	PROPERTY_ENTRY_GPIO("reset-gpios", &as9888_sim_gpio_node,
			    AS9888_SIM_RSTN, GPIO_ACTIVE_LOW),
#endif
	{ }
};

static const struct software_node as9888_sim_dev_node = {
	.name = "as9888-sim-chip",
	.properties = as9888_sim_props,
};

/* wiring=bad: interrupt-names, but a software node has no interrupts */
static const char * const as9888_sim_bad_int_names[] = { "INT1" };

static const struct property_entry as9888_sim_bad_props[] = {
	PROPERTY_ENTRY_STRING("compatible", "alsen,as9888"),
	PROPERTY_ENTRY_STRING_ARRAY("mount-matrix", as9888_sim_mount_matrix),
	PROPERTY_ENTRY_STRING_ARRAY("interrupt-names", as9888_sim_bad_int_names),
#ifdef AS9888_SIM_SWNODE_GPIO
	PROPERTY_ENTRY_GPIO("reset-gpios", &as9888_sim_gpio_node,
			    AS9888_SIM_RSTN, GPIO_ACTIVE_LOW),
#endif
	{ }
};

static const struct software_node as9888_sim_bad_node = {
	.name = "as9888-sim-chip-bad",
	.properties = as9888_sim_bad_props,
};

/* wiring=int2: the properties of a board that wires INT2 alone */
static const char * const as9888_sim_int2_names[] = { "INT2" };

static const struct property_entry as9888_sim_int2_props[] = {
	PROPERTY_ENTRY_STRING("compatible", "alsen,as9888"),
	PROPERTY_ENTRY_STRING_ARRAY("mount-matrix", as9888_sim_mount_matrix),
	PROPERTY_ENTRY_STRING_ARRAY("interrupt-names", as9888_sim_int2_names),
#ifdef AS9888_SIM_SWNODE_GPIO
	PROPERTY_ENTRY_GPIO("reset-gpios", &as9888_sim_gpio_node,
			    AS9888_SIM_RSTN, GPIO_ACTIVE_LOW),
#endif
	{ }
};

static const struct software_node as9888_sim_int2_node = {
	.name = "as9888-sim-chip-int2",
	.properties = as9888_sim_int2_props,
};

/* Registered in this order, unregistered in the reverse order */
static const struct software_node *as9888_sim_nodes[] = {
	&as9888_sim_gpio_node,
	&as9888_sim_dev_node,
	&as9888_sim_bad_node,
	&as9888_sim_int2_node,
	NULL
};

#ifndef AS9888_SIM_SWNODE_GPIO
static struct gpiod_lookup_table as9888_sim_lookup = {
	/* .dev_id is set once the adapter number is known */
	.table = {
		GPIO_LOOKUP("as9888-sim-gpio", AS9888_SIM_RSTN, "reset",
			    GPIO_ACTIVE_LOW),
		{ }
	},
};

static char as9888_sim_dev_id[32];
#endif

/* --- model, pins and timer (sim->lock held) ----------------------------- */

/* Arm the timer at the model's next event; caller holds sim->lock. */
static void as9888_sim_arm(struct as9888_sim *s)
{
	u64 next = as9888_model_next_event_ns(&s->model);

	if (next == U64_MAX)
		hrtimer_try_to_cancel(&s->timer);
	else
		hrtimer_start(&s->timer, ns_to_ktime(next), HRTIMER_MODE_ABS);
}

/*
 * delay_int1_us: hold an INT1 edge back and deliver it that much later;
 * returns the edges to deliver now. Caller holds sim->lock.
 */
static unsigned int as9888_sim_hold(struct as9888_sim *s, unsigned int fire,
				    u64 now)
{
	u32 delay_us = s->delay_int1_us;

	if (!delay_us || !(fire & BIT(AS9888_PIN_INT1)))
		return fire;
	fire &= ~BIT(AS9888_PIN_INT1);
	s->irqs_delayed++;
	if (!s->held) {
		s->held = BIT(AS9888_PIN_INT1);
		hrtimer_start(&s->delay_timer,
			      ns_to_ktime(now + (u64)delay_us * NSEC_PER_USEC),
			      HRTIMER_MODE_ABS);
	}
	return fire;
}

/*
 * Sample INT1/INT2 at @now and return the lines that need an interrupt:
 * bit n set for line AS9888_SIM_INT1 + n (an INT1 edge that delay_int1_us
 * holds back is not among them). Caller holds sim->lock.
 *
 * The level alone misses a pulse: a transfer that starts a measurement
 * (the MS write deasserts the pin) and is then held up longer than the
 * measurement (the host deschedules the guest) finds the pin high before
 * and after. The model's rise count catches it: on the wire it is a
 * falling and a rising edge.
 */
static unsigned int as9888_sim_edges(struct as9888_sim *s, u64 now)
{
	unsigned int fire = 0;
	int i;

	for (i = 0; i < 2; i++) {
		bool lvl = as9888_model_pin(&s->model, now, i);
		u32 rises = as9888_model_pin_rises(&s->model, i);
		bool rose = rises != s->rises[i];
		bool fell = s->pin[i] && (!lvl || rose);
		unsigned int irq, type;

		if (lvl == s->pin[i] && !rose)
			continue;
		s->pin[i] = lvl;
		s->rises[i] = rises;
		if (i == AS9888_PIN_INT1 &&
		    s->wiring == AS9888_SIM_WIRING_INT1_LEVEL) {
			if (lvl)
				fire |= BIT(i);
			continue;
		}
		irq = irq_find_mapping(s->domain, AS9888_SIM_INT1 + i);
		if (!irq)
			continue;
		type = irq_get_trigger_type(irq);
		if (type == IRQ_TYPE_NONE)
			type = IRQ_TYPE_EDGE_RISING;
		if (!((rose && (type & IRQ_TYPE_EDGE_RISING)) ||
		      (fell && (type & IRQ_TYPE_EDGE_FALLING))))
			continue;
		if (i == AS9888_PIN_INT1 && s->drop_int1) {
			s->drop_int1--;
			s->irqs_dropped++;
			continue;
		}
		fire |= BIT(i);
	}
	return as9888_sim_hold(s, fire, now);
}

/* Deliver the edges found by as9888_sim_edges(); without sim->lock. */
static void as9888_sim_fire(struct as9888_sim *s, unsigned int fire)
{
	unsigned long flags;
	int i;

	for (i = 0; i < 2; i++) {
		unsigned int irq;

		if (!(fire & BIT(i)))
			continue;
		if (i == AS9888_PIN_INT1 &&
		    READ_ONCE(s->wiring) == AS9888_SIM_WIRING_INT1_LEVEL) {
			/* counted when it is raised, also again */
			irq_work_queue(&s->lvl_work);
			continue;
		}
		irq = irq_find_mapping(s->domain, AS9888_SIM_INT1 + i);
		if (!irq)
			continue;
		irq_set_irqchip_state(irq, IRQCHIP_STATE_PENDING, true);
		spin_lock_irqsave(&s->lock, flags);
		s->irqs++;
		spin_unlock_irqrestore(&s->lock, flags);
	}
}

static enum hrtimer_restart as9888_sim_delay_fn(struct hrtimer *t)
{
	struct as9888_sim *s = container_of(t, struct as9888_sim, delay_timer);
	unsigned int fire;
	unsigned long flags;

	spin_lock_irqsave(&s->lock, flags);
	fire = s->held;
	s->held = 0;
	spin_unlock_irqrestore(&s->lock, flags);

	as9888_sim_fire(s, fire);
	return HRTIMER_NORESTART;
}

static enum hrtimer_restart as9888_sim_timer_fn(struct hrtimer *t)
{
	struct as9888_sim *s = container_of(t, struct as9888_sim, timer);
	unsigned int fire;
	unsigned long flags;
	u64 now;

	spin_lock_irqsave(&s->lock, flags);
	now = ktime_get_ns();
	as9888_model_advance(&s->model, now);
	fire = as9888_sim_edges(s, now);
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);

	as9888_sim_fire(s, fire);
	return HRTIMER_NORESTART;
}

/* An absolute CLOCK_MONOTONIC hrtimer calling @fn */
static void as9888_sim_timer_setup(struct hrtimer *t,
				   enum hrtimer_restart (*fn)(struct hrtimer *))
{
#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 13, 0)
	hrtimer_setup(t, fn, CLOCK_MONOTONIC, HRTIMER_MODE_ABS);
#else
	hrtimer_init(t, CLOCK_MONOTONIC, HRTIMER_MODE_ABS);
	t->function = fn;
#endif
}

/* Power the chip on as @unit; caller holds cfg_lock, device removed. */
static void as9888_sim_power_on(struct as9888_sim *s)
{
	unsigned long flags;

	spin_lock_irqsave(&s->lock, flags);
	as9888_model_init(&s->model, &s->unit, ktime_get_ns());
	as9888_model_set_bus(&s->model, spi ? AS9888_BUS_SPI : AS9888_BUS_I2C);
	s->pin[0] = false;
	s->pin[1] = false;
	s->rises[0] = 0;
	s->rises[1] = 0;
	s->ptr = 0;
	if (!s->rstn)
		as9888_model_set_rstn(&s->model, ktime_get_ns(), false);
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);
}

/* --- level-triggered interrupt controller (wiring=int1-level) --------------- */

/* Raise the level line, when it is high and unmasked; hard irq context */
static void as9888_sim_lvl_work(struct irq_work *work)
{
	struct as9888_sim *s = container_of(work, struct as9888_sim, lvl_work);
	unsigned int irq = irq_find_mapping(s->lvl_domain, 0);

	if (!irq || READ_ONCE(s->lvl_masked) || !READ_ONCE(s->pin[0]))
		return;
	spin_lock(&s->lock);
	s->irqs++;
	spin_unlock(&s->lock);
	generic_handle_irq(irq);
}

static void as9888_sim_lvl_mask(struct irq_data *d)
{
	struct as9888_sim *s = irq_data_get_irq_chip_data(d);

	WRITE_ONCE(s->lvl_masked, true);
}

/* A level interrupt unmasked while its line is still high fires again */
static void as9888_sim_lvl_unmask(struct irq_data *d)
{
	struct as9888_sim *s = irq_data_get_irq_chip_data(d);

	WRITE_ONCE(s->lvl_masked, false);
	if (READ_ONCE(s->pin[0]))
		irq_work_queue(&s->lvl_work);
}

static int as9888_sim_lvl_set_type(struct irq_data *d, unsigned int type)
{
	return type == IRQ_TYPE_LEVEL_HIGH ? 0 : -EINVAL;
}

static struct irq_chip as9888_sim_lvl_chip = {
	.name = "as9888-sim-level",
	.irq_mask = as9888_sim_lvl_mask,
	.irq_unmask = as9888_sim_lvl_unmask,
	.irq_set_type = as9888_sim_lvl_set_type,
};

static int as9888_sim_lvl_map(struct irq_domain *d, unsigned int virq,
			      irq_hw_number_t hw)
{
	irq_set_chip_data(virq, d->host_data);
	irq_set_chip_and_handler(virq, &as9888_sim_lvl_chip, handle_level_irq);
	return 0;
}

static const struct irq_domain_ops as9888_sim_lvl_ops = {
	.map = as9888_sim_lvl_map,
	.xlate = irq_domain_xlate_onecell,
};

/* --- supply ---------------------------------------------------------------- */

static int as9888_sim_supply_set(struct regulator_dev *rdev, bool on)
{
	struct as9888_sim *s = rdev_get_drvdata(rdev);
	u32 *fail = on ? &s->fail_supply_on : &s->fail_supply_off;
	unsigned long flags;

	spin_lock_irqsave(&s->lock, flags);
	if (*fail) {
		(*fail)--;
		spin_unlock_irqrestore(&s->lock, flags);
		return -EIO;
	}
	as9888_model_set_power(&s->model, ktime_get_ns(), on);
	s->pin[0] = false;
	s->pin[1] = false;
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);
	return 0;
}

static int as9888_sim_supply_enable(struct regulator_dev *rdev)
{
	return as9888_sim_supply_set(rdev, true);
}

static int as9888_sim_supply_disable(struct regulator_dev *rdev)
{
	return as9888_sim_supply_set(rdev, false);
}

/* Changed under sim->lock by the ops above and by a new unit only */
static int as9888_sim_supply_is_enabled(struct regulator_dev *rdev)
{
	struct as9888_sim *s = rdev_get_drvdata(rdev);

	return READ_ONCE(s->model.powered);
}

static const struct regulator_ops as9888_sim_supply_ops = {
	.enable = as9888_sim_supply_enable,
	.disable = as9888_sim_supply_disable,
	.is_enabled = as9888_sim_supply_is_enabled,
};

static const struct regulator_desc as9888_sim_supply_desc = {
	.name = "as9888-sim-supply",
	.type = REGULATOR_VOLTAGE,
	.owner = THIS_MODULE,
	.ops = &as9888_sim_supply_ops,
	.fixed_uV = 1800000,
	.n_voltages = 1,
};

/*
 * Both supplies of the chip; no device name: the chip's device is the
 * only consumer on this board, and its name on SPI depends on the kernel.
 */
static struct regulator_consumer_supply as9888_sim_consumers[] = {
	REGULATOR_SUPPLY("vdd", NULL),
	REGULATOR_SUPPLY("vid", NULL),
};

static struct regulator_init_data as9888_sim_supply_init = {
	.constraints = {
		.valid_ops_mask = REGULATOR_CHANGE_STATUS,
	},
	.num_consumer_supplies = ARRAY_SIZE(as9888_sim_consumers),
	.consumer_supplies = as9888_sim_consumers,
};

#ifdef CONFIG_LOCKDEP
static struct lock_class_key as9888_sim_supply_work_key;
#endif

static int as9888_sim_add_supply(struct as9888_sim *s)
{
	struct regulator_config cfg = {
		.dev = &s->pdev->dev,
		.init_data = &as9888_sim_supply_init,
		.driver_data = s,
	};

	s->rdev = regulator_register(&s->pdev->dev, &as9888_sim_supply_desc,
				     &cfg);
	if (IS_ERR(s->rdev))
		return PTR_ERR(s->rdev);

#ifdef CONFIG_LOCKDEP
	/*
	 * Every device's runtime PM work shares one lockdep class. The
	 * chip's runtime suspend work disables this regulator (taking
	 * regulator_list_mutex), and regulator_unregister() flushes the
	 * regulator device's own runtime PM work (6.1: pm_runtime_remove())
	 * with regulator_list_mutex held: a false circular dependency. The
	 * regulator device never runs runtime PM work: its own class.
	 */
	lockdep_init_map(&s->rdev->dev.power.work.lockdep_map,
			 "as9888_sim_supply_pm_work", &as9888_sim_supply_work_key,
			 0);
#endif
	return 0;
}

/* --- I2C ------------------------------------------------------------------ */

static int as9888_sim_xfer(struct i2c_adapter *adap, struct i2c_msg *msgs,
			   int num)
{
	struct as9888_sim *s = i2c_get_adapdata(adap);
	unsigned int fire;
	unsigned long flags;
	int i, ret = 0;
	u64 now;

	spin_lock_irqsave(&s->lock, flags);
	s->xfers++;
	now = ktime_get_ns();
	/* Events due before this access happen first, as on the chip. */
	as9888_model_advance(&s->model, now);
	fire = as9888_sim_edges(s, now);

	for (i = 0; i < num && !ret; i++) {
		struct i2c_msg *m = &msgs[i];
		bool pair;

		s->msgs++;
		if (m->addr != AS9888_SIM_ADDR || (m->flags & I2C_M_TEN)) {
			ret = -ENXIO;
			break;
		}
		now = ktime_get_ns();
		/* reg + repeated start + read: one model read */
		pair = !(m->flags & I2C_M_RD) && m->len == 1 && i + 1 < num &&
		       (msgs[i + 1].flags & I2C_M_RD);
		if (s->fail_next && !pair) {
			/* the transfer never reaches the chip */
			s->fail_next--;
			ret = -ENXIO;
		} else if (m->flags & I2C_M_RD) {
			ret = as9888_model_read(&s->model, now, s->ptr,
						m->buf, m->len);
			s->ptr += m->len;
		} else if (!m->len) {
			ret = as9888_model_write(&s->model, now, s->ptr,
						 NULL, 0);
		} else {
			s->ptr = m->buf[0];
			if (pair)
				continue;
			ret = as9888_model_write(&s->model, now, s->ptr,
						 m->buf + 1, m->len - 1);
			s->ptr += m->len - 1;
		}
		s->model_xfers++;
		if (ret)
			s->model_naks++;
	}

	fire |= as9888_sim_edges(s, ktime_get_ns());
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);

	as9888_sim_fire(s, fire);
	if (ret)
		return -ENXIO;
	return num;
}

static u32 as9888_sim_func(struct i2c_adapter *adap)
{
	return I2C_FUNC_I2C | I2C_FUNC_SMBUS_EMUL;
}

static const struct i2c_algorithm as9888_sim_algo = {
	.master_xfer = as9888_sim_xfer,
	.functionality = as9888_sim_func,
};

/* --- SPI ------------------------------------------------------------------ */

#define AS9888_SIM_SPI_MAX	256

static int as9888_sim_spi_transfer(struct spi_controller *ctlr,
				   struct spi_message *msg)
{
	struct as9888_sim *s = spi_controller_get_devdata(ctlr);
	u8 tx[AS9888_SIM_SPI_MAX], rx[AS9888_SIM_SPI_MAX];
	struct spi_transfer *t;
	unsigned int total = 0, at;
	unsigned int fire;
	unsigned long flags;
	int ret = 0;
	u64 now;

	list_for_each_entry(t, &msg->transfers, transfer_list) {
		if (t->len > AS9888_SIM_SPI_MAX - total) {
			ret = -EMSGSIZE;
			goto out;
		}
		if (t->tx_buf)
			memcpy(tx + total, t->tx_buf, t->len);
		else
			memset(tx + total, 0, t->len);
		total += t->len;
	}
	memset(rx, 0xff, total);

	spin_lock_irqsave(&s->lock, flags);
	s->xfers++;
	now = ktime_get_ns();
	as9888_model_advance(&s->model, now);
	fire = as9888_sim_edges(s, now);
	if (total && s->fail_next) {
		/* the transfer never reaches the chip: SO floats high */
		s->fail_next--;
		s->model_xfers++;
		s->model_naks++;
	} else if (total) {
		/* bit 7: read; bits 6:0: register; the chip drives SO from byte 1 */
		if (tx[0] & 0x80)
			as9888_model_read(&s->model, now, tx[0] & 0x7f, rx + 1,
					  total - 1);
		else
			as9888_model_write(&s->model, now, tx[0] & 0x7f,
					   tx + 1, total - 1);
		s->model_xfers++;
	}
	fire |= as9888_sim_edges(s, ktime_get_ns());
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);
	as9888_sim_fire(s, fire);

	at = 0;
	list_for_each_entry(t, &msg->transfers, transfer_list) {
		if (t->rx_buf)
			memcpy(t->rx_buf, rx + at, t->len);
		at += t->len;
	}
	msg->actual_length = total;
out:
	msg->status = ret;
	spi_finalize_current_message(ctlr);
	return ret;
}

/* --- GPIO ----------------------------------------------------------------- */

static int as9888_sim_gpio_get(struct gpio_chip *gc, unsigned int offset)
{
	struct as9888_sim *s = gpiochip_get_data(gc);
	unsigned int fire = 0;
	unsigned long flags;
	int val;
	u64 now;

	spin_lock_irqsave(&s->lock, flags);
	now = ktime_get_ns();
	if (offset == AS9888_SIM_RSTN) {
		val = s->rstn;
	} else {
		fire = as9888_sim_edges(s, now);
		val = s->pin[offset - AS9888_SIM_INT1];
		as9888_sim_arm(s);
	}
	spin_unlock_irqrestore(&s->lock, flags);
	as9888_sim_fire(s, fire);
	return val;
}

static void as9888_sim_rstn(struct as9888_sim *s, int value)
{
	unsigned int fire;
	unsigned long flags;
	u64 now;

	spin_lock_irqsave(&s->lock, flags);
	now = ktime_get_ns();
	as9888_model_advance(&s->model, now);
	fire = as9888_sim_edges(s, now);
	s->rstn = !!value;
	as9888_model_set_rstn(&s->model, now, s->rstn);
	fire |= as9888_sim_edges(s, now);
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);
	as9888_sim_fire(s, fire);
}

#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 17, 0)
static int as9888_sim_gpio_set(struct gpio_chip *gc, unsigned int offset,
			       int value)
{
	if (offset == AS9888_SIM_RSTN)
		as9888_sim_rstn(gpiochip_get_data(gc), value);
	return 0;
}
#else
static void as9888_sim_gpio_set(struct gpio_chip *gc, unsigned int offset,
				int value)
{
	if (offset == AS9888_SIM_RSTN)
		as9888_sim_rstn(gpiochip_get_data(gc), value);
}
#endif

static int as9888_sim_gpio_get_direction(struct gpio_chip *gc,
					 unsigned int offset)
{
	return offset == AS9888_SIM_RSTN ? GPIO_LINE_DIRECTION_OUT :
					   GPIO_LINE_DIRECTION_IN;
}

static int as9888_sim_gpio_direction_input(struct gpio_chip *gc,
					   unsigned int offset)
{
	/* RSTN stays an output of the board: nothing to read back there. */
	return offset == AS9888_SIM_RSTN ? -EPERM : 0;
}

static int as9888_sim_gpio_direction_output(struct gpio_chip *gc,
					    unsigned int offset, int value)
{
	if (offset != AS9888_SIM_RSTN)
		return -EPERM;	/* INT1/INT2 are driven by the chip */
	as9888_sim_rstn(gpiochip_get_data(gc), value);
	return 0;
}

static int as9888_sim_gpio_to_irq(struct gpio_chip *gc, unsigned int offset)
{
	struct as9888_sim *s = gpiochip_get_data(gc);

	if (offset == AS9888_SIM_RSTN)
		return -ENXIO;
	return irq_create_mapping(s->domain, offset) ?: -ENXIO;
}

/* --- the firmware node of wiring=int2 ------------------------------------- */

/*
 * A board that wires INT2 alone names it in interrupt-names, and the
 * driver gets it with fwnode_irq_get(). A software node has properties but
 * no interrupts, so the device gets a firmware node of its own, as a
 * device tree or ACPI node would be: its interrupts are the adapter's
 * lines, and its properties are those of as9888_sim_int2_node, its
 * secondary node. The property operations answer -EINVAL ("no such
 * property"), which sends the property API on to the secondary node.
 */
static bool as9888_sim_board_present(const struct fwnode_handle *fwnode,
				     const char *propname)
{
	return false;
}

static int as9888_sim_board_read_int(const struct fwnode_handle *fwnode,
				     const char *propname,
				     unsigned int elem_size, void *val,
				     size_t nval)
{
	return -EINVAL;
}

static int as9888_sim_board_read_str(const struct fwnode_handle *fwnode,
				     const char *propname, const char **val,
				     size_t nval)
{
	return -EINVAL;
}

static const char *as9888_sim_board_name(const struct fwnode_handle *fwnode)
{
	return "as9888-sim-board";
}

/* Interrupt 0, the only one as9888_sim_int2_props names: INT2 */
static int as9888_sim_board_irq(const struct fwnode_handle *fwnode,
				unsigned int index)
{
	struct as9888_sim *s = container_of(fwnode, struct as9888_sim,
					    board_fwnode);
	unsigned int irq;

	if (index)
		return -EINVAL;
	irq = irq_create_mapping(s->domain, AS9888_SIM_INT2);
	if (!irq)
		return -ENXIO;
	irq_set_irq_type(irq, IRQ_TYPE_EDGE_RISING);
	return irq;
}

static const struct fwnode_operations as9888_sim_board_ops = {
	.property_present = as9888_sim_board_present,
	.property_read_int_array = as9888_sim_board_read_int,
	.property_read_string_array = as9888_sim_board_read_str,
	.get_name = as9888_sim_board_name,
	.irq_get = as9888_sim_board_irq,
};

/* --- device --------------------------------------------------------------- */

/*
 * The device gets the software node as its (unmanaged) firmware node, not
 * through board_info.swnode: a managed node is put once more by every
 * child device that inherits it (the IIO core gives the IIO device its
 * parent's fwnode), see software_node_notify_remove(), and is freed while
 * still in use (KASAN use-after-free on 6.1 and 7.2 at the first unbind).
 */
static int as9888_sim_add_client(struct as9888_sim *s)
{
	struct fwnode_handle *fwnode;
	struct i2c_board_info info = {
		I2C_BOARD_INFO("as9888", AS9888_SIM_ADDR),
	};
	struct i2c_client *client;
	struct spi_device *sdev;
	int irq, ret;

	if (s->client || s->spi)
		return 0;
	switch (s->wiring) {
	case AS9888_SIM_WIRING_BAD:
		fwnode = software_node_fwnode(&as9888_sim_bad_node);
		break;
	case AS9888_SIM_WIRING_INT2:
		fwnode = &s->board_fwnode;
		break;
	default:
		fwnode = software_node_fwnode(&as9888_sim_dev_node);
		break;
	}
	s->fwnode = fwnode;
	info.fwnode = fwnode;
	/* a device (re)appears on a freshly powered chip */
	as9888_sim_power_on(s);
	if (s->wiring == AS9888_SIM_WIRING_INT1_LEVEL) {
		irq = irq_create_mapping(s->lvl_domain, 0);
		if (!irq)
			return -ENXIO;
		irq_set_irq_type(irq, IRQ_TYPE_LEVEL_HIGH);
	} else if (s->wiring == AS9888_SIM_WIRING_INT2) {
		/* the bus's interrupt is the node's first, as from firmware */
		irq = as9888_sim_board_irq(fwnode, 0);
		if (irq < 0)
			return irq;
	} else {
		irq = irq_create_mapping(s->domain, AS9888_SIM_INT1);
		if (!irq)
			return -ENXIO;
		irq_set_irq_type(irq, IRQ_TYPE_EDGE_RISING);
	}
	if (spi) {
		sdev = spi_alloc_device(s->ctlr);
		if (!sdev)
			return -ENOMEM;
		strscpy(sdev->modalias, "as9888", sizeof(sdev->modalias));
		sdev->max_speed_hz = 5000000;
		sdev->mode = SPI_MODE_3;
		sdev->irq = irq;
		device_set_node(&sdev->dev, fwnode);
		ret = spi_add_device(sdev);
		if (ret) {
			spi_dev_put(sdev);
			return ret;
		}
		s->spi = sdev;
		return 0;
	}
	info.irq = irq;
	client = i2c_new_client_device(&s->adap, &info);
	if (IS_ERR(client))
		return PTR_ERR(client);
	s->client = client;
	return 0;
}

/*
 * i2c_unregister_device() and spi_unregister_device() call
 * device_remove_software_node(), which treats a primary software node as
 * owned by the device: it drops a reference the device never took and
 * leaves the node attached, so device_del() drops one more (KASAN
 * use-after-free). Our node is the module's: unregister the device only.
 * Neither bus does anything else for a device without OF/ACPI node, and
 * the SPI controller has no cleanup callback. Since 6.12 or so (7.2 does,
 * 6.1 does not) i2c_new_client_device() takes a reference on
 * board_info.fwnode: give it back.
 */
static void as9888_sim_del_client(struct as9888_sim *s)
{
	if (s->spi) {
		device_unregister(&s->spi->dev);
		s->spi = NULL;
	}
	if (s->client) {
		device_unregister(&s->client->dev);
		s->client = NULL;
#if LINUX_VERSION_CODE >= KERNEL_VERSION(6, 12, 0)
		fwnode_handle_put(s->fwnode);
#endif
	}
}

static const char *as9888_sim_dev_name(struct as9888_sim *s, char *buf,
				       size_t len)
{
	/* 7.2 names an SPI device with a software node after the node */
	if (spi && s->spi)
		strscpy(buf, dev_name(&s->spi->dev), len);
	else if (spi)
		snprintf(buf, len, "spi%d.0", s->ctlr->bus_num);
	else
		snprintf(buf, len, "%d-%04x", s->adap.nr, AS9888_SIM_ADDR);
	return buf;
}

/* --- debugfs -------------------------------------------------------------- */

static ssize_t as9888_sim_unit_write(struct file *file, const char __user *ubuf,
				     size_t count, loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	struct as9888_unit_error err = { };
	struct as9888_unit unit;
	char *text;
	int ret;

	if (*ppos || count > AS9888_SIM_UNIT_MAX)
		return -EINVAL;
	text = memdup_user_nul(ubuf, count);
	if (IS_ERR(text))
		return PTR_ERR(text);
	ret = as9888_unit_parse(text, count, &unit, &err);
	if (ret) {
		pr_warn("as9888_sim: unit description line %u: %s\n",
			err.line, err.msg);
		kfree(text);
		return ret;
	}

	mutex_lock(&s->cfg_lock);
	as9888_sim_del_client(s);
	s->unit = unit;
	kfree(s->unit_text);
	s->unit_text = text;
	ret = as9888_sim_add_client(s);
	mutex_unlock(&s->cfg_lock);
	return ret ?: count;
}

static ssize_t as9888_sim_unit_read(struct file *file, char __user *ubuf,
				    size_t count, loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	ssize_t ret;

	mutex_lock(&s->cfg_lock);
	ret = simple_read_from_buffer(ubuf, count, ppos, s->unit_text,
				      strlen(s->unit_text));
	mutex_unlock(&s->cfg_lock);
	return ret;
}

static const struct file_operations as9888_sim_unit_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = as9888_sim_unit_read,
	.write = as9888_sim_unit_write,
	.llseek = default_llseek,
};

static ssize_t as9888_sim_present_write(struct file *file,
					const char __user *ubuf,
					size_t count, loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	bool on;
	int ret;

	ret = kstrtobool_from_user(ubuf, count, &on);
	if (ret)
		return ret;
	mutex_lock(&s->cfg_lock);
	if (on)
		ret = as9888_sim_add_client(s);
	else
		as9888_sim_del_client(s);
	mutex_unlock(&s->cfg_lock);
	return ret ?: count;
}

static ssize_t as9888_sim_present_read(struct file *file, char __user *ubuf,
				       size_t count, loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	char buf[4];
	int len;

	mutex_lock(&s->cfg_lock);
	len = scnprintf(buf, sizeof(buf), "%d\n", s->client || s->spi);
	mutex_unlock(&s->cfg_lock);
	return simple_read_from_buffer(ubuf, count, ppos, buf, len);
}

static const struct file_operations as9888_sim_present_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = as9888_sim_present_read,
	.write = as9888_sim_present_write,
	.llseek = default_llseek,
};

/*
 * A knob's value is parsed as the line "<key> = <value>" of a unit
 * description, so that it has exactly the syntax and the limits of the
 * unit file. One trailing newline is allowed, no other line.
 */
static int as9888_sim_knob_parse(struct as9888_sim_knob *k,
				 const char __user *ubuf, size_t count,
				 struct as9888_unit *unit)
{
	struct as9888_unit_error err = { };
	char val[AS9888_SIM_KNOB_MAX + 1];
	char line[AS9888_SIM_KNOB_MAX + 32];
	const char *key = as9888_sim_knob_keys[k->id];
	int len, ret;

	if (!count || count > AS9888_SIM_KNOB_MAX)
		return -EINVAL;
	if (copy_from_user(val, ubuf, count))
		return -EFAULT;
	val[count] = '\0';
	if (val[count - 1] == '\n')
		val[--count] = '\0';
	if (strlen(val) != count || strchr(val, '\n'))
		return -EINVAL;
	len = scnprintf(line, sizeof(line), "%s = %s\n", key, val);
	ret = as9888_unit_parse(line, len, unit, &err);
	if (ret)
		pr_info("as9888_sim: %s: %s\n", key, err.msg);
	return ret;
}

/*
 * A knob of the magnetic world: the model takes the value; the unit kept
 * for a re-instantiated chip follows the model (its orientation too).
 * Called under @lock.
 */
static void as9888_sim_world_write(struct as9888_sim *s,
				   enum as9888_sim_knob_id id,
				   const struct as9888_unit *u, u64 now)
{
	struct as9888_model *m = &s->model;
	struct as9888_unit *keep = &s->unit;

	switch (id) {
	case AS9888_SIM_KNOB_HEADING:
		as9888_model_set_heading(m, now, u->heading_mdeg);
		break;
	case AS9888_SIM_KNOB_ORIENTATION:
		as9888_model_set_orientation(m, now, u->orientation);
		break;
	case AS9888_SIM_KNOB_EARTH:
		as9888_model_set_earth(m, now, u->earth_nt, u->incl_mdeg,
				       u->decl_mdeg);
		break;
	case AS9888_SIM_KNOB_HARD_IRON:
		as9888_model_set_hard_iron(m, now, u->hard_nt);
		break;
	case AS9888_SIM_KNOB_SOFT_IRON:
		as9888_model_set_soft_iron(m, now, u->soft_ppm);
		break;
	case AS9888_SIM_KNOB_MAGN_NOISE:
		as9888_model_set_magn_noise(m, now, u->magn_noise_nt);
		break;
	case AS9888_SIM_KNOB_DISTURBANCE:
		as9888_model_set_disturbance(m, now, u->dist_nt,
					     u->dist_samples);
		break;
	case AS9888_SIM_KNOB_TUMBLE:
		as9888_model_set_tumble(m, now, u->tumble_mdeg);
		break;
	default:
		return;
	}
	memcpy(keep->up, m->unit.up, sizeof(keep->up));
	memcpy(keep->orientation, m->unit.orientation,
	       sizeof(keep->orientation));
	memcpy(keep->hard_nt, m->unit.hard_nt, sizeof(keep->hard_nt));
	memcpy(keep->soft_ppm, m->unit.soft_ppm, sizeof(keep->soft_ppm));
	memcpy(keep->dist_nt, m->unit.dist_nt, sizeof(keep->dist_nt));
	keep->world = m->unit.world;
	keep->heading_mdeg = m->unit.heading_mdeg;
	keep->earth_nt = m->unit.earth_nt;
	keep->incl_mdeg = m->unit.incl_mdeg;
	keep->decl_mdeg = m->unit.decl_mdeg;
	keep->magn_noise_nt = m->unit.magn_noise_nt;
	keep->dist_samples = m->unit.dist_samples;
	keep->tumble_mdeg = m->unit.tumble_mdeg;
}

static ssize_t as9888_sim_knob_write(struct file *file,
				     const char __user *ubuf, size_t count,
				     loff_t *ppos)
{
	struct as9888_sim_knob *k = file->private_data;
	struct as9888_sim *s = k->s;
	struct as9888_unit unit;
	unsigned int fire;
	unsigned long flags;
	int ret;
	u64 now;

	if (*ppos)
		return -EINVAL;
	ret = as9888_sim_knob_parse(k, ubuf, count, &unit);
	if (ret)
		return ret;

	mutex_lock(&s->cfg_lock);
	spin_lock_irqsave(&s->lock, flags);
	now = ktime_get_ns();
	switch (k->id) {
	case AS9888_SIM_KNOB_TEMPERATURE:
		as9888_model_set_temperature(&s->model, now,
					     unit.temperature_mdegc);
		s->unit.temperature_mdegc = unit.temperature_mdegc;
		break;
	case AS9888_SIM_KNOB_UP:
		as9888_model_set_up(&s->model, now, unit.up);
		memcpy(s->unit.up, unit.up, sizeof(s->unit.up));
		s->unit.world &= ~AS9888_UNIT_WORLD_ORIENTATION;
		break;
	case AS9888_SIM_KNOB_NOISE:
		as9888_model_set_noise(&s->model, now, unit.noise_mlsb);
		s->unit.noise_mlsb = unit.noise_mlsb;
		break;
	default:
		as9888_sim_world_write(s, k->id, &unit, now);
		break;
	}
	/* the setter processed the events due until now: their edges */
	fire = as9888_sim_edges(s, now);
	as9888_sim_arm(s);
	spin_unlock_irqrestore(&s->lock, flags);
	as9888_sim_fire(s, fire);
	mutex_unlock(&s->cfg_lock);
	return count;
}

/* A fixed-point value with @places decimals, e.g. -20.500 */
static int as9888_sim_put_fixed(char *buf, size_t len, s64 v,
				unsigned int places, u32 one)
{
	u64 a = v < 0 ? -(u64)v : v;
	u32 frac = do_div(a, one);

	return scnprintf(buf, len, "%s%llu.%0*u", v < 0 ? "-" : "", a,
			 places, frac);
}

/* @n fixed-point values with @places decimals, space separated */
static int as9888_sim_put_vec(char *buf, size_t len, const s64 *v, int n,
			      unsigned int places, u32 one)
{
	int pos = 0, i;

	for (i = 0; i < n; i++) {
		if (i)
			pos += scnprintf(buf + pos, len - pos, " ");
		pos += as9888_sim_put_fixed(buf + pos, len - pos, v[i], places,
					    one);
	}
	return pos;
}

/*
 * The value of a knob of the posture or the magnetic world, as the model
 * holds it now (the orientation and up move with the tumble); called
 * under @cfg_lock.
 */
static int as9888_sim_world_read(struct as9888_sim *s,
				 enum as9888_sim_knob_id id, char *buf,
				 size_t len)
{
	const struct as9888_unit *u = &s->model.unit;
	s64 v[AS9888_UNIT_AXES * AS9888_UNIT_AXES];
	s32 q[AS9888_QUAT_LEN];
	unsigned long flags;
	int i, pos;

	spin_lock_irqsave(&s->lock, flags);
	switch (id) {
	case AS9888_SIM_KNOB_UP:
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			v[i] = u->up[i];
		pos = as9888_sim_put_vec(buf, len, v, 3, 6, AS9888_UNIT_UP_ONE);
		break;
	case AS9888_SIM_KNOB_HEADING:
		pos = as9888_sim_put_fixed(buf, len, u->heading_mdeg, 3, 1000);
		break;
	case AS9888_SIM_KNOB_ORIENTATION:
		as9888_model_orientation(&s->model, q);
		for (i = 0; i < AS9888_QUAT_LEN; i++)
			v[i] = div_s64((s64)q[i] * AS9888_UNIT_UP_ONE,
				       AS9888_Q30_ONE);
		pos = as9888_sim_put_vec(buf, len, v, 4, 6, AS9888_UNIT_UP_ONE);
		break;
	case AS9888_SIM_KNOB_EARTH:
		v[0] = u->earth_nt;
		v[1] = u->incl_mdeg;
		v[2] = u->decl_mdeg;
		pos = as9888_sim_put_vec(buf, len, v, 3, 3, 1000);
		break;
	case AS9888_SIM_KNOB_HARD_IRON:
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			v[i] = u->hard_nt[i];
		pos = as9888_sim_put_vec(buf, len, v, 3, 3, 1000);
		break;
	case AS9888_SIM_KNOB_SOFT_IRON:
		for (i = 0; i < AS9888_UNIT_AXES * AS9888_UNIT_AXES; i++)
			v[i] = u->soft_ppm[i];
		pos = as9888_sim_put_vec(buf, len, v, 9, 6,
					 AS9888_UNIT_SOFT_ONE);
		break;
	case AS9888_SIM_KNOB_MAGN_NOISE:
		pos = as9888_sim_put_fixed(buf, len, u->magn_noise_nt, 3, 1000);
		break;
	case AS9888_SIM_KNOB_DISTURBANCE:
		for (i = 0; i < AS9888_UNIT_AXES; i++)
			v[i] = u->dist_nt[i];
		pos = as9888_sim_put_vec(buf, len, v, 3, 3, 1000);
		pos += scnprintf(buf + pos, len - pos, " %u", u->dist_samples);
		break;
	case AS9888_SIM_KNOB_TUMBLE:
		pos = as9888_sim_put_fixed(buf, len, u->tumble_mdeg, 3, 1000);
		break;
	default:
		pos = 0;
		break;
	}
	spin_unlock_irqrestore(&s->lock, flags);
	return pos;
}

static ssize_t as9888_sim_knob_read(struct file *file, char __user *ubuf,
				    size_t count, loff_t *ppos)
{
	struct as9888_sim_knob *k = file->private_data;
	struct as9888_sim *s = k->s;
	unsigned long flags;
	char buf[AS9888_SIM_KNOB_MAX + 40];
	int len = 0;
	s32 t;

	mutex_lock(&s->cfg_lock);
	switch (k->id) {
	case AS9888_SIM_KNOB_TEMPERATURE:
		spin_lock_irqsave(&s->lock, flags);
		t = as9888_model_temperature_mdegc(&s->model, ktime_get_ns());
		spin_unlock_irqrestore(&s->lock, flags);
		len = as9888_sim_put_fixed(buf, sizeof(buf), t, 3, 1000);
		break;
	case AS9888_SIM_KNOB_NOISE:
		len = as9888_sim_put_fixed(buf, sizeof(buf), s->unit.noise_mlsb,
					   3, 1000);
		break;
	default:
		len = as9888_sim_world_read(s, k->id, buf, sizeof(buf));
		break;
	}
	mutex_unlock(&s->cfg_lock);
	len += scnprintf(buf + len, sizeof(buf) - len, "\n");
	return simple_read_from_buffer(ubuf, count, ppos, buf, len);
}

static const struct file_operations as9888_sim_knob_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = as9888_sim_knob_read,
	.write = as9888_sim_knob_write,
	.llseek = default_llseek,
};

static int as9888_sim_stats_show(struct seq_file *sf, void *unused)
{
	struct as9888_sim *s = sf->private;
	struct as9888_model_stats st;
	u64 xfers, msgs, mx, mn, irqs, dropped, delayed;
	unsigned long flags;

	spin_lock_irqsave(&s->lock, flags);
	st = *as9888_model_stats(&s->model);
	xfers = s->xfers;
	msgs = s->msgs;
	mx = s->model_xfers;
	mn = s->model_naks;
	irqs = s->irqs;
	dropped = s->irqs_dropped;
	delayed = s->irqs_delayed;
	spin_unlock_irqrestore(&s->lock, flags);

	seq_printf(sf, "bus_calls %llu\n", xfers);
	seq_printf(sf, "i2c_msgs %llu\n", msgs);
	seq_printf(sf, "bus_transfers %llu\n", mx);
	seq_printf(sf, "bus_naks %llu\n", mn);
	seq_printf(sf, "irqs %llu\n", irqs);
	seq_printf(sf, "irqs_dropped %llu\n", dropped);
	seq_printf(sf, "irqs_delayed %llu\n", delayed);
	seq_printf(sf, "chip_transfers %llu\n", st.transfers);
	seq_printf(sf, "chip_reads %llu\n", st.reads);
	seq_printf(sf, "chip_writes %llu\n", st.writes);
	seq_printf(sf, "chip_naks %llu\n", st.naks);
	seq_printf(sf, "chip_bytes_read %llu\n", st.bytes_read);
	seq_printf(sf, "chip_bytes_written %llu\n", st.bytes_written);
	seq_printf(sf, "chip_measurements %llu\n", st.measurements);
	seq_printf(sf, "chip_magn_measurements %llu\n", st.magn_measurements);
	seq_printf(sf, "chip_aborted %llu\n", st.aborted);
	seq_printf(sf, "chip_resets %llu\n", st.resets);
	seq_printf(sf, "chip_power_offs %llu\n", st.power_offs);
	seq_printf(sf, "chip_unpowered_transfers %llu\n",
		   st.unpowered_transfers);
	seq_printf(sf, "chip_backpowered %llu\n", st.backpowered);
	return 0;
}

static int as9888_sim_stats_open(struct inode *inode, struct file *file)
{
	return single_open(file, as9888_sim_stats_show, inode->i_private);
}

static ssize_t as9888_sim_stats_write(struct file *file,
				      const char __user *ubuf, size_t count,
				      loff_t *ppos)
{
	struct as9888_sim *s = ((struct seq_file *)file->private_data)->private;
	unsigned long flags;

	spin_lock_irqsave(&s->lock, flags);
	s->xfers = 0;
	s->msgs = 0;
	s->model_xfers = 0;
	s->model_naks = 0;
	s->irqs = 0;
	s->irqs_dropped = 0;
	s->irqs_delayed = 0;
	spin_unlock_irqrestore(&s->lock, flags);
	return count;
}

static const struct file_operations as9888_sim_stats_fops = {
	.owner = THIS_MODULE,
	.open = as9888_sim_stats_open,
	.read = seq_read,
	.write = as9888_sim_stats_write,
	.llseek = seq_lseek,
	.release = single_release,
};

static ssize_t as9888_sim_wiring_write(struct file *file,
				       const char __user *ubuf, size_t count,
				       loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	char buf[16];
	int w, ret;

	if (*ppos || !count || count >= sizeof(buf))
		return -EINVAL;
	if (copy_from_user(buf, ubuf, count))
		return -EFAULT;
	buf[count] = '\0';
	w = sysfs_match_string(as9888_sim_wiring_names, buf);
	if (w < 0)
		return w;
	mutex_lock(&s->cfg_lock);
	as9888_sim_del_client(s);
	WRITE_ONCE(s->wiring, w);
	ret = as9888_sim_add_client(s);
	mutex_unlock(&s->cfg_lock);
	return ret ?: count;
}

static ssize_t as9888_sim_wiring_read(struct file *file, char __user *ubuf,
				      size_t count, loff_t *ppos)
{
	struct as9888_sim *s = file->private_data;
	char buf[16];
	int len;

	mutex_lock(&s->cfg_lock);
	len = scnprintf(buf, sizeof(buf), "%s\n",
			as9888_sim_wiring_names[s->wiring]);
	mutex_unlock(&s->cfg_lock);
	return simple_read_from_buffer(ubuf, count, ppos, buf, len);
}

static const struct file_operations as9888_sim_wiring_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = as9888_sim_wiring_read,
	.write = as9888_sim_wiring_write,
	.llseek = default_llseek,
};

/* drop_int1, fail_next, fail_supply_*: events to spoil, under sim->lock */
static int as9888_sim_count_get(void *data, u64 *val)
{
	u32 *count = data;

	*val = READ_ONCE(*count);
	return 0;
}

static int as9888_sim_count_set(struct as9888_sim *s, u32 *count, u64 val)
{
	unsigned long flags;

	if (val > U32_MAX)
		return -EINVAL;
	spin_lock_irqsave(&s->lock, flags);
	*count = val;
	spin_unlock_irqrestore(&s->lock, flags);
	return 0;
}

static int as9888_sim_count_write(void *data, u64 val)
{
	return as9888_sim_count_set(sim, data, val);
}
DEFINE_DEBUGFS_ATTRIBUTE(as9888_sim_count_fops, as9888_sim_count_get,
			 as9888_sim_count_write, "%llu\n");

static ssize_t as9888_sim_glitch_write(struct file *file,
				       const char __user *ubuf, size_t count,
				       loff_t *ppos)
{
	as9888_sim_fire(file->private_data, BIT(AS9888_PIN_INT1));
	return count;
}

static const struct file_operations as9888_sim_glitch_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.write = as9888_sim_glitch_write,
	.llseek = default_llseek,
};

static int as9888_sim_regs_show(struct seq_file *sf, void *unused)
{
	static const u8 cfg_regs[] = {
		AS9888_REG_INT1EN, AS9888_REG_INT2EN, AS9888_REG_SLCT1,
		AS9888_REG_SLCT2, AS9888_REG_MS,
	};
	u8 reg[ARRAY_SIZE(cfg_regs) + AS9888_TRIM_LEN], val[ARRAY_SIZE(reg)];
	struct as9888_sim *s = sf->private;
	unsigned int i, n = 0;
	unsigned long flags;

	for (i = 0; i < ARRAY_SIZE(cfg_regs); i++)
		reg[n++] = cfg_regs[i];
	for (i = 0; i < AS9888_TRIM_LEN; i++)
		reg[n++] = AS9888_REG_REF1 + i;

	spin_lock_irqsave(&s->lock, flags);
	as9888_model_advance(&s->model, ktime_get_ns());
	for (i = 0; i < n; i++)
		val[i] = as9888_model_peek(&s->model, reg[i]);
	spin_unlock_irqrestore(&s->lock, flags);

	for (i = 0; i < n; i++)
		seq_printf(sf, "0x%02x 0x%02x\n", reg[i], val[i]);
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(as9888_sim_regs);

static int as9888_sim_bus_show(struct seq_file *sf, void *unused)
{
	struct as9888_sim *s = sf->private;

	char name[32];

	seq_printf(sf, "%s %s\n", spi ? "spi" : "i2c",
		   as9888_sim_dev_name(s, name, sizeof(name)));
	return 0;
}
DEFINE_SHOW_ATTRIBUTE(as9888_sim_bus);

/* --- module --------------------------------------------------------------- */

static int as9888_sim_add_spi(struct as9888_sim *s)
{
	int ret;

	s->ctlr = spi_alloc_host(&s->pdev->dev, 0);
	if (!s->ctlr)
		return -ENOMEM;
	spi_controller_set_devdata(s->ctlr, s);
	s->ctlr->bus_num = -1;
	s->ctlr->num_chipselect = 1;
	s->ctlr->mode_bits = SPI_CPOL | SPI_CPHA;
	s->ctlr->bits_per_word_mask = SPI_BPW_MASK(8);
	s->ctlr->max_speed_hz = 10000000;
	s->ctlr->transfer_one_message = as9888_sim_spi_transfer;
	ret = spi_register_controller(s->ctlr);
	if (ret) {
		spi_controller_put(s->ctlr);
		s->ctlr = NULL;
	}
	return ret;
}

static void as9888_sim_dispose_irqs(struct as9888_sim *s)
{
	int i;

	for (i = 0; i < AS9888_SIM_NLINES; i++) {
		unsigned int irq = irq_find_mapping(s->domain, i);

		if (irq)
			irq_dispose_mapping(irq);
	}
}

static int __init as9888_sim_init(void)
{
	struct as9888_sim *s;
	struct gpio_chip *gc;
	const char *step = "allocation";
	char name[32];
	int i, ret;

	s = kzalloc(sizeof(*s), GFP_KERNEL);
	if (!s)
		return -ENOMEM;
	spin_lock_init(&s->lock);
	mutex_init(&s->cfg_lock);
	as9888_sim_timer_setup(&s->timer, as9888_sim_timer_fn);
	as9888_sim_timer_setup(&s->delay_timer, as9888_sim_delay_fn);
	as9888_unit_default(&s->unit);
	s->unit_text = kstrdup("# default unit\n", GFP_KERNEL);
	if (!s->unit_text) {
		ret = -ENOMEM;
		goto err_free;
	}
	s->rstn = true;

	/*
	 * Like board code that describes all its regulators: supplies no
	 * one describes (the chip's vdd and vid) get the always-on dummy.
	 */
	regulator_has_full_constraints();

	step = "software nodes";
	ret = software_node_register_node_group(as9888_sim_nodes);
	if (ret)
		goto err_free;
	fwnode_init(&s->board_fwnode, &as9888_sim_board_ops);
	s->board_fwnode.secondary = software_node_fwnode(&as9888_sim_int2_node);
	init_irq_work(&s->lvl_work, as9888_sim_lvl_work);

	step = "platform device";
	s->pdev = platform_device_register_simple("as9888-sim", -1, NULL, 0);
	if (IS_ERR(s->pdev)) {
		ret = PTR_ERR(s->pdev);
		goto err_node;
	}

	step = "interrupt simulator";
	s->domain = irq_domain_create_sim(software_node_fwnode(&as9888_sim_gpio_node),
					  AS9888_SIM_NLINES);
	if (IS_ERR(s->domain)) {
		ret = PTR_ERR(s->domain);
		goto err_pdev;
	}
	step = "level interrupt controller";
	s->lvl_domain = irq_domain_create_linear(NULL, 1, &as9888_sim_lvl_ops, s);
	if (!s->lvl_domain) {
		irq_domain_remove_sim(s->domain);
		ret = -ENOMEM;
		goto err_pdev;
	}

	gc = &s->gc;
	gc->label = "as9888-sim-gpio";
	gc->parent = &s->pdev->dev;
	gc->fwnode = software_node_fwnode(&as9888_sim_gpio_node);
	gc->owner = THIS_MODULE;
	gc->base = -1;
	gc->ngpio = AS9888_SIM_NLINES;
	gc->names = as9888_sim_line_names;
	gc->get = as9888_sim_gpio_get;
	gc->set = as9888_sim_gpio_set;
	gc->get_direction = as9888_sim_gpio_get_direction;
	gc->direction_input = as9888_sim_gpio_direction_input;
	gc->direction_output = as9888_sim_gpio_direction_output;
	gc->to_irq = as9888_sim_gpio_to_irq;
	gc->can_sleep = false;
	step = "GPIO chip";
	ret = gpiochip_add_data(gc, s);
	if (ret)
		goto err_domain;

	s->adap.owner = THIS_MODULE;
	s->adap.algo = &as9888_sim_algo;
	s->adap.dev.parent = &s->pdev->dev;
	s->adap.nr = -1;
	strscpy(s->adap.name, "as9888-sim-i2c", sizeof(s->adap.name));
	i2c_set_adapdata(&s->adap, s);
	step = "I2C adapter";
	ret = i2c_add_adapter(&s->adap);
	if (ret)
		goto err_gpio;

	/* The SPI controller only exists on the SPI board */
	if (spi) {
		step = "SPI controller";
		ret = as9888_sim_add_spi(s);
		if (ret)
			goto err_i2c;
	}

#ifndef AS9888_SIM_SWNODE_GPIO
	as9888_sim_dev_name(s, as9888_sim_dev_id, sizeof(as9888_sim_dev_id));
	as9888_sim_lookup.dev_id = as9888_sim_dev_id;
	gpiod_add_lookup_table(&as9888_sim_lookup);
#endif

	step = "supply";
	ret = as9888_sim_add_supply(s);
	if (ret)
		goto err_spi;

	s->dir = debugfs_create_dir("as9888_sim", NULL);
	debugfs_create_file("unit", 0600, s->dir, s, &as9888_sim_unit_fops);
	debugfs_create_file("present", 0600, s->dir, s,
			    &as9888_sim_present_fops);
	debugfs_create_file("stats", 0600, s->dir, s, &as9888_sim_stats_fops);
	debugfs_create_file("bus", 0400, s->dir, s, &as9888_sim_bus_fops);
	debugfs_create_file("regs", 0400, s->dir, s, &as9888_sim_regs_fops);
	debugfs_create_file("wiring", 0600, s->dir, s, &as9888_sim_wiring_fops);
	debugfs_create_file_unsafe("drop_int1", 0600, s->dir, &s->drop_int1,
				   &as9888_sim_count_fops);
	debugfs_create_file_unsafe("fail_next", 0600, s->dir, &s->fail_next,
				   &as9888_sim_count_fops);
	debugfs_create_file_unsafe("fail_supply_on", 0600, s->dir,
				   &s->fail_supply_on, &as9888_sim_count_fops);
	debugfs_create_file_unsafe("fail_supply_off", 0600, s->dir,
				   &s->fail_supply_off, &as9888_sim_count_fops);
	debugfs_create_file_unsafe("delay_int1_us", 0600, s->dir,
				   &s->delay_int1_us, &as9888_sim_count_fops);
	debugfs_create_file("glitch_int1", 0200, s->dir, s,
			    &as9888_sim_glitch_fops);
	for (i = 0; i < AS9888_SIM_NKNOBS; i++) {
		s->knobs[i].s = s;
		s->knobs[i].id = i;
		debugfs_create_file(as9888_sim_knob_keys[i], 0600, s->dir,
				    &s->knobs[i], &as9888_sim_knob_fops);
	}

	sim = s;
	mutex_lock(&s->cfg_lock);
	step = "device";
	ret = as9888_sim_add_client(s);
	mutex_unlock(&s->cfg_lock);
	if (ret)
		goto err_debugfs;
	pr_info("as9888_sim: chip at %s, GPIO %s\n",
		as9888_sim_dev_name(s, name, sizeof(name)), gc->label);
	return 0;

err_debugfs:
	debugfs_remove_recursive(s->dir);
	regulator_unregister(s->rdev);
err_spi:
#ifndef AS9888_SIM_SWNODE_GPIO
	gpiod_remove_lookup_table(&as9888_sim_lookup);
#endif
	if (s->ctlr)
		spi_unregister_controller(s->ctlr);
err_i2c:
	i2c_del_adapter(&s->adap);
err_gpio:
	gpiochip_remove(gc);
err_domain:
	hrtimer_cancel(&s->timer);
	hrtimer_cancel(&s->delay_timer);
	as9888_sim_dispose_irqs(s);
	irq_domain_remove_sim(s->domain);
	irq_domain_remove(s->lvl_domain);
err_pdev:
	platform_device_unregister(s->pdev);
err_node:
	software_node_unregister_node_group(as9888_sim_nodes);
err_free:
	hrtimer_cancel(&s->timer);
	hrtimer_cancel(&s->delay_timer);
	kfree(s->unit_text);
	kfree(s);
	sim = NULL;
	pr_err("as9888_sim: %s: error %d\n", step, ret);
	return ret;
}
module_init(as9888_sim_init);

static void __exit as9888_sim_exit(void)
{
	struct as9888_sim *s = sim;

	debugfs_remove_recursive(s->dir);
	mutex_lock(&s->cfg_lock);
	as9888_sim_del_client(s);
	mutex_unlock(&s->cfg_lock);
	regulator_unregister(s->rdev);
#ifndef AS9888_SIM_SWNODE_GPIO
	gpiod_remove_lookup_table(&as9888_sim_lookup);
#endif
	if (s->ctlr)
		spi_unregister_controller(s->ctlr);
	i2c_del_adapter(&s->adap);
	gpiochip_remove(&s->gc);
	hrtimer_cancel(&s->timer);
	hrtimer_cancel(&s->delay_timer);
	as9888_sim_dispose_irqs(s);
	irq_domain_remove_sim(s->domain);
	irq_work_sync(&s->lvl_work);
	if (irq_find_mapping(s->lvl_domain, 0))
		irq_dispose_mapping(irq_find_mapping(s->lvl_domain, 0));
	irq_domain_remove(s->lvl_domain);
	platform_device_unregister(s->pdev);
	software_node_unregister_node_group(as9888_sim_nodes);
	kfree(s->unit_text);
	kfree(s);
}
module_exit(as9888_sim_exit);

MODULE_DESCRIPTION("AS9888 test adapter: chip model on a simulated I2C bus and GPIO chip");
MODULE_LICENSE("GPL");
