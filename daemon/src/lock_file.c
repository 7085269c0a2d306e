// SPDX-License-Identifier: GPL-2.0
/* The lock file of a record: opened without being fooled, waited for with a deadline. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "lock_file.h"

/* How often a held lock is tried again */
#define LOCK_RETRY_MS	50

int lock_file_open(const char *path, unsigned int mode, char *err, size_t errlen)
{
	struct stat st;
	mode_t loose;
	int fd;

	fd = open(path, O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY |
		  O_CLOEXEC, (mode_t)mode);
	if (fd < 0) {
		snprintf(err, errlen, errno == ELOOP ?
			 "cannot open lock %s: it is a symbolic link (remove it)" :
			 "cannot open lock %s: %s", path, strerror(errno));
		return -errno;
	}
	if (fstat(fd, &st) || !S_ISREG(st.st_mode)) {
		snprintf(err, errlen, "lock %s is not a regular file: remove it", path);
		close(fd);
		return -EINVAL;
	}
	/*
	 * flock() works on a descriptor opened read-only: a lock others may
	 * read is one they may hold. One made looser (by an older version,
	 * or by hand) is tightened to @mode when it is ours; one that others
	 * could write is left as it is, for the caller's trust check to refuse.
	 */
	loose = st.st_mode & 0777 & ~(mode_t)mode;
	if (loose && !(loose & (S_IWGRP | S_IWOTH)) && st.st_uid == geteuid() &&
	    fchmod(fd, (mode_t)mode)) {
		snprintf(err, errlen, "cannot make lock %s private (chmod %04o): %s",
			 path, mode, strerror(errno));
		close(fd);
		return -EPERM;
	}

	return fd;
}

int lock_file_try(int fd)
{
	if (!flock(fd, LOCK_EX | LOCK_NB))
		return 0;

	return errno == EWOULDBLOCK ? -EWOULDBLOCK : -errno;
}

static long long now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

int lock_file_wait(int fd, unsigned int timeout_ms)
{
	long long deadline = now_ms() + timeout_ms;
	struct timespec pause = { .tv_nsec = LOCK_RETRY_MS * 1000000L };
	int ret;

	while ((ret = lock_file_try(fd)) == -EWOULDBLOCK) {
		if (now_ms() >= deadline)
			return -ETIMEDOUT;
		nanosleep(&pause, NULL);
	}

	return ret;
}
