// SPDX-License-Identifier: GPL-2.0
/*
 * The uevent socket filter (see uevent_filter.h).
 *
 * A kernel uevent is "ACTION@DEVPATH\0ACTION=<action>\0DEVPATH=<devpath>\0
 * SUBSYSTEM=<subsystem>\0..." (lib/kobject_uevent.c: the header, then the
 * three default keys in this order). The header, NUL included, is H =
 * len(action) + len(devpath) + 2 bytes; the two keys after it take 15 + H
 * more, so "SUBSYSTEM=" starts at 2H + 15. Classic BPF has no loops: the
 * filter is unrolled over the first UEVENT_FILTER_SCAN bytes, a word at a
 * time (a word holds a zero byte iff (v - 0x01010101) & ~v & 0x80808080 is
 * not 0), then finds the header's NUL k in that word (H = k + 1), loads
 * X = 2k + 17 and compares the 14 bytes "SUBSYSTEM=iio\0" there.
 *
 * It drops only what it has recognised as another subsystem's uevent: a
 * message whose key at that place is not SUBSYSTEM (another layout, a
 * header longer than the scan) is passed and left to uevent_parse(), so
 * no iio uevent is ever lost to it. A message that ends within the word of
 * its header's NUL, with no NUL at all, or too short for the key it claims,
 * is dropped (an out-of-bounds load returns 0): it carries no SUBSYSTEM
 * and uevent_parse() would not find an appearance in it. The socket only
 * listens to the kernel's group; udev's messages ("libudev" header) never
 * reach it.
 */
#include <errno.h>
#include <sys/socket.h>

#include "service/uevent_filter.h"

#define KEEP	0xffffffffU
#define DROP	0U

/* big-endian words, as BPF_LD loads them */
#define BE32(a, b, c, d) \
	(((unsigned int)(a) << 24) | ((unsigned int)(b) << 16) | \
	 ((unsigned int)(c) << 8) | (unsigned int)(d))

size_t uevent_filter_build(struct sock_filter *prog)
{
	struct sock_filter *p = prog;
	unsigned int k, locate, check, here;

	/* the scan: 12 instructions per word, then "keep" (no NUL in range) */
	locate = 12 * (UEVENT_FILTER_SCAN / 4) + 1;
	for (k = 0; k < UEVENT_FILTER_SCAN; k += 4) {
		here = (unsigned int)(p - prog);
		*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_W | BPF_ABS, k);
		*p++ = (struct sock_filter)BPF_STMT(BPF_MISC | BPF_TAX, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_XOR | BPF_K, 0xffffffffU);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ST, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_MISC | BPF_TXA, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_SUB | BPF_K, 0x01010101U);
		*p++ = (struct sock_filter)BPF_STMT(BPF_LDX | BPF_MEM, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_AND | BPF_X, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_AND | BPF_K, 0x80808080U);
		/* no zero byte: the next word (skip the two below) */
		*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0, 2, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_LDX | BPF_W | BPF_IMM, k);
		/* ja is relative to the next instruction */
		*p++ = (struct sock_filter)BPF_STMT(BPF_JMP | BPF_JA,
						    locate - (here + 12));
	}
	*p++ = (struct sock_filter)BPF_STMT(BPF_RET | BPF_K, KEEP);

	/*
	 * locate: X = k, the word's first byte; the NUL is at k + i, the
	 * first zero byte of the word; then X = 2 (k + i) + 17
	 */
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_B | BPF_IND, 0);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0, 19, 0);
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_B | BPF_IND, 1);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0, 12, 0);
	*p++ = (struct sock_filter)BPF_STMT(BPF_LD | BPF_B | BPF_IND, 2);
	*p++ = (struct sock_filter)BPF_JUMP(BPF_JMP | BPF_JEQ | BPF_K, 0, 5, 0);
	for (k = 3; ; k--) {	/* blocks for i = 3, 2, 1, 0 */
		*p++ = (struct sock_filter)BPF_STMT(BPF_MISC | BPF_TXA, 0);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_LSH | BPF_K, 1);
		*p++ = (struct sock_filter)BPF_STMT(BPF_ALU | BPF_ADD | BPF_K, 2 * k + 17);
		*p++ = (struct sock_filter)BPF_STMT(BPF_MISC | BPF_TAX, 0);
		if (!k)
			break;
		/* to check: its offset is filled in below */
		*p++ = (struct sock_filter)BPF_STMT(BPF_JMP | BPF_JA, 0);
	}
	/* the ja of blocks 3, 2, 1 go to check, right here */
	check = (unsigned int)(p - prog);
	for (here = locate + 6; here < check; here++)
		if (prog[here].code == (BPF_JMP | BPF_JA))
			prog[here].k = check - (here + 1);

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
