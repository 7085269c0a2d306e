// SPDX-License-Identifier: GPL-2.0
/* Tests of the AS9888 userspace simulator: clocks, bus timing, waits. */

#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "as9888_sim.h"

#define US	1000ULL
#define MSEC	1000000ULL

static struct as9888_sim *new_sim(enum as9888_sim_clock clock,
				  const struct as9888_unit *u)
{
	struct as9888_sim_opts o = { .clock = clock, .virtual_start_ns = 0 };
	struct as9888_sim *sim = as9888_sim_new(u, &o);

	assert_non_null(sim);
	return sim;
}

static uint64_t mono(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000000ULL + ts.tv_nsec;
}

static void test_transfer_time(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, NULL);
	struct as9888_sim_opts spi = { .clock = AS9888_SIM_CLOCK_VIRTUAL,
				       .bus = AS9888_BUS_SPI };
	struct as9888_sim *s2;

	/* 400 kHz: 2.5 us per bit */
	assert_int_equal(as9888_sim_transfer_ns(sim, true, 1), 97500);
	assert_int_equal(as9888_sim_transfer_ns(sim, false, 1), 72500);
	assert_int_equal(as9888_sim_transfer_ns(sim, true, 16), 435000);
	assert_int_equal(as9888_sim_transfer_ns(sim, true, 21), 547500);
	as9888_sim_free(sim);
	s2 = as9888_sim_new(NULL, &spi);
	assert_non_null(s2);
	/* 5 MHz: (1 + 16) * 8 + 2 clocks of 200 ns */
	assert_int_equal(as9888_sim_transfer_ns(s2, true, 16), 27600);
	as9888_sim_free(s2);
}

static void test_virtual_charges_transfers(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, NULL);
	uint8_t v, b[16];

	assert_int_equal(as9888_sim_now_ns(sim), 0);
	as9888_sim_sleep_ns(sim, 100 * US);	/* t_BOOT */
	assert_int_equal(as9888_sim_now_ns(sim), 100 * US);
	assert_int_equal(as9888_sim_read_reg(sim, 0, &v), 0);
	assert_int_equal(v, 0x48);
	assert_int_equal(as9888_sim_now_ns(sim), 100 * US + 97500);
	assert_int_equal(as9888_sim_write_reg(sim, 2, 1), 0);
	assert_int_equal(as9888_sim_now_ns(sim), 100 * US + 97500 + 72500);
	assert_int_equal(as9888_sim_read(sim, 0x10, b, 16), 0);
	assert_int_equal(as9888_sim_now_ns(sim),
			 100 * US + 97500 + 72500 + 435000);
	assert_int_equal(as9888_sim_stats(sim)->transfers, 3);
	as9888_sim_free(sim);
}

static void test_virtual_boot_nak(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, NULL);
	uint8_t v;

	/* the transfer ends 97.5 us after power-on: still booting */
	assert_int_equal(as9888_sim_read_reg(sim, 0, &v), -EIO);
	assert_int_equal(as9888_sim_read_reg(sim, 0, &v), 0);
	assert_int_equal(v, 0x48);
	/* reset: low 5 us, then boot */
	as9888_sim_set_rstn(sim, false);
	as9888_sim_sleep_ns(sim, 5 * US);
	as9888_sim_set_rstn(sim, true);
	assert_int_equal(as9888_sim_read_reg(sim, 0, &v), -EIO);
	assert_int_equal(as9888_sim_read_reg(sim, 0, &v), 0);
	assert_int_equal(as9888_sim_stats(sim)->resets, 1);
	assert_int_equal(as9888_sim_read(sim, 0, NULL, 1), -EINVAL);
	as9888_sim_free(sim);
}

static void test_virtual_wait_int(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, NULL);
	uint64_t t0;
	uint8_t v;

	as9888_sim_sleep_ns(sim, 100 * US);
	assert_int_equal(as9888_sim_write_reg(sim, 2, 1), 0);
	assert_int_equal(as9888_sim_write_reg(sim, 8, 1), 0);
	t0 = as9888_sim_now_ns(sim);
	assert_false(as9888_sim_int(sim, AS9888_PIN_INT1));
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT1, 10 * MSEC),
			 1);
	/* woke exactly at the end of the measurement */
	assert_int_equal(as9888_sim_now_ns(sim) - t0, 1200 * US);
	/* already high: returns at once */
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT1, 0), 1);
	assert_int_equal(as9888_sim_now_ns(sim) - t0, 1200 * US);
	assert_int_equal(as9888_sim_read_reg(sim, 4, &v), 0);
	assert_int_equal(v, 1);
	assert_false(as9888_sim_int(sim, AS9888_PIN_INT1));
	/* INT2 not enabled: timeout, clock at the deadline */
	assert_int_equal(as9888_sim_write_reg(sim, 8, 1), 0);
	t0 = as9888_sim_now_ns(sim);
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT2, 3 * MSEC),
			 0);
	assert_int_equal(as9888_sim_now_ns(sim) - t0, 3 * MSEC);
	as9888_sim_free(sim);
}

static void test_virtual_wait_int_open(void **state)
{
	struct as9888_unit u;
	struct as9888_sim *sim;
	uint8_t v;

	as9888_unit_default(&u);
	u.faults = AS9888_FAULT_INT1_OPEN;
	sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, &u);
	as9888_sim_sleep_ns(sim, 100 * US);
	assert_int_equal(as9888_sim_write_reg(sim, 2, 1), 0);
	assert_int_equal(as9888_sim_write_reg(sim, 8, 1), 0);
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT1, 20 * MSEC),
			 0);
	assert_int_equal(as9888_sim_read_reg(sim, 4, &v), 0);
	assert_int_equal(v, 1);		/* INT1ST still says DR1 */
	as9888_sim_free(sim);
}

static void test_virtual_deterministic(void **state)
{
	struct as9888_unit u;
	uint8_t a[16], b[16];
	int run, k;

	as9888_unit_default(&u);
	u.noise_mlsb = 4000;
	u.seed = 7;
	for (run = 0; run < 2; run++) {
		struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, &u);
		uint8_t *buf = run ? b : a;

		as9888_sim_sleep_ns(sim, 100 * US);
		as9888_sim_write_reg(sim, 2, 1);
		for (k = 0; k < 20; k++) {
			as9888_sim_write_reg(sim, 8, 1);
			as9888_sim_wait_int(sim, AS9888_PIN_INT1, 10 * MSEC);
			as9888_sim_read(sim, 0x10, buf, 16);
		}
		assert_int_equal(as9888_sim_now_ns(sim),
				 100 * US + 72500 +
				 20 * (72500 + 1200 * US + 435000));
		as9888_sim_free(sim);
	}
	assert_memory_equal(a, b, 16);
}

static void test_real_measurement_time(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_REAL, NULL);
	uint64_t t0, t1;
	uint8_t v;

	as9888_sim_sleep_ns(sim, 100 * US);
	assert_int_equal(as9888_sim_write_reg(sim, 2, 1), 0);
	assert_int_equal(as9888_sim_write_reg(sim, 7, 0x08), 0); /* ALPF */
	t0 = mono();
	assert_int_equal(as9888_sim_write_reg(sim, 8, 1), 0);
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT1, 1000 * MSEC),
			 1);
	t1 = mono();
	/* 72.5 us write + 4.8 ms; generous upper bound on a shared host */
	assert_true(t1 - t0 >= 4800 * US + 72500);
	assert_true(t1 - t0 < 4800 * US + 200 * MSEC);
	assert_int_equal(as9888_sim_read_reg(sim, 0x10, &v), 0);
	assert_int_equal(v, 1);
	as9888_sim_free(sim);
}

static void test_real_transfers_charged(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_REAL, NULL);
	uint64_t t0, t1;
	uint8_t b[16];
	int k;

	as9888_sim_sleep_ns(sim, 100 * US);
	t0 = mono();
	for (k = 0; k < 20; k++)
		assert_int_equal(as9888_sim_read(sim, 0x10, b, 16), 0);
	t1 = mono();
	assert_true(t1 - t0 >= 20 * 435000ULL);
	as9888_sim_free(sim);
}

static void test_real_timeout(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_REAL, NULL);
	uint64_t t0, t1;

	t0 = mono();
	assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT2, 3 * MSEC),
			 0);
	t1 = mono();
	assert_true(t1 - t0 >= 3 * MSEC);
	assert_true(t1 - t0 < 200 * MSEC);
	as9888_sim_free(sim);
}

static void test_real_clock_is_monotonic(void **state)
{
	struct as9888_sim *sim = new_sim(AS9888_SIM_CLOCK_REAL, NULL);
	uint64_t a = as9888_sim_now_ns(sim), b = mono();

	assert_true(b >= a && b - a < 100 * MSEC);
	as9888_sim_free(sim);
}

static char tmpdir[64];

static const char *write_tmp(const char *name, const char *text)
{
	static char path[128];
	FILE *f;

	if (!tmpdir[0]) {
		strcpy(tmpdir, "/tmp/as9888simXXXXXX");
		assert_non_null(mkdtemp(tmpdir));
	}
	snprintf(path, sizeof(path), "%s/%s", tmpdir, name);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
	return path;
}

static void test_load_unit_file(void **state)
{
	struct as9888_unit u;
	char err[256];
	const char *p;

	p = write_tmp("good.unit", "# good\nnoise = 2.5\nfault = wia\n");
	assert_int_equal(as9888_sim_load_unit_file(p, &u, err, sizeof(err)),
			 0);
	assert_int_equal(u.noise_mlsb, 2500);
	assert_int_equal(u.faults, AS9888_FAULT_WIA);
	assert_string_equal(err, "");
	unlink(p);

	p = write_tmp("bad.unit", "noise = 2.5\n\nfault = wia, flaky\n");
	assert_int_equal(as9888_sim_load_unit_file(p, &u, err, sizeof(err)),
			 -EINVAL);
	{
		char want[256];

		snprintf(want, sizeof(want),
			 "%s:3: unknown fault 'flaky'", p);
		assert_string_equal(err, want);
	}
	unlink(p);

	assert_int_equal(as9888_sim_load_unit_file("/nonexistent/x.unit", &u,
						   err, sizeof(err)), -ENOENT);
	assert_non_null(strstr(err, "/nonexistent/x.unit: "));
	rmdir(tmpdir);
}

/*
 * The magnetic world from a unit file, as the daemon's --backend sim --unit
 * gives it: the field turns with the tumble, and every sample is the
 * Earth's field (48 uT) off the hard iron, whatever the orientation.
 */
static void test_magnetic_world_unit_file(void **state)
{
	static const double hard[3] = { 120, -80, 40 };
	double first[3] = { 0 }, moved = 0;
	struct as9888_sim *sim;
	struct as9888_unit u;
	char err[256];
	const char *p;
	uint8_t b[16];
	int k, i;

	tmpdir[0] = '\0';	/* test_load_unit_file removed its directory */
	p = write_tmp("world.unit", "earth = 48 60 2\nhard_iron = 120 -80 40\n"
		      "tumble = 5\nmagn_noise = 0.3\nseed = 11\n");
	assert_int_equal(as9888_sim_load_unit_file(p, &u, err, sizeof(err)),
			 0);
	unlink(p);
	rmdir(tmpdir);
	sim = new_sim(AS9888_SIM_CLOCK_VIRTUAL, &u);
	as9888_sim_sleep_ns(sim, 100 * US);
	as9888_sim_write_reg(sim, 2, 1);		/* INT1EN: DR */
	as9888_sim_write_reg(sim, 7, AS9888_SLCT2_MEN_MSK);
	for (k = 0; k < 100; k++) {
		double m[3], r = 0;

		as9888_sim_sleep_ns(sim, 100 * US);
		as9888_sim_write_reg(sim, 8, 1);
		assert_int_equal(as9888_sim_wait_int(sim, AS9888_PIN_INT1,
						     20 * MSEC), 1);
		assert_int_equal(as9888_sim_read(sim, 0x10, b, 16), 0);
		for (i = 0; i < 3; i++) {
			m[i] = (int16_t)(b[1 + 2 * i] | b[2 + 2 * i] << 8) *
			       (u.eeprom[4 + i] + 128) / 256.0 * 0.3;
			r += (m[i] - hard[i]) * (m[i] - hard[i]);
			if (!k)
				first[i] = m[i];
			moved = fmax(moved, fabs(m[i] - first[i]));
		}
		if (fabs(sqrt(r) - 48) > 1.5)
			fail_msg("sample %d: |m - h| = %.2f uT", k, sqrt(r));
	}
	assert_true(moved > 40);
	as9888_sim_free(sim);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_transfer_time),
		cmocka_unit_test(test_virtual_charges_transfers),
		cmocka_unit_test(test_virtual_boot_nak),
		cmocka_unit_test(test_virtual_wait_int),
		cmocka_unit_test(test_virtual_wait_int_open),
		cmocka_unit_test(test_virtual_deterministic),
		cmocka_unit_test(test_real_measurement_time),
		cmocka_unit_test(test_real_transfers_charged),
		cmocka_unit_test(test_real_timeout),
		cmocka_unit_test(test_real_clock_is_monotonic),
		cmocka_unit_test(test_load_unit_file),
		cmocka_unit_test(test_magnetic_world_unit_file),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
