/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The daemon's request protocol. A client sends one line: a request word,
 * optionally followed by " --json". The daemon answers with the command's
 * output and a last line "exit status N" (N: the command's exit status).
 * With --json the output is the JSON document when N is 0 and the error
 * text otherwise, never both.
 */
#ifndef AS9888_REQUEST_H
#define AS9888_REQUEST_H

#include <stdbool.h>
#include <stddef.h>

/* Longest request line, newline included */
#define REQUEST_LINE_MAX	64
#define REQUEST_STATUS_PREFIX	"exit status "

enum request_kind {
	REQUEST_STATUS = 0,
	REQUEST_CHECK,
	REQUEST_RECALIBRATE,
	REQUEST_ROLLBACK,
	REQUEST_MAGN,
	REQUEST_MAGN_FEED,
};

/*
 * "magn-feed Y1 Y2 Y3 A1 A2 A3": a magnetometer consumer's sample for the
 * field mode (magn_field.h): the driver's output in uT (up to 3 decimals)
 * and the accelerometer's raw reading at the same time (integers)
 */
#define REQUEST_FEED_VALUES	6

struct request {
	enum request_kind kind;
	bool json;
	double feed[REQUEST_FEED_VALUES];
};

const char *request_name(enum request_kind kind);

/* Changes the record or the device: its requester is logged */
bool request_changes_state(enum request_kind kind);

/* Uses the chip or writes the record: one such request at a time */
bool request_exclusive(enum request_kind kind);
/* Frequent and routine (magn-feed): not logged when asked and done */
bool request_quiet(enum request_kind kind);
/*
 * Only root and the daemon's operator group may ask (check, recalibrate,
 * rollback: the chip alone, or the record changed); status, magn and
 * magn-feed are open to every client of the socket
 */
bool request_for_operator(enum request_kind kind);

/*
 * Parse the request line @line of @len bytes (without its newline; any
 * byte may appear). 0, or -EINVAL with the reason in @err, the words
 * quoted with anything unprintable shown as '?'.
 */
int request_parse(const char *line, size_t len, struct request *r, char *err,
		  size_t errlen);

/*
 * The exit status in the last line of a reply of @len bytes: 0..255, or
 * -1 when the reply does not end with a status line. @body_len gets the
 * length of what precedes that line.
 */
int request_reply_status(const char *reply, size_t len, size_t *body_len);

#endif
