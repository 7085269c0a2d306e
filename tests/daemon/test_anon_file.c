// SPDX-License-Identifier: GPL-2.0
/*
 * The files a request's reply is held in: memfd_create() where the build
 * found it, else a file with no name in a directory (O_TMPFILE, or one
 * made and unlinked at once), as on bionic before API 30. Both fallbacks
 * run here whatever the C library; memfd_create() is also refused by a
 * seccomp filter in a child, so that the choice of the fallback and a
 * --json reply through it run on a C library that has memfd_create().
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "common/anon_file.h"
#include "commands/cli.h"
#include "common/request.h"
#include "service/request_reply.h"

struct dir {
	char path[64];
};

static int setup(void **state)
{
	struct dir *d = calloc(1, sizeof(*d));

	assert_non_null(d);
	snprintf(d->path, sizeof(d->path), "/tmp/as9888-anon-XXXXXX");
	assert_non_null(mkdtemp(d->path));
	*state = d;
	return 0;
}

static int teardown(void **state)
{
	struct dir *d = *state;

	assert_int_equal(rmdir(d->path), 0);
	free(d);
	return 0;
}

/* How many names @path holds besides . and .. */
static int entries(const char *path)
{
	struct dirent *e;
	DIR *dir = opendir(path);
	int n = 0;

	assert_non_null(dir);
	while ((e = readdir(dir)))
		if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
			n++;
	closedir(dir);
	return n;
}

/* @fd: a regular file with no name, close-on-exec, that gives back what is written */
static void check_nameless(int fd, const char *dir)
{
	static const char text[] = "{\"advisable\": false}\n";
	char back[sizeof(text)];
	struct stat st;

	assert_true(fd >= 0);
	assert_true(fcntl(fd, F_GETFD) & FD_CLOEXEC);
	assert_int_equal(fstat(fd, &st), 0);
	assert_true(S_ISREG(st.st_mode));
	assert_int_equal(st.st_nlink, 0);
	if (dir)
		assert_int_equal(entries(dir), 0);
	assert_int_equal(write(fd, text, strlen(text)), (ssize_t)strlen(text));
	assert_int_equal(pread(fd, back, sizeof(back), 0), (ssize_t)strlen(text));
	assert_memory_equal(back, text, strlen(text));
	close(fd);
}

/* @fd: a file in a directory, the owner's alone (0600); closed */
static void check_private(int fd)
{
	struct stat st;

	assert_true(fd >= 0);
	assert_int_equal(fstat(fd, &st), 0);
	assert_int_equal(st.st_mode & 07777, 0600);
	close(fd);
}

static void tmpfile_in_dir(void **state)
{
	struct dir *d = *state;

	check_private(anon_file_in(d->path));
	check_nameless(anon_file_in(d->path), d->path);
}

static void unlinked_in_dir(void **state)
{
	struct dir *d = *state;

	check_private(anon_file_unlinked(d->path));
	check_nameless(anon_file_unlinked(d->path), d->path);
}

/* where no file can be made: -errno, nothing left, no crash */
static void refused(void **state)
{
	struct dir *d = *state;
	char path[128], name[8192];
	int fd;

	snprintf(path, sizeof(path), "%s/missing", d->path);
	assert_int_equal(anon_file_in(path), -ENOENT);
	assert_int_equal(anon_file_unlinked(path), -ENOENT);
	/* a file where a directory should be */
	fd = open(path, O_CREAT | O_WRONLY | O_CLOEXEC, 0600);
	assert_true(fd >= 0);
	close(fd);
	assert_int_equal(anon_file_in(path), -ENOTDIR);
	assert_int_equal(anon_file_unlinked(path), -ENOTDIR);
	assert_int_equal(unlink(path), 0);
	/* a path too long for the unlinked file's name */
	memset(name, 'a', sizeof(name) - 1);
	name[sizeof(name) - 1] = '\0';
	assert_int_equal(anon_file_unlinked(name), -ENAMETOOLONG);
	assert_int_equal(entries(d->path), 0);
}

/* What /proc/self/fd says @fd is */
static void fd_target(int fd, char *out, size_t size)
{
	char link[64];
	ssize_t n;

	snprintf(link, sizeof(link), "/proc/self/fd/%d", fd);
	n = readlink(link, out, size - 1);
	assert_true(n > 0);
	out[n] = '\0';
}

/* The build's choice: a memfd named @name, or (without it) a file in the directory */
static void build_choice(void **state)
{
	struct dir *d = *state;
	char target[256];
	int fd = anon_file_open("as9888-test", d->path);

	assert_true(fd >= 0);
	fd_target(fd, target, sizeof(target));
#ifdef HAVE_MEMFD_CREATE
	assert_non_null(strstr(target, "memfd:as9888-test"));
#else
	assert_true(!strncmp(target, d->path, strlen(d->path)));
#endif
	check_nameless(fd, d->path);
}

/* In this process from now on, memfd_create() fails with ENOSYS */
static int refuse_memfd(void)
{
#ifdef __NR_memfd_create
	struct sock_filter f[] = {
		BPF_STMT(BPF_LD | BPF_W | BPF_ABS, offsetof(struct seccomp_data, nr)),
		BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, __NR_memfd_create, 0, 1),
		BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ERRNO | ENOSYS),
		BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_ALLOW),
	};
	struct sock_fprog prog = { .len = sizeof(f) / sizeof(f[0]), .filter = f };

	if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) ||
	    prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &prog))
		return -errno;
	return 0;
#else
	return -ENOSYS;
#endif
}

/* what the command of the reply below says */
static int answer(const struct cli_opts *o)
{
	printf("{\"advisable\": false}\n");
	fprintf(stderr, "not for a JSON reply\n");
	return 0;
}

/*
 * A --json reply to @reply from a child in which memfd_create() is
 * refused, the record at @record; with @dir, the child first checks that
 * the fallback puts its file there. The child's exit status.
 */
static int reply_without_memfd(const char *record, const char *dir,
			       char *reply, size_t size)
{
	struct cli_opts o = { .log_fd = -1, .record_path = record };
	int sv[2], status;
	ssize_t n, got = 0;
	pid_t pid;

	assert_int_equal(socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv), 0);
	pid = fork();
	assert_true(pid >= 0);
	if (!pid) {
		char target[256];
		int fd;

		close(sv[0]);
		unsetenv("RUNTIME_DIRECTORY");
		if (refuse_memfd() || syscall(SYS_memfd_create, "x", 0) >= 0 ||
		    errno != ENOSYS)
			_exit(10);
		if (dir) {
			fd = anon_file_open("as9888-test", dir);
			if (fd < 0)
				_exit(11);
			fd_target(fd, target, sizeof(target));
			if (strncmp(target, dir, strlen(dir)))
				_exit(12);
			close(fd);
		}
		_exit(request_reply_run(sv[1], answer, &o, true));
	}
	close(sv[1]);
	while ((n = read(sv[0], reply + got, size - 1 - (size_t)got)) > 0)
		got += n;
	reply[got] = '\0';
	close(sv[0]);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status));
	return WEXITSTATUS(status);
}

/*
 * With memfd_create() refused (a kernel before 3.17 or a seccomp policy):
 * the files go into the record's directory, and a --json reply is whole
 */
static void reply_in_record_dir(void **state)
{
	struct dir *d = *state;
	char record[128], reply[256];

	snprintf(record, sizeof(record), "%s/calibration", d->path);
	assert_int_equal(reply_without_memfd(record, d->path, reply, sizeof(reply)), 0);
	assert_string_equal(reply, "{\"advisable\": false}\n" REQUEST_STATUS_PREFIX "0\n");
	assert_int_equal(entries(d->path), 0);
}

/* the reply's files cannot be made: the client is told why, status 1 */
static void reply_cannot_buffer(void **state)
{
	struct dir *d = *state;
	char record[128], reply[512];

	snprintf(record, sizeof(record), "%s/missing/calibration", d->path);
	assert_int_equal(reply_without_memfd(record, NULL, reply, sizeof(reply)), 1);
	assert_non_null(strstr(reply, "cannot buffer the reply"));
	assert_non_null(strstr(reply, "/missing): No such file or directory"));
	assert_non_null(strstr(reply, REQUEST_STATUS_PREFIX "1\n"));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(tmpfile_in_dir, setup, teardown),
		cmocka_unit_test_setup_teardown(unlinked_in_dir, setup, teardown),
		cmocka_unit_test_setup_teardown(refused, setup, teardown),
		cmocka_unit_test_setup_teardown(build_choice, setup, teardown),
		cmocka_unit_test_setup_teardown(reply_in_record_dir, setup, teardown),
		cmocka_unit_test_setup_teardown(reply_cannot_buffer, setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
