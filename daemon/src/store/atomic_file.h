/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Crash-safe file replacement and symlink-refusing reads, for the
 * calibration record.
 */
#ifndef AS9888_ATOMIC_FILE_H
#define AS9888_ATOMIC_FILE_H

#include <limits.h>
#include <stddef.h>
#include <sys/stat.h>
#include <sys/types.h>

/*
 * Replace @path with @data: write "<path>.new" in the same directory
 * (O_EXCL, O_NOFOLLOW, mode @mode), fsync it, rename it over @path, fsync
 * the directory. At every instant @path holds either the old or the new
 * content. A symlink at @path is refused, not followed. Returns 0 or
 * -errno with what failed in @err; on failure the old file is untouched
 * and the temporary file removed.
 */
int atomic_write_file(const char *path, const void *data, size_t len,
		      mode_t mode, char *err, size_t errlen);

/*
 * The same in two steps, so that a file that cannot be written is known
 * before the work that makes its content: atomic_begin() checks @path and
 * creates "<path>.new" (0, or -errno with why in @err, nothing left);
 * atomic_commit() writes @data into it and renames it over @path (as
 * atomic_write_file()); atomic_abort() gives up, removing it. Either of
 * the last two ends @p.
 */
struct atomic_pending {
	int dfd;
	int fd;
	char path[PATH_MAX];
	char base[PATH_MAX];
	char tmp[PATH_MAX + 8];
};

int atomic_begin(struct atomic_pending *p, const char *path, mode_t mode,
		 char *err, size_t errlen);
int atomic_commit(struct atomic_pending *p, const void *data, size_t len,
		  char *err, size_t errlen);
void atomic_abort(struct atomic_pending *p);

/*
 * Read a regular file of at most @max bytes without following a symlink
 * at @path. Returns the length, or -errno with the reason in @err.
 */
long read_file_nofollow(const char *path, char *buf, size_t max, char *err,
			size_t errlen);

/* The same, with the status of the file read in @st */
long read_file_nofollow_stat(const char *path, char *buf, size_t max,
			     struct stat *st, char *err, size_t errlen);

/* rename(2) @from to @to (same directory) and fsync the directory */
int durable_rename(const char *from, const char *to, char *err, size_t errlen);

/* unlink(2) @path and fsync its directory */
int durable_unlink(const char *path, char *err, size_t errlen);

/* fsync the directory of @path, after a change of its entries */
int durable_sync_dir(const char *path, char *err, size_t errlen);

/* Create the directory of @path (one level) with @mode if it is missing. */
int ensure_parent_dir(const char *path, mode_t mode, char *err, size_t errlen);

#endif
