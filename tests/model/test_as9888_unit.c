// SPDX-License-Identifier: GPL-2.0
/* Tests of the AS9888 unit description parser (datasheet section 8). */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include <linux/errno.h>

#include "as9888_unit.h"

static const u8 example_ee[21] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static int parse(const char *text, struct as9888_unit *u,
		 struct as9888_unit_error *err)
{
	return as9888_unit_parse(text, strlen(text), u, err);
}

static void parse_ok(const char *text, struct as9888_unit *u)
{
	struct as9888_unit_error err;
	int ret = parse(text, u, &err);

	if (ret)
		fail_msg("line %u: %s", err.line, err.msg);
	assert_int_equal(err.line, 0);
}

/* Parsing @text fails on @line with a message containing @needle. */
static void parse_err(const char *text, unsigned int line, const char *needle)
{
	struct as9888_unit_error err;
	struct as9888_unit u;

	memset(&err, 0x55, sizeof(err));
	assert_int_equal(parse(text, &u, &err), -EINVAL);
	if (err.line != line || !strstr(err.msg, needle))
		fail_msg("'%s': got line %u '%s', want line %u '%s'", text,
			 err.line, err.msg, line, needle);
	assert_true(strlen(err.msg) < sizeof(err.msg));
}

static void test_default(void **state)
{
	struct as9888_unit u;

	as9888_unit_default(&u);
	assert_memory_equal(u.eeprom, example_ee, 21);
	assert_int_equal(u.up[0], 0);
	assert_int_equal(u.up[1], 0);
	assert_int_equal(u.up[2], 1000000);
	assert_int_equal(u.offset_mlsb[0], 0);
	assert_int_equal(u.offset_mlsb[2], 0);
	assert_int_equal(u.temperature_mdegc, 25000);
	assert_int_equal(u.drift_udegc_s, 0);
	assert_int_equal(u.noise_mlsb, 1000);
	assert_int_equal(u.field_nt[0], 20000);
	assert_int_equal(u.field_nt[1], -5000);
	assert_int_equal(u.field_nt[2], -40000);
	assert_int_equal(u.faults, 0);
}

static void test_empty_is_default(void **state)
{
	struct as9888_unit u, d;

	as9888_unit_default(&d);
	parse_ok("", &u);
	assert_memory_equal(&u, &d, sizeof(u));
	parse_ok("# only a comment\n\n   \n\t# another\n", &u);
	assert_memory_equal(&u, &d, sizeof(u));
	assert_int_equal(as9888_unit_parse(NULL, 0, &u, NULL), 0);
	assert_int_equal(as9888_unit_parse(NULL, 3, &u, NULL), -EINVAL);
}

static void test_full_example(void **state)
{
	static const char text[] =
		"# unit 7, tilted\n"
		"eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 50\n"
		"offset = 40 -25 60\n"
		"up = 0 0 1\n"
		"temperature = 31.25\n"
		"temperature_drift = 0.5\n"
		"noise = 1.5\n"
		"field = 20 -5 -40\n"
		"seed = 42\n"
		"fault = int2_open, nak\n";
	struct as9888_unit u;

	parse_ok(text, &u);
	assert_memory_equal(u.eeprom, example_ee, 21);
	assert_int_equal(u.offset_mlsb[0], 40000);
	assert_int_equal(u.offset_mlsb[1], -25000);
	assert_int_equal(u.offset_mlsb[2], 60000);
	assert_int_equal(u.up[2], 1000000);
	assert_int_equal(u.temperature_mdegc, 31250);
	assert_int_equal(u.drift_udegc_s, 500000);
	assert_int_equal(u.noise_mlsb, 1500);
	assert_int_equal(u.field_nt[0], 20000);
	assert_int_equal(u.field_nt[1], -5000);
	assert_int_equal(u.field_nt[2], -40000);
	assert_int_equal(u.seed, 42);
	assert_int_equal(u.faults, AS9888_FAULT_INT2_OPEN | AS9888_FAULT_NAK);
}

static void test_partial_keeps_defaults(void **state)
{
	struct as9888_unit u;

	parse_ok("noise = 0\n", &u);
	assert_int_equal(u.noise_mlsb, 0);
	assert_int_equal(u.temperature_mdegc, 25000);
	assert_memory_equal(u.eeprom, example_ee, 21);
}

static void test_syntax_variants_ok(void **state)
{
	struct as9888_unit u;

	parse_ok("\ttemperature=-12.5   # cold\r\n"
		 "offset = 1.5,-2.25 , +3.125\r\n"
		 "eeprom = 0x9A 71 15 5C 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 4 65 c3 88 50\n"
		 "field = .5 -0.001 1200", &u);
	assert_int_equal(u.temperature_mdegc, -12500);
	assert_int_equal(u.offset_mlsb[0], 1500);
	assert_int_equal(u.offset_mlsb[1], -2250);
	assert_int_equal(u.offset_mlsb[2], 3125);
	assert_memory_equal(u.eeprom, example_ee, 21);
	assert_int_equal(u.field_nt[0], 500);
	assert_int_equal(u.field_nt[1], -1);
	assert_int_equal(u.field_nt[2], 1200000);
	/* extra zero decimals are fine */
	parse_ok("temperature = 25.000000\n", &u);
	assert_int_equal(u.temperature_mdegc, 25000);
}

static void test_up_normalised(void **state)
{
	struct as9888_unit u;

	parse_ok("up = 3 4 0\n", &u);
	assert_int_equal(u.up[0], 600000);
	assert_int_equal(u.up[1], 800000);
	assert_int_equal(u.up[2], 0);
	parse_ok("up = 0 0 -9.81\n", &u);
	assert_int_equal(u.up[2], -1000000);
	parse_ok("up = 0.1 -0.2 0.97\n", &u);
	/* 0.1 / 0.99544 (the root rounded to 1e-6) */
	assert_int_equal(u.up[0], 100458);
	assert_int_equal(u.up[1], -200916);
	assert_int_equal(u.up[2], 974443);
	parse_ok("up = 0.000001 0 0\n", &u);
	assert_int_equal(u.up[0], 1000000);
}

static void test_normalise_function(void **state)
{
	s32 in[3] = { INT32_MIN, INT32_MIN, INT32_MIN }, out[3];
	s32 zero[3] = { 0, 0, 0 };

	assert_int_equal(as9888_unit_normalise(in, out), 0);
	assert_int_equal(out[0], -577350);
	assert_int_equal(out[1], -577350);
	assert_int_equal(as9888_unit_normalise(zero, out), -EINVAL);
}

static void test_seed_forms(void **state)
{
	struct as9888_unit u;

	parse_ok("seed = 18446744073709551615\n", &u);
	assert_true(u.seed == UINT64_MAX);
	parse_ok("seed = 0xDEADbeef00000001\n", &u);
	assert_true(u.seed == 0xdeadbeef00000001ULL);
	parse_ok("seed = 0\n", &u);
	assert_true(u.seed == 0);
}

static void test_faults_all(void **state)
{
	struct as9888_unit u;
	unsigned int i;

	parse_ok("fault = no_drdy int1_open,int2_open, rstn_open wia "
		 "eeprom_blank stuck_x saturate_z nak selftest_weak hofl\n",
		 &u);
	assert_int_equal(u.faults, AS9888_FAULT_ALL);
	parse_ok("fault = none\n", &u);
	assert_int_equal(u.faults, 0);
	for (i = 0; i < AS9888_FAULT_COUNT; i++) {
		char line[64];

		snprintf(line, sizeof(line), "fault = %s\n",
			 as9888_fault_name(1U << i));
		parse_ok(line, &u);
		assert_int_equal(u.faults, 1U << i);
	}
	assert_null(as9888_fault_name(0));
	assert_null(as9888_fault_name(3));
	assert_null(as9888_fault_name(1U << AS9888_FAULT_COUNT));
}

static void test_err_unknown_key(void **state)
{
	parse_err("noise = 1\n\n# c\ncolour = red\n", 4, "unknown key 'colour'");
	parse_err("Noise = 1\n", 1, "unknown key");
}

static void test_err_malformed_number(void **state)
{
	parse_err("noise = 1x\n", 1, "malformed number");
	parse_err("temperature = 1e3\n", 1, "malformed number");
	parse_err("\noffset = 1 2 -\n", 2, "malformed number");
	parse_err("field = 1 2 3.4.5\n", 1, "malformed number");
	parse_err("noise = .\n", 1, "malformed number");
	parse_err("seed = -1\n", 1, "seed: malformed number");
	parse_err("seed = 0xg\n", 1, "seed: malformed number");
}

static void test_err_decimals(void **state)
{
	parse_err("offset = 1 2 3.0001\n", 1, "too many decimal places");
	parse_err("temperature = 25.0005\n", 1, "too many decimal places");
	parse_err("up = 0 0 1.0000001\n", 1, "too many decimal places");
}

static void test_err_counts(void **state)
{
	parse_err("offset = 1 2\n", 1, "offset: too few values");
	parse_err("# x\noffset = 1 2 3 4\n", 2, "offset: too many values");
	parse_err("up = 1\n", 1, "up: too few values");
	parse_err("field = 1 2 3 4\n", 1, "field: too many values");
	parse_err("noise = 1 2\n", 1, "noise: too many values");
	parse_err("temperature = 1 2\n", 1, "too many values");
	parse_err("seed = 1 2\n", 1, "seed: too many values");
	parse_err("eeprom = 9a 71\n", 1, "eeprom: too few bytes");
	parse_err("eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c "
		  "04 65 c3 88 50 00\n", 1, "eeprom: too many bytes");
}

static void test_err_eeprom_byte(void **state)
{
	parse_err("eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c "
		  "04 65 c3 88 5g\n", 1, "eeprom: malformed byte '5g'");
	parse_err("eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c "
		  "04 65 c3 88 150\n", 1, "eeprom: malformed byte");
}

static void test_err_ranges(void **state)
{
	parse_err("temperature = 150.001\n", 1, "temperature");
	parse_err("temperature = -50.001\n", 1, "out of range");
	parse_err("noise = -1\n", 1, "noise");
	parse_err("noise = 100.001\n", 1, "out of range");
	parse_err("offset = 0 4096.001 0\n", 1, "out of range");
	parse_err("field = 0 0 -5000.001\n", 1, "out of range");
	parse_err("temperature_drift = 100.000001\n", 1, "out of range");
	parse_err("up = 1000.000001 0 0\n", 1, "out of range");
	parse_err("seed = 18446744073709551616\n", 1, "out of range");
	parse_err("seed = 0x10000000000000000\n", 1, "out of range");
	parse_err("noise = 99999999999999999999999999999\n", 1,
		  "out of range");
	/* boundaries are accepted */
	{
		struct as9888_unit u;

		parse_ok("temperature = -50\nnoise = 100\noffset = 4096 -4096 0\n"
			 "field = 5000 -5000 0\ntemperature_drift = -100\n",
			 &u);
		assert_int_equal(u.temperature_mdegc, -50000);
		assert_int_equal(u.drift_udegc_s, -100000000);
	}
}

static void test_err_unknown_fault(void **state)
{
	parse_err("seed = 1\nfault = nak, int3_open\n", 2,
		  "unknown fault 'int3_open'");
	parse_err("fault = none nak\n", 1, "'none' combined");
	parse_err("fault = ,\n", 1, "fault: missing value");
}

static void test_err_zero_up(void **state)
{
	parse_err("\n\nup = 0 0 0.0\n", 3, "up: zero vector");
}

static void test_err_duplicate(void **state)
{
	parse_err("noise = 1\nseed = 2\nnoise = 2\n", 3,
		  "duplicate key 'noise'");
}

static void test_err_structure(void **state)
{
	parse_err("noise 1\n", 1, "expected 'key = value'");
	parse_err("seed = 1\n = 3\n", 2, "missing key");
	parse_err("noise =\n", 1, "missing value for 'noise'");
	parse_err("noise = # nothing\n", 1, "missing value");
}

static void test_err_non_printable_quoted(void **state)
{
	struct as9888_unit_error err;
	struct as9888_unit u;
	static const char text[] = "n\x01ise = 1\n";

	assert_int_equal(as9888_unit_parse(text, sizeof(text) - 1, &u, &err),
			 -EINVAL);
	assert_string_equal(err.msg, "unknown key 'n?ise'");
	/* long tokens are cut */
	parse_err("abcdefghijklmnopqrstuvwxyz0123456789 = 1\n", 1,
		  "'abcdefghijklmnopqrstuvwx...'");
	/* an embedded NUL is just a bad character, the length rules */
	{
		static const char nul[] = "noise = 1\0\nseed = 2\n";

		assert_int_equal(as9888_unit_parse(nul, sizeof(nul) - 1, &u,
						   &err), -EINVAL);
		assert_int_equal(err.line, 1);
	}
	/* error without an error struct */
	assert_int_equal(parse("bad\n", &u, NULL), -EINVAL);
}

/* The magnetic world's keys and their defaults */
static void test_world_keys(void **state)
{
	struct as9888_unit u;
	int i;

	as9888_unit_default(&u);
	assert_int_equal(u.world, 0);
	assert_int_equal(u.orientation[0], 1000000);
	for (i = 0; i < 9; i++)
		assert_int_equal(u.soft_ppm[i], i % 4 ? 0 : 1000000);
	parse_ok("earth = 48.5 -60.25 3.125\n"
		 "heading = -12.5\n"
		 "hard_iron = 150 -200.5, 0.001\n"
		 "soft_iron = 1.05 0.02 0  0.02 0.95 -0.05  0 -0.05 1\n"
		 "magn_noise = 0.6\n"
		 "disturbance = 300 -20 0.5 25\n"
		 "tumble = 6.5\n", &u);
	assert_int_equal(u.world, AS9888_UNIT_WORLD_EARTH);
	assert_int_equal(u.earth_nt, 48500);
	assert_int_equal(u.incl_mdeg, -60250);
	assert_int_equal(u.decl_mdeg, 3125);
	assert_int_equal(u.heading_mdeg, -12500);
	assert_int_equal(u.hard_nt[0], 150000);
	assert_int_equal(u.hard_nt[1], -200500);
	assert_int_equal(u.hard_nt[2], 1);
	assert_int_equal(u.soft_ppm[0], 1050000);
	assert_int_equal(u.soft_ppm[5], -50000);
	assert_int_equal(u.soft_ppm[8], 1000000);
	assert_int_equal(u.magn_noise_nt, 600);
	assert_int_equal(u.dist_nt[0], 300000);
	assert_int_equal(u.dist_nt[2], 500);
	assert_int_equal(u.dist_samples, 25);
	assert_int_equal(u.tumble_mdeg, 6500);
	parse_ok("orientation = 0.5 0.5 -0.5 0.5\n", &u);
	assert_int_equal(u.world, AS9888_UNIT_WORLD_ORIENTATION);
	assert_int_equal(u.orientation[2], -500000);
	/* the old keys alone leave the world as it was */
	parse_ok("field = 1 2 3\nup = 0 1 0\n", &u);
	assert_int_equal(u.world, 0);
}

static void test_world_errors(void **state)
{
	parse_err("up = 0 0 1\norientation = 1 0 0 0\n", 2,
		  "orientation: not with 'up' or 'heading'");
	parse_err("orientation = 1 0 0 0\nheading = 3\n", 2,
		  "orientation: not with 'up' or 'heading'");
	parse_err("field = 1 2 3\nearth = 50 60 0\n", 2,
		  "earth: not with 'field'");
	parse_err("orientation = 0 0 0 0\n", 1, "zero quaternion");
	parse_err("earth = 201 60 0\n", 1, "out of range");
	parse_err("earth = -1 60 0\n", 1, "magnitude out of range");
	parse_err("earth = 50 91 0\n", 1, "inclination out of range");
	parse_err("earth = 50 60 180.001\n", 1, "declination out of range");
	parse_err("earth = 50 60\n", 1, "too few values");
	parse_err("heading = 360.001\n", 1, "out of range");
	parse_err("hard_iron = 2000.001 0 0\n", 1, "out of range");
	parse_err("soft_iron = 1 0 0 0 1 0 0 0\n", 1, "too few values");
	parse_err("soft_iron = 1 0 0 0 1 0 0 0 2.000001\n", 1, "out of range");
	parse_err("magn_noise = -0.1\n", 1, "out of range");
	parse_err("disturbance = 1 2 3\n", 1, "too few values");
	parse_err("disturbance = 1 2 3 1.5\n", 1, "too many decimal places");
	parse_err("disturbance = 1 2 3 -1\n", 1, "length out of range");
	parse_err("disturbance = 1 2 3 4 5\n", 1, "too many values");
	parse_err("tumble = 90.001\n", 1, "out of range");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_default),
		cmocka_unit_test(test_empty_is_default),
		cmocka_unit_test(test_full_example),
		cmocka_unit_test(test_partial_keeps_defaults),
		cmocka_unit_test(test_syntax_variants_ok),
		cmocka_unit_test(test_up_normalised),
		cmocka_unit_test(test_normalise_function),
		cmocka_unit_test(test_seed_forms),
		cmocka_unit_test(test_faults_all),
		cmocka_unit_test(test_err_unknown_key),
		cmocka_unit_test(test_err_malformed_number),
		cmocka_unit_test(test_err_decimals),
		cmocka_unit_test(test_err_counts),
		cmocka_unit_test(test_err_eeprom_byte),
		cmocka_unit_test(test_err_ranges),
		cmocka_unit_test(test_err_unknown_fault),
		cmocka_unit_test(test_err_zero_up),
		cmocka_unit_test(test_err_duplicate),
		cmocka_unit_test(test_err_structure),
		cmocka_unit_test(test_err_non_printable_quoted),
		cmocka_unit_test(test_world_keys),
		cmocka_unit_test(test_world_errors),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
