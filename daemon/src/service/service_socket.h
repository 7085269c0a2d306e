/* SPDX-License-Identifier: GPL-2.0 */
/* The daemon's listening socket, and who is on the other end of a client's. */
#ifndef AS9888_SERVICE_SOCKET_H
#define AS9888_SERVICE_SOCKET_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#include "commands/cli.h"

/* The socket Android init passes: "socket as9888_calibd stream ..." in the .rc */
#define ANDROID_SOCKET_NAME	"as9888_calibd"
#define ANDROID_SOCKET_ENV	"ANDROID_SOCKET_" ANDROID_SOCKET_NAME

struct service_socket {
	int fd;
	bool activated;		/* passed by systemd or init: not ours to remove */
	dev_t dev;		/* the socket file we created */
	ino_t ino;
};

/*
 * The socket passed by systemd (LISTEN_FDS), else the one passed by
 * Android init (ANDROID_SOCKET_ENV); either set to anything but one
 * listening Unix stream socket is an error, else a new one at @o->socket_path with
 * @o's mode and group. A socket file another process still listens on is
 * never replaced: the call fails, saying so; a stale one (nobody
 * listening) is. 0, or -errno with the reason in @err.
 */
int service_socket_open(const struct cli_opts *o, struct service_socket *s,
			char *err, size_t errlen);

/* Close it, and remove the socket file if it is still the one we created */
void service_socket_close(const struct cli_opts *o, struct service_socket *s);

#define PEER_DESC_LEN	64

#define PEER_UID_UNKNOWN	((uid_t)-1)

/*
 * "uid U gid G pid P" of the process that connected @fd, or "unknown
 * peer"; its uid, or PEER_UID_UNKNOWN
 */
uid_t peer_describe(int fd, char desc[PEER_DESC_LEN]);

/*
 * Whether the process that connected @fd was in group @gid then (its
 * primary group or one of its supplementary groups); false when that
 * cannot be told
 */
bool peer_in_group(int fd, gid_t gid);

#endif
