// SPDX-License-Identifier: GPL-2.0
/*
 * as9888-calibd: the AS9888 factory on-board test, offset DAC optimisation,
 * calibration record and boot-time restore.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "as9888_regs.h"
#include "atomic_file.h"
#include "backend_raw.h"
#include "backend_sim.h"
#include "cli.h"
#include "ftest.h"
#include "json.h"
#include "record.h"
#include "show.h"

#define EXIT_USAGE	2
#define RECORD_MODE	0644
#define STATE_DIR_MODE	0755
#define ERR_LEN		512

static const char usage_text[] =
"Usage: as9888-calibd COMMAND [OPTIONS]\n"
"\n"
"Commands:\n"
"  factory-test   run the on-board function test (steps 1-4 of the\n"
"                 application note) and write the calibration record\n"
"  restore        check the record against the chip and apply it\n"
"  show           print the calibration at a temperature\n"
"  help           this text\n"
"\n"
"Common options:\n"
"  --record PATH        calibration record (default " CLI_DEFAULT_RECORD ")\n"
"  --backend sim|raw    chip access: the simulator (default), or the chip on\n"
"                       an I2C bus through i2c-dev with the kernel driver\n"
"                       unbound, its pins through libgpiod\n"
"  --unit FILE          simulated unit description (default: built-in unit)\n"
"  --sim-clock real|virtual  simulator time base (default real)\n"
"  --json               JSON output (factory-test, show)\n"
"\n"
"raw backend options:\n"
"  --i2c-dev PATH       i2c-dev node (default " CLI_DEFAULT_I2C_DEV ")\n"
"  --i2c-address ADDR   0x0c..0x0f (default 0x0c)\n"
"  --gpiochip CHIP      GPIO chip of the lines below\n"
"  --rstn-line N, --int1-line N, --int2-line N\n"
"                       line offsets; a pin not given is not monitored (its\n"
"                       check is skipped, DRDY is polled without INT1)\n"
"\n"
"factory-test options:\n"
"  --samples N          samples averaged per level measurement (10..4096,\n"
"                       default 10)\n"
"  --permissible-error E  derive N from a pilot run so that the average's\n"
"                       error stays within E LSB (Note 2)\n"
"  --fluctuation N      max - min limit per axis in LSB (default 15)\n"
"  --lpf                accelerometer low-pass filter on\n"
"  --gravity DIR        direction of gravity in the sensor frame: x+ x- y+\n"
"                       y- z+ z- (z- = Z axis up); default: detected\n"
"  --stable-timeout MS  how long to wait for a stable temperature\n"
"                       (default 10000)\n"
"  --keep-going         do not stop at the first failed judgment\n"
"\n"
"show options:\n"
"  --temperature T      degrees Celsius, -30..85 (default: the level test's)\n"
"\n"
"Exit status: 0 success, 1 a judgment or check failed, 2 usage error.\n";

static int open_backend(const struct cli_opts *o, struct transport **t)
{
	struct backend_sim_opts sim = {
		.unit_path = o->unit_path,
		.virtual_clock = o->virtual_clock,
	};
	char err[ERR_LEN];
	int ret;

	if (o->backend == CLI_BACKEND_RAW)
		ret = backend_raw_open(&o->raw, t, err, sizeof(err));
	else
		ret = backend_sim_open(&sim, t, err, sizeof(err));
	if (ret)
		fprintf(stderr, "as9888-calibd: %s\n", err);

	return ret;
}

static void print_axes_q16(FILE *out, const int32_t v[AS9888_AXES])
{
	fprintf(out, "[%.6f, %.6f, %.6f]", v[0] / 65536.0, v[1] / 65536.0,
		v[2] / 65536.0);
}

static void print_factory_json(FILE *out, const struct ftest_result *res,
			       const char *record_path, bool stored)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;
	uint32_t w;
	bool first = true;

	fputs("{\n  \"result\": ", out);
	json_string(out, failed ? "fail" : "pass");
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

static void print_factory_text(FILE *out, const struct ftest_result *res)
{
	const struct judgment *failed = report_first_failure(&res->report);
	const struct calib_record *rec = &res->rec;

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

/* Step 4-1: store the record crash-safely */
static bool store_record(const struct cli_opts *o, struct ftest_result *res)
{
	char buf[RECORD_MAX_SIZE], err[ERR_LEN];
	int len, ret;

	res->rec.created = (int64_t)time(NULL);
	len = record_format(&res->rec, buf, sizeof(buf));
	ret = len < 0 ? len : ensure_parent_dir(o->record_path, STATE_DIR_MODE,
						 err, sizeof(err));
	if (len < 0)
		snprintf(err, sizeof(err), "cannot format the record: %s",
			 strerror(-len));
	if (!ret)
		ret = atomic_write_file(o->record_path, buf, (size_t)len,
					RECORD_MODE, err, sizeof(err));
	report_add(&res->report, "4-1", "store calibration record",
		   ret ? JUDGMENT_FAIL : JUDGMENT_PASS, NULL, "%s",
		   ret ? err : o->record_path);

	return ret == 0;
}

static int cmd_factory_test(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	struct transport *t;
	bool stored = false;
	int ret;

	ret = open_backend(o, &t);
	if (ret)
		return EXIT_FAILURE;

	ftest_run(t, &o->ftest, &res);
	transport_destroy(t);

	if (res.have_calibration && !report_first_failure(&res.report))
		stored = store_record(o, &res);

	if (o->json) {
		print_factory_json(stdout, &res, o->record_path, stored);
	} else {
		print_factory_text(stdout, &res);
		if (stored)
			printf("Record written to %s\n", o->record_path);
	}
	ret = report_first_failure(&res.report) || res.report.oom ?
	      EXIT_FAILURE : EXIT_SUCCESS;
	ftest_result_free(&res);

	return ret;
}

static int load_record(const char *path, struct calib_record *rec)
{
	char buf[RECORD_MAX_SIZE + 1], err[ERR_LEN];
	long len;

	len = read_file_nofollow(path, buf, RECORD_MAX_SIZE, err, sizeof(err));
	if (len < 0) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return (int)len;
	}
	if (record_parse(buf, (size_t)len, rec, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s: not a valid record: %s\n", path,
			err);
		return -EINVAL;
	}

	return 0;
}

static int cmd_restore(const struct cli_opts *o)
{
	struct ftest_result res = { 0 };
	struct calib_record rec;
	struct transport *t;
	uint8_t back[AS9888_AXES];
	int ret;

	if (load_record(o->record_path, &rec))
		return EXIT_FAILURE;
	ret = open_backend(o, &t);
	if (ret)
		return EXIT_FAILURE;

	ret = ftest_step1(t, &res, false);
	if (ret) {
		const struct judgment *j = report_first_failure(&res.report);

		fprintf(stderr, "as9888-calibd: restore: chip initialisation failed at step %s (%s: %s); nothing applied\n",
			j ? j->step : "1", j ? j->name : "step 1",
			j ? j->measured : strerror(-ret));
		goto out;
	}
	if (memcmp(res.ee.raw, rec.eeprom, AS9888_EEPROM_LEN)) {
		fprintf(stderr, "as9888-calibd: restore: %s belongs to chip %016llx, this chip is %016llx; nothing applied\n",
			o->record_path,
			(unsigned long long)record_fingerprint(rec.eeprom),
			(unsigned long long)record_fingerprint(res.ee.raw));
		ret = -ENODEV;
		goto out;
	}

	ret = transport_write(t, AS9888_REG_AXDA, rec.dac, AS9888_AXES);
	if (!ret)
		ret = transport_read(t, AS9888_REG_AXDA, back, AS9888_AXES);
	if (!ret && memcmp(back, rec.dac, AS9888_AXES))
		ret = -EIO;
	if (ret) {
		fprintf(stderr, "as9888-calibd: restore: writing the offset DAC failed: %s\n",
			strerror(-ret));
		goto out;
	}
	if (o->verbose)
		printf("restored DAC 0x%02x 0x%02x 0x%02x on chip %016llx\n",
		       rec.dac[0], rec.dac[1], rec.dac[2],
		       (unsigned long long)record_fingerprint(rec.eeprom));
out:
	transport_destroy(t);
	ftest_result_free(&res);

	return ret ? EXIT_FAILURE : EXIT_SUCCESS;
}

static int cmd_show(const struct cli_opts *o)
{
	struct calib_record rec;
	struct show_result s;
	char err[ERR_LEN];

	if (load_record(o->record_path, &rec))
		return EXIT_FAILURE;
	if (show_compute(&rec, o->temperature_given, o->temperature_mdegc, &s,
			 err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: show: %s\n", err);
		return EXIT_FAILURE;
	}
	if (o->json)
		show_print_json(stdout, &rec, &s);
	else
		show_print_text(stdout, &rec, &s);

	return EXIT_SUCCESS;
}

int main(int argc, char **argv)
{
	struct cli_opts o;
	char err[ERR_LEN];
	int ret;

	ret = cli_parse(argc, argv, &o, err, sizeof(err));
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s\nTry 'as9888-calibd help'.\n", err);
		return EXIT_USAGE;
	}

	switch (o.command) {
	case CLI_HELP:
		fputs(usage_text, stdout);
		return EXIT_SUCCESS;
	case CLI_FACTORY_TEST:
		return cmd_factory_test(&o);
	case CLI_RESTORE:
		return cmd_restore(&o);
	case CLI_SHOW:
		return cmd_show(&o);
	}

	return EXIT_USAGE;
}
