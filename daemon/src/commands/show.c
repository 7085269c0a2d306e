// SPDX-License-Identifier: GPL-2.0
/* "show": the calibration of a record at a temperature (datasheet 6). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "common/json.h"
#include "magn/magn_show.h"
#include "commands/show.h"

static const char *const axis_key[AS9888_AXES] = { "x", "y", "z" };

int show_compute(const struct calib_record *rec, bool t_given, int32_t t_mdegc,
		 struct show_result *s, char *err, size_t errlen)
{
	struct as9888_eeprom ee;
	int32_t ot_l[AS9888_AXES];
	int axis, ret;

	memset(s, 0, sizeof(*s));
	s->t_mdegc = t_given ? t_mdegc : rec->t_level_mdegc;
	ret = as9888_eeprom_decode(rec->eeprom, &ee);
	if (!ret)
		ret = record_level_offsets(rec, &ee, ot_l);
	for (axis = 0; !ret && axis < AS9888_AXES; axis++) {
		const struct as9888_axis_trim *trim = &ee.axis[axis];

		ret = as9888_sensitivity_q16(trim, ee.t_rt_mdegc, s->t_mdegc,
					     &s->st_q16[axis]);
		if (!ret)
			ret = as9888_offset_q16(trim, ot_l[axis], rec->t_level_mdegc,
						s->t_mdegc, &s->ot_q16[axis]);
		s->kote_milli[axis] = (int32_t)as9888_div_round_s64(
			(int64_t)trim->kote_num * 1000, trim->kote_den);
	}
	if (ret) {
		snprintf(err, errlen, "cannot compute the calibration: %s",
			 strerror(-ret));
		return ret;
	}
	s->warnings = ee.warnings;

	return 0;
}

void show_print_text(FILE *out, const struct calib_record *rec,
		     const struct show_result *s)
{
	uint32_t w;
	int axis;

	fprintf(out, "Chip %016llx, level test at %.3f degC, gravity %d %d %d, N %u%s\n",
		(unsigned long long)record_fingerprint(rec->eeprom),
		rec->t_level_mdegc / 1000.0, rec->gravity[0], rec->gravity[1],
		rec->gravity[2], rec->samples, rec->lpf ? ", LPF on" : "");
	fprintf(out, "DAC 0x%02x 0x%02x 0x%02x, level mean %.3f %.3f %.3f LSB\n",
		rec->dac[0], rec->dac[1], rec->dac[2],
		rec->level_mean_q16[0] / 65536.0, rec->level_mean_q16[1] / 65536.0,
		rec->level_mean_q16[2] / 65536.0);
	fprintf(out, "At %.3f degC:\n", s->t_mdegc / 1000.0);
	fprintf(out, "  axis  sensitivity [LSB/g]  offset [LSB]  Kote [LSB/degC]\n");
	for (axis = 0; axis < AS9888_AXES; axis++)
		fprintf(out, "  %-4s  %19.4f  %12.4f  %15.3f\n", axis_key[axis],
			s->st_q16[axis] / 65536.0, s->ot_q16[axis] / 65536.0,
			s->kote_milli[axis] / 1000.0);
	for (w = s->warnings; w; w &= w - 1)
		fprintf(out, "warning: %s\n", as9888_ee_warning_str(w & -w));
	magn_show_text(out, rec);
}

void show_print_json(FILE *out, const struct calib_record *rec,
		     const struct show_result *s)
{
	int axis;

	fprintf(out, "{\n  \"temperature\": %.3f,\n  \"axes\": {", s->t_mdegc / 1000.0);
	for (axis = 0; axis < AS9888_AXES; axis++)
		fprintf(out, "%s\n    \"%s\": {\"sensitivity\": %.6f, \"offset\": %.6f}",
			axis ? "," : "", axis_key[axis], s->st_q16[axis] / 65536.0,
			s->ot_q16[axis] / 65536.0);
	fprintf(out, "\n  },\n  \"record\": {\"chip\": \"%016llx\", \"dac\": [%u, %u, %u], "
		"\"level_mean\": [%.6f, %.6f, %.6f], \"t_level\": %.3f, "
		"\"gravity\": [%d, %d, %d], \"samples\": %u, \"lpf\": %s}",
		(unsigned long long)record_fingerprint(rec->eeprom),
		rec->dac[0], rec->dac[1], rec->dac[2],
		rec->level_mean_q16[0] / 65536.0, rec->level_mean_q16[1] / 65536.0,
		rec->level_mean_q16[2] / 65536.0, rec->t_level_mdegc / 1000.0,
		rec->gravity[0], rec->gravity[1], rec->gravity[2], rec->samples,
		rec->lpf ? "true" : "false");
	if (rec->magn.present) {
		fputs(",\n  \"magnetometer\": ", out);
		magn_show_json(out, rec, 2);
	}
	fputs("\n}\n", out);
}
