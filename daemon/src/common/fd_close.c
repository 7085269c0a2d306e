// SPDX-License-Identifier: GPL-2.0
/*
 * Closing a child's inherited descriptors. close_range() is detected by
 * the build (HAVE_CLOSE_RANGE, meson's cc.has_function()), not guessed
 * from the C library; where it is missing, or the kernel answers ENOSYS
 * (before 5.9) or EINVAL, /proc/self/fd is scanned instead.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "common/fd_close.h"

/* The kernel's struct linux_dirent64; not every C library declares it */
struct fd_dirent64 {
	uint64_t d_ino;
	int64_t d_off;
	unsigned short d_reclen;
	unsigned char d_type;
	char d_name[];
};

/* The descriptor named by a /proc/self/fd entry, or -1 ("." and "..") */
static int entry_fd(const char *name)
{
	long v = 0;

	if (*name < '0' || *name > '9')
		return -1;
	for (; *name; name++) {
		if (*name < '0' || *name > '9' || v > (INT32_MAX - 9) / 10)
			return -1;
		v = v * 10 + (*name - '0');
	}
	return (int)v;
}

/*
 * One pass over /proc/self/fd: every listed descriptor >= @lowfd but
 * @dirfd closed. The number closed, or -errno.
 */
static int scan_pass(int dirfd, int lowfd)
{
	/* aligned for the records' 64-bit fields */
	uint64_t buf[512];
	int closed = 0;
	long n;

	if (lseek(dirfd, 0, SEEK_SET) < 0)
		return -errno;
	while ((n = syscall(SYS_getdents64, dirfd, buf, sizeof(buf))) > 0) {
		long off = 0;

		while (off < n) {
			const struct fd_dirent64 *d =
				(const void *)((const char *)buf + off);
			int fd = entry_fd(d->d_name);

			off += d->d_reclen;
			if (fd >= lowfd && fd != dirfd) {
				/* EBADF: not open (any other error closed it) */
				if (!close(fd) || errno != EBADF)
					closed++;
			}
		}
	}
	return n < 0 ? -errno : closed;
}

int fd_close_scan(int lowfd)
{
	struct rlimit lim;
	int dirfd, rc, fd;

	dirfd = open("/proc/self/fd", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (dirfd >= 0) {
		/*
		 * Closing while reading may make the kernel skip entries:
		 * read again from the start until a pass closes nothing.
		 */
		do
			rc = scan_pass(dirfd, lowfd);
		while (rc > 0);
		close(dirfd);
		if (rc == 0)
			return 0;
	} else {
		rc = -errno;
	}
	/* no /proc (early boot, a chroot): every possible descriptor */
	if (getrlimit(RLIMIT_NOFILE, &lim) || lim.rlim_cur == RLIM_INFINITY ||
	    lim.rlim_cur > INT32_MAX)
		lim.rlim_cur = 65536;
	for (fd = lowfd; fd < (int)lim.rlim_cur; fd++)
		close(fd);
	return rc;
}

void fd_close_from(int lowfd)
{
#ifdef HAVE_CLOSE_RANGE
	if (!close_range((unsigned int)lowfd, ~0U, 0))
		return;
#endif
	fd_close_scan(lowfd);
}
