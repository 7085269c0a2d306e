// SPDX-License-Identifier: GPL-2.0
/*
 * Another program capturing from the device (iio_busy.h): the programs
 * that hold a character device are found and named, in a made-up /proc
 * and in the real one; a list too long for its buffer is cut short with
 * "..."; the wait for a free buffer returns at once when it is off, gives
 * up with -EBUSY when it stays on, ends when another process turns it off,
 * and passes on a read error.
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "chip/iio_busy.h"

#define CHARDEV		"/dev/iio:device0"
/* Longer than any wait below needs on a busy machine */
#define GENEROUS_MS	60000

static char tmp[] = "/tmp/as9888-busy-XXXXXX";

static void put(const char *rel, const char *text)
{
	char path[PATH_MAX];
	FILE *f;

	snprintf(path, sizeof(path), "%s/%s", tmp, rel);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	assert_int_equal(fclose(f), 0);
}

static void mkdir_in(const char *rel)
{
	char path[PATH_MAX];

	snprintf(path, sizeof(path), "%s/%s", tmp, rel);
	assert_int_equal(mkdir(path, 0755), 0);
}

static void link_in(const char *rel, const char *target)
{
	char path[PATH_MAX];

	snprintf(path, sizeof(path), "%s/%s", tmp, rel);
	assert_int_equal(symlink(target, path), 0);
}

/* A made-up /proc: 12 and 345 hold the device, 67 holds another, "self" and a file are no processes */
static void fake_proc(void)
{
	mkdir_in("proc");
	mkdir_in("proc/12");
	mkdir_in("proc/12/fd");
	put("proc/12/comm", "iio-sensor-prox\n");
	link_in("proc/12/fd/0", "/dev/null");
	link_in("proc/12/fd/7", CHARDEV);
	mkdir_in("proc/345");
	mkdir_in("proc/345/fd");
	put("proc/345/comm", "iio_readdev\n");
	link_in("proc/345/fd/3", CHARDEV);
	mkdir_in("proc/67");
	mkdir_in("proc/67/fd");
	put("proc/67/comm", "other\n");
	link_in("proc/67/fd/3", "/dev/iio:device1");
	mkdir_in("proc/89");		/* gone while we looked: no fd, no comm */
	mkdir_in("proc/self");
	mkdir_in("proc/self/fd");
	link_in("proc/self/fd/3", CHARDEV);
	put("proc/uptime", "1.0 1.0\n");
}

static int setup(void **state)
{
	(void)state;
	if (!mkdtemp(tmp))
		return -1;
	fake_proc();
	mkdir_in("dev");
	mkdir_in("dev/buffer");

	return 0;
}

static int teardown(void **state)
{
	char cmd[PATH_MAX + 16];

	(void)state;
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", tmp);

	return system(cmd) ? -1 : 0;
}

static void holders_in_fake_proc(void **state)
{
	char proc[PATH_MAX], out[256];
	int n;

	(void)state;
	snprintf(proc, sizeof(proc), "%s/proc", tmp);
	n = iio_chardev_holders(proc, CHARDEV, out, sizeof(out));
	assert_int_equal(n, 2);
	assert_non_null(strstr(out, "iio-sensor-prox (pid 12)"));
	assert_non_null(strstr(out, "iio_readdev (pid 345)"));
	assert_null(strstr(out, "other"));
	assert_null(strstr(out, "self"));

	assert_int_equal(iio_chardev_holders(proc, "/dev/iio:device9", out, sizeof(out)), 0);
	assert_string_equal(out, "");
}

static void holders_cut_short(void **state)
{
	char proc[PATH_MAX], out[30];
	int n;

	(void)state;
	snprintf(proc, sizeof(proc), "%s/proc", tmp);
	n = iio_chardev_holders(proc, CHARDEV, out, sizeof(out));
	/* both are counted; the second no longer fits */
	assert_int_equal(n, 2);
	assert_true(strlen(out) < sizeof(out));
	assert_non_null(strstr(out, "..."));
	assert_int_equal(iio_chardev_holders(proc, CHARDEV, out, 0), 2);
}

static void holders_no_proc(void **state)
{
	char out[64];

	(void)state;
	assert_int_equal(iio_chardev_holders("/nonexistent/proc", CHARDEV, out, sizeof(out)),
			 -ENOENT);
	assert_string_equal(out, "");
}

/* This process, holding a file open, is found in the real /proc */
static void holders_real_proc(void **state)
{
	char path[PATH_MAX], out[512], me[64];
	int fd, n;

	(void)state;
	snprintf(path, sizeof(path), "%s/dev/chardev", tmp);
	fd = open(path, O_CREAT | O_RDWR, 0600);
	assert_true(fd >= 0);
	n = iio_chardev_holders("/proc", path, out, sizeof(out));
	assert_int_equal(n, 1);
	snprintf(me, sizeof(me), "(pid %d)", (int)getpid());
	assert_non_null(strstr(out, me));
	assert_non_null(strstr(out, "test_iio_busy"));
	close(fd);
	assert_int_equal(iio_chardev_holders("/proc", path, out, sizeof(out)), 0);
}

static void wait_free_at_once(void **state)
{
	char dir[PATH_MAX];

	(void)state;
	put("dev/buffer/enable", "0\n");
	snprintf(dir, sizeof(dir), "%s/dev", tmp);
	assert_int_equal(iio_wait_buffer_free(dir, 0, IIO_BUSY_POLL_MS), 0);
}

static void wait_gives_up(void **state)
{
	char dir[PATH_MAX];

	(void)state;
	put("dev/buffer/enable", "1\n");
	snprintf(dir, sizeof(dir), "%s/dev", tmp);
	assert_int_equal(iio_wait_buffer_free(dir, 0, IIO_BUSY_POLL_MS), -EBUSY);
	assert_int_equal(iio_wait_buffer_free(dir, 250, 10), -EBUSY);
}

/*
 * A value printed with its string's NUL, as the IIO core prints some
 * (current_timestamp_clock): read without it
 */
static void wait_value_with_nul(void **state)
{
	char dir[PATH_MAX], path[PATH_MAX];
	FILE *f;

	(void)state;
	snprintf(path, sizeof(path), "%s/dev/buffer/enable", tmp);
	f = fopen(path, "w");
	assert_non_null(f);
	assert_int_equal(fwrite("0\n", 1, 3, f), 3);
	assert_int_equal(fclose(f), 0);
	snprintf(dir, sizeof(dir), "%s/dev", tmp);
	assert_int_equal(iio_wait_buffer_free(dir, 0, IIO_BUSY_POLL_MS), 0);
}

/* Another process ends its capture: the wait ends, long before its bound */
static void wait_for_turn(void **state)
{
	char dir[PATH_MAX], path[PATH_MAX];
	int status;
	pid_t pid;

	(void)state;
	put("dev/buffer/enable", "1\n");
	snprintf(dir, sizeof(dir), "%s/dev", tmp);
	snprintf(path, sizeof(path), "%s/dev/buffer/enable", tmp);
	pid = fork();
	assert_true(pid >= 0);
	if (pid == 0) {
		struct timespec d = { 0, 300000000 };
		FILE *f;

		nanosleep(&d, NULL);
		f = fopen(path, "w");
		_exit(f && fputs("0\n", f) >= 0 && !fclose(f) ? 0 : 1);
	}
	assert_int_equal(iio_wait_buffer_free(dir, GENEROUS_MS, 20), 0);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

static void wait_read_error(void **state)
{
	char dir[PATH_MAX];

	(void)state;
	snprintf(dir, sizeof(dir), "%s/proc", tmp);	/* no buffer/enable */
	assert_int_equal(iio_wait_buffer_free(dir, GENEROUS_MS, 10), -ENOENT);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(holders_in_fake_proc),
		cmocka_unit_test(holders_cut_short),
		cmocka_unit_test(holders_no_proc),
		cmocka_unit_test(holders_real_proc),
		cmocka_unit_test(wait_free_at_once),
		cmocka_unit_test(wait_gives_up),
		cmocka_unit_test(wait_value_with_nul),
		cmocka_unit_test(wait_for_turn),
		cmocka_unit_test(wait_read_error),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
