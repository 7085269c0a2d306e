// SPDX-License-Identifier: GPL-2.0
/*
 * "as9888-calibd request WHAT": ask the running daemon over its socket and
 * exit with the status of the command it ran (request.h). The text reply
 * goes to stdout as it is; with --json only a successful reply (the JSON
 * document) does, a failed one's error text goes to stderr.
 */
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "commands/commands.h"
#include "common/remedy.h"
#include "common/request.h"

/*
 * Longest wait for the whole answer: a recalibration may wait for the lock
 * and the stable temperature, then measures; a daemon silent for this long
 * is stuck.
 */
#define CLIENT_ANSWER_TIMEOUT_MS	120000
/* The longest reply taken (a report is a few kB) */
#define CLIENT_REPLY_MAX		(1 << 20)

struct reply {
	char *buf;
	size_t len;
};

static long long now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static int connect_daemon(const char *path)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	int fd;

	if (strlen(path) >= sizeof(addr.sun_path)) {
		fprintf(stderr, "as9888-calibd: socket path %s is too long\n", path);
		return -1;
	}
	strcpy(addr.sun_path, path);
	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0 || connect(fd, (struct sockaddr *)&addr, sizeof(addr))) {
		int errnum = errno;
		char what[REMEDY_LEN];

		remedy_socket(errnum, path, what, sizeof(what));
		fprintf(stderr, "as9888-calibd: cannot reach the daemon at %s: %s: %s\n",
			path, strerror(errnum), what);
		if (fd >= 0)
			close(fd);
		return -1;
	}

	return fd;
}

/* Everything the daemon sends until it hangs up, within the deadline */
static int read_reply(int fd, struct reply *r, const char *path)
{
	long long deadline = now_ms() + CLIENT_ANSWER_TIMEOUT_MS;
	size_t cap = 0;

	for (;;) {
		struct pollfd p = { .fd = fd, .events = POLLIN };
		long long left = deadline - now_ms();
		ssize_t n;
		int ready;

		ready = left > 0 ? poll(&p, 1, (int)left) : 0;
		if (ready < 0 && errno == EINTR)
			continue;
		if (ready <= 0) {
			fprintf(stderr, "as9888-calibd: no complete answer from the daemon at %s within %d s\n",
				path, CLIENT_ANSWER_TIMEOUT_MS / 1000);
			return -ETIMEDOUT;
		}
		if (r->len == cap) {
			char *bigger;

			if (cap == CLIENT_REPLY_MAX) {
				fprintf(stderr, "as9888-calibd: the daemon's answer is longer than %d bytes\n",
					CLIENT_REPLY_MAX);
				return -EFBIG;
			}
			cap = cap ? cap * 2 : 4096;
			bigger = realloc(r->buf, cap);
			if (!bigger)
				return -ENOMEM;
			r->buf = bigger;
		}
		n = read(fd, r->buf + r->len, cap - r->len);
		if (n < 0 && errno == EINTR)
			continue;
		/* a daemon that refuses us hangs up without reading all we sent */
		if (n < 0 && errno == ECONNRESET)
			return 0;
		if (n < 0) {
			fprintf(stderr, "as9888-calibd: reading the daemon's answer: %s\n",
				strerror(errno));
			return -errno;
		}
		if (n == 0)
			return 0;
		r->len += (size_t)n;
	}
}

int cmd_request(const struct cli_opts *o)
{
	struct reply r = { 0 };
	char line[REQUEST_LINE_MAX + 16];
	size_t body;
	int fd, len, status, send_errno;

	fd = connect_daemon(o->socket_path);
	if (fd < 0)
		return EXIT_FAILURE;
	len = snprintf(line, sizeof(line), "%s%s\n", o->request,
		       o->json ? " --json" : "");
	if (len >= (int)sizeof(line)) {
		fprintf(stderr, "as9888-calibd: cannot send the request to %s: request too long\n",
			o->socket_path);
		close(fd);
		return EXIT_FAILURE;
	}
	send_errno = send(fd, line, (size_t)len, MSG_NOSIGNAL) == len ? 0 : errno;
	/*
	 * A daemon that refuses us (busy) answers and hangs up before it
	 * reads: the send fails, and the answer is there to be read.
	 */
	if (send_errno && send_errno != EPIPE && send_errno != ECONNRESET) {
		fprintf(stderr, "as9888-calibd: cannot send the request to %s: %s\n",
			o->socket_path, strerror(send_errno));
		close(fd);
		return EXIT_FAILURE;
	}
	shutdown(fd, SHUT_WR);
	status = read_reply(fd, &r, o->socket_path);
	close(fd);
	if (!status && send_errno && !r.len) {
		fprintf(stderr, "as9888-calibd: cannot send the request to %s: %s\n",
			o->socket_path, strerror(send_errno));
		status = -send_errno;
	}
	if (status) {
		free(r.buf);
		return EXIT_FAILURE;
	}

	status = request_reply_status(r.buf, r.len, &body);
	if (status < 0) {
		fwrite(r.buf, 1, r.len, stderr);
		fprintf(stderr, "as9888-calibd: the daemon at %s hung up without an exit status\n",
			o->socket_path);
		status = EXIT_FAILURE;
	} else if (o->json) {
		fwrite(r.buf, 1, body, status ? stderr : stdout);
	} else {
		fwrite(r.buf, 1, r.len, stdout);
	}
	if (status > 0)
		fprintf(stderr, "as9888-calibd: request %s failed (exit status %d)\n",
			o->request, status);
	free(r.buf);

	return status;
}
