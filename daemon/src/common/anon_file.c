// SPDX-License-Identifier: GPL-2.0
/*
 * A file with no name (anon_file.h). memfd_create() is detected by the
 * build (HAVE_MEMFD_CREATE, meson's cc.has_function()), not guessed from
 * the C library: bionic declares it from API 30 only, and an Android.bp
 * build defines nothing, so it takes the fallback on every API level.
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "common/anon_file.h"

int anon_file_unlinked(const char *dir)
{
	char path[PATH_MAX];
	int fd;

	if ((size_t)snprintf(path, sizeof(path), "%s/.as9888-anon-XXXXXX", dir) >=
	    sizeof(path))
		return -ENAMETOOLONG;
	fd = mkostemp(path, O_CLOEXEC);
	if (fd < 0)
		return -errno;
	if (unlink(path)) {
		int ret = -errno;

		close(fd);
		return ret;
	}

	return fd;
}

int anon_file_in(const char *dir)
{
	/* O_EXCL: the file can never be given a name (linkat) */
	int fd = open(dir, O_TMPFILE | O_EXCL | O_RDWR | O_CLOEXEC, 0600);

	if (fd >= 0)
		return fd;
	/*
	 * The file system has none (EOPNOTSUPP), or a kernel before 3.11
	 * took O_TMPFILE's O_DIRECTORY alone and found a directory (EISDIR)
	 */
	if (errno == EOPNOTSUPP || errno == EISDIR)
		return anon_file_unlinked(dir);

	return -errno;
}

int anon_file_open(const char *name, const char *dir)
{
#ifdef HAVE_MEMFD_CREATE
	int fd = memfd_create(name, MFD_CLOEXEC);

	/* a kernel before 3.17, or a seccomp policy that refuses it */
	if (fd >= 0 || (errno != ENOSYS && errno != EPERM))
		return fd < 0 ? -errno : fd;
#endif

	return anon_file_in(dir);
}
