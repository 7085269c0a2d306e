// SPDX-License-Identifier: GPL-2.0
/* The lock file of a record: opened without being fooled, waited for with a deadline. */
#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "store/lock_file.h"

/* How often a held lock is tried again */
#define LOCK_RETRY_MS	50

/*
 * Put a new, private (@mode) lock file at @path in place of the one there:
 * created beside it and renamed over it, so that a descriptor someone
 * opened while the old one was readable locks an inode nobody uses.
 */
static int lock_file_replace(const char *path, unsigned int mode, char *err,
			     size_t errlen)
{
	char tmp[PATH_MAX];
	int fd, ret;

	if (snprintf(tmp, sizeof(tmp), "%s.XXXXXX", path) >= (int)sizeof(tmp)) {
		snprintf(err, errlen, "lock %s: path too long", path);
		return -ENAMETOOLONG;
	}
	fd = mkostemp(tmp, O_CLOEXEC);
	if (fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "cannot make a private lock beside %s: %s",
			 path, strerror(-ret));
		return ret;
	}
	ret = fchmod(fd, (mode_t)mode) ? -errno : 0;
	close(fd);
	if (!ret && rename(tmp, path))
		ret = -errno;
	if (ret) {
		snprintf(err, errlen, "cannot replace lock %s by a private one: %s",
			 path, strerror(-ret));
		unlink(tmp);
	}

	return ret;
}

int lock_file_open(const char *path, unsigned int mode, bool replace, char *err,
		   size_t errlen)
{
	struct stat st;
	mode_t loose;
	bool replaced = false;
	int fd, ret;

again:
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
	 * read is one they may hold, then and later (a chmod does not take
	 * back a descriptor). One made looser (by an older version, or by
	 * hand) is replaced by a new file of @mode when it is ours and
	 * @replace (a lock that holds no data), else tightened; one that
	 * others could write is left as it is, for the caller's trust check
	 * to refuse.
	 */
	loose = st.st_mode & 0777 & ~(mode_t)mode;
	if (!loose || (loose & (S_IWGRP | S_IWOTH)) || st.st_uid != geteuid())
		return fd;
	if (!replace) {
		if (!fchmod(fd, (mode_t)mode))
			return fd;
		snprintf(err, errlen, "cannot make %s private (chmod %04o): %s",
			 path, mode, strerror(errno));
		close(fd);
		return -EPERM;
	}
	close(fd);
	if (replaced) {
		snprintf(err, errlen, "lock %s is loose again right after it was replaced: "
			 "something changes it, remove it", path);
		return -EPERM;
	}
	ret = lock_file_replace(path, mode, err, errlen);
	if (ret)
		return ret;
	replaced = true;
	goto again;
}

bool lock_file_current(int fd, const char *path)
{
	struct stat held, named;

	return !fstat(fd, &held) && !lstat(path, &named) &&
	       held.st_dev == named.st_dev && held.st_ino == named.st_ino;
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
