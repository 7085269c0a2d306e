// SPDX-License-Identifier: GPL-2.0
/* The daemon's request line and the status line of its reply. */
#include <errno.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "common/request.h"

#define JSON_SUFFIX	" --json"
#define QUOTED_MAX	REQUEST_LINE_MAX

/*
 * operator: only root and the operator group may ask (it uses the chip
 * alone or changes the record); the others are a consumer's requests
 */
static const struct {
	const char *name;
	bool changes_state;
	bool exclusive;
	bool quiet;
	bool operator;
} kinds[] = {
	[REQUEST_STATUS] = { "status", false, false, false, false },
	[REQUEST_CHECK] = { "check", false, true, false, true },
	[REQUEST_RECALIBRATE] = { "recalibrate", true, true, false, true },
	[REQUEST_ROLLBACK] = { "rollback", true, true, false, true },
	[REQUEST_MAGN] = { "magn", false, false, false, false },
	/* its rare record rewrite is logged by the field mode itself */
	[REQUEST_MAGN_FEED] = { "magn-feed", false, false, true, false },
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

bool request_quiet(enum request_kind kind)
{
	return kinds[kind].quiet;
}

bool request_for_operator(enum request_kind kind)
{
	return kinds[kind].operator;
}

/*
 * magn-feed's values after the word: REQUEST_FEED_VALUES decimal numbers
 * within +-100000, each after one space, nothing else. 0 or -EINVAL.
 */
static int parse_feed(const char *s, size_t len, double *out)
{
	char text[REQUEST_LINE_MAX], *p, *end;
	int i;

	if (len >= sizeof(text))
		return -EINVAL;
	memcpy(text, s, len);
	text[len] = '\0';
	p = text;
	for (i = 0; i < REQUEST_FEED_VALUES; i++) {
		if (*p != ' ' || p[1] == ' ' || !p[1])
			return -EINVAL;
		p++;
		end = p + strspn(p, "-0123456789.");
		if (end == p || (*end && *end != ' '))
			return -EINVAL;
		errno = 0;
		out[i] = strtod(p, &end);
		if (errno || (*end && *end != ' ') || out[i] != out[i] ||
		    out[i] > 100000 || out[i] < -100000)
			return -EINVAL;
		p = end;
	}

	return *p ? -EINVAL : 0;
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

	if (word == strlen(kinds[REQUEST_MAGN_FEED].name) &&
	    !memcmp(line, kinds[REQUEST_MAGN_FEED].name, word)) {
		memset(r, 0, sizeof(*r));
		r->kind = REQUEST_MAGN_FEED;
		if (!sp || parse_feed(sp, len - word, r->feed)) {
			snprintf(err, errlen, "magn-feed takes %d numbers: the driver's field in uT, the accelerometer's reading",
				 REQUEST_FEED_VALUES);
			return -EINVAL;
		}
		return 0;
	}
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
		snprintf(err, errlen, "unknown request \"%s\": expected one of status, check, recalibrate, rollback, magn, magn-feed",
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
