/* SPDX-License-Identifier: GPL-2.0 */
/* Command-line parsing of as9888-calibd. */
#ifndef AS9888_CLI_H
#define AS9888_CLI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "chip/backend_raw.h"
#include "ftest/ftest.h"

/* the build sets it from -Dstatedir= (meson_options.txt) */
#ifndef CLI_DEFAULT_RECORD
#define CLI_DEFAULT_RECORD	"/var/lib/as9888/calibration"
#endif
#define CLI_DEFAULT_I2C_DEV	"/dev/i2c-0"
#define CLI_DEFAULT_SOCKET	"/run/as9888-calibd.sock"
#define CLI_DEFAULT_SOCKET_MODE	0660
#define CLI_DEFAULT_I2C_ADDRESS	0x0c
#define CLI_DEFAULT_LOCK_TIMEOUT_S	30
/* magn-calibrate --timeout: default and largest, seconds */
#define CLI_MAGN_TIMEOUT_S	120
#define CLI_MAGN_TIMEOUT_MAX_S	3600
/* magn-calibrate --earth-field: the plausible Earth field, nT (magcal's) */
#define CLI_MAGN_EARTH_MIN_NT	20000
#define CLI_MAGN_EARTH_MAX_NT	70000

/*
 * How the chip is reached. Without --backend, cli_parse() picks one
 * (cli_pick_backend()): a simulator option (--unit, --sim-clock) names the
 * simulator, a raw option the raw backend; else the bound driver, else a
 * chip answering on the raw bus, else CLI_BACKEND_NONE (the commands that
 * need the chip fail, saying @backend_why). The simulator never runs
 * unless named.
 */
enum cli_backend {
	CLI_BACKEND_SIM = 0,
	CLI_BACKEND_RAW,
	CLI_BACKEND_IIO,
	CLI_BACKEND_NONE,
};

#define CLI_BACKEND_WHY_LEN	768

enum cli_command {
	CLI_HELP = 0,
	CLI_FACTORY_TEST,
	CLI_RESTORE,
	CLI_SHOW,
	CLI_RECALIBRATE,
	CLI_ROLLBACK,
	CLI_CHECK,
	CLI_DAEMON,
	CLI_REQUEST,
	CLI_MAGN_CALIBRATE,
};

/**
 * struct cli_opts - everything the command line says
 * @command:		what to do
 * @record_path:	calibration record
 * @backend:		how the chip is reached
 * @raw:		where, for the raw backend
 * @unit_path:		simulated unit (NULL: built-in)
 * @virtual_clock:	simulator in virtual time
 * @json:		JSON output
 * @verbose:		say what was done on success
 * @fluctuation_given:	--fluctuation was given
 * @temperature_given:	--temperature was given
 * @temperature_mdegc:	its value
 * @socket_path:	the daemon's Unix socket
 * @socket_mode:	its permissions: who may send requests
 * @socket_group:	its group (NULL: the daemon's)
 * @operator_group:	daemon: the group whose members may ask for check,
 *			recalibrate and rollback besides root (NULL: root only)
 * @request:		what "request" asks the daemon
 * @lock_timeout_s:	longest wait for the record's lock
 * @state_group:	group trusted to write the record's files (NULL: none)
 * @backend_given:	--backend was given
 * @backend_auto:	@backend was picked, not given by --backend
 * @backend_why:	why no backend was found (CLI_BACKEND_NONE)
 * @junit_path:		factory-test: also write the report as JUnit XML there
 * @device:		restore --backend iio --device: the one IIO device
 *			(its sysfs directory) to restore, the other left
 *			alone; NULL: the chip's accelerometer and magnetometer
 * @magn_timeout_s:	magn-calibrate: the session's longest run
 * @magn_earth_nt:	magn-calibrate --earth-field: the site's field
 *			strength, nT, the calibrated magnitude; 0: none
 * @magn_feed:		the daemon's magn-feed request: its sample
 *			(REQUEST_FEED_VALUES), NULL otherwise
 * @log_fd:		in a request the daemon runs: its log (its stderr
 *			before the reply took it), else -1
 * @requester:		in a request the daemon runs: who asked ("uid U
 *			gid G pid P"), for the log; else NULL
 * @ftest:		factory-test options
 */
struct cli_opts {
	enum cli_command command;
	const char *record_path;
	enum cli_backend backend;
	struct backend_raw_opts raw;
	const char *unit_path;
	bool virtual_clock;
	bool json;
	bool verbose;
	bool fluctuation_given;
	bool temperature_given;
	int32_t temperature_mdegc;
	const char *socket_path;
	unsigned int socket_mode;
	const char *socket_group;
	const char *operator_group;
	const char *request;
	unsigned int lock_timeout_s;
	const char *state_group;
	bool backend_given;
	bool backend_auto;
	char backend_why[CLI_BACKEND_WHY_LEN];
	const char *junit_path;
	const char *device;
	unsigned int magn_timeout_s;
	int32_t magn_earth_nt;
	const double *magn_feed;
	int log_fd;
	const char *requester;
	struct ftest_opts ftest;
};

/* Returns 0, or -EINVAL with a message in @err */
int cli_parse(int argc, char **argv, struct cli_opts *o, char *err,
	      size_t errlen);

/* "sim", "raw", "iio" or "none" */
const char *cli_backend_name(enum cli_backend b);

/*
 * Without --backend: the bound AS9888 IIO driver, else a chip answering
 * (WIA) at @o->raw's bus and address, else CLI_BACKEND_NONE with the
 * reason and what to install in @o->backend_why. In backend_pick.c.
 */
void cli_pick_backend(struct cli_opts *o);

/* Parse a decimal with up to @decimals fraction digits, scaled by 10^@decimals */
int cli_parse_fixed(const char *s, int decimals, int64_t lo, int64_t hi,
		    int64_t *out);

#endif
