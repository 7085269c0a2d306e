/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Chip operations over a transport: reset, mode changes that respect t_PD,
 * single measurements with event-driven waits and the one-burst sample
 * read. Register knowledge comes from as9888_regs.h.
 */
#ifndef AS9888_CHIP_H
#define AS9888_CHIP_H

#include <stdbool.h>
#include <stdint.h>

#include "chip/transport.h"

#define CHIP_AXES	3

/**
 * struct chip - a chip behind a transport
 * @t:		the transport
 * @pd_since_ns: when the chip last entered power-down (as far as we know)
 * @use_int1:	wait on INT1 (else poll ST1 DRDY)
 * @powered_down: the chip is known to be in power-down (after a reset, an
 *		MS = 0 write or a completed single measurement)
 * @int1_dr:	INT1EN is known to hold DR1EN (cleared by a reset)
 * @started_ns:	when the last chip_start() wrote MS
 * @timeout_ns:	how long chip_wait() waits for that measurement
 */
struct chip {
	struct transport *t;
	uint64_t pd_since_ns;
	bool use_int1;
	bool powered_down;
	bool int1_dr;
	uint64_t started_ns;
	uint64_t timeout_ns;
};

/* A sample's registers ST1..ST2, decoded */
struct chip_sample {
	uint8_t st1;
	int16_t mag[CHIP_AXES];
	uint8_t tmps;
	uint8_t empt;
	int16_t acc[CHIP_AXES];
	uint8_t st2;
};

/* How a measurement ended */
enum chip_wait {
	CHIP_WAIT_INT1 = 0,	/* INT1 rose */
	CHIP_WAIT_DRDY,		/* DRDY polled (INT1 not monitored or failed) */
	CHIP_WAIT_TIMEOUT,	/* nothing within the timeout */
};

void chip_init(struct chip *c, struct transport *t);
/* RSTN low for t_RSTL, high, then t_BOOT; -EOPNOTSUPP without RSTN */
int chip_reset(struct chip *c);
/* Write MS, first waiting out t_PD when the new mode needs it */
int chip_set_mode(struct chip *c, uint8_t ms);
/* Start @ms (single or self-test) and wait for its end; see enum chip_wait */
int chip_measure(struct chip *c, uint8_t ms, uint64_t duration_us,
		 enum chip_wait *how);
/*
 * chip_measure() in two halves, so that the bus can be used while the chip
 * converts: chip_start() writes MS (after t_PD), chip_wait() waits for the
 * end of that measurement (@duration_us plus a margin after the write)
 */
int chip_start(struct chip *c, uint8_t ms, uint64_t duration_us);
int chip_wait(struct chip *c, enum chip_wait *how);
/*
 * Read a finished measurement: with @men (step 2) ST1, the magnetometer
 * data and ST2; without (step 3) ST1, then TMPS..ST2. What is not read
 * reads 0.
 */
int chip_read_sample(struct chip *c, bool men, struct chip_sample *s);
/*
 * The rest of an accelerometer sample whose ST1 was read: TMPS..ST2 (the
 * fields after ST1 in @s; @s->st1 is left alone)
 */
int chip_read_rest(struct chip *c, struct chip_sample *s);
/*
 * The rest of the last sample while the next measurement runs (datasheet
 * section 3: the data registers hold the last sample until the end of the
 * next measurement; only ST1 must be read before the MS write). One burst
 * of ST1..ST2, so the chip itself tells whether the next measurement ended
 * before the read: then @newer is set, the data belong to that newer
 * measurement and the last sample is lost. Fills the fields after ST1.
 */
int chip_read_overlapped(struct chip *c, struct chip_sample *s, bool *newer);
/* The datasheet time of a measurement with these SLCT2 settings */
uint64_t chip_measure_time_us(bool men, bool alpf);

#endif
