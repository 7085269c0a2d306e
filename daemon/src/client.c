// SPDX-License-Identifier: GPL-2.0
/* "as9888-calibd request WHAT": ask the running daemon over its socket. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include "commands.h"

/*
 * Longest wait for the answer: a recalibration waits up to the stability
 * timeout (10 s) and then measures; a daemon silent for this long is stuck.
 */
#define CLIENT_ANSWER_TIMEOUT_S	120

int cmd_request(const struct cli_opts *o)
{
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	struct timeval tv = { .tv_sec = CLIENT_ANSWER_TIMEOUT_S };
	char buf[4096];
	ssize_t n;
	int fd;

	if (strlen(o->socket_path) >= sizeof(addr.sun_path)) {
		fprintf(stderr, "as9888-calibd: socket path %s is too long\n",
			o->socket_path);
		return EXIT_FAILURE;
	}
	strcpy(addr.sun_path, o->socket_path);
	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0 || connect(fd, (struct sockaddr *)&addr, sizeof(addr))) {
		fprintf(stderr, "as9888-calibd: cannot reach the daemon at %s: %s\n",
			o->socket_path, strerror(errno));
		if (fd >= 0)
			close(fd);
		return EXIT_FAILURE;
	}
	setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
	dprintf(fd, "%s%s\n", o->request, o->json ? " --json" : "");
	shutdown(fd, SHUT_WR);
	while ((n = read(fd, buf, sizeof(buf))) > 0)
		fwrite(buf, 1, (size_t)n, stdout);
	if (n < 0)
		fprintf(stderr, "as9888-calibd: no answer from the daemon at %s: %s\n",
			o->socket_path,
			errno == EAGAIN ? "timed out" : strerror(errno));
	close(fd);

	return n < 0 ? EXIT_FAILURE : EXIT_SUCCESS;
}
