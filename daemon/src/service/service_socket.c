// SPDX-License-Identifier: GPL-2.0
/* The daemon's listening socket, and who is on the other end of a client's. */
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <limits.h>
#include <stdbool.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "common/remedy.h"
#include "service/service_socket.h"

/* Connections the kernel holds for us between two accept() rounds */
#define LISTEN_BACKLOG		64
#define SD_LISTEN_FDS_START	3

/*
 * Is a process listening on the socket file at @addr? Connecting tells:
 * ECONNREFUSED means a stale file. Anything else but a refusal counts as
 * alive, so that an unclear answer never makes us take a live socket.
 */
static bool socket_alive(const struct sockaddr_un *addr, char *pid, size_t len)
{
	struct ucred cred;
	socklen_t cl = sizeof(cred);
	bool alive;
	int fd;

	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
	if (fd < 0)
		return true;
	alive = !connect(fd, (const struct sockaddr *)addr, sizeof(*addr)) ||
		errno != ECONNREFUSED;
	snprintf(pid, len, "unknown");
	if (alive && !getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &cl) && cred.pid)
		snprintf(pid, len, "%ld", (long)cred.pid);
	close(fd);

	return alive;
}

static int fail(char *err, size_t errlen, int errnum, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

/* Say why in @err; -@errnum */
static int fail(char *err, size_t errlen, int errnum, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(err, errlen, fmt, ap);
	va_end(ap);

	return -errnum;
}

/*
 * Is @fd a listening Unix stream socket? 0, or -errno saying what it is
 * instead, after @what (where the descriptor came from)
 */
static int check_listening(int fd, const char *what, char *err, size_t errlen)
{
	int domain = 0, type = 0, listening = 0;
	socklen_t len = sizeof(int);
	struct stat st;

	if (fstat(fd, &st))
		return fail(err, errlen, EBADF, "%s: descriptor %d is not open (%s)",
			    what, fd, strerror(errno));
	if (!S_ISSOCK(st.st_mode))
		return fail(err, errlen, ENOTSOCK, "%s: descriptor %d is not a socket",
			    what, fd);
	if (getsockopt(fd, SOL_SOCKET, SO_DOMAIN, &domain, &len) || domain != AF_UNIX)
		return fail(err, errlen, EAFNOSUPPORT,
			    "%s: descriptor %d is not a Unix socket", what, fd);
	len = sizeof(int);
	if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &len) || type != SOCK_STREAM)
		return fail(err, errlen, EPROTOTYPE,
			    "%s: descriptor %d is not a stream socket (ListenStream= in the socket unit, \"stream\" in the .rc's socket line)",
			    what, fd);
	len = sizeof(int);
	if (getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &len) || !listening)
		return fail(err, errlen, EINVAL,
			    "%s: descriptor %d is not listening", what, fd);

	return 0;
}

/* A whole decimal number, nothing before or after it */
static bool parse_count(const char *s, long *n)
{
	char *end;

	if (*s < '0' || *s > '9')
		return false;
	errno = 0;
	*n = strtol(s, &end, 10);

	return !errno && !*end && *n <= INT_MAX;
}

/*
 * The socket passed by systemd (sd_listen_fds(3)): LISTEN_PID names this
 * process and LISTEN_FDS says how many descriptors follow fd 3. 0 with the
 * descriptor in *@fd, or with -1 when none was passed to this process;
 * -errno with the reason in @err when the variables are malformed or fd 3
 * is anything but one listening Unix stream socket (a TCP socket would
 * bypass the socket file's permissions; anything else would never be
 * served).
 */
static int activated_socket(int *fd, char *err, size_t errlen)
{
	const char *pid = getenv("LISTEN_PID"), *fds = getenv("LISTEN_FDS");
	long p, n;
	int ret;

	*fd = -1;
	if (!pid && !fds)
		return 0;
	if (!pid || !parse_count(pid, &p))
		return fail(err, errlen, EINVAL,
			    "LISTEN_PID=\"%.32s\" is not a process id: start the daemon from its socket unit, or unset LISTEN_PID and LISTEN_FDS",
			    pid ? pid : "");
	if (p != (long)getpid())
		return 0;	/* meant for another process */
	if (!fds || !parse_count(fds, &n) || n != 1)
		return fail(err, errlen, EINVAL,
			    "LISTEN_FDS=\"%.32s\": exactly one socket must be passed (as9888-calibd.socket has one ListenStream=)",
			    fds ? fds : "");
	ret = check_listening(SD_LISTEN_FDS_START, "the socket passed by systemd (LISTEN_FDS)",
			      err, errlen);
	if (ret)
		return ret;
	unsetenv("LISTEN_PID");
	unsetenv("LISTEN_FDS");
	unsetenv("LISTEN_FDNAMES");
	fcntl(SD_LISTEN_FDS_START, F_SETFD, FD_CLOEXEC);
	*fd = SD_LISTEN_FDS_START;

	return 0;
}

/*
 * The socket Android init passed (the .rc's "socket as9888_calibd stream
 * ..." line: init puts its descriptor number in ANDROID_SOCKET_as9888_calibd,
 * which libcutils' android_get_control_socket() reads). 0 with the
 * descriptor in *@fd, or with -1 when the variable is not set; -errno with
 * the reason in @err when it is set to anything but a listening Unix
 * stream socket.
 */
static int android_socket(int *fd, char *err, size_t errlen)
{
	const char *v = getenv(ANDROID_SOCKET_ENV);
	char what[64];
	long n;
	int ret;

	*fd = -1;
	if (!v)
		return 0;
	if (!parse_count(v, &n))
		return fail(err, errlen, EINVAL,
			    "%s=\"%.32s\" is not a descriptor number: start the daemon from init with \"socket %s stream 0660 root system\" in its .rc, or unset the variable",
			    ANDROID_SOCKET_ENV, v, ANDROID_SOCKET_NAME);
	snprintf(what, sizeof(what), "%s=%ld", ANDROID_SOCKET_ENV, n);
	ret = check_listening((int)n, what, err, errlen);
	if (ret)
		return ret;
	unsetenv(ANDROID_SOCKET_ENV);
	fcntl((int)n, F_SETFD, FD_CLOEXEC);
	*fd = (int)n;

	return 0;
}

/* Bind @fd to @addr; a stale socket file there is replaced, a live one is not */
static int bind_socket(int fd, const struct sockaddr_un *addr, mode_t mode,
		       char *err, size_t errlen)
{
	char pid[24];
	struct stat st;
	mode_t old;
	int ret;

	old = umask(0777 & ~mode);
	ret = bind(fd, (const struct sockaddr *)addr, sizeof(*addr));
	if (ret && errno == EADDRINUSE && !lstat(addr->sun_path, &st) &&
	    S_ISSOCK(st.st_mode)) {
		if (socket_alive(addr, pid, sizeof(pid))) {
			umask(old);
			return fail(err, errlen, EADDRINUSE,
				    "another as9888-calibd (pid %s) is serving %s: stop it first, or give this one another --socket",
				    pid, addr->sun_path);
		}
		unlink(addr->sun_path);
		ret = bind(fd, (const struct sockaddr *)addr, sizeof(*addr));
	}
	umask(old);
	if (ret) {
		ret = errno;
		return fail(err, errlen, ret, "cannot listen on %s: %s%s",
			    addr->sun_path, strerror(ret),
			    ret == EACCES ? ": " REMEDY_SOCKET_CREATE : "");
	}

	return 0;
}

int service_socket_open(const struct cli_opts *o, struct service_socket *s,
			char *err, size_t errlen)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	struct stat st;
	int fd, ret;

	memset(s, 0, sizeof(*s));
	ret = activated_socket(&s->fd, err, errlen);
	if (ret)
		return ret;
	if (s->fd < 0) {
		ret = android_socket(&s->fd, err, errlen);
		if (ret)
			return ret;
	}
	s->activated = s->fd >= 0;
	if (s->activated)	/* the loop never waits in accept() */
		return fcntl(s->fd, F_SETFL, fcntl(s->fd, F_GETFL) | O_NONBLOCK) ?
		       fail(err, errlen, errno, "socket from systemd or init: %s",
			    strerror(errno)) : 0;

	if (strlen(o->socket_path) >= sizeof(addr.sun_path))
		return fail(err, errlen, ENAMETOOLONG, "socket path %s is too long",
			    o->socket_path);
	strcpy(addr.sun_path, o->socket_path);
	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
	if (fd < 0)
		return fail(err, errlen, errno, "cannot create a socket: %s",
			    strerror(errno));
	ret = bind_socket(fd, &addr, o->socket_mode, err, errlen);
	if (ret) {
		close(fd);
		return ret;
	}
	if (lstat(o->socket_path, &st) || listen(fd, LISTEN_BACKLOG)) {
		ret = errno;
		unlink(o->socket_path);
		close(fd);
		return fail(err, errlen, ret, "cannot listen on %s: %s",
			    o->socket_path, strerror(ret));
	}
	s->dev = st.st_dev;
	s->ino = st.st_ino;
	s->fd = fd;
	if (o->socket_group) {
		struct group *gr = getgrnam(o->socket_group);

		if (!gr || chown(o->socket_path, (uid_t)-1, gr->gr_gid)) {
			service_socket_close(o, s);
			return fail(err, errlen, EPERM,
				    "cannot give %s to group %s", o->socket_path,
				    o->socket_group);
		}
	}

	return 0;
}

void service_socket_close(const struct cli_opts *o, struct service_socket *s)
{
	struct stat st;

	if (s->fd < 0)
		return;
	if (!s->activated && !lstat(o->socket_path, &st) && st.st_dev == s->dev &&
	    st.st_ino == s->ino)
		unlink(o->socket_path);
	close(s->fd);
	s->fd = -1;
}

uid_t peer_describe(int fd, char desc[PEER_DESC_LEN])
{
	struct ucred cred;
	socklen_t len = sizeof(cred);

	if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len)) {
		snprintf(desc, PEER_DESC_LEN, "unknown peer");
		return PEER_UID_UNKNOWN;
	}
	snprintf(desc, PEER_DESC_LEN, "uid %u gid %u pid %ld",
		 (unsigned int)cred.uid, (unsigned int)cred.gid, (long)cred.pid);

	return cred.uid;
}

/* The Linux option number, where the libc's headers do not name it */
#ifndef SO_PEERGROUPS
#define SO_PEERGROUPS	59
#endif
/* Supplementary groups of a peer read without an allocation */
#define PEER_GROUPS_FEW	64

bool peer_in_group(int fd, gid_t gid)
{
	gid_t few[PEER_GROUPS_FEW], *groups = few;
	socklen_t len = sizeof(few);
	struct ucred cred;
	socklen_t clen = sizeof(cred);
	bool in = false;
	size_t i;

	if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &clen))
		return false;
	if (cred.gid == gid)
		return true;
	/*
	 * The groups the peer had when it connected (Linux 4.13 and later);
	 * ERANGE tells how much room more of them need
	 */
	if (getsockopt(fd, SOL_SOCKET, SO_PEERGROUPS, groups, &len)) {
		if (errno != ERANGE || !len || !(groups = malloc(len)))
			return false;
		if (getsockopt(fd, SOL_SOCKET, SO_PEERGROUPS, groups, &len))
			len = 0;
	}
	for (i = 0; i < len / sizeof(groups[0]) && !in; i++)
		in = groups[i] == gid;
	if (groups != few)
		free(groups);

	return in;
}
