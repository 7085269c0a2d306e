/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A file with no name, for output held back before it is sent (a
 * request's reply): gone when its last descriptor closes.
 */
#ifndef AS9888_ANON_FILE_H
#define AS9888_ANON_FILE_H

/*
 * A new empty file open for reading and writing, close-on-exec: a
 * memfd_create() one where the C library has it (HAVE_MEMFD_CREATE:
 * glibc >= 2.27, musl >= 1.1.20, bionic API 30), else one with no name
 * in @dir (anon_file_in()). @name labels a memfd (/proc/PID/fd). The
 * descriptor, or -errno.
 */
int anon_file_open(const char *name, const char *dir);

/*
 * The fallback: an O_TMPFILE file in @dir, or where the kernel or the
 * file system has no O_TMPFILE, anon_file_unlinked(). The descriptor, or
 * -errno.
 */
int anon_file_in(const char *dir);

/*
 * A file made in @dir under a name of its own (mkostemp()) and unlinked
 * at once. The descriptor, or -errno.
 */
int anon_file_unlinked(const char *dir);

#endif
