// SPDX-License-Identifier: GPL-2.0
/* Whether the record's files may be believed and written. */
#include <errno.h>
#include <grp.h>
#include <libgen.h>
#include <limits.h>
#include <pwd.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "store/storage_trust.h"

int storage_trust_init(struct storage_trust *t, const char *group_name,
		       char *err, size_t errlen)
{
	struct group *gr;

	t->enforce = geteuid() == 0;
	t->group_allowed = false;
	if (!group_name)
		return 0;
	gr = getgrnam(group_name);
	if (!gr) {
		snprintf(err, errlen, "--state-group: no group \"%s\"", group_name);
		return -EINVAL;
	}
	t->group = gr->gr_gid;
	t->group_allowed = true;

	return 0;
}

/* What @st's mode lets others do, given the named group */
static bool foreign_write(const struct storage_trust *t, const struct stat *st)
{
	if (st->st_mode & S_IWOTH)
		return true;

	return st->st_mode & S_IWGRP && !(t->group_allowed && st->st_gid == t->group);
}

/* Root's files only */
static bool trusted_owner(const struct stat *st)
{
	return st->st_uid == 0;
}

static int refuse(const struct storage_trust *t, const char *what,
		  const char *path, const struct stat *st, char *err, size_t errlen)
{
	unsigned int mode = st->st_mode & 07777, fixed = mode & ~(S_IWGRP | S_IWOTH);

	if (!trusted_owner(st))
		snprintf(err, errlen, "%s %s belongs to uid %u, not to root: not trusted; if its content is right, chown 0 %s",
			 what, path, (unsigned int)st->st_uid, path);
	else
		snprintf(err, errlen, "%s %s is writable by %s (mode %04o): not trusted; chmod %04o %s%s",
			 what, path, mode & S_IWOTH ? "everyone" : "its group", mode,
			 fixed, path, mode & S_IWOTH ? "" :
			 ", or name its group with --state-group");

	return -EPERM;
}

int storage_trust_file(const struct storage_trust *t, const char *path,
		       const struct stat *st, char *err, size_t errlen)
{
	if (!t->enforce)
		return 0;
	if (!trusted_owner(st) || foreign_write(t, st))
		return refuse(t, "file", path, st, err, errlen);

	return 0;
}

int storage_trust_parent(const struct storage_trust *t, const char *path,
			 char *err, size_t errlen)
{
	char copy[PATH_MAX], *dir;
	struct stat st;

	if (!t->enforce)
		return 0;
	if (snprintf(copy, sizeof(copy), "%s", path) >= (int)sizeof(copy)) {
		snprintf(err, errlen, "path %s is too long", path);
		return -ENAMETOOLONG;
	}
	dir = dirname(copy);
	if (lstat(dir, &st)) {
		snprintf(err, errlen, "cannot examine directory %s: %s", dir,
			 strerror(errno));
		return -errno;
	}
	if (S_ISLNK(st.st_mode)) {
		snprintf(err, errlen, "directory %s is a symbolic link: not followed; give the real directory's path",
			 dir);
		return -ELOOP;
	}
	if (!S_ISDIR(st.st_mode)) {
		snprintf(err, errlen, "%s is not a directory", dir);
		return -ENOTDIR;
	}
	if (!trusted_owner(&st) || foreign_write(t, &st))
		return refuse(t, "directory", dir, &st, err, errlen);

	return 0;
}
