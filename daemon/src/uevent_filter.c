// SPDX-License-Identifier: GPL-2.0
/*
 * The uevent socket filter (see uevent_filter.h).
 *
 * A kernel uevent is "ACTION@DEVPATH\0ACTION=<action>\0DEVPATH=<devpath>\0
 * SUBSYSTEM=<subsystem>\0..." (lib/kobject_uevent.c: the header, then the
 * three default keys in this order). The header, NUL included, is H =
 * len(action) + len(devpath) + 2 bytes; the two keys after it take 15 + H
 * more, so "SUBSYSTEM=" starts at 2H + 15. Classic BPF has no loops: the
 * filter is unrolled over the first UEVENT_FILTER_SCAN bytes to find the
 * header's NUL at k (H = k + 1), loads X = 2k + 17 and compares the 14
 * bytes "SUBSYSTEM=iio\0" there.
 *
 * It drops only what it has recognised as another subsystem's uevent: a
 * message whose key at that place is not SUBSYSTEM (another layout, a
 * header longer than the scan) is passed and left to uevent_parse(), so
 * no iio uevent is ever lost to it. A message with no NUL at all, or too
 * short for the key it claims, is dropped (an out-of-bounds load returns
 * 0): uevent_parse() would refuse it too. The socket only listens to the
 * kernel's group; udev's messages ("libudev" header) never reach it.
 */
#include <errno.h>
#include <sys/socket.h>

#include "uevent_filter.h"

#define KEEP	0xffffffffU
#define DROP	0U

/* big-endian words, as BPF_LD loads them */
#define BE32(a, b, c, d) \
	(((unsigned int)(a) << 24) | ((unsigned int)(b) << 16) | \
	 ((unsigned int)(c) << 8) | (unsigned int)(d))

size_t uevent_filter_build(struct sock_filter *prog)
{
	struct sock_filter *p = prog;
	unsigned int k, check;

	/* the scan: 4 instructions per byte, then "keep" (no NUL in range) */
	check = 4 * UEVENT_FILTER_SCAN + 1;
	for (k = 0; k < UEVENT_FILTER_SCAN; k++) {
		unsigned int here = (unsigned int)(p - prog);

		*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_B | BPF_ABS, k);
		*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0, 0, 2);
		*p++ = (struct sock_filter)BPF_STMT(BPF_LDX | BPF_W | BPF_IMM,
						    2 * k + 17);
		/* ja is relative to the next instruction */
		*p++ = (struct sock_filter)BPF_STMT(BPF_JMP | BPF_JA,
						    check - (here + 4));
	}
	*p++ = (struct sock_filter)BPF_STMT(BPF_RET | BPF_K, KEEP);

	/* check: X is where SUBSYSTEM= must be; 8 instructions to "keep" */
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_W | BPF_IND, 0);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K,
					    BE32('S', 'U', 'B', 'S'), 0, 6);
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_W | BPF_IND, 4);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K,
					    BE32('Y', 'S', 'T', 'E'), 0, 4);
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_H | BPF_IND, 8);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K,
					    ('M' << 8) | '=', 0, 2);
	/* the key is SUBSYSTEM: from here on, not iio means drop */
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_W | BPF_IND, 10);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K,
					    BE32('i', 'i', 'o', 0), 0, 1);
	*p++ = (struct sock_filter)BPF_STMT(BPF_RET | BPF_K, KEEP);
	*p++ = (struct sock_filter)BPF_STMT(BPF_RET | BPF_K, DROP);

	return (size_t)(p - prog);
}

int uevent_filter_attach(int fd)
{
	static struct sock_filter prog[UEVENT_FILTER_LEN];
	struct sock_fprog fprog = { .filter = prog };

	fprog.len = (unsigned short)uevent_filter_build(prog);
	if (setsockopt(fd, SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof(fprog)))
		return -errno;

	return 0;
}
