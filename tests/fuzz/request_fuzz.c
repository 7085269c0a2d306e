// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: the daemon's request line (any bytes a client sends)
 * and the status line the client looks for in a reply. A request line
 * accepted names a request and formats back to itself (magn-feed: its six
 * numbers are in range); a refusal's message is printable text.
 */
#include <stdio.h>

#include "fuzz_text.h"
#include "common/request.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *line = (const char *)data;
	char err[256], again[REQUEST_LINE_MAX * 2];
	struct request r;
	size_t body, i;
	int status;

	if (request_parse(line, size, &r, err, sizeof(err))) {
		for (i = 0; err[i]; i++)
			if ((unsigned char)err[i] < 0x20 || err[i] == 0x7f)
				abort();
	} else if (r.kind == REQUEST_MAGN_FEED) {
		/* six numbers in range after the word, nothing else */
		if (r.json || size < 10 || memcmp(line, "magn-feed ", 10))
			abort();
		for (i = 0; i < REQUEST_FEED_VALUES; i++)
			if (!(r.feed[i] >= -100000 && r.feed[i] <= 100000))
				abort();
	} else {
		snprintf(again, sizeof(again), "%s%s", request_name(r.kind),
			 r.json ? " --json" : "");
		if (strlen(again) != size || memcmp(again, line, size))
			abort();
	}

	status = request_reply_status(line, size, &body);
	if (status > 255 || (status >= 0 && body >= size))
		abort();

	return 0;
}
