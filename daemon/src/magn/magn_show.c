// SPDX-License-Identifier: GPL-2.0
/* The magnetometer's calibration shown (magn_show.h). */
#include <time.h>

#include "common/magn_cal.h"
#include "magn/magn_show.h"

#define NT_PER_UT	1000.0
#define MICRO		1000000.0

/* Both parts of @rec's calibration; false when the driver's cannot be made */
static bool split(const struct calib_record *rec, struct magn_driver_cal *d,
		  struct magn_user_cal *u)
{
	if (magn_driver_split(&rec->magn, rec->eeprom, d))
		return false;
	magn_user_split(&rec->magn, rec->eeprom, d, u);

	return true;
}

static void learned_text(const struct calib_magn *m, char *buf, size_t size)
{
	time_t t = (time_t)m->learned;
	struct tm tm;

	if (!gmtime_r(&t, &tm) ||
	    !strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm))
		snprintf(buf, size, "?");
}

/* "  @label" padded to the columns, then @v with @decimals decimals */
static void print_vec(FILE *out, const char *label, int decimals,
		      const double v[AS9888_AXES])
{
	fprintf(out, "  %-25s %9.*f %9.*f %9.*f\n", label, decimals, v[0],
		decimals, v[1], decimals, v[2]);
}

/* A 3x3 matrix under print_vec()'s columns, @label on its first row */
static void print_mat(FILE *out, const char *label,
		      const double m[AS9888_AXES][AS9888_AXES])
{
	int i;

	for (i = 0; i < AS9888_AXES; i++)
		print_vec(out, i ? "" : label, 6, m[i]);
}

void magn_show_text(FILE *out, const struct calib_record *rec)
{
	const struct calib_magn *m = &rec->magn;
	struct magn_driver_cal d;
	struct magn_user_cal u;
	char when[32];

	if (!m->present)
		return;
	learned_text(m, when, sizeof(when));
	fprintf(out, "Magnetometer, learned %s from %u samples (coverage %.3f):\n",
		when, m->samples, m->coverage_milli / 1000.0);
	fprintf(out, "  field %.3f uT, residual %.3f uT rms\n",
		m->field_nt / NT_PER_UT, m->residual_nt / NT_PER_UT);
	if (!split(rec, &d, &u)) {
		fprintf(out, "  (its hard iron is beyond the driver's calibbias range)\n");
		return;
	}
	print_vec(out, "hard iron b [uT]", 3, u.bias_ut);
	print_mat(out, "soft iron W", u.soft);
	print_mat(out, "turn Rrot", u.rotation);
	print_mat(out, "Rrot W (f = Rrot W(m-b))", u.full);
	fprintf(out, "  driver calibbias [LSB]    %9d %9d %9d\n",
		d.calibbias[0], d.calibbias[1], d.calibbias[2]);
	fprintf(out, "  driver calibscale         %9.6f %9.6f %9.6f\n",
		d.calibscale_micro[0] / MICRO, d.calibscale_micro[1] / MICRO,
		d.calibscale_micro[2] / MICRO);
	print_mat(out, "residual R (f = R(y-e))", u.residual);
	print_vec(out, "offset e [uT]", 4, u.offset_ut);
	print_vec(out, "HAL bias Rrot W b [uT]", 3, u.hal_bias_ut);
}

static void json_matrix(FILE *out, const double a[AS9888_AXES][AS9888_AXES])
{
	int i;

	fputc('[', out);
	for (i = 0; i < AS9888_AXES; i++)
		fprintf(out, "%s[%.6f, %.6f, %.6f]", i ? ", " : "", a[i][0],
			a[i][1], a[i][2]);
	fputc(']', out);
}

void magn_show_json(FILE *out, const struct calib_record *rec, int indent)
{
	const struct calib_magn *m = &rec->magn;
	struct magn_driver_cal d;
	struct magn_user_cal u;
	char when[32];
	int in = indent + 2;

	if (!m->present || !split(rec, &d, &u)) {
		fputs("null", out);
		return;
	}
	learned_text(m, when, sizeof(when));
	fprintf(out, "{\n%*s\"learned\": \"%s\", \"samples\": %u, \"coverage\": %.3f,\n",
		in, "", when, m->samples, m->coverage_milli / 1000.0);
	fprintf(out, "%*s\"field\": %.3f, \"residual\": %.3f,\n", in, "",
		m->field_nt / NT_PER_UT, m->residual_nt / NT_PER_UT);
	fprintf(out, "%*s\"hard_iron\": [%.3f, %.3f, %.3f],\n%*s\"soft_iron\": ", in,
		"", u.bias_ut[0], u.bias_ut[1], u.bias_ut[2], in, "");
	json_matrix(out, u.soft);
	fprintf(out, ",\n%*s\"rotation\": ", in, "");
	json_matrix(out, u.rotation);
	fprintf(out, ",\n%*s\"correction\": ", in, "");
	json_matrix(out, u.full);
	fprintf(out, ",\n%*s\"calibbias\": [%d, %d, %d], \"calibscale\": [%.6f, %.6f, %.6f],\n%*s\"residual_matrix\": ",
		in, "", d.calibbias[0], d.calibbias[1], d.calibbias[2],
		d.calibscale_micro[0] / MICRO, d.calibscale_micro[1] / MICRO,
		d.calibscale_micro[2] / MICRO, in, "");
	json_matrix(out, u.residual);
	fprintf(out, ",\n%*s\"offset\": [%.6f, %.6f, %.6f],\n%*s\"hal_bias\": [%.6f, %.6f, %.6f]\n%*s}",
		in, "", u.offset_ut[0], u.offset_ut[1], u.offset_ut[2], in, "",
		u.hal_bias_ut[0], u.hal_bias_ut[1], u.hal_bias_ut[2], indent, "");
}
