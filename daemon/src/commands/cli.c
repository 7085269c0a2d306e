// SPDX-License-Identifier: GPL-2.0
/* Command-line parsing of as9888-calibd: strict, with clear messages. */
#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands/cli.h"

static int bad(char *err, size_t errlen, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

static int bad(char *err, size_t errlen, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(err, errlen, fmt, ap);
	va_end(ap);

	return -EINVAL;
}

int cli_parse_fixed(const char *s, int decimals, int64_t lo, int64_t hi,
		    int64_t *out)
{
	bool neg = false, point = false;
	int64_t v = 0;
	int digits = 0, frac = 0;

	if (*s == '-' || *s == '+')
		neg = *s++ == '-';
	for (; *s; s++) {
		if (*s == '.' && !point && digits) {
			point = true;
			continue;
		}
		if (*s < '0' || *s > '9' || ++digits > 15)
			return -EINVAL;
		if (point && ++frac > decimals)
			return -EINVAL;
		v = v * 10 + (*s - '0');
	}
	if (!digits || (point && !frac))
		return -EINVAL;
	for (; frac < decimals; frac++)
		v *= 10;
	if (neg)
		v = -v;
	if (v < lo || v > hi)
		return -ERANGE;
	*out = v;

	return 0;
}

static int parse_gravity(const char *s, int8_t g[3])
{
	static const char axes[] = "xyz";
	const char *axis = strlen(s) == 2 ? strchr(axes, s[0]) : NULL;

	if (!axis || !s[0] || (s[1] != '+' && s[1] != '-'))
		return -EINVAL;
	memset(g, 0, 3);
	g[axis - axes] = s[1] == '+' ? 1 : -1;

	return 0;
}

/* A socket mode: octal, no set-id or sticky bits */
static int parse_mode(const char *s, unsigned int *mode)
{
	unsigned long v;
	char *end;

	if (*s < '0' || *s > '7')	/* strtoul() would take " 1", "+1" */
		return -EINVAL;
	errno = 0;
	v = strtoul(s, &end, 8);
	if (errno || end == s || *end || v > 0777)
		return -EINVAL;
	*mode = (unsigned int)v;

	return 0;
}

/* An I2C address the chip can have: 0x0c..0x0f (CAD1/CAD0) */
static int parse_address(const char *s, unsigned int *address)
{
	unsigned long v;
	char *end;

	if (*s < '0' || *s > '9')
		return -EINVAL;
	errno = 0;
	v = strtoul(s, &end, 0);
	if (errno || end == s || *end || v < 0x0c || v > 0x0f)
		return -EINVAL;
	*address = (unsigned int)v;

	return 0;
}

/* Option handlers: apply @arg to @o, or say what the option takes */
typedef int (*cli_apply_fn)(struct cli_opts *o, const char *arg, char *err,
			    size_t errlen);

static int apply_record(struct cli_opts *o, const char *arg, char *err,
			size_t errlen)
{
	if (!*arg)
		return bad(err, errlen, "--record needs a path");
	o->record_path = arg;

	return 0;
}

static int apply_backend(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	if (!strcmp(arg, "sim"))
		o->backend = CLI_BACKEND_SIM;
	else if (!strcmp(arg, "raw"))
		o->backend = CLI_BACKEND_RAW;
	else if (!strcmp(arg, "iio"))
		o->backend = CLI_BACKEND_IIO;
	else
		return bad(err, errlen, "unknown backend \"%s\" (sim, raw or iio)",
			   arg);
	o->backend_given = true;

	return 0;
}

static int apply_unit(struct cli_opts *o, const char *arg, char *err,
		      size_t errlen)
{
	o->unit_path = arg;

	return 0;
}

static int apply_sim_clock(struct cli_opts *o, const char *arg, char *err,
			   size_t errlen)
{
	if (!strcmp(arg, "virtual"))
		o->virtual_clock = true;
	else if (strcmp(arg, "real"))
		return bad(err, errlen, "--sim-clock takes real or virtual, not \"%s\"",
			   arg);

	return 0;
}

static int apply_json(struct cli_opts *o, const char *arg, char *err,
		      size_t errlen)
{
	o->json = true;

	return 0;
}

static int apply_samples(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, AS9888_SAMPLES_MIN, AS9888_SAMPLES_MAX, &v))
		return bad(err, errlen, "--samples takes an integer %d..%d, not \"%s\"",
			   AS9888_SAMPLES_MIN, AS9888_SAMPLES_MAX, arg);
	o->ftest.samples = (uint32_t)v;

	return 0;
}

/* LSB with up to 3 decimals, 0.001..100 */
static int apply_permissible_error(struct cli_opts *o, const char *arg,
				   char *err, size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 3, 1, 100000, &v))
		return bad(err, errlen, "--permissible-error takes LSB in 0.001..100, not \"%s\"",
			   arg);
	o->ftest.permissible_error_q16 =
		(uint32_t)((v * AS9888_Q16_ONE + 500) / 1000);

	return 0;
}

/* P with up to 4 decimals, 0.5..0.9999 */
static int apply_confidence(struct cli_opts *o, const char *arg, char *err,
			    size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 4, FTEST_CONFIDENCE_MIN_1E4,
			    FTEST_CONFIDENCE_MAX_1E4, &v))
		return bad(err, errlen, "--confidence takes a probability in 0.5..0.9999, not \"%s\"",
			   arg);
	o->ftest.confidence_1e4 = (uint32_t)v;

	return 0;
}

/* note: the application note's literal order; datasheet: the faster one */
static int apply_sequence(struct cli_opts *o, const char *arg, char *err,
			  size_t errlen)
{
	if (!strcmp(arg, "note"))
		o->ftest.note_order = true;
	else if (!strcmp(arg, "datasheet"))
		o->ftest.note_order = false;
	else
		return bad(err, errlen, "--sequence takes note or datasheet, not \"%s\"",
			   arg);

	return 0;
}

static int apply_fluctuation(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 0, 4095, &v))
		return bad(err, errlen, "--fluctuation takes an integer 0..4095, not \"%s\"",
			   arg);
	o->ftest.fluctuation = (uint32_t)v;
	o->fluctuation_given = true;

	return 0;
}

static int apply_lpf(struct cli_opts *o, const char *arg, char *err,
		     size_t errlen)
{
	o->ftest.lpf = true;

	return 0;
}

static int apply_gravity(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	if (parse_gravity(arg, o->ftest.gravity))
		return bad(err, errlen, "--gravity takes x+ x- y+ y- z+ z-, not \"%s\"",
			   arg);
	o->ftest.gravity_given = true;

	return 0;
}

static int apply_stable_timeout(struct cli_opts *o, const char *arg,
				char *err, size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 0, 600000, &v))
		return bad(err, errlen, "--stable-timeout takes milliseconds 0..600000, not \"%s\"",
			   arg);
	o->ftest.stable_timeout_ms = (uint32_t)v;

	return 0;
}

static int apply_keep_going(struct cli_opts *o, const char *arg, char *err,
			    size_t errlen)
{
	o->ftest.keep_going = true;

	return 0;
}

static int apply_temperature(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 3, -30000, 85000, &v))
		return bad(err, errlen, "--temperature takes degrees Celsius -30..85, not \"%s\"",
			   arg);
	o->temperature_given = true;
	o->temperature_mdegc = (int32_t)v;

	return 0;
}

static int apply_verbose(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	o->verbose = true;

	return 0;
}

static int apply_help(struct cli_opts *o, const char *arg, char *err,
		      size_t errlen)
{
	o->command = CLI_HELP;

	return 0;
}

static int apply_i2c_dev(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	o->raw.i2c_dev = arg;

	return 0;
}

static int apply_i2c_address(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	if (parse_address(arg, &o->raw.address))
		return bad(err, errlen, "--i2c-address takes 0x0c..0x0f, not \"%s\"",
			   arg);

	return 0;
}

static int apply_gpiochip(struct cli_opts *o, const char *arg, char *err,
			  size_t errlen)
{
	o->raw.gpiochip = arg;

	return 0;
}

static int parse_line(const char *name, const char *arg, int *line, char *err,
		      size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 0, 4095, &v))
		return bad(err, errlen, "--%s takes a line offset 0..4095, not \"%s\"",
			   name, arg);
	*line = (int)v;

	return 0;
}

static int apply_rstn_line(struct cli_opts *o, const char *arg, char *err,
			   size_t errlen)
{
	return parse_line("rstn-line", arg, &o->raw.rstn, err, errlen);
}

static int apply_int1_line(struct cli_opts *o, const char *arg, char *err,
			   size_t errlen)
{
	return parse_line("int1-line", arg, &o->raw.int1, err, errlen);
}

static int apply_int2_line(struct cli_opts *o, const char *arg, char *err,
			   size_t errlen)
{
	return parse_line("int2-line", arg, &o->raw.int2, err, errlen);
}

static int apply_socket(struct cli_opts *o, const char *arg, char *err,
			size_t errlen)
{
	if (!*arg)
		return bad(err, errlen, "--socket needs a path");
	o->socket_path = arg;

	return 0;
}

static int apply_socket_mode(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	if (parse_mode(arg, &o->socket_mode))
		return bad(err, errlen, "--socket-mode takes an octal mode such as 0660, not \"%s\"",
			   arg);

	return 0;
}

static int apply_socket_group(struct cli_opts *o, const char *arg, char *err,
			      size_t errlen)
{
	o->socket_group = arg;

	return 0;
}

static int apply_operator_group(struct cli_opts *o, const char *arg, char *err,
				size_t errlen)
{
	if (!*arg)
		return bad(err, errlen, "--operator-group needs a group name");
	o->operator_group = arg;

	return 0;
}

static int apply_lock_timeout(struct cli_opts *o, const char *arg, char *err,
			      size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 0, 3600, &v))
		return bad(err, errlen, "--lock-timeout takes seconds 0..3600, not \"%s\"",
			   arg);
	o->lock_timeout_s = (unsigned int)v;

	return 0;
}

static int apply_busy_timeout(struct cli_opts *o, const char *arg, char *err,
			      size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 0, FTEST_BUSY_TIMEOUT_S_MAX, &v))
		return bad(err, errlen, "--busy-timeout takes seconds 0..%d, not \"%s\"",
			   FTEST_BUSY_TIMEOUT_S_MAX, arg);
	o->ftest.busy_timeout_ms = (uint32_t)v * 1000;

	return 0;
}

static int apply_state_group(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	if (!*arg)
		return bad(err, errlen, "--state-group needs a group name");
	o->state_group = arg;

	return 0;
}

static int apply_junit(struct cli_opts *o, const char *arg, char *err,
		       size_t errlen)
{
	if (!*arg)
		return bad(err, errlen, "--junit needs a path");
	o->junit_path = arg;

	return 0;
}

static int apply_device(struct cli_opts *o, const char *arg, char *err,
			size_t errlen)
{
	if (arg[0] != '/')
		return bad(err, errlen, "--device takes the absolute sysfs path of an AS9888 IIO device (as systemd's %%f gives it), not \"%s\"",
			   arg);
	o->device = arg;

	return 0;
}

static int apply_earth_field(struct cli_opts *o, const char *arg, char *err,
			     size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 3, CLI_MAGN_EARTH_MIN_NT, CLI_MAGN_EARTH_MAX_NT,
			    &v))
		return bad(err, errlen, "--earth-field takes the site's field strength in uT, %d..%d (the World Magnetic Model's total intensity there), not \"%s\"",
			   CLI_MAGN_EARTH_MIN_NT / 1000,
			   CLI_MAGN_EARTH_MAX_NT / 1000, arg);
	o->magn_earth_nt = (int32_t)v;

	return 0;
}

static int apply_timeout(struct cli_opts *o, const char *arg, char *err,
			 size_t errlen)
{
	int64_t v;

	if (cli_parse_fixed(arg, 0, 1, CLI_MAGN_TIMEOUT_MAX_S, &v))
		return bad(err, errlen, "--timeout takes seconds 1..%d, not \"%s\"",
			   CLI_MAGN_TIMEOUT_MAX_S, arg);
	o->magn_timeout_s = (unsigned int)v;

	return 0;
}

/* The commands an option belongs to */
#define CMD(c)		(1u << (c))
#define CMDS_ALL	(~0u)
#define CMDS_CHIP	(CMD(CLI_FACTORY_TEST) | CMD(CLI_RESTORE) |		\
			 CMD(CLI_RECALIBRATE) | CMD(CLI_ROLLBACK) |		\
			 CMD(CLI_CHECK) | CMD(CLI_DAEMON) | CMD(CLI_MAGN_CALIBRATE))
#define CMDS_LEVEL	(CMD(CLI_FACTORY_TEST) | CMD(CLI_RECALIBRATE) |	\
			 CMD(CLI_CHECK))
#define CMDS_LOCKING	(CMD(CLI_FACTORY_TEST) | CMD(CLI_RECALIBRATE) |	\
			 CMD(CLI_ROLLBACK) | CMD(CLI_DAEMON) |			\
			 CMD(CLI_MAGN_CALIBRATE))

/**
 * struct cli_option - one option: its name, whether it takes a value, the
 * commands that take it, and what it sets
 */
struct cli_option {
	const char *name;
	bool has_arg;
	unsigned int commands;
	cli_apply_fn apply;
};

static const struct cli_option cli_options[] = {
	{ "record", true, CMDS_ALL & ~CMD(CLI_REQUEST), apply_record },
	{ "state-group", true, CMDS_ALL & ~CMD(CLI_REQUEST), apply_state_group },
	{ "help", false, CMDS_ALL, apply_help },
	{ "socket", true, CMD(CLI_DAEMON) | CMD(CLI_REQUEST), apply_socket },
	{ "socket-mode", true, CMD(CLI_DAEMON), apply_socket_mode },
	{ "socket-group", true, CMD(CLI_DAEMON), apply_socket_group },
	{ "operator-group", true, CMD(CLI_DAEMON), apply_operator_group },
	{ "backend", true, CMDS_CHIP, apply_backend },
	{ "unit", true, CMDS_CHIP, apply_unit },
	{ "sim-clock", true, CMDS_CHIP, apply_sim_clock },
	{ "i2c-dev", true, CMDS_CHIP, apply_i2c_dev },
	{ "i2c-address", true, CMDS_CHIP, apply_i2c_address },
	{ "gpiochip", true, CMDS_CHIP, apply_gpiochip },
	{ "rstn-line", true, CMDS_CHIP, apply_rstn_line },
	{ "int1-line", true, CMDS_CHIP, apply_int1_line },
	{ "int2-line", true, CMDS_CHIP, apply_int2_line },
	{ "json", false, CMDS_LEVEL | CMD(CLI_SHOW) | CMD(CLI_REQUEST), apply_json },
	{ "temperature", true, CMD(CLI_SHOW), apply_temperature },
	{ "lock-timeout", true, CMDS_LOCKING, apply_lock_timeout },
	{ "verbose", false, CMD(CLI_RESTORE), apply_verbose },
	{ "samples", true, CMDS_LEVEL, apply_samples },
	{ "fluctuation", true, CMDS_LEVEL, apply_fluctuation },
	{ "lpf", false, CMDS_LEVEL, apply_lpf },
	{ "gravity", true, CMDS_LEVEL, apply_gravity },
	{ "stable-timeout", true, CMDS_LEVEL, apply_stable_timeout },
	{ "busy-timeout", true, CMDS_LEVEL, apply_busy_timeout },
	{ "permissible-error", true, CMD(CLI_FACTORY_TEST), apply_permissible_error },
	{ "keep-going", false, CMD(CLI_FACTORY_TEST), apply_keep_going },
	{ "sequence", true, CMD(CLI_FACTORY_TEST), apply_sequence },
	{ "confidence", true, CMD(CLI_FACTORY_TEST), apply_confidence },
	{ "junit", true, CMD(CLI_FACTORY_TEST), apply_junit },
	{ "device", true, CMD(CLI_RESTORE), apply_device },
	{ "timeout", true, CMD(CLI_MAGN_CALIBRATE), apply_timeout },
	{ "earth-field", true, CMD(CLI_MAGN_CALIBRATE), apply_earth_field },
};

#define CLI_N_OPTIONS	(sizeof(cli_options) / sizeof(cli_options[0]))
/* getopt_long()'s value of cli_options[i]: past every short option */
#define CLI_OPT_BASE	256

static const char *const commands[] = {
	[CLI_HELP] = "help",
	[CLI_FACTORY_TEST] = "factory-test",
	[CLI_RESTORE] = "restore",
	[CLI_SHOW] = "show",
	[CLI_RECALIBRATE] = "recalibrate",
	[CLI_ROLLBACK] = "rollback",
	[CLI_CHECK] = "check",
	[CLI_DAEMON] = "daemon",
	[CLI_REQUEST] = "request",
	[CLI_MAGN_CALIBRATE] = "magn-calibrate",
};

const char *cli_backend_name(enum cli_backend b)
{
	static const char *const names[] = {
		[CLI_BACKEND_SIM] = "sim",
		[CLI_BACKEND_RAW] = "raw",
		[CLI_BACKEND_IIO] = "iio",
		[CLI_BACKEND_NONE] = "none",
	};

	return (unsigned int)b < sizeof(names) / sizeof(names[0]) ? names[b] : "none";
}

/*
 * No --backend: a simulator option names the simulator, a raw option the
 * raw backend; the daemon serves the driver; the other chip commands look
 * for the chip (cli_pick_backend()). The simulator is never a fallback.
 */
static void pick_backend(struct cli_opts *o)
{
	bool sim = o->unit_path || o->virtual_clock;
	bool raw = o->raw.gpiochip || o->raw.rstn >= 0 || o->raw.int1 >= 0 ||
		   o->raw.int2 >= 0 || strcmp(o->raw.i2c_dev, CLI_DEFAULT_I2C_DEV) ||
		   o->raw.address != CLI_DEFAULT_I2C_ADDRESS;

	o->backend_auto = true;
	if (sim)	/* with a raw option too: refused below */
		o->backend = CLI_BACKEND_SIM;
	else if (raw)
		o->backend = CLI_BACKEND_RAW;
	else if (o->command == CLI_DAEMON)
		o->backend = CLI_BACKEND_IIO;
	else if (o->command == CLI_FACTORY_TEST || o->command == CLI_RESTORE ||
		 o->command == CLI_RECALIBRATE || o->command == CLI_ROLLBACK ||
		 o->command == CLI_CHECK || o->command == CLI_MAGN_CALIBRATE)
		cli_pick_backend(o);
	else
		o->backend = CLI_BACKEND_NONE;
}

int cli_parse(int argc, char **argv, struct cli_opts *o, char *err,
	      size_t errlen)
{
	struct option long_opts[CLI_N_OPTIONS + 1] = { { 0 } };
	const struct cli_option *spec;
	unsigned int i;
	int opt, ret;

	memset(o, 0, sizeof(*o));
	o->record_path = CLI_DEFAULT_RECORD;
	o->raw.i2c_dev = CLI_DEFAULT_I2C_DEV;
	o->raw.address = CLI_DEFAULT_I2C_ADDRESS;
	o->raw.rstn = RAW_LINE_NONE;
	o->raw.int1 = RAW_LINE_NONE;
	o->raw.int2 = RAW_LINE_NONE;
	o->socket_path = CLI_DEFAULT_SOCKET;
	o->socket_mode = CLI_DEFAULT_SOCKET_MODE;
	o->lock_timeout_s = CLI_DEFAULT_LOCK_TIMEOUT_S;
	o->magn_timeout_s = CLI_MAGN_TIMEOUT_S;
	o->log_fd = -1;
	ftest_opts_default(&o->ftest);

	for (i = 0; i < CLI_N_OPTIONS; i++) {
		long_opts[i].name = cli_options[i].name;
		long_opts[i].has_arg = cli_options[i].has_arg ?
				       required_argument : no_argument;
		long_opts[i].val = CLI_OPT_BASE + (int)i;
	}

	if (argc < 2)
		return bad(err, errlen, "no command given");
	for (i = 0; i < sizeof(commands) / sizeof(commands[0]); i++)
		if (!strcmp(argv[1], commands[i]))
			break;
	if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))
		i = CLI_HELP;
	if (i == sizeof(commands) / sizeof(commands[0]))
		return bad(err, errlen, "unknown command \"%s\"", argv[1]);
	o->command = (enum cli_command)i;

	optind = 2;
	opterr = 0;
	while ((opt = getopt_long(argc, argv, "", long_opts, NULL)) != -1) {
		if (opt < CLI_OPT_BASE || opt >= CLI_OPT_BASE + (int)CLI_N_OPTIONS) {
			if (optopt)
				return bad(err, errlen, "option needs a value or is unknown: %s",
					   argv[optind - 1]);
			return bad(err, errlen, "unknown option %s", argv[optind - 1]);
		}
		spec = &cli_options[opt - CLI_OPT_BASE];
		if (!(spec->commands & CMD(o->command)))
			return bad(err, errlen, "%s does not take --%s",
				   commands[o->command], spec->name);
		ret = spec->apply(o, optarg, err, errlen);
		if (ret)
			return ret;
	}
	if (o->command == CLI_REQUEST && optind < argc)
		o->request = argv[optind++];
	if (o->command == CLI_REQUEST && !o->request)
		return bad(err, errlen, "request needs what to ask: status, check, recalibrate, rollback or magn");
	if (optind < argc)
		return bad(err, errlen, "unexpected argument \"%s\"", argv[optind]);
	if (o->ftest.confidence_1e4 && !o->ftest.permissible_error_q16)
		return bad(err, errlen, "--confidence needs --permissible-error (the E it bounds)");
	if (!o->backend_given)
		pick_backend(o);
	if (o->backend == CLI_BACKEND_RAW && (o->unit_path || o->virtual_clock))
		return bad(err, errlen, "--unit and --sim-clock are for --backend sim");
	if (o->backend == CLI_BACKEND_SIM &&
	    (o->raw.gpiochip || o->raw.rstn >= 0 || o->raw.int1 >= 0 ||
	     o->raw.int2 >= 0 || strcmp(o->raw.i2c_dev, CLI_DEFAULT_I2C_DEV)))
		return bad(err, errlen, "--i2c-dev, --gpiochip and the line options are for --backend raw");
	if (o->device && o->backend != CLI_BACKEND_IIO &&
	    o->backend != CLI_BACKEND_NONE)
		return bad(err, errlen, "--device is for --backend iio (a device of the bound driver)");

	return 0;
}
