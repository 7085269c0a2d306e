// SPDX-License-Identifier: GPL-2.0
/* The daemon's request line and the status line of its reply. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "request.h"

#define JSON_SUFFIX	" --json"
#define QUOTED_MAX	REQUEST_LINE_MAX

static const struct {
	const char *name;
	bool changes_state;
	bool exclusive;
} kinds[] = {
	[REQUEST_STATUS] = { "status", false, false },
	[REQUEST_CHECK] = { "check", false, true },
	[REQUEST_RECALIBRATE] = { "recalibrate", true, true },
	[REQUEST_ROLLBACK] = { "rollback", true, true },
	[REQUEST_MAGN] = { "magn", false, false },
};

#define KINDS	(sizeof(kinds) / sizeof(kinds[0]))

const char *request_name(enum request_kind kind)
{
	return kinds[kind].name;
}

bool request_changes_state(enum request_kind kind)
{
	return kinds[kind].changes_state;
}

bool request_exclusive(enum request_kind kind)
{
	return kinds[kind].exclusive;
}

/* @len bytes of @s as printable text, at most QUOTED_MAX - 1 of them */
static void printable(const char *s, size_t len, char out[QUOTED_MAX])
{
	size_t i;

	if (len > QUOTED_MAX - 1)
		len = QUOTED_MAX - 1;
	for (i = 0; i < len; i++)
		out[i] = s[i] >= 0x20 && s[i] < 0x7f && s[i] != '"' ? s[i] : '?';
	out[i] = '\0';
}

int request_parse(const char *line, size_t len, struct request *r, char *err,
		  size_t errlen)
{
	const char *sp = memchr(line, ' ', len);
	size_t word = sp ? (size_t)(sp - line) : len;
	char quoted[QUOTED_MAX];
	unsigned int i;

	if (sp && (len - word != strlen(JSON_SUFFIX) ||
		   memcmp(sp, JSON_SUFFIX, len - word))) {
		printable(sp + 1, len - word - 1, quoted);
		snprintf(err, errlen, "unexpected \"%s\" after the request: only --json may follow",
			 quoted);
		return -EINVAL;
	}
	for (i = 0; i < KINDS; i++)
		if (strlen(kinds[i].name) == word && !memcmp(line, kinds[i].name, word))
			break;
	if (i == KINDS) {
		printable(line, word, quoted);
		snprintf(err, errlen, "unknown request \"%s\": expected one of status, check, recalibrate, rollback, magn",
			 quoted);
		return -EINVAL;
	}
	r->kind = (enum request_kind)i;
	r->json = sp != NULL;

	return 0;
}

int request_reply_status(const char *reply, size_t len, size_t *body_len)
{
	size_t start, plen = strlen(REQUEST_STATUS_PREFIX), i;
	int status = 0;

	if (!len || reply[len - 1] != '\n')
		return -1;
	for (start = len - 1; start && reply[start - 1] != '\n'; start--)
		;
	if (len - 1 - start <= plen || len - 1 - start > plen + 3 ||
	    memcmp(reply + start, REQUEST_STATUS_PREFIX, plen))
		return -1;
	for (i = start + plen; i < len - 1; i++) {
		if (reply[i] < '0' || reply[i] > '9')
			return -1;
		status = status * 10 + reply[i] - '0';
	}
	if (status > 255)
		return -1;
	*body_len = start;

	return status;
}
