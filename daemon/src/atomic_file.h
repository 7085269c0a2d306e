/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Crash-safe file replacement and symlink-refusing reads, for the
 * calibration record.
 */
#ifndef AS9888_ATOMIC_FILE_H
#define AS9888_ATOMIC_FILE_H

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

/* Create the directory of @path (one level) with @mode if it is missing. */
int ensure_parent_dir(const char *path, mode_t mode, char *err, size_t errlen);

#endif
