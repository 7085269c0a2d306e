// SPDX-License-Identifier: GPL-2.0
/* Crash-safe file replacement and symlink-refusing reads. */
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "store/atomic_file.h"

#define TMP_SUFFIX ".new"

static int failed(char *err, size_t errlen, const char *what,
		  const char *path, int errnum)
{
	snprintf(err, errlen, "%s %s: %s", what, path, strerror(errnum));
	return -errnum;
}

/* Split @path into its directory and its last component */
static int split_path(const char *path, char *dir, char *base, char *err,
		      size_t errlen)
{
	char a[PATH_MAX], b[PATH_MAX];

	if (!*path || strlen(path) >= PATH_MAX - sizeof(TMP_SUFFIX)) {
		snprintf(err, errlen, "invalid record path \"%s\"", path);
		return -EINVAL;
	}
	strcpy(a, path);
	strcpy(b, path);
	snprintf(dir, PATH_MAX, "%s", dirname(a));
	snprintf(base, PATH_MAX, "%s", basename(b));
	if (!strcmp(base, "/") || !strcmp(base, ".") || !strcmp(base, "..")) {
		snprintf(err, errlen, "record path \"%s\" names a directory", path);
		return -EISDIR;
	}

	return 0;
}

static int write_all(int fd, const char *data, size_t len)
{
	while (len) {
		ssize_t n = write(fd, data, len);

		if (n < 0) {
			if (errno == EINTR)
				continue;
			return -errno;
		}
		data += n;
		len -= (size_t)n;
	}

	return 0;
}

int atomic_begin(struct atomic_pending *p, const char *path, mode_t mode,
		 char *err, size_t errlen)
{
	char dir[PATH_MAX];
	struct stat st;
	int ret;

	p->dfd = p->fd = -1;
	ret = split_path(path, dir, p->base, err, errlen);
	if (ret)
		return ret;
	snprintf(p->path, sizeof(p->path), "%s", path);
	snprintf(p->tmp, sizeof(p->tmp), "%s%s", p->base, TMP_SUFFIX);

	p->dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (p->dfd < 0)
		return failed(err, errlen, "cannot open directory", dir, errno);

	if (fstatat(p->dfd, p->base, &st, AT_SYMLINK_NOFOLLOW) == 0) {
		if (S_ISLNK(st.st_mode)) {
			snprintf(err, errlen, "%s is a symbolic link: refusing to replace it",
				 path);
			ret = -ELOOP;
		} else if (!S_ISREG(st.st_mode)) {
			snprintf(err, errlen, "%s exists and is not a regular file", path);
			ret = -EEXIST;
		}
	} else if (errno != ENOENT) {
		ret = failed(err, errlen, "cannot stat", path, errno);
	}

	/*
	 * A leftover of an interrupted save is ours to remove: a regular file
	 * of our own user. Anything else (another user's file in a shared,
	 * sticky directory) stays, and the save is refused.
	 */
	if (!ret && fstatat(p->dfd, p->tmp, &st, AT_SYMLINK_NOFOLLOW) == 0) {
		if (!S_ISREG(st.st_mode) || st.st_uid != geteuid()) {
			snprintf(err, errlen,
				 "%s/%s is in the way and not a file of ours: move it away",
				 dir, p->tmp);
			ret = -EEXIST;
		} else if (unlinkat(p->dfd, p->tmp, 0) && errno != ENOENT) {
			ret = failed(err, errlen, "cannot remove stale", p->tmp, errno);
		}
	}
	if (!ret) {
		p->fd = openat(p->dfd, p->tmp, O_WRONLY | O_CREAT | O_EXCL |
			       O_NOFOLLOW | O_CLOEXEC, mode);
		if (p->fd < 0)
			ret = failed(err, errlen, "cannot create", p->tmp, errno);
	}
	if (!ret && fchmod(p->fd, mode))
		ret = failed(err, errlen, "cannot set the mode of", p->tmp, errno);
	if (ret)
		atomic_abort(p);

	return ret;
}

void atomic_abort(struct atomic_pending *p)
{
	if (p->fd >= 0) {
		close(p->fd);
		unlinkat(p->dfd, p->tmp, 0);
	}
	if (p->dfd >= 0)
		close(p->dfd);
	p->dfd = p->fd = -1;
}

int atomic_commit(struct atomic_pending *p, const void *data, size_t len,
		  char *err, size_t errlen)
{
	int ret;

	ret = write_all(p->fd, data, len);
	if (ret)
		failed(err, errlen, "cannot write", p->tmp, -ret);
	if (!ret && fsync(p->fd)) {
		ret = -errno;
		failed(err, errlen, "cannot flush", p->tmp, errno);
	}
	if (close(p->fd) && !ret) {
		ret = -errno;
		failed(err, errlen, "cannot close", p->tmp, errno);
	}
	p->fd = -1;
	if (!ret && renameat(p->dfd, p->tmp, p->dfd, p->base)) {
		ret = -errno;
		failed(err, errlen, "cannot rename over", p->path, errno);
	}
	if (ret) {
		unlinkat(p->dfd, p->tmp, 0);
		atomic_abort(p);
		return ret;
	}

	/* the rename is durable once the directory is */
	if (fsync(p->dfd)) {
		ret = -errno;
		failed(err, errlen, "cannot flush the directory of", p->path, errno);
	}
	atomic_abort(p);

	return ret;
}

int atomic_write_file(const char *path, const void *data, size_t len,
		      mode_t mode, char *err, size_t errlen)
{
	struct atomic_pending p;
	int ret;

	ret = atomic_begin(&p, path, mode, err, errlen);

	return ret ? ret : atomic_commit(&p, data, len, err, errlen);
}

long read_file_nofollow(const char *path, char *buf, size_t max, char *err,
			size_t errlen)
{
	struct stat st;

	return read_file_nofollow_stat(path, buf, max, &st, err, errlen);
}

long read_file_nofollow_stat(const char *path, char *buf, size_t max,
			     struct stat *st, char *err, size_t errlen)
{
	size_t len = 0;
	int fd;

	fd = open(path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
	if (fd < 0) {
		if (errno == ELOOP) {
			snprintf(err, errlen, "%s is a symbolic link: not followed", path);
			return -ELOOP;
		}
		return failed(err, errlen, "cannot open", path, errno);
	}
	if (fstat(fd, st) || !S_ISREG(st->st_mode)) {
		snprintf(err, errlen, "%s is not a regular file", path);
		close(fd);
		return -EINVAL;
	}
	for (;;) {
		ssize_t n = read(fd, buf + len, max - len);

		if (n < 0) {
			if (errno == EINTR)
				continue;
			n = -errno;
			failed(err, errlen, "cannot read", path, errno);
			close(fd);
			return n;
		}
		if (n == 0)
			break;
		len += (size_t)n;
		if (len == max) {
			char extra;

			if (read(fd, &extra, 1) == 1) {
				snprintf(err, errlen, "%s: larger than %zu bytes", path, max);
				close(fd);
				return -EFBIG;
			}
			break;
		}
	}
	close(fd);

	return (long)len;
}

int ensure_parent_dir(const char *path, mode_t mode, char *err, size_t errlen)
{
	char dir[PATH_MAX], base[PATH_MAX];
	int ret;

	ret = split_path(path, dir, base, err, errlen);
	if (ret)
		return ret;
	if (mkdir(dir, mode) && errno != EEXIST)
		return failed(err, errlen, "cannot create directory", dir, errno);

	return 0;
}

int durable_sync_dir(const char *path, char *err, size_t errlen)
{
	char dir[PATH_MAX], base[PATH_MAX];
	int dfd, ret;

	ret = split_path(path, dir, base, err, errlen);
	if (ret)
		return ret;
	dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (dfd < 0)
		return failed(err, errlen, "cannot open directory", dir, errno);
	ret = fsync(dfd) ? failed(err, errlen, "cannot flush directory", dir, errno) : 0;
	close(dfd);

	return ret;
}

int durable_rename(const char *from, const char *to, char *err, size_t errlen)
{
	if (rename(from, to))
		return failed(err, errlen, "cannot rename to", to, errno);

	return durable_sync_dir(to, err, errlen);
}

int durable_unlink(const char *path, char *err, size_t errlen)
{
	if (unlink(path) && errno != ENOENT)
		return failed(err, errlen, "cannot remove", path, errno);

	return durable_sync_dir(path, err, errlen);
}
