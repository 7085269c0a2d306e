// SPDX-License-Identifier: GPL-2.0
/*
 * as9888-hal-cat: the sensors HAL core driven from the command line, as
 * the Android adapter drives it, its events printed one a line. For
 * bringing a board up on Linux and for the VM bench (tests/vm/guest/
 * tests/87-hal.sh).
 *
 *   as9888-hal-cat --list
 *   as9888-hal-cat [--seconds S] [--flush-at S] HANDLE:PERIOD_MS[:LATENCY_MS]...
 *
 * Lines: "sensor HANDLE TYPE MIN_DELAY_US MAX_DELAY_US NAME",
 * "ev HANDLE TYPE TIMESTAMP RECEIVED V0 V1 V2 V3 V4 V5 STATUS",
 * "flush-asked HANDLE CALLED" and "flush HANDLE RECEIVED" (times in ns of
 * CLOCK_BOOTTIME), "done" after every sensor was deactivated.
 * Options: --sysfs DIR, --dev DIR, --record PATH, --socket PATH (empty:
 * no feed), --config FILE.
 */
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "as9888_hal.h"

#define MAX_ACTIVE	AS9888_SENSOR_COUNT

static int64_t boottime_ns(void)
{
	struct timespec t;

	clock_gettime(CLOCK_BOOTTIME, &t);
	return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

static void print_events(void *ctx, const struct as9888_event *ev, size_t n)
{
	int64_t now = boottime_ns();
	size_t i;

	flockfile(stdout);
	for (i = 0; i < n; i++) {
		if (ev[i].type == AS9888_TYPE_META_DATA)
			printf("flush %d %lld\n", ev[i].handle, (long long)now);
		else
			printf("ev %d %d %lld %lld %.5f %.5f %.5f %.5f %.5f %.5f %d\n",
			       ev[i].handle, ev[i].type, (long long)ev[i].timestamp_ns,
			       (long long)now, ev[i].v[0], ev[i].v[1], ev[i].v[2],
			       ev[i].v[3], ev[i].v[4], ev[i].v[5], ev[i].status);
	}
	fflush(stdout);
	funlockfile(stdout);
}

static int usage(void)
{
	fprintf(stderr, "usage: as9888-hal-cat [--sysfs DIR] [--dev DIR] [--record PATH] [--socket PATH] [--config FILE]\n"
		"                      --list | [--seconds S] [--flush-at S] HANDLE:PERIOD_MS[:LATENCY_MS]...\n");
	return 2;
}

/* "H:P[:L]" into a handle, period and latency (ns): 0 or -EINVAL */
static int parse_sensor(const char *s, int *handle, int64_t *period, int64_t *latency)
{
	double p, l = 0;
	char *end;
	long h;

	h = strtol(s, &end, 10);
	if (end == s || *end != ':')
		return -EINVAL;
	s = end + 1;
	p = strtod(s, &end);
	if (end == s || (*end && *end != ':'))
		return -EINVAL;
	if (*end) {
		s = end + 1;
		l = strtod(s, &end);
		if (end == s || *end)
			return -EINVAL;
	}
	if (h < 1 || h > AS9888_SENSOR_COUNT || !(p > 0 && p <= 10000) || !(l >= 0 && l <= 600000))
		return -EINVAL;
	*handle = (int)h;
	*period = (int64_t)(p * 1e6);
	*latency = (int64_t)(l * 1e6);
	return 0;
}

int main(int argc, char **argv)
{
	static const struct option opts[] = {
		{ "sysfs", required_argument, NULL, 's' },
		{ "dev", required_argument, NULL, 'd' },
		{ "record", required_argument, NULL, 'r' },
		{ "socket", required_argument, NULL, 'k' },
		{ "config", required_argument, NULL, 'c' },
		{ "seconds", required_argument, NULL, 't' },
		{ "flush-at", required_argument, NULL, 'f' },
		{ "list", no_argument, NULL, 'l' },
		{ 0 }
	};
	struct as9888_hal_config cfg;
	const struct as9888_sensor_info *info;
	struct as9888_hal *h;
	int handle[MAX_ACTIVE], n = 0, c, i, ret = 0;
	int64_t period[MAX_ACTIVE], latency[MAX_ACTIVE];
	double seconds = 5, flush_at = -1;
	struct timespec pause;
	bool list = false;
	char err[512];

	as9888_hal_config_defaults(&cfg);
	while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
		char *dst = c == 's' ? cfg.sysfs : c == 'd' ? cfg.dev : c == 'r' ? cfg.record :
			    c == 'k' ? cfg.socket : NULL;
		size_t size = c == 's' ? sizeof(cfg.sysfs) : c == 'd' ? sizeof(cfg.dev) :
			      c == 'r' ? sizeof(cfg.record) : sizeof(cfg.socket);

		if (dst) {
			if (strlen(optarg) >= size) {
				fprintf(stderr, "as9888-hal-cat: %s: too long\n", optarg);
				return 2;
			}
			strcpy(dst, optarg);
		} else if (c == 'c') {
			if (as9888_hal_config_load(optarg, &cfg, err, sizeof(err))) {
				fprintf(stderr, "as9888-hal-cat: %s\n", err);
				return 1;
			}
		} else if (c == 't' || c == 'f') {
			char *end;
			double v = strtod(optarg, &end);

			if (*end || v < 0 || v > 86400)
				return usage();
			*(c == 't' ? &seconds : &flush_at) = v;
		} else if (c == 'l') {
			list = true;
		} else {
			return usage();
		}
	}
	for (i = optind; i < argc; i++) {
		if (n == MAX_ACTIVE || parse_sensor(argv[i], &handle[n], &period[n], &latency[n])) {
			fprintf(stderr, "as9888-hal-cat: %s: expected HANDLE:PERIOD_MS[:LATENCY_MS], handle 1..%d, at most %d\n",
				argv[i], AS9888_SENSOR_COUNT, MAX_ACTIVE);
			return 2;
		}
		n++;
	}
	if (!list && !n)
		return usage();
	if (as9888_hal_open(&cfg, print_events, NULL, &h, err, sizeof(err))) {
		fprintf(stderr, "as9888-hal-cat: %s\n", err);
		return 1;
	}
	if (list) {
		size_t k, count = as9888_hal_sensors(h, &info);

		for (k = 0; k < count; k++)
			printf("sensor %d %d %d %d %s\n", info[k].handle, info[k].type,
			       info[k].min_delay_us, info[k].max_delay_us, info[k].name);
		fflush(stdout);
	}
	for (i = 0; i < n && !ret; i++) {
		ret = as9888_hal_batch(h, handle[i], period[i], latency[i]);
		if (!ret)
			ret = as9888_hal_activate(h, handle[i], true);
		if (ret) {
			as9888_hal_error(h, err, sizeof(err));
			fprintf(stderr, "as9888-hal-cat: sensor %d: %s (%s)\n", handle[i],
				strerror(-ret), err);
		}
	}
	if (!ret && n) {
		double first = flush_at >= 0 && flush_at < seconds ? flush_at : seconds;

		pause.tv_sec = (time_t)first;
		pause.tv_nsec = (long)((first - (double)pause.tv_sec) * 1e9);
		nanosleep(&pause, NULL);
		if (first < seconds) {
			for (i = 0; i < n; i++) {
				flockfile(stdout);
				printf("flush-asked %d %lld\n", handle[i], (long long)boottime_ns());
				fflush(stdout);
				funlockfile(stdout);
				as9888_hal_flush(h, handle[i]);
			}
			pause.tv_sec = (time_t)(seconds - first);
			pause.tv_nsec = (long)((seconds - first - (double)pause.tv_sec) * 1e9);
			nanosleep(&pause, NULL);
		}
	}
	for (i = 0; i < n; i++)
		as9888_hal_activate(h, handle[i], false);
	as9888_hal_close(h);
	if (!ret && !list)
		printf("done\n");
	return ret ? 1 : 0;
}
