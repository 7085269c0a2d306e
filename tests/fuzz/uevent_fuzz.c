// SPDX-License-Identifier: GPL-2.0
/*
 * libFuzzer target: a kernel uevent datagram ("action@devpath\0KEY=value
 * \0..."), which the daemon reads from the netlink socket: every field
 * parsed is NUL-terminated within its buffer.
 */
#include "fuzz_text.h"
#include "service/uevent.h"

#define TERMINATED(f)	(memchr((f), '\0', sizeof(f)) != NULL)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct uevent ev;

	if (size > UEVENT_BUF_SIZE)
		return 0;
	if (uevent_parse((const char *)data, size, &ev))
		return 0;
	if (!TERMINATED(ev.action) || !TERMINATED(ev.devpath) ||
	    !TERMINATED(ev.subsystem) || !TERMINATED(ev.devtype) ||
	    !TERMINATED(ev.driver))
		abort();
	uevent_is_appearance(&ev);

	return 0;
}
