/* SPDX-License-Identifier: GPL-2.0 */
/* Run a command for a client, its output framed as the daemon's reply. */
#ifndef AS9888_REQUEST_REPLY_H
#define AS9888_REQUEST_REPLY_H

#include <stdbool.h>

#include "commands/cli.h"

/* A reply the client does not take within this long is abandoned */
#define REQUEST_SEND_TIMEOUT_S	10

/*
 * In the request's child process: run @fn(@o) with its output going to
 * the client on @fd (request.h: the output, then "exit status N"; with
 * @json the JSON document on success, the error text on failure).
 * Returns @fn's exit status. A client that has gone away does not stop
 * the command: what it would have been told is dropped.
 */
int request_reply_run(int fd, int (*fn)(const struct cli_opts *o),
		      const struct cli_opts *o, bool json);

/* "exit status N\n" (and @text before it, when not NULL) to @fd, never blocking */
void request_reply_status_now(int fd, const char *text, int status);

#endif
