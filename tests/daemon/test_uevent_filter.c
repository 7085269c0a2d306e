// SPDX-License-Identifier: GPL-2.0
/*
 * The uevent socket filter run by the kernel: attached to one end of an
 * AF_UNIX datagram socket pair (socket filters work on any socket), fed
 * kernel-layout uevents of several subsystems; only iio ones and the ones
 * it cannot place (left to uevent_parse()) come through.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmocka.h>

#include "service/uevent.h"
#include "service/uevent_filter.h"

static int sv[2];

static int setup(void **state)
{
	if (socketpair(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0, sv))
		return -1;
	return uevent_filter_attach(sv[1]);
}

static int teardown(void **state)
{
	close(sv[0]);
	close(sv[1]);
	return 0;
}

/* A kernel uevent as lib/kobject_uevent.c lays it out, with extra keys */
static size_t kernel_uevent(char *buf, size_t size, const char *action,
			    const char *devpath, const char *subsystem,
			    const char *extra)
{
	int n = snprintf(buf, size, "%s@%s%cACTION=%s%cDEVPATH=%s%cSUBSYSTEM=%s%c%s",
			 action, devpath, 0, action, 0, devpath, 0, subsystem, 0,
			 extra);

	assert_true(n > 0 && (size_t)n < size);
	return (size_t)n + 1;	/* the last NUL */
}

/* Whether @msg sent on sv[0] comes out of sv[1] */
static bool passes(const char *msg, size_t len)
{
	char buf[UEVENT_BUF_SIZE];
	ssize_t n;

	assert_int_equal(send(sv[0], msg, len, 0), (ssize_t)len);
	n = recv(sv[1], buf, sizeof(buf), MSG_DONTWAIT);
	if (n < 0) {
		assert_int_equal(errno, EAGAIN);
		return false;
	}
	assert_int_equal(n, (ssize_t)len);
	assert_memory_equal(buf, msg, len);
	return true;
}

static void iio_passes(void **state)
{
	char msg[UEVENT_BUF_SIZE];
	struct uevent ev;
	size_t len;

	len = kernel_uevent(msg, sizeof(msg), "add",
			    "/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0", "iio",
			    "DEVTYPE=iio_device\0MAJOR=250\0MINOR=0\0SEQNUM=1234");
	assert_true(passes(msg, len));
	/* and it is still the appearance the daemon acts on */
	assert_int_equal(uevent_parse(msg, len, &ev), 0);
	assert_true(uevent_is_appearance(&ev));

	len = kernel_uevent(msg, sizeof(msg), "change", "/devices/x/iio:device3",
			    "iio", "SYNTH_UUID=0\0SEQNUM=7");
	assert_true(passes(msg, len));
	len = kernel_uevent(msg, sizeof(msg), "remove", "/devices/x/trigger0", "iio",
			    "SEQNUM=8");
	assert_true(passes(msg, len));
}

static void others_dropped(void **state)
{
	static const char *const subsystems[] = {
		"power_supply", "net", "i2c", "iiox", "ii", "input", "block",
		"usb", "module", "iio2", "IIO",
	};
	char msg[UEVENT_BUF_SIZE];
	unsigned int i;

	for (i = 0; i < sizeof(subsystems) / sizeof(subsystems[0]); i++) {
		size_t len = kernel_uevent(msg, sizeof(msg), "change",
					   "/devices/virtual/net/lo", subsystems[i],
					   "INTERFACE=lo\0IFINDEX=1\0SEQNUM=9");

		assert_false(passes(msg, len));
	}
	/* "SUBSYSTEM=iio" elsewhere in the message does not let it through */
	{
		size_t len = kernel_uevent(msg, sizeof(msg), "change",
					   "/devices/SUBSYSTEM=iio", "net",
					   "SUBSYSTEM=iio\0SEQNUM=10");

		assert_false(passes(msg, len));
	}
}

/* every header length the scan covers, and one just beyond it */
static void every_length(void **state)
{
	char msg[UEVENT_BUF_SIZE], path[UEVENT_FILTER_SCAN + 8];
	unsigned int n;

	for (n = 1; n + 8 <= UEVENT_FILTER_SCAN + 4; n++) {
		size_t len;

		path[0] = '/';
		memset(path + 1, 'd', n - 1);
		path[n] = '\0';
		/* "add@" + path + NUL: the NUL at n + 4 */
		len = kernel_uevent(msg, sizeof(msg), "add", path, "iio", "SEQNUM=1");
		if (n + 4 >= UEVENT_FILTER_SCAN) {
			/* not placed: passed, for uevent_parse() to judge */
			assert_true(passes(msg, len));
			continue;
		}
		assert_true(passes(msg, len));
		len = kernel_uevent(msg, sizeof(msg), "add", path, "usb", "SEQNUM=1");
		assert_false(passes(msg, len));
	}
}

static void not_placed_passes(void **state)
{
	/* another layout (keys in another order): left to uevent_parse() */
	static const char odd[] = "add@/devices/x\0SUBSYSTEM=net\0ACTION=add\0"
				  "DEVPATH=/devices/x\0";
	/* no NUL at all, and too short for the key it claims: dropped */
	static const char no_nul[] = { 'a', 'd', 'd', '@', '/', 'x' };
	static const char short_key[] = "add@/x\0ACTION=add\0DEVPATH=/x\0SUBS";

	assert_true(passes(odd, sizeof(odd)));
	assert_false(passes(no_nul, sizeof(no_nul)));
	assert_false(passes(short_key, sizeof(short_key) - 1));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(iio_passes),
		cmocka_unit_test(others_dropped),
		cmocka_unit_test(every_length),
		cmocka_unit_test(not_placed_passes),
	};

	return cmocka_run_group_tests(tests, setup, teardown);
}
