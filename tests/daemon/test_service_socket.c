// SPDX-License-Identifier: GPL-2.0
/*
 * The daemon's listening socket passed by Android init: a real listening
 * Unix socket handed over in ANDROID_SOCKET_as9888_calibd, as init's
 * "socket" line does, is taken (and answers a client); anything else in
 * the variable is refused with a message naming it, and the daemon then
 * creates no socket of its own.
 */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cmocka.h>

#include "commands/cli.h"
#include "service/service_socket.h"

struct fixture {
	char dir[64];
	char init_path[96];	/* the socket init made */
	char own_path[96];	/* where the daemon would make its own */
	struct cli_opts o;
	struct service_socket s;
	char err[512];
};

static int setup(void **state)
{
	struct fixture *f = calloc(1, sizeof(*f));

	if (!f)
		return -1;
	strcpy(f->dir, "/tmp/as9888-sock-XXXXXX");
	if (!mkdtemp(f->dir))
		return -1;
	snprintf(f->init_path, sizeof(f->init_path), "%s/init", f->dir);
	snprintf(f->own_path, sizeof(f->own_path), "%s/own", f->dir);
	f->o.socket_path = f->own_path;
	f->o.socket_mode = CLI_DEFAULT_SOCKET_MODE;
	f->s.fd = -1;
	unsetenv("LISTEN_PID");
	unsetenv("LISTEN_FDS");
	*state = f;
	return 0;
}

static int teardown(void **state)
{
	struct fixture *f = *state;

	unsetenv(ANDROID_SOCKET_ENV);
	unlink(f->init_path);
	unlink(f->own_path);
	rmdir(f->dir);
	free(f);
	return 0;
}

/* A Unix stream socket bound to @path and listening, as init makes it */
static int init_socket(const char *path)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	int fd = socket(AF_UNIX, SOCK_STREAM, 0);

	assert_true(fd >= 0);
	snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", path);
	assert_int_equal(bind(fd, (struct sockaddr *)&addr, sizeof(addr)), 0);
	assert_int_equal(listen(fd, 4), 0);
	return fd;
}

static void set_fd_env(int fd)
{
	char v[16];

	snprintf(v, sizeof(v), "%d", fd);
	assert_int_equal(setenv(ANDROID_SOCKET_ENV, v, 1), 0);
}

static void takes_init_socket(void **state)
{
	struct fixture *f = *state;
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	int fd = init_socket(f->init_path), client, conn;
	char c = 0;

	set_fd_env(fd);
	assert_int_equal(service_socket_open(&f->o, &f->s, f->err, sizeof(f->err)), 0);
	assert_int_equal(f->s.fd, fd);
	assert_true(f->s.activated);
	/* taken as systemd's: not inherited further, never waits in accept() */
	assert_null(getenv(ANDROID_SOCKET_ENV));
	assert_true(fcntl(fd, F_GETFD) & FD_CLOEXEC);
	assert_true(fcntl(fd, F_GETFL) & O_NONBLOCK);
	/* no socket of its own */
	assert_int_equal(access(f->own_path, F_OK), -1);

	/* a client on init's path reaches it */
	client = socket(AF_UNIX, SOCK_STREAM, 0);
	assert_true(client >= 0);
	snprintf(addr.sun_path, sizeof(addr.sun_path), "%s", f->init_path);
	assert_int_equal(connect(client, (struct sockaddr *)&addr, sizeof(addr)), 0);
	conn = accept(f->s.fd, NULL, NULL);
	assert_true(conn >= 0);
	assert_int_equal(write(client, "s", 1), 1);
	assert_int_equal(read(conn, &c, 1), 1);
	assert_int_equal(c, 's');
	close(conn);
	close(client);

	/* init's socket file is init's: closing does not remove it */
	service_socket_close(&f->o, &f->s);
	assert_int_equal(access(f->init_path, F_OK), 0);
	assert_int_equal(fcntl(fd, F_GETFD), -1);
}

/* @value in the variable is refused: -@errnum, @says in the message, no socket made */
static void refused(struct fixture *f, const char *value, int errnum,
		    const char *says)
{
	assert_int_equal(setenv(ANDROID_SOCKET_ENV, value, 1), 0);
	assert_int_equal(service_socket_open(&f->o, &f->s, f->err, sizeof(f->err)),
			 -errnum);
	if (!strstr(f->err, ANDROID_SOCKET_ENV) || !strstr(f->err, says))
		fail_msg("\"%s\": message \"%s\" does not name the variable or say \"%s\"",
			 value, f->err, says);
	assert_int_equal(access(f->own_path, F_OK), -1);
}

static void refuses_garbage(void **state)
{
	struct fixture *f = *state;
	const char *bad[] = {
		"", "abc", "3x", "x3", "-1", "4.0", "2147483648",
		"99999999999999999999999", "0x10",
	};
	size_t i;

	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		refused(f, bad[i], EINVAL, "is not a descriptor number");
}

static void refuses_descriptors_that_are_not_listening_unix_streams(void **state)
{
	struct fixture *f = *state;
	struct sockaddr_in in = { .sin_family = AF_INET,
				  .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
	int closed, pipefd[2], dgram[2], unbound, tcp;
	char v[16];

	closed = dup(0);
	assert_true(closed >= 0);
	close(closed);
	snprintf(v, sizeof(v), "%d", closed);
	refused(f, v, EBADF, "is not open");

	assert_int_equal(pipe(pipefd), 0);
	snprintf(v, sizeof(v), "%d", pipefd[0]);
	refused(f, v, ENOTSOCK, "is not a socket");

	assert_int_equal(socketpair(AF_UNIX, SOCK_DGRAM, 0, dgram), 0);
	snprintf(v, sizeof(v), "%d", dgram[0]);
	refused(f, v, EPROTOTYPE, "is not a stream socket");

	unbound = socket(AF_UNIX, SOCK_STREAM, 0);
	assert_true(unbound >= 0);
	snprintf(v, sizeof(v), "%d", unbound);
	refused(f, v, EINVAL, "is not listening");

	tcp = socket(AF_INET, SOCK_STREAM, 0);
	assert_true(tcp >= 0);
	assert_int_equal(bind(tcp, (struct sockaddr *)&in, sizeof(in)), 0);
	assert_int_equal(listen(tcp, 1), 0);
	snprintf(v, sizeof(v), "%d", tcp);
	refused(f, v, EAFNOSUPPORT, "is not a Unix socket");

	/* a refused descriptor is left as it was */
	assert_int_not_equal(fcntl(pipefd[0], F_GETFD), -1);
	close(pipefd[0]);
	close(pipefd[1]);
	close(dgram[0]);
	close(dgram[1]);
	close(unbound);
	close(tcp);
}

/* Without the variable: its own socket, as before */
static void without_the_variable_its_own(void **state)
{
	struct fixture *f = *state;
	struct stat st;

	unsetenv(ANDROID_SOCKET_ENV);
	assert_int_equal(service_socket_open(&f->o, &f->s, f->err, sizeof(f->err)), 0);
	assert_false(f->s.activated);
	assert_int_equal(stat(f->own_path, &st), 0);
	assert_true(S_ISSOCK(st.st_mode));
	service_socket_close(&f->o, &f->s);
	assert_int_equal(access(f->own_path, F_OK), -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(takes_init_socket, setup, teardown),
		cmocka_unit_test_setup_teardown(refuses_garbage, setup, teardown),
		cmocka_unit_test_setup_teardown(refuses_descriptors_that_are_not_listening_unix_streams,
						setup, teardown),
		cmocka_unit_test_setup_teardown(without_the_variable_its_own, setup, teardown),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
