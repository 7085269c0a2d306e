// SPDX-License-Identifier: GPL-2.0
/* The simulator backend: adapts daemon/sim to the transport interface. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "as9888_sim.h"
#include "chip/backend_sim.h"

struct sim_transport {
	struct transport base;
	struct as9888_sim *sim;
};

static struct as9888_sim *to_sim(struct transport *t)
{
	return ((struct sim_transport *)t)->sim;
}

static int sim_read(struct transport *t, uint8_t reg, uint8_t *buf, size_t len)
{
	return as9888_sim_read(to_sim(t), reg, buf, (unsigned int)len);
}

static int sim_write(struct transport *t, uint8_t reg, const uint8_t *buf,
		     size_t len)
{
	return as9888_sim_write(to_sim(t), reg, buf, (unsigned int)len);
}

static int sim_set_rstn(struct transport *t, bool level)
{
	as9888_sim_set_rstn(to_sim(t), level);
	return 0;
}

static bool sim_pin_monitored(struct transport *t, enum transport_pin pin)
{
	return true;
}

static int sim_wait_pin(struct transport *t, enum transport_pin pin,
			uint64_t timeout_ns)
{
	return as9888_sim_wait_int(to_sim(t), pin == TRANSPORT_INT1 ?
				   AS9888_PIN_INT1 : AS9888_PIN_INT2,
				   timeout_ns);
}

static uint64_t sim_now_ns(struct transport *t)
{
	return as9888_sim_now_ns(to_sim(t));
}

static void sim_sleep_ns(struct transport *t, uint64_t ns)
{
	as9888_sim_sleep_ns(to_sim(t), ns);
}

static void sim_destroy(struct transport *t)
{
	as9888_sim_free(to_sim(t));
	free(t);
}

static const struct transport_ops sim_ops = {
	.read = sim_read,
	.write = sim_write,
	.set_rstn = sim_set_rstn,
	.pin_monitored = sim_pin_monitored,
	.wait_pin = sim_wait_pin,
	.now_ns = sim_now_ns,
	.sleep_ns = sim_sleep_ns,
	.destroy = sim_destroy,
};

struct as9888_sim *backend_sim_get(struct transport *t)
{
	return t->ops == &sim_ops ? to_sim(t) : NULL;
}

int backend_sim_open_unit(const struct as9888_unit *unit, bool virtual_clock,
			  struct transport **out, char *err, size_t errlen)
{
	struct as9888_sim_opts sim_opts = {
		.clock = virtual_clock ? AS9888_SIM_CLOCK_VIRTUAL :
					 AS9888_SIM_CLOCK_REAL,
	};
	struct sim_transport *st;

	st = calloc(1, sizeof(*st));
	if (!st) {
		snprintf(err, errlen, "simulator: out of memory");
		return -ENOMEM;
	}
	st->sim = as9888_sim_new(unit, &sim_opts);
	if (!st->sim) {
		free(st);
		snprintf(err, errlen, "simulator: cannot create the chip model");
		return -ENOMEM;
	}
	st->base.ops = &sim_ops;
	st->base.name = "sim";
	*out = &st->base;

	return 0;
}

int backend_sim_open(const struct backend_sim_opts *opts,
		     struct transport **out, char *err, size_t errlen)
{
	struct as9888_unit unit;
	int ret;

	as9888_unit_default(&unit);
	if (opts->unit_path) {
		ret = as9888_sim_load_unit_file(opts->unit_path, &unit, err,
						errlen);
		if (ret)
			return ret;
	}

	return backend_sim_open_unit(&unit, opts->virtual_clock, out, err,
				     errlen);
}
