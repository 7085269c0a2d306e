// SPDX-License-Identifier: GPL-2.0
/* Command-line parsing of as9888-calibd: strict, with clear messages. */
#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

enum {
	OPT_RECORD = 256,
	OPT_BACKEND,
	OPT_UNIT,
	OPT_SIM_CLOCK,
	OPT_JSON,
	OPT_SAMPLES,
	OPT_PERMISSIBLE_ERROR,
	OPT_FLUCTUATION,
	OPT_LPF,
	OPT_GRAVITY,
	OPT_STABLE_TIMEOUT,
	OPT_KEEP_GOING,
	OPT_TEMPERATURE,
	OPT_VERBOSE,
	OPT_HELP,
	OPT_I2C_DEV,
	OPT_I2C_ADDRESS,
	OPT_GPIOCHIP,
	OPT_RSTN_LINE,
	OPT_INT1_LINE,
	OPT_INT2_LINE,
	OPT_SOCKET,
	OPT_SOCKET_MODE,
	OPT_SOCKET_GROUP,
	OPT_LOCK_TIMEOUT,
	OPT_STATE_GROUP,
	OPT_JUNIT,
};

static const struct option long_opts[] = {
	{ "record", required_argument, NULL, OPT_RECORD },
	{ "backend", required_argument, NULL, OPT_BACKEND },
	{ "unit", required_argument, NULL, OPT_UNIT },
	{ "sim-clock", required_argument, NULL, OPT_SIM_CLOCK },
	{ "json", no_argument, NULL, OPT_JSON },
	{ "samples", required_argument, NULL, OPT_SAMPLES },
	{ "permissible-error", required_argument, NULL, OPT_PERMISSIBLE_ERROR },
	{ "fluctuation", required_argument, NULL, OPT_FLUCTUATION },
	{ "lpf", no_argument, NULL, OPT_LPF },
	{ "gravity", required_argument, NULL, OPT_GRAVITY },
	{ "stable-timeout", required_argument, NULL, OPT_STABLE_TIMEOUT },
	{ "keep-going", no_argument, NULL, OPT_KEEP_GOING },
	{ "temperature", required_argument, NULL, OPT_TEMPERATURE },
	{ "verbose", no_argument, NULL, OPT_VERBOSE },
	{ "help", no_argument, NULL, OPT_HELP },
	{ "i2c-dev", required_argument, NULL, OPT_I2C_DEV },
	{ "i2c-address", required_argument, NULL, OPT_I2C_ADDRESS },
	{ "gpiochip", required_argument, NULL, OPT_GPIOCHIP },
	{ "rstn-line", required_argument, NULL, OPT_RSTN_LINE },
	{ "int1-line", required_argument, NULL, OPT_INT1_LINE },
	{ "int2-line", required_argument, NULL, OPT_INT2_LINE },
	{ "socket", required_argument, NULL, OPT_SOCKET },
	{ "socket-mode", required_argument, NULL, OPT_SOCKET_MODE },
	{ "socket-group", required_argument, NULL, OPT_SOCKET_GROUP },
	{ "lock-timeout", required_argument, NULL, OPT_LOCK_TIMEOUT },
	{ "state-group", required_argument, NULL, OPT_STATE_GROUP },
	{ "junit", required_argument, NULL, OPT_JUNIT },
	{ NULL, 0, NULL, 0 },
};

/* The long name of option @opt (the option, never its value) */
static const char *option_name(int opt)
{
	const struct option *l;

	for (l = long_opts; l->name; l++)
		if (l->val == opt)
			return l->name;

	return "?";
}

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

	errno = 0;
	v = strtoul(s, &end, 0);
	if (errno || end == s || *end || v < 0x0c || v > 0x0f)
		return -EINVAL;
	*address = (unsigned int)v;

	return 0;
}

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
};

/* Which options each command takes */
static bool option_allowed(enum cli_command cmd, int opt)
{
	bool chip = cmd == CLI_FACTORY_TEST || cmd == CLI_RESTORE ||
		    cmd == CLI_RECALIBRATE || cmd == CLI_ROLLBACK ||
		    cmd == CLI_CHECK || cmd == CLI_DAEMON;
	bool level = cmd == CLI_FACTORY_TEST || cmd == CLI_RECALIBRATE ||
		     cmd == CLI_CHECK;

	switch (opt) {
	case OPT_RECORD:
	case OPT_STATE_GROUP:
		return cmd != CLI_REQUEST;
	case OPT_HELP:
		return true;
	case OPT_SOCKET:
		return cmd == CLI_DAEMON || cmd == CLI_REQUEST;
	case OPT_SOCKET_MODE:
	case OPT_SOCKET_GROUP:
		return cmd == CLI_DAEMON;
	case OPT_BACKEND:
	case OPT_UNIT:
	case OPT_SIM_CLOCK:
	case OPT_I2C_DEV:
	case OPT_I2C_ADDRESS:
	case OPT_GPIOCHIP:
	case OPT_RSTN_LINE:
	case OPT_INT1_LINE:
	case OPT_INT2_LINE:
		return chip;
	case OPT_JSON:
		return level || cmd == CLI_SHOW || cmd == CLI_REQUEST;
	case OPT_TEMPERATURE:
		return cmd == CLI_SHOW;
	case OPT_LOCK_TIMEOUT:
		return cmd == CLI_FACTORY_TEST || cmd == CLI_RECALIBRATE ||
		       cmd == CLI_ROLLBACK || cmd == CLI_DAEMON;
	case OPT_VERBOSE:
		return cmd == CLI_RESTORE;
	case OPT_SAMPLES:
	case OPT_FLUCTUATION:
	case OPT_LPF:
	case OPT_GRAVITY:
	case OPT_STABLE_TIMEOUT:
		return level;
	default:
		return cmd == CLI_FACTORY_TEST;
	}
}

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
		 o->command == CLI_CHECK)
		cli_pick_backend(o);
	else
		o->backend = CLI_BACKEND_NONE;
}

int cli_parse(int argc, char **argv, struct cli_opts *o, char *err,
	      size_t errlen)
{
	bool backend_given = false;
	unsigned int i;
	int64_t v;
	int opt;

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
	ftest_opts_default(&o->ftest);

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
		if (opt == '?') {
			if (optopt)
				return bad(err, errlen, "option needs a value or is unknown: %s",
					   argv[optind - 1]);
			return bad(err, errlen, "unknown option %s", argv[optind - 1]);
		}
		if (!option_allowed(o->command, opt))
			return bad(err, errlen, "%s does not take --%s",
				   commands[o->command], option_name(opt));
		switch (opt) {
		case OPT_RECORD:
			if (!*optarg)
				return bad(err, errlen, "--record needs a path");
			o->record_path = optarg;
			break;
		case OPT_BACKEND:
			if (!strcmp(optarg, "sim"))
				o->backend = CLI_BACKEND_SIM;
			else if (!strcmp(optarg, "raw"))
				o->backend = CLI_BACKEND_RAW;
			else if (!strcmp(optarg, "iio"))
				o->backend = CLI_BACKEND_IIO;
			else
				return bad(err, errlen, "unknown backend \"%s\" (sim, raw or iio)",
					   optarg);
			backend_given = true;
			break;
		case OPT_SOCKET:
			if (!*optarg)
				return bad(err, errlen, "--socket needs a path");
			o->socket_path = optarg;
			break;
		case OPT_SOCKET_MODE:
			if (parse_mode(optarg, &o->socket_mode))
				return bad(err, errlen, "--socket-mode takes an octal mode such as 0660, not \"%s\"",
					   optarg);
			break;
		case OPT_SOCKET_GROUP:
			o->socket_group = optarg;
			break;
		case OPT_I2C_DEV:
			o->raw.i2c_dev = optarg;
			break;
		case OPT_I2C_ADDRESS:
			if (parse_address(optarg, &o->raw.address))
				return bad(err, errlen, "--i2c-address takes 0x0c..0x0f, not \"%s\"",
					   optarg);
			break;
		case OPT_GPIOCHIP:
			o->raw.gpiochip = optarg;
			break;
		case OPT_RSTN_LINE:
		case OPT_INT1_LINE:
		case OPT_INT2_LINE:
			if (cli_parse_fixed(optarg, 0, 0, 4095, &v))
				return bad(err, errlen, "%s takes a line offset 0..4095, not \"%s\"",
					   argv[optind - 2], optarg);
			*(opt == OPT_RSTN_LINE ? &o->raw.rstn :
			  opt == OPT_INT1_LINE ? &o->raw.int1 : &o->raw.int2) = (int)v;
			break;
		case OPT_UNIT:
			o->unit_path = optarg;
			break;
		case OPT_SIM_CLOCK:
			if (!strcmp(optarg, "virtual"))
				o->virtual_clock = true;
			else if (strcmp(optarg, "real"))
				return bad(err, errlen, "--sim-clock takes real or virtual, not \"%s\"",
					   optarg);
			break;
		case OPT_JSON:
			o->json = true;
			break;
		case OPT_SAMPLES:
			if (cli_parse_fixed(optarg, 0, AS9888_SAMPLES_MIN,
					    AS9888_SAMPLES_MAX, &v))
				return bad(err, errlen, "--samples takes an integer %d..%d, not \"%s\"",
					   AS9888_SAMPLES_MIN, AS9888_SAMPLES_MAX,
					   optarg);
			o->ftest.samples = (uint32_t)v;
			break;
		case OPT_PERMISSIBLE_ERROR:
			/* LSB with up to 3 decimals, 0.001..100 */
			if (cli_parse_fixed(optarg, 3, 1, 100000, &v))
				return bad(err, errlen, "--permissible-error takes LSB in 0.001..100, not \"%s\"",
					   optarg);
			o->ftest.permissible_error_q16 =
				(uint32_t)((v * AS9888_Q16_ONE + 500) / 1000);
			break;
		case OPT_FLUCTUATION:
			if (cli_parse_fixed(optarg, 0, 0, 4095, &v))
				return bad(err, errlen, "--fluctuation takes an integer 0..4095, not \"%s\"",
					   optarg);
			o->ftest.fluctuation = (uint32_t)v;
			o->fluctuation_given = true;
			break;
		case OPT_LPF:
			o->ftest.lpf = true;
			break;
		case OPT_GRAVITY:
			if (parse_gravity(optarg, o->ftest.gravity))
				return bad(err, errlen, "--gravity takes x+ x- y+ y- z+ z-, not \"%s\"",
					   optarg);
			o->ftest.gravity_given = true;
			break;
		case OPT_STABLE_TIMEOUT:
			if (cli_parse_fixed(optarg, 0, 0, 600000, &v))
				return bad(err, errlen, "--stable-timeout takes milliseconds 0..600000, not \"%s\"",
					   optarg);
			o->ftest.stable_timeout_ms = (uint32_t)v;
			break;
		case OPT_STATE_GROUP:
			if (!*optarg)
				return bad(err, errlen, "--state-group needs a group name");
			o->state_group = optarg;
			break;
		case OPT_LOCK_TIMEOUT:
			if (cli_parse_fixed(optarg, 0, 0, 3600, &v))
				return bad(err, errlen, "--lock-timeout takes seconds 0..3600, not \"%s\"",
					   optarg);
			o->lock_timeout_s = (unsigned int)v;
			break;
		case OPT_KEEP_GOING:
			o->ftest.keep_going = true;
			break;
		case OPT_JUNIT:
			if (!*optarg)
				return bad(err, errlen, "--junit needs a path");
			o->junit_path = optarg;
			break;
		case OPT_TEMPERATURE:
			if (cli_parse_fixed(optarg, 3, -30000, 85000, &v))
				return bad(err, errlen, "--temperature takes degrees Celsius -30..85, not \"%s\"",
					   optarg);
			o->temperature_given = true;
			o->temperature_mdegc = (int32_t)v;
			break;
		case OPT_VERBOSE:
			o->verbose = true;
			break;
		case OPT_HELP:
			o->command = CLI_HELP;
			break;
		}
	}
	if (o->command == CLI_REQUEST && optind < argc)
		o->request = argv[optind++];
	if (o->command == CLI_REQUEST && !o->request)
		return bad(err, errlen, "request needs what to ask: status, check, recalibrate or rollback");
	if (optind < argc)
		return bad(err, errlen, "unexpected argument \"%s\"", argv[optind]);
	if (!backend_given)
		pick_backend(o);
	if (o->backend == CLI_BACKEND_RAW && (o->unit_path || o->virtual_clock))
		return bad(err, errlen, "--unit and --sim-clock are for --backend sim");
	if (o->backend == CLI_BACKEND_SIM &&
	    (o->raw.gpiochip || o->raw.rstn >= 0 || o->raw.int1 >= 0 ||
	     o->raw.int2 >= 0 || strcmp(o->raw.i2c_dev, CLI_DEFAULT_I2C_DEV)))
		return bad(err, errlen, "--i2c-dev, --gpiochip and the line options are for --backend raw");

	return 0;
}
