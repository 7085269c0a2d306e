// SPDX-License-Identifier: GPL-2.0
/*
 * The magnetometer's calibration: shown (the daemon's "magn" request).
 */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "magn_show.h"
#include "session.h"

int cmd_magn_show(const struct cli_opts *o)
{
	struct calib_record rec;

	if (session_load_record(o->record_path, &rec))
		return EXIT_FAILURE;
	if (!rec.magn.present) {
		fprintf(stderr, "as9888-calibd: %s has no magnetometer calibration (a format 1 record): run as9888-calibd magn-calibrate\n",
			o->record_path);
		return EXIT_FAILURE;
	}
	if (o->json) {
		magn_show_json(stdout, &rec, 0);
		fputc('\n', stdout);
	} else {
		magn_show_text(stdout, &rec);
	}

	return EXIT_SUCCESS;
}
