/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The register-level transport the factory test and restore run over: a
 * bus (register reads and writes with auto-increment), the RSTN pin, the
 * INT1/INT2 pins and a clock. Backends: the simulator (backend_sim.c) and,
 * for a chip on a real bus, i2c-dev plus libgpiod (backend_raw.c).
 */
#ifndef AS9888_TRANSPORT_H
#define AS9888_TRANSPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum transport_pin {
	TRANSPORT_INT1 = 0,
	TRANSPORT_INT2,
};

struct transport;

/**
 * struct transport_ops - what a backend provides
 * @read:	one burst read from @reg; 0 or -errno
 * @write:	one burst write to @reg; 0 or -errno
 * @set_rstn:	drive RSTN; -EOPNOTSUPP when the backend has no reset line
 * @pin_monitored: whether INT1/INT2 can be observed
 * @wait_pin:	wait until @pin is high, at most @timeout_ns; 1 high,
 *		0 timeout, -errno (never called for an unmonitored pin)
 * @now_ns:	monotonic clock of the backend
 * @sleep_ns:	sleep on that clock
 * @destroy:	release everything
 */
struct transport_ops {
	int (*read)(struct transport *t, uint8_t reg, uint8_t *buf, size_t len);
	int (*write)(struct transport *t, uint8_t reg, const uint8_t *buf,
		     size_t len);
	int (*set_rstn)(struct transport *t, bool level);
	bool (*pin_monitored)(struct transport *t, enum transport_pin pin);
	int (*wait_pin)(struct transport *t, enum transport_pin pin,
			uint64_t timeout_ns);
	uint64_t (*now_ns)(struct transport *t);
	void (*sleep_ns)(struct transport *t, uint64_t ns);
	void (*destroy)(struct transport *t);
};

/**
 * struct transport - a backend instance
 * @ops:	its operations
 * @name:	backend name for messages ("sim", "raw")
 */
struct transport {
	const struct transport_ops *ops;
	const char *name;
};

static inline int transport_read(struct transport *t, uint8_t reg,
				 uint8_t *buf, size_t len)
{
	return t->ops->read(t, reg, buf, len);
}

static inline int transport_write(struct transport *t, uint8_t reg,
				  const uint8_t *buf, size_t len)
{
	return t->ops->write(t, reg, buf, len);
}

static inline int transport_write_reg(struct transport *t, uint8_t reg,
				      uint8_t val)
{
	return t->ops->write(t, reg, &val, 1);
}

static inline int transport_read_reg(struct transport *t, uint8_t reg,
				     uint8_t *val)
{
	return t->ops->read(t, reg, val, 1);
}

static inline uint64_t transport_now_ns(struct transport *t)
{
	return t->ops->now_ns(t);
}

static inline void transport_sleep_ns(struct transport *t, uint64_t ns)
{
	t->ops->sleep_ns(t, ns);
}

static inline void transport_destroy(struct transport *t)
{
	if (t)
		t->ops->destroy(t);
}

#endif /* AS9888_TRANSPORT_H */
