// SPDX-License-Identifier: GPL-2.0
/* The factory test's report as text or JSON. */
#include <stdio.h>
#include <string.h>

#include "ftest_print.h"
#include "json.h"

static void print_axes_q16(FILE *out, const int32_t v[AS9888_AXES])
{
	fprintf(out, "[%.6f, %.6f, %.6f]", v[0] / 65536.0, v[1] / 65536.0,
		v[2] / 65536.0);
}

void ftest_print_json(FILE *out, const struct ftest_result *res,
			       const char *record_path, bool stored)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;
	uint32_t w;
	bool first = true;

	fputs("{\n  \"result\": ", out);
	json_string(out, failed ? "fail" : "pass");
	fputs(",\n  \"backend\": ", out);
	json_string(out, res->backend);
	fputs(",\n  \"failed_step\": ", out);
	json_string(out, failed ? failed->step : NULL);
	fputs(",\n  \"steps\": ", out);
	report_print_json_steps(out, &res->report);
	fputs(",\n  \"warnings\": [", out);
	for (w = res->warnings; w; w &= w - 1, first = false) {
		fputs(first ? "" : ", ", out);
		json_string(out, as9888_ee_warning_str(w & -w));
	}
	fputs("],\n  \"calibration\": ", out);
	if (!res->have_calibration) {
		fputs("null", out);
	} else {
		fprintf(out, "{\n    \"dac\": [%u, %u, %u],\n    \"level_mean\": ",
			rec->dac[0], rec->dac[1], rec->dac[2]);
		print_axes_q16(out, rec->level_mean_q16);
		fputs(",\n    \"offset\": ", out);
		print_axes_q16(out, res->offset_q16);
		fprintf(out, ",\n    \"t_level\": %.3f,\n    \"gravity\": [%d, %d, %d],\n"
			"    \"samples\": %u,\n    \"lpf\": %s\n  }",
			rec->t_level_mdegc / 1000.0, rec->gravity[0],
			rec->gravity[1], rec->gravity[2], rec->samples,
			rec->lpf ? "true" : "false");
	}
	fprintf(out, ",\n  \"duration_ms\": %.3f", res->duration_ns / 1e6);
	fputs(",\n  \"record\": ", out);
	json_string(out, stored ? record_path : NULL);
	fputs("\n}\n", out);
}

void ftest_print_text(FILE *out, const struct ftest_result *res)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;

	if (res->backend)
		fprintf(out, "Backend: %s%s\n\n", res->backend,
			!strcmp(res->backend, "sim") ?
			" (the SIMULATED chip, not a unit: its record is marked so)" : "");
	report_print_text(out, &res->report);
	if (res->have_calibration) {
		fprintf(out, "\nCalibration\n");
		fprintf(out, "  DAC          0x%02x 0x%02x 0x%02x\n", rec->dac[0],
			rec->dac[1], rec->dac[2]);
		fprintf(out, "  level mean   %.3f %.3f %.3f LSB\n",
			rec->level_mean_q16[0] / 65536.0,
			rec->level_mean_q16[1] / 65536.0,
			rec->level_mean_q16[2] / 65536.0);
		fprintf(out, "  offset Ot_L  %.3f %.3f %.3f LSB\n",
			res->offset_q16[0] / 65536.0, res->offset_q16[1] / 65536.0,
			res->offset_q16[2] / 65536.0);
		fprintf(out, "  t_L          %.3f degC\n", rec->t_level_mdegc / 1000.0);
		fprintf(out, "  gravity      %d %d %d\n", rec->gravity[0],
			rec->gravity[1], rec->gravity[2]);
		fprintf(out, "  samples      %u%s\n", rec->samples,
			rec->lpf ? " (low-pass filter on)" : "");
	}
	fprintf(out, "\nSteps 1-3 took %.1f ms\n", res->duration_ns / 1e6);
	if (failed)
		fprintf(out, "\nResult: FAIL at step %s (%s: %s)\n", failed->step,
			failed->name, failed->measured);
	else
		fprintf(out, "\nResult: PASS\n");
}

