// SPDX-License-Identifier: GPL-2.0
/* Run a command for a client, its output framed as the daemon's reply. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include "common/anon_file.h"
#include "common/request.h"
#include "service/request_reply.h"

#define COPY_CHUNK	4096

/* All of @len bytes, or until the client is gone or stalls */
static int send_all(int fd, const char *buf, size_t len, int flags)
{
	while (len) {
		ssize_t n = send(fd, buf, len, MSG_NOSIGNAL | flags);

		if (n < 0) {
			if (errno == EINTR)
				continue;
			return -errno;
		}
		buf += n;
		len -= (size_t)n;
	}

	return 0;
}

/* What the command wrote to @mfd, to the client */
static int send_file(int fd, int mfd)
{
	char buf[COPY_CHUNK];
	ssize_t n;
	int ret = 0;

	if (lseek(mfd, 0, SEEK_SET))
		return -errno;
	while (!ret && (n = read(mfd, buf, sizeof(buf))) > 0)
		ret = send_all(fd, buf, (size_t)n, 0);

	return ret;
}

static void send_status(int fd, int status, int flags)
{
	char line[32];
	int len = snprintf(line, sizeof(line), "%s%d\n", REQUEST_STATUS_PREFIX,
			   status);

	send_all(fd, line, (size_t)len, flags);
}

/*
 * Where a reply's files go without memfd_create(): $RUNTIME_DIRECTORY
 * (systemd's, a tmpfs), else the record's directory, the one directory
 * the daemon may always write (on Android, with the record on persist)
 */
static void reply_dir(const struct cli_opts *o, char *dir, size_t size)
{
	const char *run = getenv("RUNTIME_DIRECTORY");
	const char *slash = strrchr(o->record_path, '/');

	if (run && *run && !strchr(run, ':'))
		snprintf(dir, size, "%s", run);
	else if (!slash)
		snprintf(dir, size, ".");
	else
		snprintf(dir, size, "%.*s", slash == o->record_path ? 1 :
			 (int)(slash - o->record_path), o->record_path);
}

int request_reply_run(int fd, int (*fn)(const struct cli_opts *o),
		      const struct cli_opts *o, bool json)
{
	struct timeval tv = { .tv_sec = REQUEST_SEND_TIMEOUT_S };
	int out = fd, err = fd, status;

	setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof(tv));
	if (json) {
		char dir[PATH_MAX];

		/* kept apart until the status says which one the client gets */
		reply_dir(o, dir, sizeof(dir));
		out = anon_file_open("as9888-reply-json", dir);
		err = out < 0 ? out : anon_file_open("as9888-reply-errors", dir);
		if (err < 0) {
			if (out >= 0)
				close(out);
			dprintf(fd, "as9888-calibd: cannot buffer the reply (memfd, or a file without a name in %s): %s\n",
				dir, strerror(-err));
			send_status(fd, 1, 0);
			return 1;
		}
	}
	fflush(NULL);
	dup2(out, STDOUT_FILENO);
	dup2(err, STDERR_FILENO);
	status = fn(o);
	fflush(NULL);
	if (json)
		send_file(fd, status ? err : out);
	send_status(fd, status, 0);

	return status;
}

void request_reply_status_now(int fd, const char *text, int status)
{
	if (text)
		send_all(fd, text, strlen(text), MSG_DONTWAIT);
	send_status(fd, status, MSG_DONTWAIT);
}
