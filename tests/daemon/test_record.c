// SPDX-License-Identifier: GPL-2.0
/*
 * The calibration record: format/parse round trip, every corruption and
 * truncation refused, every field validated, and the file helpers
 * (permissions, no temporary left, symlinks refused).
 */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "store/atomic_file.h"
#include "common/record.h"

static const u8 example[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

/* sample_record() with a magnetometer calibration: a format 2 record */
static bool with_magn;

static const struct calib_magn sample_magn = {
	.present = true,
	.hard_iron_nt = { -123456, 45000, 200125 },
	.soft_iron_micro = {
		{ 1020000, 10000, -20000 },
		{ 10000, 980000, 0 },
		{ -20000, 0, 1001000 },
	},
	.field_nt = 48123,
	.residual_nt = 412,
	.coverage_milli = 875,
	.samples = 300,
	.learned = 1795392000,	/* 2026-11-23T00:00:00Z */
};

static void sample_record(struct calib_record *rec)
{
	memset(rec, 0, sizeof(*rec));
	memcpy(rec->eeprom, example, sizeof(example));
	rec->dac[0] = 0x0f;
	rec->dac[1] = 0x8e;
	rec->dac[2] = 0x8c;
	rec->level_mean_q16[0] = -26214;	/* -0.4 */
	rec->level_mean_q16[1] = 6553;
	rec->level_mean_q16[2] = 258 * 65536 + 6554;
	rec->t_level_mdegc = 24583;
	rec->gravity[2] = -1;
	rec->samples = 16;
	rec->lpf = true;
	rec->created = 1795305600;	/* 2026-11-22T00:00:00Z */
	if (with_magn)
		rec->magn = sample_magn;
}

static int format(const struct calib_record *rec, char *buf, size_t size)
{
	int len = record_format(rec, buf, size);

	assert_true(len > 0);
	return len;
}

static void round_trip(void **state)
{
	struct calib_record rec, back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len, q;

	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	assert_int_equal(record_parse(buf, (size_t)len, &back, err, sizeof(err)), 0);
	assert_memory_equal(&rec, &back, sizeof(rec));
	assert_non_null(strstr(buf, "created = 2026-11-22T00:00:00Z\n"));
	assert_non_null(strstr(buf, "level_mean = -0.399994 0.099991 258.100006\n"));

	/* every Q16 mean survives the 6-decimal text form */
	for (q = -2048 * 65536; q <= 2048 * 65536; q += 65536 / 16 * 7 + 1) {
		rec.level_mean_q16[0] = q;
		len = format(&rec, buf, sizeof(buf));
		assert_int_equal(record_parse(buf, (size_t)len, &back, err,
					      sizeof(err)), 0);
		assert_int_equal(back.level_mean_q16[0], q);
	}
}

/* Any single changed byte is refused: syntax, range or checksum */
static void every_corruption_refused(void **state)
{
	static const u8 flips[] = { 0x01, 0x02, 0x10, 0x20, 0x80, 0xff };
	struct calib_record rec, back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len, i;
	unsigned int f;

	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	for (i = 0; i < len; i++) {
		for (f = 0; f < sizeof(flips); f++) {
			char copy[RECORD_MAX_SIZE];

			memcpy(copy, buf, (size_t)len);
			copy[i] ^= flips[f];
			if (record_parse(copy, (size_t)len, &back, err,
					 sizeof(err)) == 0)
				fail_msg("byte %d ^ 0x%02x accepted", i, flips[f]);
		}
	}
}

static void every_truncation_refused(void **state)
{
	struct calib_record rec, back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len, i;

	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	for (i = 0; i < len; i++)
		assert_int_equal(record_parse(buf, (size_t)i, &back, err,
					      sizeof(err)), -EINVAL);
	/* and nothing may follow the checksum line */
	memcpy(buf + len, "x\n", 2);
	assert_int_equal(record_parse(buf, (size_t)len + 2, &back, err,
				      sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "after the crc32"));
}

/* @text with @key's line replaced by @line, re-sealed with a fresh checksum */
static int edit_text(const char *text, const char *key, const char *line,
		     char *out)
{
	char body[RECORD_MAX_SIZE];
	const char *p, *q;
	char *crc;
	size_t blen;

	body[0] = '\0';
	for (p = text; *p; p = q + 1) {
		q = strchr(p, '\n');
		if (!strncmp(p, key, strlen(key)) && p[strlen(key)] == ' ') {
			if (line)
				strcat(strcat(body, line), "\n");
		} else {
			strncat(body, p, (size_t)(q - p + 1));
		}
	}
	crc = strstr(body, "crc32 = ");
	*crc = '\0';
	blen = strlen(body);
	return sprintf(out, "%scrc32 = %08x\n", body, record_crc32(body, blen));
}

/* The sample record with @key's line replaced by @line, re-sealed */
static int edit(const char *key, const char *line, char *out)
{
	struct calib_record rec;
	char buf[RECORD_MAX_SIZE];
	int len;

	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	buf[len] = '\0';
	return edit_text(buf, key, line, out);
}

static void expect_refused(const char *key, const char *line, const char *why)
{
	struct calib_record back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len = edit(key, line, buf);

	assert_int_equal(record_parse(buf, (size_t)len, &back, err, sizeof(err)),
			 -EINVAL);
	if (!strstr(err, why))
		fail_msg("%s: \"%s\" does not say \"%s\"", key, err, why);
}

/* A record made on the simulator says so; older records read as a chip's */
static void source_marked(void **state)
{
	struct calib_record rec, back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len, i;

	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	buf[len] = '\0';
	assert_null(strstr(buf, "source"));
	rec.simulated = true;
	len = format(&rec, buf, sizeof(buf));
	buf[len] = '\0';
	assert_non_null(strstr(buf, "\nsource = simulator\ncrc32 = "));
	assert_int_equal(record_parse(buf, (size_t)len, &back, err, sizeof(err)), 0);
	assert_true(back.simulated);
	assert_memory_equal(&rec, &back, sizeof(rec));
	/* no byte of the mark can change unnoticed */
	for (i = (int)(strstr(buf, "source") - buf); buf[i] != '\n'; i++) {
		char copy[RECORD_MAX_SIZE];

		memcpy(copy, buf, (size_t)len);
		copy[i] ^= 0x20;
		assert_int_not_equal(record_parse(copy, (size_t)len, &back, err,
						  sizeof(err)), 0);
	}

	len = edit("lpf", "lpf = off\nsource = chip", buf);
	assert_int_equal(record_parse(buf, (size_t)len, &back, err, sizeof(err)), 0);
	assert_false(back.simulated);
	expect_refused("lpf", "lpf = off\nsource = sim", "source must be simulator or chip");
	expect_refused("lpf", "lpf = off\nsource = simulator\nsource = chip",
		       "source given twice");
}

static void fields_validated(void **state)
{
	expect_refused("format", "format = as9888-calibration 3", "format must be");
	expect_refused("format", "format = as9888-calibration 2",
		       "magn_hard_iron is missing (format 2");
	expect_refused("format", "format = something 1", "format must be");
	expect_refused("format", NULL, "format is missing");
	expect_refused("chip", "chip = 0000000000000000", "does not match");
	expect_refused("chip", "chip = 676f64b435a720bA", "chip must be");
	expect_refused("created", "created = yesterday", "created must be");
	expect_refused("created", "created = 2026-13-01T00:00:00Z", "created must be");
	expect_refused("eeprom", "eeprom = 9a 71 15", "eeprom must be");
	expect_refused("dac", "dac = 0f 8e 8c 00", "dac must be");
	expect_refused("dac", "dac = 0f 8e c4", "DAC value 0xc4");
	expect_refused("dac", "dac = 44 8e 8c", "DAC value 0x44");
	expect_refused("level_mean", "level_mean = 1 2 3", "level_mean must be");
	expect_refused("level_mean", "level_mean = 0.000000 0.000000 2048.000001",
		       "level_mean must be");
	expect_refused("level_mean", "level_mean = nan 0.000000 0.000000",
		       "level_mean must be");
	expect_refused("t_level", "t_level = 85.001", "t_level must be");
	expect_refused("t_level", "t_level = 25", "t_level must be");
	expect_refused("gravity", "gravity = 0 0 0", "exactly one axis");
	expect_refused("gravity", "gravity = 0 -1 -1", "exactly one axis");
	expect_refused("gravity", "gravity = 0 0 2", "gravity must be");
	expect_refused("samples", "samples = 9", "samples must be");
	expect_refused("samples", "samples = 4097", "samples must be");
	expect_refused("samples", "samples = 16.0", "samples must be");
	expect_refused("lpf", "lpf = yes", "lpf must be");
	expect_refused("lpf", "lpf = on\nlpf = off", "given twice");
	expect_refused("lpf", "lpf = on\nfoo = 1", "unknown key");
	expect_refused("lpf", "lpf on", "expected \"key = value\"");
}

/*
 * The example of RECORD.md, written by the code before format 2: it reads,
 * and is written back byte for byte (a record without a magnetometer
 * calibration stays format 1, which older as9888-calibd read)
 */
static void format1_unchanged(void **state)
{
	static const char old[] =
		"# AS9888 accelerometer calibration, written by as9888-calibd.\n"
		"# Do not edit: the crc32 line covers every byte above it.\n"
		"format = as9888-calibration 1\n"
		"chip = 676f64b435a720ba\n"
		"created = 2026-11-22T00:44:53Z\n"
		"eeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 50\n"
		"dac = 0d 8f 8c\n"
		"level_mean = -0.399994 0.100006 258.100006\n"
		"t_level = 25.000\n"
		"gravity = 0 0 -1\n"
		"samples = 10\n"
		"lpf = off\n"
		"crc32 = 81229d28\n";
	struct calib_record rec;
	char buf[RECORD_MAX_SIZE], err[256];
	int len;

	assert_int_equal(record_parse(old, strlen(old), &rec, err, sizeof(err)), 0);
	assert_false(rec.magn.present);
	len = format(&rec, buf, sizeof(buf));
	assert_int_equal(len, (int)strlen(old));
	assert_memory_equal(buf, old, strlen(old));
}

/* Format 2: the magnetometer section round-trips and every byte is guarded */
static void format2_round_trip(void **state)
{
	struct calib_record rec, back;
	char buf[RECORD_MAX_SIZE], err[256];
	int len, v;

	with_magn = true;
	sample_record(&rec);
	len = format(&rec, buf, sizeof(buf));
	buf[len] = '\0';
	assert_non_null(strstr(buf, "format = as9888-calibration 2\n"));
	assert_non_null(strstr(buf, "# AS9888 accelerometer and magnetometer calibration"));
	assert_non_null(strstr(buf, "\nmagn_hard_iron = -123.456 45.000 200.125\n"
				    "magn_soft_iron = 1.020000 0.010000 -0.020000 0.010000 0.980000 0.000000 -0.020000 0.000000 1.001000\n"
				    "magn_field = 48.123\n"
				    "magn_residual = 0.412\n"
				    "magn_coverage = 0.875\n"
				    "magn_samples = 300\n"
				    "magn_learned = 2026-11-23T00:00:00Z\n"
				    "crc32 = "));
	assert_int_equal(record_parse(buf, (size_t)len, &back, err, sizeof(err)), 0);
	assert_memory_equal(&rec, &back, sizeof(rec));
	/* negative and extreme values survive the text form */
	for (v = -1000000; v <= 1000000; v += 99991) {
		rec.magn.hard_iron_nt[1] = v;
		rec.magn.soft_iron_micro[0][2] = v / 2;
		rec.magn.soft_iron_micro[2][0] = v / 2;
		len = format(&rec, buf, sizeof(buf));
		assert_int_equal(record_parse(buf, (size_t)len, &back, err,
					      sizeof(err)), 0);
		assert_memory_equal(&rec, &back, sizeof(rec));
	}
	every_corruption_refused(state);
	every_truncation_refused(state);
	with_magn = false;
}

static void format2_fields_validated(void **state)
{
	struct calib_record rec;
	char err[256];

	with_magn = true;
	expect_refused("magn_hard_iron", "magn_hard_iron = 1000.001 0.000 0.000",
		       "magn_hard_iron must be");
	expect_refused("magn_hard_iron", "magn_hard_iron = 1.0 0.000 0.000",
		       "magn_hard_iron must be");
	expect_refused("magn_hard_iron", NULL,
		       "magn_hard_iron is missing (format 2");
	expect_refused("magn_soft_iron",
		       "magn_soft_iron = 1.020000 0.010000 -0.020000 0.011000 0.980000 0.000000 -0.020000 0.000000 1.001000",
		       "not symmetric");
	expect_refused("magn_soft_iron",
		       "magn_soft_iron = 2.020000 0.010000 -0.020000 0.010000 0.980000 0.000000 -0.020000 0.000000 1.001000",
		       "magn_soft_iron must be");
	expect_refused("magn_soft_iron",
		       "magn_soft_iron = 0.490000 0.010000 -0.020000 0.010000 0.980000 0.000000 -0.020000 0.000000 1.001000",
		       "outside 0.5..2");
	expect_refused("magn_soft_iron",
		       "magn_soft_iron = 1.020000 0.600000 -0.020000 0.600000 0.980000 0.000000 -0.020000 0.000000 1.001000",
		       "beyond +-0.5");
	expect_refused("magn_soft_iron",
		       "magn_soft_iron = 1.020000 0.010000 -0.020000 0.010000 0.980000 0.000000 -0.020000 0.000000",
		       "magn_soft_iron must be");
	expect_refused("magn_field", "magn_field = 19.999", "magn_field must be");
	expect_refused("magn_field", "magn_field = 70.001", "magn_field must be");
	expect_refused("magn_residual", "magn_residual = -0.001", "magn_residual must be");
	expect_refused("magn_coverage", "magn_coverage = 1.001", "magn_coverage must be");
	expect_refused("magn_samples", "magn_samples = 9", "magn_samples must be");
	expect_refused("magn_learned", "magn_learned = now", "magn_learned must be");
	expect_refused("magn_learned", "magn_learned = 2026-11-23T00:00:00Z\nmagn_samples = 3",
		       "given twice");
	/* a format 1 record with (part of) the section is refused */
	expect_refused("format", "format = as9888-calibration 1",
		       "magn_* keys need format 2");
	with_magn = false;
	expect_refused("lpf", "lpf = off\nmagn_field = 48.000",
		       "magn_* keys need format 2");
	/* record_validate() checks the section too */
	sample_record(&rec);
	rec.magn = sample_magn;
	rec.magn.soft_iron_micro[1][1] = 2000001;
	assert_int_equal(record_validate(&rec, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "soft-iron gain 1,1"));
	rec.magn = sample_magn;
	rec.magn.present = false;
	rec.magn.field_nt = 0;	/* ignored: no section */
	assert_int_equal(record_validate(&rec, err, sizeof(err)), 0);
}

/* The sample calibration with a turn of 2 deg about Z, as <record>.magn holds it */
static int magn_file_text(struct calib_magn *m, char *buf, size_t size)
{
	static const int32_t rz[3][3] = {
		{ 999391, -34899, 0 }, { 34899, 999391, 0 }, { 0, 0, 1000000 },
	};
	int len;

	*m = sample_magn;
	m->has_rotation = true;
	memcpy(m->rotation_micro, rz, sizeof(rz));
	len = record_magn_format(m, example, 1795305600, buf, size);
	assert_true(len > 0);
	buf[len] = '\0';
	return len;
}

/* @text (a magnetometer file) with @key's line replaced is refused, saying @why */
static void expect_magn_refused(const char *text, const char *key,
				const char *line, const char *why)
{
	char buf[RECORD_MAX_SIZE], err[256];
	struct calib_magn back;
	uint64_t chip;
	int len = edit_text(text, key, line, buf);

	assert_int_equal(record_magn_parse(buf, (size_t)len, &back, &chip, err,
					   sizeof(err)), -EINVAL);
	if (!strstr(err, why))
		fail_msg("%s: \"%s\" does not say \"%s\"", key, err, why);
}

/*
 * <record>.magn (issue 40 N6, issue 39 point 5): written, sealed, read back
 * whole with its turn; a file of none; every truncation and corruption,
 * a turn that is no rotation or too large, a key of the record's, part of
 * a calibration refused; magn_rotation never in a record
 */
static void magn_file(void **state)
{
	char buf[RECORD_MAX_SIZE], text[RECORD_MAX_SIZE], err[256];
	struct calib_magn m, back, none = { 0 };
	uint64_t chip = 0;
	int len, n;

	(void)state;
	len = magn_file_text(&m, text, sizeof(text));
	assert_non_null(strstr(text, "\nformat = as9888-magnetometer 1\n"
				     "chip = 676f64b435a720ba\n"
				     "created = 2026-11-22T00:00:00Z\n"
				     "magn_hard_iron = -123.456 45.000 200.125\n"));
	assert_non_null(strstr(text, "\nmagn_rotation = 0.999391 -0.034899 0.000000 0.034899 0.999391 0.000000 0.000000 0.000000 1.000000\n"
				     "magn_field = 48.123\n"));
	assert_null(strstr(text, "eeprom"));
	assert_int_equal(record_magn_parse(text, (size_t)len, &back, &chip, err,
					   sizeof(err)), 0);
	assert_memory_equal(&m, &back, sizeof(m));
	assert_true(chip == record_fingerprint(example));
	/* a file of none: what rollback restores after the first calibration */
	n = record_magn_format(&none, example, 1795305600, buf, sizeof(buf));
	assert_true(n > 0);
	assert_int_equal(record_magn_parse(buf, (size_t)n, &back, &chip, err,
					   sizeof(err)), 0);
	assert_false(back.present);
	/* every truncation, every flipped byte */
	for (n = 0; n < len; n++)
		assert_int_equal(record_magn_parse(text, (size_t)n, &back, &chip,
						   err, sizeof(err)), -EINVAL);
	for (n = 0; n < len; n++) {
		memcpy(buf, text, (size_t)len);
		buf[n] ^= 0x04;
		assert_int_equal(record_magn_parse(buf, (size_t)len, &back, &chip,
						   err, sizeof(err)), -EINVAL);
	}
	expect_magn_refused(text, "magn_rotation",
			    "magn_rotation = 0.994522 -0.104528 0.000000 0.104528 0.994522 0.000000 0.000000 0.000000 1.000000",
			    "more than 5 degrees");
	expect_magn_refused(text, "magn_rotation",
			    "magn_rotation = 0.999391 -0.034899 0.000000 0.044899 0.999391 0.000000 0.000000 0.000000 1.000000",
			    "not a rotation");
	expect_magn_refused(text, "magn_rotation",
			    "magn_rotation = 1.000000 0.000000 0.000000 0.000000 1.000000 0.000000 0.000000 0.000000 -1.000000",
			    "reflection");
	expect_magn_refused(text, "magn_rotation",
			    "magn_rotation = 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0",
			    "magn_rotation must be");
	expect_magn_refused(text, "magn_rotation", NULL, "magn_rotation is missing");
	expect_magn_refused(text, "magn_field", NULL, "magn_field is missing");
	expect_magn_refused(text, "chip", "chip = 676f64b435a720ba\neeprom = 9a",
			    "unknown key \"eeprom\"");
	expect_magn_refused(text, "format", "format = as9888-calibration 2",
			    "format must be");
	expect_magn_refused(text, "created", NULL, "created is missing");
	/* a record never holds the turn: an older build would refuse it */
	with_magn = true;
	expect_refused("magn_field", "magn_field = 48.123\nmagn_rotation = 1.000000 0.000000 0.000000 0.000000 1.000000 0.000000 0.000000 0.000000 1.000000",
		       "unknown key \"magn_rotation\"");
	with_magn = false;
}

/* A record whose EEPROM data is unusable is refused too */
static void eeprom_validated(void **state)
{
	struct calib_record rec;
	char err[256];

	sample_record(&rec);
	rec.eeprom[AS9888_EE_EAGA(1)] = 0x3f;		/* gain 63 */
	assert_int_equal(record_validate(&rec, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "EEPROM"));
	sample_record(&rec);
	memset(rec.eeprom, 0xff, sizeof(rec.eeprom));
	assert_int_equal(record_validate(&rec, err, sizeof(err)), -EINVAL);
}

static void make_tmpdir(char *dir, size_t len)
{
	snprintf(dir, len, "/tmp/as9888-record-XXXXXX");
	assert_non_null(mkdtemp(dir));
}

static void atomic_write_and_read(void **state)
{
	char dir[64], path[128], tmp[160], buf[64], err[256];
	struct stat st;
	mode_t old = umask(0077);

	make_tmpdir(dir, sizeof(dir));
	snprintf(path, sizeof(path), "%s/cal", dir);
	snprintf(tmp, sizeof(tmp), "%s/cal.new", dir);

	assert_int_equal(atomic_write_file(path, "one\n", 4, 0644, err, sizeof(err)), 0);
	assert_int_equal(stat(path, &st), 0);
	assert_int_equal(st.st_mode & 07777, 0644);	/* whatever the umask */
	assert_int_equal(access(tmp, F_OK), -1);
	/* a stale temporary from a crash is replaced */
	close(open(tmp, O_CREAT | O_WRONLY, 0600));
	assert_int_equal(atomic_write_file(path, "two\n", 4, 0644, err, sizeof(err)), 0);
	assert_int_equal(access(tmp, F_OK), -1);
	assert_int_equal(read_file_nofollow(path, buf, sizeof(buf), err, sizeof(err)), 4);
	assert_memory_equal(buf, "two\n", 4);
	/* too large */
	assert_int_equal(read_file_nofollow(path, buf, 3, err, sizeof(err)), -EFBIG);
	/* missing */
	unlink(path);
	assert_int_equal(read_file_nofollow(path, buf, sizeof(buf), err, sizeof(err)),
			 -ENOENT);
	assert_non_null(strstr(err, path));
	rmdir(dir);
	umask(old);
}

static void symlinks_refused(void **state)
{
	char dir[64], path[128], target[128], buf[64], err[256];

	make_tmpdir(dir, sizeof(dir));
	snprintf(path, sizeof(path), "%s/cal", dir);
	snprintf(target, sizeof(target), "%s/elsewhere", dir);
	assert_int_equal(atomic_write_file(target, "keep\n", 5, 0644, err,
					   sizeof(err)), 0);
	assert_int_equal(symlink(target, path), 0);

	assert_int_equal(read_file_nofollow(path, buf, sizeof(buf), err, sizeof(err)),
			 -ELOOP);
	assert_non_null(strstr(err, "symbolic link"));
	assert_int_equal(atomic_write_file(path, "new\n", 4, 0644, err, sizeof(err)),
			 -ELOOP);
	/* the link and its target are untouched */
	assert_int_equal(read_file_nofollow(target, buf, sizeof(buf), err, sizeof(err)), 5);
	assert_memory_equal(buf, "keep\n", 5);

	unlink(path);
	unlink(target);
	/* a directory at the record path */
	assert_int_equal(mkdir(path, 0755), 0);
	assert_int_equal(atomic_write_file(path, "new\n", 4, 0644, err, sizeof(err)),
			 -EEXIST);
	rmdir(path);
	rmdir(dir);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(round_trip),
		cmocka_unit_test(every_corruption_refused),
		cmocka_unit_test(every_truncation_refused),
		cmocka_unit_test(source_marked),
		cmocka_unit_test(fields_validated),
		cmocka_unit_test(eeprom_validated),
		cmocka_unit_test(format1_unchanged),
		cmocka_unit_test(format2_round_trip),
		cmocka_unit_test(format2_fields_validated),
		cmocka_unit_test(magn_file),
		cmocka_unit_test(atomic_write_and_read),
		cmocka_unit_test(symlinks_refused),
	};

	return cmocka_run_group_tests_name("record", tests, NULL, NULL);
}
