// SPDX-License-Identifier: GPL-2.0
/*
 * as9888-calibd: the AS9888 factory on-board test, offset DAC optimisation,
 * calibration record, boot-time restore and field recalibration.
 */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "commands/cli.h"
#include "commands/commands.h"
#include "commands/session.h"

#define EXIT_USAGE	2
#define ERR_LEN		512

static const char usage_text[] =
"Usage: as9888-calibd COMMAND [OPTIONS]\n"
"\n"
"Commands:\n"
"  factory-test   run the on-board function test (steps 1-4 of the\n"
"                 application note) and write the calibration record\n"
"  restore        check the record against the chip and apply it\n"
"  show           print the calibration at a temperature\n"
"  recalibrate    field repair after a shock: the level test again, on top\n"
"                 of the factory record (the device lying still and flat,\n"
"                 any side down); the old record is kept for rollback\n"
"  check          compare a level reading with the record's prediction and\n"
"                 say whether a recalibration is advisable\n"
"  rollback       bring back the calibration before the last recalibrate\n"
"                 or magn-calibrate\n"
"  magn-calibrate learn the magnetometer's hard and soft iron while the\n"
"                 device is turned through every direction; stored in the\n"
"                 record (the old one kept for rollback), applied to the\n"
"                 driver\n"
"  daemon         stay running: apply the record whenever the AS9888 IIO\n"
"                 device appears, and serve requests on a Unix socket\n"
"  request WHAT   ask the daemon: status, check, recalibrate, rollback,\n"
"                 magn (the magnetometer's calibration), \"magn-feed Y1 Y2 Y3\n"
"                 A1 A2 A3\" (a consumer's sample for the field mode)\n"
"  help           this text\n"
"\n"
"Common options:\n"
"  --record PATH        calibration record (default " CLI_DEFAULT_RECORD ")\n"
"  --backend sim|raw|iio  chip access: sim: the simulator (only when named:\n"
"                       its report and record say so); raw: the chip on an\n"
"                       I2C bus through i2c-dev with the kernel driver\n"
"                       unbound, its pins through libgpiod; iio: the bound\n"
"                       driver's interfaces (RSTN and INT2 checks skipped).\n"
"                       Default: iio if the driver is bound, else raw if the\n"
"                       chip answers on the bus, else an error; --unit or\n"
"                       --sim-clock name sim, a raw option raw\n"
"  --unit FILE          simulated unit description (default: built-in unit)\n"
"  --sim-clock real|virtual  simulator time base (default real)\n"
"  --json               JSON output (factory-test, show)\n"
"  --state-group NAME   group allowed to write the record's directory and\n"
"                       files (run as root, they must otherwise be root's\n"
"                       and writable by root alone)\n"
"  --lock-timeout S     longest wait for the record's lock held by another\n"
"                       command (factory-test, recalibrate, rollback,\n"
"                       daemon; default 30)\n"
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
"  --permissible-error E  derive N from a 32-sample pilot so that the level\n"
"                       mean's standard error is within E LSB with 95 %\n"
"                       confidence (Note 2; chi-square bound on sigma): a\n"
"                       one-sigma bound, |error| <= E in about 68 % of means\n"
"  --confidence P       with --permissible-error: |level mean - true value|\n"
"                       <= E with probability P per axis (0.5..0.9999; N\n"
"                       grows by the normal quantile squared: 3.8 x at 0.95)\n"
"  --fluctuation N      max - min limit per axis in LSB (default 15)\n"
"  --lpf                accelerometer low-pass filter on\n"
"  --gravity DIR        direction of gravity in the sensor frame: x+ x- y+\n"
"                       y- z+ z- (z- = Z axis up); default: detected\n"
"  --stable-timeout MS  how long to wait for a stable temperature\n"
"                       (default 10000)\n"
"  --busy-timeout S     through the driver: how long to wait for another\n"
"                       program's capture to end (default 30; then the\n"
"                       holder is named)\n"
"  --keep-going         do not stop at the first failed judgment\n"
"  --sequence ORDER     raw and simulator backends: datasheet (default: a\n"
"                       sample's rest is read while the next converts) or\n"
"                       note (the application note's literal order); the\n"
"                       same judgments\n"
"  --junit FILE         also write the judgments as JUnit XML to FILE\n"
"\n"
"restore options:\n"
"  --device DIR         --backend iio: restore only this IIO device (its\n"
"                       sysfs directory, as9888-accel or as9888-magn), as\n"
"                       the restore unit started for each device does;\n"
"                       default: both devices of the first chip found\n"
"  --verbose            say what was applied\n"
"\n"
"recalibrate and check take --samples, --fluctuation (default 8), --lpf,\n"
"--gravity, --stable-timeout, --busy-timeout and --json as well.\n"
"\n"
"daemon and request options:\n"
"  --socket PATH        Unix socket (default " CLI_DEFAULT_SOCKET ")\n"
"  --socket-mode MODE   its permissions, who may connect (default 0660)\n"
"  --socket-group NAME  its group: who may ask for status, magn, magn-feed\n"
"  --operator-group NAME  daemon: who besides root may also ask for check,\n"
"                       recalibrate and rollback (default: root only)\n"
"\n"
"magn-calibrate options (and the common ones):\n"
"  --timeout S          give up after S seconds, 1..3600 (default 120)\n"
"  --earth-field UT     the site's field strength (the World Magnetic Model's\n"
"                       total intensity), 20..70 uT: the calibrated field's\n"
"                       magnitude (default: the fitted one)\n"
"\n"
"show options:\n"
"  --temperature T      degrees Celsius, -30..85 (default: the level test's)\n"
"\n"
"Exit status: 0 success, 1 a judgment or check failed, 2 usage error;\n"
"request exits with the status of the command the daemon ran.\n";

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

	if (record_store_trust_setup(o.state_group, err, sizeof(err))) {
		fprintf(stderr, "as9888-calibd: %s\n", err);
		return EXIT_USAGE;
	}

	switch (o.command) {
	case CLI_HELP:
		/*
		 * In one write: the text is longer than stdio's pipe buffer,
		 * and a reader that stops at the line it wants ("grep -q")
		 * must not kill us with SIGPIPE on a second write
		 */
		return write(STDOUT_FILENO, usage_text, sizeof(usage_text) - 1) ==
		       (ssize_t)sizeof(usage_text) - 1 ? EXIT_SUCCESS : EXIT_FAILURE;
	case CLI_FACTORY_TEST:
		return cmd_factory_test(&o);
	case CLI_RESTORE:
		return cmd_restore(&o);
	case CLI_SHOW:
		return cmd_show(&o);
	case CLI_RECALIBRATE:
		return cmd_recalibrate(&o);
	case CLI_ROLLBACK:
		return cmd_rollback(&o);
	case CLI_CHECK:
		return cmd_check(&o);
	case CLI_DAEMON:
		return cmd_daemon(&o);
	case CLI_REQUEST:
		return cmd_request(&o);
	case CLI_MAGN_CALIBRATE:
		return cmd_magn_calibrate(&o);
	}

	return EXIT_USAGE;
}
