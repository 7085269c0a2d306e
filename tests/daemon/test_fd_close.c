// SPDX-License-Identifier: GPL-2.0
/*
 * A request's child closes every descriptor it inherited but the ones it
 * keeps: close_range() where the build found it, the /proc/self/fd scan
 * (musl, bionic before API 34, kernels before 5.9) otherwise. Both run
 * here, whatever the C library, in a child that reports what is still
 * open.
 */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "common/fd_close.h"

/* Descriptors opened by the test: more than one getdents64 read lists */
#define SPREAD 600

/*
 * Open /dev/null at @n descriptors from 3 up, and at a few far ones; the
 * highest opened.
 */
static int open_many(int n)
{
	struct rlimit lim;
	int fd, top = -1, i;

	assert_int_equal(getrlimit(RLIMIT_NOFILE, &lim), 0);
	for (i = 0; i < n; i++) {
		fd = open("/dev/null", O_RDONLY);
		assert_true(fd >= 0);
		if (fd > top)
			top = fd;
	}
	/* a far one, near the soft limit, after a gap */
	if (lim.rlim_cur != RLIM_INFINITY && lim.rlim_cur > (rlim_t)top + 2) {
		fd = (int)lim.rlim_cur - 1;
		assert_int_equal(dup2(0, fd), fd);
		top = fd;
	}
	return top;
}

/* How many of 0..@top are open */
static int count_open(int from, int top)
{
	int fd, n = 0;

	for (fd = from; fd <= top; fd++)
		if (fcntl(fd, F_GETFD) >= 0)
			n++;
	return n;
}

/*
 * In a child: @n descriptors opened, @close_fn(@lowfd) run; the child
 * exits 0 when nothing >= @lowfd is open and everything below still is,
 * 1 or 2 otherwise.
 */
static void check_in_child(int n, int lowfd, int (*close_fn)(int lowfd))
{
	int status, top;
	pid_t pid;

	pid = fork();
	assert_true(pid >= 0);
	if (!pid) {
		top = open_many(n);
		if (top < n + 2)
			_exit(3);
		close_fn(lowfd);
		if (count_open(lowfd, top))
			_exit(1);
		if (count_open(0, lowfd - 1) != lowfd)
			_exit(2);
		_exit(0);
	}
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status));
	assert_int_equal(WEXITSTATUS(status), 0);
}

static int run_scan(int lowfd)
{
	return fd_close_scan(lowfd);
}

static int run_from(int lowfd)
{
	fd_close_from(lowfd);
	return 0;
}

/* The fallback closes hundreds of descriptors over several reads, and a far one */
static void test_scan_closes_all(void **state)
{
	check_in_child(SPREAD, 4, run_scan);
}

/* The first descriptor to close is respected (3 kept: the child's connection) */
static void test_scan_keeps_below(void **state)
{
	check_in_child(8, 6, run_scan);
}

/* What the daemon calls: close_range() or the scan */
static void test_from_closes_all(void **state)
{
	check_in_child(SPREAD, 4, run_from);
}

/* Nothing to close: the scan returns at once with 0 */
static void test_scan_nothing_open(void **state)
{
	pid_t pid;
	int status;

	pid = fork();
	assert_true(pid >= 0);
	if (!pid)
		_exit(fd_close_scan(1 << 20) ? 1 : 0);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status));
	assert_int_equal(WEXITSTATUS(status), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_scan_closes_all),
		cmocka_unit_test(test_scan_keeps_below),
		cmocka_unit_test(test_from_closes_all),
		cmocka_unit_test(test_scan_nothing_open),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
