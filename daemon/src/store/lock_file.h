/* SPDX-License-Identifier: GPL-2.0 */
/* The lock file of a record: opened without being fooled, waited for with a deadline. */
#ifndef AS9888_LOCK_FILE_H
#define AS9888_LOCK_FILE_H

#include <stdbool.h>
#include <stddef.h>

/*
 * Open (creating it with @mode) the lock file @path: never through a
 * symbolic link, never blocking on a FIFO or device put there, and only a
 * regular file. Whoever may open the file may flock() it, even read-only:
 * @mode must let nobody else read it (0600). A file of ours with looser
 * permissions is, with @replace (a lock that holds no data), replaced by a
 * new file of @mode renamed over it (a descriptor opened on the old one no
 * longer counts: the caller checks lock_file_current() once it holds the
 * lock), else tightened to @mode. The fd, or -errno with the reason in @err.
 */
int lock_file_open(const char *path, unsigned int mode, bool replace, char *err,
		   size_t errlen);

/*
 * Whether @path still names the file @fd is open on: a lock taken on a
 * file that was replaced meanwhile locks nothing, and is taken again
 */
bool lock_file_current(int fd, const char *path);

/* flock(LOCK_EX) of @fd now: 0, -EWOULDBLOCK when someone holds it, or -errno */
int lock_file_try(int fd);

/* flock(LOCK_EX) of @fd within @timeout_ms: 0, -ETIMEDOUT, or -errno */
int lock_file_wait(int fd, unsigned int timeout_ms);

#endif
