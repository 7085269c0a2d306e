// SPDX-License-Identifier: GPL-2.0
/*
 * AS9888 userspace simulator: model + clock + bus timing. See as9888_sim.h.
 */

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "as9888_sim.h"

#define NSEC_PER_SEC		1000000000ULL
#define UNIT_FILE_MAX		(1U << 20)

struct as9888_sim {
	struct as9888_model model;
	enum as9888_sim_clock clock;
	enum as9888_bus bus;
	uint32_t bus_hz;
	uint64_t vnow_ns;
};

static uint64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * NSEC_PER_SEC + (uint64_t)ts.tv_nsec;
}

uint64_t as9888_sim_now_ns(struct as9888_sim *sim)
{
	if (sim->clock == AS9888_SIM_CLOCK_VIRTUAL)
		return sim->vnow_ns;
	return mono_ns();
}

void as9888_sim_sleep_until_ns(struct as9888_sim *sim, uint64_t t_ns)
{
	struct timespec ts;

	if (sim->clock == AS9888_SIM_CLOCK_VIRTUAL) {
		if (t_ns > sim->vnow_ns)
			sim->vnow_ns = t_ns;
		return;
	}
	ts.tv_sec = (time_t)(t_ns / NSEC_PER_SEC);
	ts.tv_nsec = (long)(t_ns % NSEC_PER_SEC);
	while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) ==
	       EINTR)
		;
}

static uint64_t add_sat(uint64_t a, uint64_t b)
{
	return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

void as9888_sim_sleep_ns(struct as9888_sim *sim, uint64_t ns)
{
	as9888_sim_sleep_until_ns(sim, add_sat(as9888_sim_now_ns(sim), ns));
}

struct as9888_sim *as9888_sim_new(const struct as9888_unit *unit,
				  const struct as9888_sim_opts *opts)
{
	struct as9888_sim_opts def = { 0 };
	struct as9888_sim *sim;

	if (!opts)
		opts = &def;
	if ((opts->clock != AS9888_SIM_CLOCK_REAL &&
	     opts->clock != AS9888_SIM_CLOCK_VIRTUAL) ||
	    (opts->bus != AS9888_BUS_I2C && opts->bus != AS9888_BUS_SPI))
		return NULL;
	sim = calloc(1, sizeof(*sim));
	if (!sim)
		return NULL;
	sim->clock = opts->clock;
	/*
	 * A real chip's waits are microseconds long: without this, every
	 * sleep of the real-time clock would overshoot by the default 50 us
	 * of timer slack.
	 */
	if (sim->clock == AS9888_SIM_CLOCK_REAL)
		prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
	sim->bus = opts->bus;
	sim->bus_hz = opts->bus_hz;
	if (!sim->bus_hz)
		sim->bus_hz = opts->bus == AS9888_BUS_SPI ?
			AS9888_SIM_SPI_HZ_DEFAULT : AS9888_SIM_I2C_HZ_DEFAULT;
	sim->vnow_ns = opts->virtual_start_ns;
	as9888_model_init(&sim->model, unit, as9888_sim_now_ns(sim));
	as9888_model_set_bus(&sim->model, sim->bus);
	return sim;
}

void as9888_sim_free(struct as9888_sim *sim)
{
	free(sim);
}

uint64_t as9888_sim_transfer_ns(const struct as9888_sim *sim, bool read,
				unsigned int len)
{
	uint64_t bits;

	if (sim->bus == AS9888_BUS_SPI)
		bits = (1 + (uint64_t)len) * 8 + 2;
	else if (read)
		bits = 1 + 9 + 9 + 1 + 9 + 9 * (uint64_t)len + 1;
	else
		bits = 1 + 9 + 9 + 9 * (uint64_t)len + 1;
	return (bits * NSEC_PER_SEC + sim->bus_hz - 1) / sim->bus_hz;
}

/* Charge the bus time of a transfer; returns the time it ends. */
static uint64_t charge(struct as9888_sim *sim, bool read, unsigned int len)
{
	uint64_t end = add_sat(as9888_sim_now_ns(sim),
			       as9888_sim_transfer_ns(sim, read, len));

	as9888_sim_sleep_until_ns(sim, end);
	return as9888_sim_now_ns(sim);
}

int as9888_sim_read(struct as9888_sim *sim, uint8_t reg, uint8_t *buf,
		    unsigned int len)
{
	if (!buf && len)
		return -EINVAL;
	return as9888_model_read(&sim->model, charge(sim, true, len), reg, buf,
				 len);
}

int as9888_sim_write(struct as9888_sim *sim, uint8_t reg, const uint8_t *buf,
		     unsigned int len)
{
	if (!buf && len)
		return -EINVAL;
	return as9888_model_write(&sim->model, charge(sim, false, len), reg,
				  buf, len);
}

int as9888_sim_read_reg(struct as9888_sim *sim, uint8_t reg, uint8_t *val)
{
	return as9888_sim_read(sim, reg, val, 1);
}

int as9888_sim_write_reg(struct as9888_sim *sim, uint8_t reg, uint8_t val)
{
	return as9888_sim_write(sim, reg, &val, 1);
}

void as9888_sim_set_rstn(struct as9888_sim *sim, bool level)
{
	as9888_model_set_rstn(&sim->model, as9888_sim_now_ns(sim), level);
}

bool as9888_sim_int(struct as9888_sim *sim, enum as9888_pin pin)
{
	return as9888_model_pin(&sim->model, as9888_sim_now_ns(sim), pin);
}

int as9888_sim_wait_int(struct as9888_sim *sim, enum as9888_pin pin,
			uint64_t timeout_ns)
{
	uint64_t deadline = add_sat(as9888_sim_now_ns(sim), timeout_ns);

	for (;;) {
		uint64_t now = as9888_sim_now_ns(sim);
		uint64_t wake;

		if (as9888_model_pin(&sim->model, now, pin))
			return 1;
		if (now >= deadline)
			return 0;
		/* after the pin() call every pending event lies after now */
		wake = as9888_model_next_event_ns(&sim->model);
		if (wake > deadline)
			wake = deadline;
		if (wake <= now)
			wake = now + 1;
		as9888_sim_sleep_until_ns(sim, wake);
	}
}

struct as9888_model *as9888_sim_model(struct as9888_sim *sim)
{
	return &sim->model;
}

const struct as9888_model_stats *as9888_sim_stats(struct as9888_sim *sim)
{
	return as9888_model_stats(&sim->model);
}

static void set_err(char *errbuf, size_t errlen, const char *path,
		    const char *msg)
{
	if (errbuf && errlen)
		snprintf(errbuf, errlen, "%s: %s", path, msg);
}

/*
 * The unit file for reading: never waiting on a FIFO or socket put there
 * (refused: only a file or a device such as /dev/null gives a unit).
 */
static FILE *open_unit_file(const char *path, char *errbuf, size_t errlen,
			    int *ret)
{
	struct stat st;
	FILE *f;
	int fd;

	fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0) {
		*ret = -errno;
		set_err(errbuf, errlen, path, strerror(errno));
		return NULL;
	}
	if (fstat(fd, &st) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode) ||
	    S_ISDIR(st.st_mode)) {
		*ret = -EINVAL;
		set_err(errbuf, errlen, path,
			"not a unit file (a FIFO, socket or directory): give a regular file");
		close(fd);
		return NULL;
	}
	f = fdopen(fd, "rb");
	if (!f) {
		*ret = -errno;
		set_err(errbuf, errlen, path, strerror(errno));
		close(fd);
	}

	return f;
}

int as9888_sim_load_unit_file(const char *path, struct as9888_unit *unit,
			      char *errbuf, size_t errlen)
{
	struct as9888_unit_error perr;
	char *text;
	size_t n;
	FILE *f;
	int ret;

	if (errbuf && errlen)
		errbuf[0] = '\0';
	f = open_unit_file(path, errbuf, errlen, &ret);
	if (!f)
		return ret;
	text = malloc(UNIT_FILE_MAX + 1);
	if (!text) {
		fclose(f);
		set_err(errbuf, errlen, path, strerror(ENOMEM));
		return -ENOMEM;
	}
	n = fread(text, 1, UNIT_FILE_MAX + 1, f);
	if (ferror(f)) {
		ret = errno ? -errno : -EIO;
		set_err(errbuf, errlen, path, strerror(-ret));
		goto out;
	}
	if (n > UNIT_FILE_MAX) {
		ret = -EFBIG;
		set_err(errbuf, errlen, path, "file too large");
		goto out;
	}
	ret = as9888_unit_parse(text, (unsigned int)n, unit, &perr);
	if (ret && errbuf && errlen)
		snprintf(errbuf, errlen, "%s:%u: %s", path, perr.line,
			 perr.msg);
out:
	free(text);
	fclose(f);
	return ret;
}
