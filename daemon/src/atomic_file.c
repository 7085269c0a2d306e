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

#include "atomic_file.h"

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

int atomic_write_file(const char *path, const void *data, size_t len,
		      mode_t mode, char *err, size_t errlen)
{
	char dir[PATH_MAX], base[PATH_MAX], tmp[PATH_MAX + sizeof(TMP_SUFFIX)];
	struct stat st;
	int dfd, fd, ret;

	ret = split_path(path, dir, base, err, errlen);
	if (ret)
		return ret;
	snprintf(tmp, sizeof(tmp), "%s%s", base, TMP_SUFFIX);

	dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	if (dfd < 0)
		return failed(err, errlen, "cannot open directory", dir, errno);

	if (fstatat(dfd, base, &st, AT_SYMLINK_NOFOLLOW) == 0) {
		if (S_ISLNK(st.st_mode)) {
			snprintf(err, errlen, "%s is a symbolic link: refusing to replace it",
				 path);
			close(dfd);
			return -ELOOP;
		}
		if (!S_ISREG(st.st_mode)) {
			snprintf(err, errlen, "%s exists and is not a regular file", path);
			close(dfd);
			return -EEXIST;
		}
	} else if (errno != ENOENT) {
		ret = failed(err, errlen, "cannot stat", path, errno);
		close(dfd);
		return ret;
	}

	/* a leftover of an interrupted save is ours to remove */
	if (unlinkat(dfd, tmp, 0) && errno != ENOENT) {
		ret = failed(err, errlen, "cannot remove stale", tmp, errno);
		close(dfd);
		return ret;
	}

	fd = openat(dfd, tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
		    mode);
	if (fd < 0) {
		ret = failed(err, errlen, "cannot create", tmp, errno);
		close(dfd);
		return ret;
	}

	ret = fchmod(fd, mode) ? -errno : 0;
	if (ret)
		failed(err, errlen, "cannot set the mode of", tmp, -ret);
	if (!ret) {
		ret = write_all(fd, data, len);
		if (ret)
			failed(err, errlen, "cannot write", tmp, -ret);
	}
	if (!ret && fsync(fd)) {
		ret = -errno;
		failed(err, errlen, "cannot flush", tmp, errno);
	}
	if (close(fd) && !ret) {
		ret = -errno;
		failed(err, errlen, "cannot close", tmp, errno);
	}
	if (!ret && renameat(dfd, tmp, dfd, base)) {
		ret = -errno;
		failed(err, errlen, "cannot rename over", path, errno);
	}
	if (ret) {
		unlinkat(dfd, tmp, 0);
		close(dfd);
		return ret;
	}

	/* the rename is durable once the directory is */
	if (fsync(dfd)) {
		ret = -errno;
		failed(err, errlen, "cannot flush directory", dir, errno);
	}
	close(dfd);

	return ret;
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

/* fsync the directory of @path, after a change of its entries */
static int sync_parent(const char *path, char *err, size_t errlen)
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

	return sync_parent(to, err, errlen);
}

int durable_unlink(const char *path, char *err, size_t errlen)
{
	if (unlink(path) && errno != ENOENT)
		return failed(err, errlen, "cannot remove", path, errno);

	return sync_parent(path, err, errlen);
}
