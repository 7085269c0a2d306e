// SPDX-License-Identifier: GPL-2.0
/* Built with -Dsimulator=false: --backend sim says so and does nothing. */
#include <errno.h>
#include <stdio.h>

#include "chip/backend_sim.h"

int backend_sim_open(const struct backend_sim_opts *opts,
		     struct transport **out, char *err, size_t errlen)
{
	snprintf(err, errlen,
		 "this as9888-calibd is built without the simulator (meson -Dsimulator=false): use --backend iio or raw");
	return -EOPNOTSUPP;
}

int backend_sim_open_unit(const struct as9888_unit *unit, bool virtual_clock,
			  struct transport **out, char *err, size_t errlen)
{
	return backend_sim_open(NULL, out, err, errlen);
}
