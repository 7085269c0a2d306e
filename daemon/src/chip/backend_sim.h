/* SPDX-License-Identifier: GPL-2.0 */
/* The simulator backend: the chip model behind the transport interface. */
#ifndef AS9888_BACKEND_SIM_H
#define AS9888_BACKEND_SIM_H

#include <stdbool.h>
#include <stddef.h>

#include "chip/transport.h"


/**
 * struct backend_sim_opts - how to build the simulated chip
 * @unit_path:	unit description file (NULL: the built-in default unit)
 * @virtual_clock: run in virtual time (tests) instead of real time
 */
struct backend_sim_opts {
	const char *unit_path;
	bool virtual_clock;
};

/* Returns 0 and the transport in @out, or -errno with a message in @err. */
int backend_sim_open(const struct backend_sim_opts *opts,
		     struct transport **out, char *err, size_t errlen);
struct as9888_unit;
/* The same with a unit already parsed */
int backend_sim_open_unit(const struct as9888_unit *unit, bool virtual_clock,
			  struct transport **out, char *err, size_t errlen);

struct as9888_sim;
/* The simulator behind @t, NULL when @t is not one (for tests: its model) */
struct as9888_sim *backend_sim_get(struct transport *t);

#endif
