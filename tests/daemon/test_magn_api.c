// SPDX-License-Identifier: GPL-2.0
/*
 * as9888_magn.h, as an application uses it (linked with libas9888magn
 * alone): the record read, the driver's output corrected to W * (m - b),
 * the HAL's bias, every record it must not use refused with a reason, and
 * a sample handed to the daemon.
 */
#include <errno.h>
#include <signal.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "as9888_magn.h"
#include "common/record.h"

static const uint8_t example[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static char dir[64];

/* The example chip's record, with the magnetometer's calibration (@magn) */
static void fill_record(struct calib_record *rec, bool magn, bool simulated)
{
	static const struct calib_magn cal = {
		.hard_iron_nt = { -150000, 75500, 12345 },
		.soft_iron_micro = {
			{ 1080000, 40000, -50000 },
			{ 40000, 920000, 25000 },
			{ -50000, 25000, 1010000 },
		},
		.field_nt = 47000, .residual_nt = 500,
		.coverage_milli = 910, .samples = 280,
		.learned = 1795392000,
	};

	memset(rec, 0, sizeof(*rec));
	memcpy(rec->eeprom, example, sizeof(example));
	rec->simulated = simulated;
	rec->dac[0] = 0x0d;
	rec->dac[1] = 0x8f;
	rec->dac[2] = 0x8c;
	rec->level_mean_q16[2] = 256 << 16;
	rec->t_level_mdegc = 25000;
	rec->gravity[2] = -1;
	rec->samples = 16;
	rec->created = 1795305600;
	rec->magn = cal;
	rec->magn.present = magn;
}

/* @len bytes of @buf as the file @name of the test's directory, its path in @path */
static void write_text(const char *name, const char *buf, int len, char *path,
		       size_t size)
{
	FILE *f;

	assert_true(len > 0);
	snprintf(path, size, "%s/%s", dir, name);
	f = fopen(path, "w");
	assert_non_null(f);
	assert_int_equal(fwrite(buf, 1, (size_t)len, f), (size_t)len);
	fclose(f);
}

static void write_record_from(const char *name, bool magn, bool simulated,
			      char *path, size_t size)
{
	struct calib_record rec;
	char buf[RECORD_MAX_SIZE];

	fill_record(&rec, magn, simulated);
	write_text(name, buf, record_format(&rec, buf, sizeof(buf)), path, size);
}

static void write_record(const char *name, bool magn, char *path, size_t size)
{
	write_record_from(name, magn, false, path, size);
}

static void loads_and_corrects(void **state)
{
	struct as9888_magn_calibration cal;
	char path[128], err[256];
	double scale[3], bias[3];
	int n, i, j;

	write_record("cal", true, path, sizeof(path));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), 0);
	assert_true(cal.hard_iron_ut[0] == -150 && cal.hard_iron_ut[1] == 75.5 &&
		    fabs(cal.hard_iron_ut[2] - 12.345) < 1e-12);
	assert_true(cal.soft_iron[0][1] == 0.04 && cal.soft_iron[2][0] == -0.05);
	assert_true(cal.field_ut == 47 && cal.samples == 280 &&
		    cal.coverage == 0.91 && cal.learned == 1795392000);
	/* 150 / 0.3, -75.5 / 0.305859, -12.345 / 0.294141 */
	assert_int_equal(cal.calibbias[0], 500);
	assert_int_equal(cal.calibbias[1], -247);
	assert_int_equal(cal.calibbias[2], -42);
	assert_true(cal.calibscale[0] == 1.08 && cal.calibscale[1] == 0.92);
	for (i = 0; i < 3; i++)
		scale[i] = 0.3 * (example[4 + i] + 128) / 256;
	as9888_magn_hal_bias(&cal, bias);
	srand(7);
	for (n = 0; n < 500; n++) {
		double m[3], y[3], f[3], g[3], want[3];

		for (i = 0; i < 3; i++)
			m[i] = (rand() / (double)RAND_MAX - 0.5) * 600;
		/* what the driver outputs: D * (m + calibbias * scale) */
		for (i = 0; i < 3; i++)
			y[i] = cal.calibscale[i] * (m[i] + cal.calibbias[i] * scale[i]);
		as9888_magn_correct(&cal, y, f);
		as9888_magn_correct_uncalibrated(&cal, m, g);
		for (i = 0; i < 3; i++) {
			double unc = 0;

			want[i] = 0;
			for (j = 0; j < 3; j++) {
				want[i] += cal.soft_iron[i][j] * (m[j] - cal.hard_iron_ut[j]);
				unc += cal.soft_iron[i][j] * m[j];
			}
			assert_true(fabs(f[i] - want[i]) < 1e-9);
			assert_true(fabs(g[i] - want[i]) < 1e-9);
			/* the HAL: uncalibrated (W m) - bias = calibrated */
			assert_true(fabs(unc - bias[i] - want[i]) < 1e-9);
		}
	}
}

/*
 * A turned board (issue 39 point 5): the record format 1, the calibration
 * with its turn Rrot in <record>.magn; the application gets Rrot W (m - b)
 * and the HAL's uncalibrated field Rrot W m with the bias Rrot W b. A
 * .magn file of another chip, or of another change of the record, is
 * refused; one of none is no calibration.
 */
static void turned_board(void **state)
{
	/* 3 deg about (2, -1, 2) / 3, in micro units */
	static const int32_t rot[3][3] = {
		{ 999239, -35195, -16836 },
		{ 34586, 998782, -35195 },
		{ 18054, 34586, 999239 },
	};
	struct as9888_magn_calibration cal;
	char path[128], file[160], buf[RECORD_MAX_SIZE], err[256];
	double scale[3], bias[3];
	struct calib_record rec;
	int n, i, j, k;

	(void)state;
	write_record("turned", false, path, sizeof(path));
	fill_record(&rec, true, false);
	rec.magn.has_rotation = true;
	memcpy(rec.magn.rotation_micro, rot, sizeof(rot));
	write_text("turned.magn", buf,
		   record_magn_format(&rec.magn, example, rec.created, buf,
				      sizeof(buf)), file, sizeof(file));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), 0);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			assert_true(cal.rotation[i][j] == rot[i][j] / 1e6);
	for (i = 0; i < 3; i++)
		scale[i] = 0.3 * (example[4 + i] + 128) / 256;
	as9888_magn_hal_bias(&cal, bias);
	srand(11);
	for (n = 0; n < 200; n++) {
		double m[3], y[3], f[3], wm[3], w[3] = { 0 }, want[3], unc[3];

		for (i = 0; i < 3; i++)
			m[i] = (rand() / (double)RAND_MAX - 0.5) * 600;
		for (i = 0; i < 3; i++)
			y[i] = cal.calibscale[i] * (m[i] + cal.calibbias[i] * scale[i]);
		as9888_magn_correct(&cal, y, f);
		for (i = 0; i < 3; i++)
			for (j = 0, wm[i] = 0, w[i] = 0; j < 3; j++) {
				w[i] += cal.soft_iron[i][j] * (m[j] - cal.hard_iron_ut[j]);
				wm[i] += cal.soft_iron[i][j] * m[j];
			}
		for (i = 0; i < 3; i++) {
			for (k = 0, want[i] = 0, unc[i] = 0; k < 3; k++) {
				want[i] += rec.magn.rotation_micro[i][k] / 1e6 * w[k];
				unc[i] += rec.magn.rotation_micro[i][k] / 1e6 * wm[k];
			}
			assert_true(fabs(f[i] - want[i]) < 1e-9);
			/* the HAL: Rrot W m - Rrot W b = the calibrated field */
			assert_true(fabs(unc[i] - bias[i] - want[i]) < 1e-9);
		}
		/* the turn is applied: W (m - b) alone is off by about 3 deg */
		assert_true(fabs(f[0] - w[0]) + fabs(f[1] - w[1]) + fabs(f[2] - w[2]) >
			    1e-3 * sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]));
	}
	/* the .magn file of another chip: refused, saying so */
	rec.eeprom[0] ^= 1;
	write_text("turned.magn", buf,
		   record_magn_format(&rec.magn, rec.eeprom, rec.created, buf,
				      sizeof(buf)), file, sizeof(file));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "another chip"));
	/* one of another change of the record (its created): refused too */
	write_text("turned.magn", buf,
		   record_magn_format(&rec.magn, example, rec.created + 1, buf,
				      sizeof(buf)), file, sizeof(file));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "another change of the record"));
	/*
	 * ... unless its previous one is the record's (a change of both cut
	 * between the files): that one is used, as recovery will put it back
	 * (its hard iron 2 uT apart, to tell the two files apart)
	 */
	rec.magn.hard_iron_nt[0] += 2000;
	write_text("turned.magn.previous", buf,
		   record_magn_format(&rec.magn, example, rec.created, buf,
				      sizeof(buf)), file, sizeof(file));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), 0);
	assert_true(cal.rotation[0][1] == rot[0][1] / 1e6);
	assert_true(fabs(cal.hard_iron_ut[0] -
			 rec.magn.hard_iron_nt[0] / 1e3) < 1e-9);
	unlink(file);
	/* a .magn file of none (after a rollback): no calibration */
	rec.magn.present = false;
	write_text("turned.magn", buf,
		   record_magn_format(&rec.magn, example, rec.created, buf,
				      sizeof(buf)), file, sizeof(file));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -ENODATA);
}

static void refuses(void **state)
{
	struct as9888_magn_calibration cal;
	char path[128], link[160], err[256];
	FILE *f;

	write_record("old", false, path, sizeof(path));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -ENODATA);
	assert_non_null(strstr(err, "magn-calibrate"));
	snprintf(path, sizeof(path), "%s/none", dir);
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -ENOENT);
	/* one byte changed: the checksum */
	write_record("bad", true, path, sizeof(path));
	f = fopen(path, "r+");
	assert_non_null(f);
	fseek(f, -20, SEEK_END);
	fputc('9', f);
	fclose(f);
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "not a valid record"));
	/* made on the simulator: never applied to a real chip's output */
	write_record_from("sim", true, true, path, sizeof(path));
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -EPERM);
	assert_non_null(strstr(err, "simulator"));
	/* a symbolic link is not followed */
	write_record("cal", true, path, sizeof(path));
	snprintf(link, sizeof(link), "%s/link", dir);
	assert_int_equal(symlink(path, link), 0);
	assert_int_equal(as9888_magn_load(link, &cal, err, sizeof(err)), -ELOOP);
	/*
	 * A FIFO at the path (issue 40, N7): refused at once, not waited on
	 * for a writer; the alarm ends the test should the load block
	 */
	snprintf(path, sizeof(path), "%s/fifo", dir);
	assert_int_equal(mkfifo(path, 0600), 0);
	alarm(20);
	assert_int_equal(as9888_magn_load(path, &cal, err, sizeof(err)), -EINVAL);
	alarm(0);
	assert_non_null(strstr(err, "not a regular file"));
}

/*
 * A daemon stand-in on @path: takes one connection, checks its line is
 * @want, answers @reply (NULL: never), exits 0 when the line was right
 */
static pid_t serve_once(const char *path, const char *want, const char *reply)
{
	struct sockaddr_un sa = { .sun_family = AF_UNIX };
	int fd = socket(AF_UNIX, SOCK_STREAM, 0);
	pid_t pid;

	assert_true(fd >= 0);
	snprintf(sa.sun_path, sizeof(sa.sun_path), "%s", path);
	assert_int_equal(bind(fd, (struct sockaddr *)&sa, sizeof(sa)), 0);
	assert_int_equal(listen(fd, 1), 0);
	pid = fork();
	assert_true(pid >= 0);
	if (!pid) {
		char line[128] = { 0 };
		int c = accept(fd, NULL, NULL);
		ssize_t n = c < 0 ? -1 : read(c, line, sizeof(line) - 1);
		bool ok = n > 0 && !strcmp(line, want);

		if (!reply)	/* a stuck daemon */
			pause();
		if (c >= 0 && write(c, reply, strlen(reply)) < 0)
			ok = false;
		_exit(ok ? 0 : 1);
	}
	close(fd);

	return pid;
}

static void feeds_the_daemon(void **state)
{
	static const double y[3] = { 12.3456, -0.5, 40 }, a[3] = { 3, -1, 255 };
	static const char *const line = "magn-feed 12.346 -0.500 40.000 3 -1 255\n";
	char path[128], err[256];
	int status;
	pid_t pid;

	snprintf(path, sizeof(path), "%s/sock", dir);
	pid = serve_once(path, line, "fit: ok\nexit status 0\n");
	assert_int_equal(as9888_magn_feed(path, y, a, err, sizeof(err)), 0);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
	unlink(path);
	/* refused by the daemon: said */
	pid = serve_once(path, line, "as9888-calibd: no record\nexit status 1\n");
	assert_int_equal(as9888_magn_feed(path, y, a, err, sizeof(err)), -EIO);
	assert_non_null(strstr(err, "exit status 1"));
	waitpid(pid, &status, 0);
	unlink(path);
	/* no daemon */
	assert_int_equal(as9888_magn_feed(path, y, a, err, sizeof(err)), -ENOENT);
	assert_non_null(strstr(err, path));
	/* a daemon that does not answer: given up on, not waited for */
	pid = serve_once(path, line, NULL);
	assert_int_equal(as9888_magn_feed(path, y, a, err, sizeof(err)), -EAGAIN);
	kill(pid, SIGKILL);
	waitpid(pid, &status, 0);
	unlink(path);
}

static int setup(void **state)
{
	snprintf(dir, sizeof(dir), "/tmp/as9888-magn-api-XXXXXX");
	return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
	char cmd[128];

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
	return system(cmd);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(loads_and_corrects),
		cmocka_unit_test(turned_board),
		cmocka_unit_test(refuses),
		cmocka_unit_test(feeds_the_daemon),
	};

	return cmocka_run_group_tests_name("magn-api", tests, setup, teardown);
}
