/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Whether the record's files may be believed and written: run as root, a
 * record, lock or state directory that another user could have written
 * (not owned by root, or writable by group or others) is refused, as is a
 * state directory that is a symbolic link. A group-writable one is
 * accepted when its group is the one the administrator named
 * (--state-group). Run as another user, a command can hurt only what that
 * user may write anyway: nothing is checked.
 * Every refusal names the path and the fix.
 */
#ifndef AS9888_STORAGE_TRUST_H
#define AS9888_STORAGE_TRUST_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/stat.h>
#include <sys/types.h>

struct storage_trust {
	bool enforce;		/* run as root: the files must be root's */
	bool group_allowed;	/* group write is fine for @group */
	gid_t group;
};

/* The policy for this process, with @group_name (NULL: none) allowed to write */
int storage_trust_init(struct storage_trust *t, const char *group_name,
		       char *err, size_t errlen);

/* May the file at @path, whose status is @st, be believed? 0 or -EPERM (why in @err) */
int storage_trust_file(const struct storage_trust *t, const char *path,
		       const struct stat *st, char *err, size_t errlen);

/* May the directory holding @path be believed? It must not be a symlink. */
int storage_trust_parent(const struct storage_trust *t, const char *path,
			 char *err, size_t errlen);

#endif
