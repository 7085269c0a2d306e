// SPDX-License-Identifier: GPL-2.0
/*
 * "as9888-calibd daemon": the long-running service. It sleeps in poll()
 * until something happens (no periodic wake-up):
 * - a kernel uevent says an AS9888 IIO device appeared (boot, module
 *   reload, rebind): the record is applied to it;
 * - a client on the Unix socket asks for status, check, recalibrate or
 *   rollback: the request runs in a child process whose output goes to the
 *   client, one request at a time (requests are serialised);
 * - SIGTERM or SIGINT: it stops cleanly (a request in progress completes
 *   first, so a record being written is never cut short by us).
 * Who may ask is decided by the socket's file permissions.
 */
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "commands.h"
#include "iio.h"
#include "uevent.h"

#define REQUEST_MAX		64
#define LISTEN_BACKLOG		8
#define SD_LISTEN_FDS_START	3
/* A client has this long to send its request line */
#define REQUEST_TIMEOUT_S	5

struct service {
	const struct cli_opts *o;
	int listen_fd;
	int uevent_fd;
	int signal_fd;
	bool socket_activated;
	unsigned long applied;
	unsigned long apply_failures;
};

static void log_msg(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* stderr goes to the journal under systemd */
static void log_msg(const char *fmt, ...)
{
	va_list ap;

	fputs("as9888-calibd: ", stderr);
	va_start(ap, fmt);
	vfprintf(stderr, fmt, ap);
	va_end(ap);
	fputc('\n', stderr);
}

/* A socket passed by systemd (LISTEN_PID/LISTEN_FDS), or -1 */
static int activated_socket(void)
{
	const char *pid = getenv("LISTEN_PID"), *fds = getenv("LISTEN_FDS");

	if (!pid || !fds || atol(pid) != (long)getpid() || atoi(fds) != 1)
		return -1;
	unsetenv("LISTEN_PID");
	unsetenv("LISTEN_FDS");
	unsetenv("LISTEN_FDNAMES");
	fcntl(SD_LISTEN_FDS_START, F_SETFD, FD_CLOEXEC);

	return SD_LISTEN_FDS_START;
}

static int open_socket(const struct cli_opts *o)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	mode_t old;
	int fd, ret;

	if (strlen(o->socket_path) >= sizeof(addr.sun_path)) {
		log_msg("socket path %s is too long", o->socket_path);
		return -ENAMETOOLONG;
	}
	strcpy(addr.sun_path, o->socket_path);

	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0)
		return -errno;
	/* a stale socket of an earlier run; anything else is left alone */
	{
		struct stat st;

		if (!lstat(o->socket_path, &st) && S_ISSOCK(st.st_mode))
			unlink(o->socket_path);
	}
	old = umask(0777 & ~o->socket_mode);
	ret = bind(fd, (struct sockaddr *)&addr, sizeof(addr));
	umask(old);
	if (ret || listen(fd, LISTEN_BACKLOG)) {
		ret = -errno;
		log_msg("cannot listen on %s: %s", o->socket_path, strerror(errno));
		close(fd);
		return ret;
	}
	if (o->socket_group) {
		struct group *gr = getgrnam(o->socket_group);

		if (!gr || chown(o->socket_path, (uid_t)-1, gr->gr_gid)) {
			log_msg("cannot give %s to group %s", o->socket_path,
				o->socket_group);
			close(fd);
			unlink(o->socket_path);
			return -EPERM;
		}
	}

	return fd;
}

static int open_signals(void)
{
	sigset_t set;

	sigemptyset(&set);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGHUP);
	if (sigprocmask(SIG_BLOCK, &set, NULL))
		return -errno;

	return signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
}

/* Run @fn in a child with stdout and stderr on @out; its exit status */
static int run_child(int out, int (*fn)(const struct cli_opts *, const char *),
		     const struct cli_opts *o, const char *arg)
{
	sigset_t set;
	pid_t pid;
	int status;

	fflush(NULL);
	pid = fork();
	if (pid < 0)
		return -errno;
	if (pid == 0) {
		sigemptyset(&set);
		sigprocmask(SIG_SETMASK, &set, NULL);
		if (out >= 0) {
			dup2(out, STDOUT_FILENO);
			dup2(out, STDERR_FILENO);
		}
		status = fn(o, arg);
		fflush(NULL);
		_exit(status);
	}
	while (waitpid(pid, &status, 0) < 0)
		if (errno != EINTR)
			return -errno;

	return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

static int request_status(const struct cli_opts *o, const char *arg)
{
	struct cli_opts show = *o;

	show.temperature_given = false;
	return cmd_show(&show);
}

static int request_check(const struct cli_opts *o, const char *arg)
{
	return cmd_check(o);
}

static int request_recalibrate(const struct cli_opts *o, const char *arg)
{
	return cmd_recalibrate(o);
}

static int request_rollback(const struct cli_opts *o, const char *arg)
{
	return cmd_rollback(o);
}

static int apply_to_device(const struct cli_opts *o, const char *devpath)
{
	return iio_restore(o->record_path, devpath) ? EXIT_FAILURE : EXIT_SUCCESS;
}

static const struct {
	const char *name;
	int (*fn)(const struct cli_opts *o, const char *arg);
} requests[] = {
	{ "status", request_status },
	{ "check", request_check },
	{ "recalibrate", request_recalibrate },
	{ "rollback", request_rollback },
};

/* Read one request line; only the known words, optionally " --json" */
static int read_request(int fd, char *line, size_t size, bool *json)
{
	struct timeval tv = { .tv_sec = REQUEST_TIMEOUT_S };
	size_t len = 0;
	char *sp;

	setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
	while (len < size - 1) {
		ssize_t n = read(fd, line + len, 1);

		if (n <= 0)
			return -EINVAL;
		if (line[len] == '\n')
			break;
		len++;
	}
	line[len] = '\0';
	*json = false;
	sp = strchr(line, ' ');
	if (sp) {
		if (strcmp(sp, " --json"))
			return -EINVAL;
		*sp = '\0';
		*json = true;
	}

	return 0;
}

static void serve_client(struct service *s)
{
	char line[REQUEST_MAX];
	struct cli_opts o = *s->o;
	unsigned int i;
	bool json;
	int fd, status;

	fd = accept4(s->listen_fd, NULL, NULL, SOCK_CLOEXEC);
	if (fd < 0)
		return;
	if (read_request(fd, line, sizeof(line), &json)) {
		dprintf(fd, "error: expected one of status, check, recalibrate, rollback\n");
		close(fd);
		return;
	}
	for (i = 0; i < sizeof(requests) / sizeof(requests[0]); i++)
		if (!strcmp(line, requests[i].name))
			break;
	if (i == sizeof(requests) / sizeof(requests[0])) {
		dprintf(fd, "error: unknown request \"%s\"\n", line);
		close(fd);
		return;
	}

	o.json = json;
	log_msg("%s requested", requests[i].name);
	status = run_child(fd, requests[i].fn, &o, NULL);
	if (!json)
		dprintf(fd, "exit status %d\n", status);
	close(fd);
	log_msg("%s done: exit status %d", requests[i].name, status);
}

static uint64_t monotonic_us(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000 + (uint64_t)ts.tv_nsec / 1000;
}

static void apply(struct service *s, const char *devpath)
{
	uint64_t start = monotonic_us();
	int status = run_child(-1, apply_to_device, s->o, devpath);

	if (status) {
		s->apply_failures++;
		log_msg("calibration not applied to %s", devpath);
	} else {
		s->applied++;
		log_msg("calibration applied to %s in %llu us", devpath,
			(unsigned long long)(monotonic_us() - start));
	}
}

static void handle_uevents(struct service *s)
{
	char buf[UEVENT_BUF_SIZE];
	struct uevent ev;
	char iio[IIO_PATH_MAX];
	ssize_t n;

	while ((n = recv(s->uevent_fd, buf, sizeof(buf), 0)) > 0) {
		if (uevent_parse(buf, (size_t)n, &ev) || !uevent_is_appearance(&ev))
			continue;
		if (iio_find_device(ev.devpath, iio, sizeof(iio)))
			continue;
		apply(s, iio);
	}
}

/* At start: every AS9888 IIO device already there gets its calibration */
static void apply_present(struct service *s)
{
	char iio[IIO_PATH_MAX];

	if (!iio_find_device(NULL, iio, sizeof(iio)))
		apply(s, iio);
}

int cmd_daemon(const struct cli_opts *o)
{
	struct service s = { .o = o, .listen_fd = -1, .uevent_fd = -1 };
	struct pollfd fds[3];
	int ret = EXIT_SUCCESS;

	s.signal_fd = open_signals();
	if (s.signal_fd < 0) {
		log_msg("cannot set up signals: %s", strerror(errno));
		return EXIT_FAILURE;
	}
	s.listen_fd = activated_socket();
	s.socket_activated = s.listen_fd >= 0;
	if (!s.socket_activated)
		s.listen_fd = open_socket(o);
	if (s.listen_fd < 0)
		return EXIT_FAILURE;
	s.uevent_fd = uevent_open();
	if (s.uevent_fd < 0)
		log_msg("no kernel uevents (%s): devices that appear later are not seen",
			strerror(-s.uevent_fd));

	log_msg("ready: record %s, socket %s", o->record_path, o->socket_path);
	apply_present(&s);

	for (;;) {
		struct signalfd_siginfo si;

		fds[0] = (struct pollfd){ .fd = s.signal_fd, .events = POLLIN };
		fds[1] = (struct pollfd){ .fd = s.listen_fd, .events = POLLIN };
		fds[2] = (struct pollfd){ .fd = s.uevent_fd, .events = POLLIN };
		if (poll(fds, s.uevent_fd >= 0 ? 3 : 2, -1) < 0) {
			if (errno == EINTR)
				continue;
			log_msg("poll: %s", strerror(errno));
			ret = EXIT_FAILURE;
			break;
		}
		if (fds[0].revents & POLLIN &&
		    read(s.signal_fd, &si, sizeof(si)) == sizeof(si)) {
			log_msg("signal %u: stopping", si.ssi_signo);
			break;
		}
		if (fds[2].revents & POLLIN)
			handle_uevents(&s);
		if (fds[1].revents & POLLIN)
			serve_client(&s);
	}

	if (!s.socket_activated)
		unlink(o->socket_path);
	close(s.listen_fd);
	if (s.uevent_fd >= 0)
		close(s.uevent_fd);
	close(s.signal_fd);
	log_msg("stopped: calibration applied %lu times, %lu failures", s.applied,
		s.apply_failures);

	return ret;
}
