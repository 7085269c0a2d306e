// SPDX-License-Identifier: GPL-2.0
/*
 * magn-calibrate's session: the coverage a stored fit needs follows the
 * samples' noise (MAGN_SESSION_COVERAGE for samples that are the mean of
 * MAGN_SOURCE_AVERAGE measurements, MAGN_SESSION_COVERAGE_SINGLE for
 * samples of one), the refusal says the coverage judged, and a session on
 * the simulated chip (a tumbling board, virtual clock) takes averaged
 * samples and stores its fit once they cover MAGN_SESSION_COVERAGE. The
 * hint of the progress lines names the turn that leaves what is covered.
 */
#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "chip/backend_sim.h"
#include "fake_sysfs.h"
#include "magn/magn_session.h"

#define NS_PER_S	1000000000ULL
#define DEG		(M_PI / 180.0)

static struct magcal_result fit_at(enum magcal_status status, double coverage)
{
	struct magcal_result r;

	memset(&r, 0, sizeof(r));
	r.status = status;
	r.coverage = coverage;

	return r;
}

static void coverage_by_noise(void **state)
{
	struct magcal_result r = fit_at(MAGCAL_OK, 0.57);

	(void)state;
	assert_true(MAGN_SESSION_COVERAGE < MAGN_SESSION_COVERAGE_SINGLE);
	/* averaged samples: 57 % is enough, samples of one measurement not */
	assert_true(magn_session_done(&r, true));
	assert_false(magn_session_done(&r, false));
	r.coverage = MAGN_SESSION_COVERAGE_SINGLE;
	assert_true(magn_session_done(&r, false));
	r.coverage = MAGN_SESSION_COVERAGE - 0.001;
	assert_false(magn_session_done(&r, true));
	/* coverage is not all: magcal's verdict first */
	r = fit_at(MAGCAL_INCONSISTENT, 1.0);
	assert_false(magn_session_done(&r, true));
	assert_false(magn_session_done(&r, false));
}

static void refusal_says_the_coverage(void **state)
{
	struct magn_session_result res;
	char why[512];

	(void)state;
	memset(&res, 0, sizeof(res));
	res.solved = true;
	res.fit = fit_at(MAGCAL_OK, 0.57);
	res.elapsed_ns = 120 * NS_PER_S;
	res.samples = 1860;
	res.averaged = false;
	magn_session_why(&res, why, sizeof(why));
	if (!strstr(why, "not enough orientations covered (57% in 120 s, 1860 samples)"))
		fail_msg("refusal of a 57 %% fit of single samples: \"%s\"", why);
}

/*
 * The hint: a cap of 60 degrees about +Z covered, the field read 50
 * degrees from +Z toward +X: the way out is on to +X, a turn of the
 * device about -Y (which turns the field it sees from +Z toward +X)
 */
static void hint_way_out(void **state)
{
	static const double hard[3] = { 120, -80, 45 };
	static const double turned[3][3] = { { 0, -1, 0 }, { 1, 0, 0 },
					     { 0, 0, 1 } };
	struct magcal_session *fit = magcal_new(NULL);
	struct magn_hint h;
	double m[3], polar, azim;
	char text[128];
	int i;

	(void)state;
	assert_non_null(fit);
	for (polar = 0; polar <= 60; polar += 5)
		for (azim = 0; azim < 360; azim += 10) {
			m[0] = 48 * sin(polar * DEG) * cos(azim * DEG);
			m[1] = 48 * sin(polar * DEG) * sin(azim * DEG);
			m[2] = 48 * cos(polar * DEG);
			for (i = 0; i < 3; i++)
				m[i] += hard[i];
			magcal_add(fit, m, NULL);
		}
	m[0] = 48 * sin(50 * DEG) + hard[0];
	m[1] = hard[1];
	m[2] = 48 * cos(50 * DEG) + hard[2];
	assert_int_equal(magn_session_hint(fit, m, NULL, &h), 0);
	assert_int_equal(h.axis, 1);
	assert_int_equal(h.sign, -1);
	assert_true(fabs(h.deg - 40) < 0.5);
	magn_hint_text(&h, text, sizeof(text));
	assert_string_equal(text, "turn it about the chip's Y axis, +Z toward -X, about 40 deg");
	/*
	 * the chip mounted turned by 90 deg about Z (the device's X is the
	 * chip's -Y): the same turn named in the device's axes
	 */
	assert_int_equal(magn_session_hint(fit, m, turned, &h), 0);
	magn_hint_text(&h, text, sizeof(text));
	assert_string_equal(text, "turn it about the device's X axis, +Y toward +Z, about 40 deg");
	/* the right-handed sense, named as such */
	h = (struct magn_hint){ .axis = 0, .sign = 1, .deg = 12.4 };
	magn_hint_text(&h, text, sizeof(text));
	assert_string_equal(text, "turn it about the chip's X axis, +Y toward +Z, about 12 deg");
	h = (struct magn_hint){ .axis = 2, .sign = 1, .deg = 90 };
	magn_hint_text(&h, text, sizeof(text));
	assert_string_equal(text, "turn it about the chip's Z axis, +X toward +Y, about 90 deg");
	magcal_free(fit);
}

/* A board tumbling 4 degrees a measurement, its field 48 uT */
static void session_on_the_chip(void **state)
{
	char unit[] = "/tmp/as9888-magnsession-XXXXXX";
	static const char text[] =
		"earth = 48 60 3\n"
		"hard_iron = 120 -80 45\n"
		"magn_noise = 0.4\n"
		"tumble = 4\n";
	struct calib_record rec = {
		.dac = { 0x0d, 0x8f, 0x8c },	/* the EEPROM's EAxDA */
		.gravity = { 0, 0, -1 },
		.samples = 16,
	};
	struct backend_sim_opts o = { .virtual_clock = true };
	struct magn_session_result res;
	struct magn_source *src;
	struct transport *t;
	char err[256];
	int fd;

	(void)state;
	fd = mkstemp(unit);
	assert_true(fd >= 0);
	assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
	close(fd);
	o.unit_path = unit;
	if (backend_sim_open(&o, &t, err, sizeof(err)))
		fail_msg("simulator: %s", err);
	memcpy(rec.eeprom, fake_example_eeprom, AS9888_EEPROM_LEN);
	assert_int_equal(magn_source_open_chip(t, &rec, &src, err, sizeof(err)), 0);
	assert_int_equal(magn_session_run(src, 120 * NS_PER_S, 0, NULL, &res,
					  err, sizeof(err)), 0);
	magn_source_close(src);
	unlink(unit);
	assert_true(res.averaged);
	assert_true(res.solved && res.fit.status == MAGCAL_OK);
	/* stored at the averaged samples' coverage, before the single's */
	if (!(res.fit.coverage >= MAGN_SESSION_COVERAGE &&
	      res.fit.coverage < MAGN_SESSION_COVERAGE_SINGLE))
		fail_msg("stored at %.3f coverage", res.fit.coverage);
	/* the hard iron learned */
	assert_true(fabs(res.fit.bias[0] - 120) < 1.0 &&
		    fabs(res.fit.bias[1] + 80) < 1.0 &&
		    fabs(res.fit.bias[2] - 45) < 1.0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(coverage_by_noise),
		cmocka_unit_test(refusal_says_the_coverage),
		cmocka_unit_test(hint_way_out),
		cmocka_unit_test(session_on_the_chip),
	};

	return cmocka_run_group_tests_name("magn-session", tests, NULL, NULL);
}
