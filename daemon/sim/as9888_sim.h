/* SPDX-License-Identifier: GPL-2.0 */
/*
 * AS9888 userspace simulator: the chip model (tests/model) behind a bus
 * transport, for the daemon's "--backend sim" and for tests.
 *
 * The simulator owns a model and a clock. With AS9888_SIM_CLOCK_REAL the
 * clock is CLOCK_MONOTONIC and the calls really take time; with
 * AS9888_SIM_CLOCK_VIRTUAL the clock is a counter that only moves when the
 * simulator charges time (transfers, sleeps, waits), so tests run fast and
 * deterministically.
 *
 * Every transfer is charged its bus time before the model sees it (the
 * model acts at the end of the transfer). I2C at bus_hz (default 400 kHz):
 * one bit time for START, repeated START and STOP each, nine bit times per
 * byte; a write is START addr reg data... STOP, a read is START addr reg
 * Sr addr data... STOP. So a one-byte read costs 39 bit times (97.5 us),
 * a one-byte write 29 (72.5 us), the 16-byte sample burst 174 (435 us).
 * SPI at bus_hz (default 5 MHz): (1 + len) * 8 clocks plus one clock of
 * chip-select setup and one of hold.
 *
 * Not thread-safe: use one simulator from one thread (or lock around it).
 */
#ifndef AS9888_SIM_H
#define AS9888_SIM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "as9888_model.h"
#include "as9888_unit.h"

enum as9888_sim_clock {
	AS9888_SIM_CLOCK_REAL = 0,
	AS9888_SIM_CLOCK_VIRTUAL,
};

#define AS9888_SIM_I2C_HZ_DEFAULT	400000
#define AS9888_SIM_SPI_HZ_DEFAULT	5000000

/**
 * struct as9888_sim_opts - simulator options (all-zero = defaults)
 * @clock:		real CLOCK_MONOTONIC (default) or virtual
 * @bus:		I2C (default) or SPI: bus timing and failure flavour
 * @bus_hz:		bus clock, 0 for the default of the bus
 * @virtual_start_ns:	virtual clock at creation (virtual clock only)
 */
struct as9888_sim_opts {
	enum as9888_sim_clock clock;
	enum as9888_bus bus;
	uint32_t bus_hz;
	uint64_t virtual_start_ns;
};

struct as9888_sim;

/*
 * Power on a simulated chip with @unit (NULL: as9888_unit_default()) and
 * @opts (NULL: defaults). Returns NULL on allocation failure or bad opts.
 * The chip boots (t_BOOT) from the creation time on.
 */
struct as9888_sim *as9888_sim_new(const struct as9888_unit *unit,
				  const struct as9888_sim_opts *opts);
void as9888_sim_free(struct as9888_sim *sim);

/* Clock: current time, sleeping (virtual: advances the clock). */
uint64_t as9888_sim_now_ns(struct as9888_sim *sim);
void as9888_sim_sleep_ns(struct as9888_sim *sim, uint64_t ns);
void as9888_sim_sleep_until_ns(struct as9888_sim *sim, uint64_t t_ns);

/*
 * One bus transfer with auto-increment (burst). Returns 0, -EIO when the
 * chip NAKs (I2C), -EINVAL for a NULL buffer with a non-zero length.
 */
int as9888_sim_read(struct as9888_sim *sim, uint8_t reg, uint8_t *buf,
		    unsigned int len);
int as9888_sim_write(struct as9888_sim *sim, uint8_t reg, const uint8_t *buf,
		     unsigned int len);
int as9888_sim_read_reg(struct as9888_sim *sim, uint8_t reg, uint8_t *val);
int as9888_sim_write_reg(struct as9888_sim *sim, uint8_t reg, uint8_t val);

/* Bus time charged for one transfer of @len data bytes. */
uint64_t as9888_sim_transfer_ns(const struct as9888_sim *sim, bool read,
				unsigned int len);

/* RSTN level (true = high); takes no bus time. */
void as9888_sim_set_rstn(struct as9888_sim *sim, bool level);

/* Level of INT1/INT2 now. */
bool as9888_sim_int(struct as9888_sim *sim, enum as9888_pin pin);

/*
 * Wait until @pin is high (returns at once if it already is): sleeps until
 * the model's next internal event or the timeout, never polls. Returns 1
 * when the pin is high, 0 on timeout.
 */
int as9888_sim_wait_int(struct as9888_sim *sim, enum as9888_pin pin,
			uint64_t timeout_ns);

/* The model inside (for tests and benches) and its counters. */
struct as9888_model *as9888_sim_model(struct as9888_sim *sim);
const struct as9888_model_stats *as9888_sim_stats(struct as9888_sim *sim);

/*
 * Read a unit description file and parse it. Returns 0, or a negative
 * errno with a message in @errbuf (may be NULL): "<path>: <strerror>" or
 * "<path>:<line>: <problem>".
 */
int as9888_sim_load_unit_file(const char *path, struct as9888_unit *unit,
			      char *errbuf, size_t errlen);

#endif /* AS9888_SIM_H */
