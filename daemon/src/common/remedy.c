// SPDX-License-Identifier: GPL-2.0
/* What to do about the errors a new integrator meets first. */
#include <errno.h>
#include <grp.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "common/remedy.h"

const char *remedy_record(int errnum)
{
	switch (errnum) {
	case EACCES:
		return "run as root (the record and its directory are root's), or ask the daemon: as9888-calibd request status (check, recalibrate and rollback: root or the daemon's --operator-group)";
	case EROFS:
		return "the file system is read-only: give --record a path on a writable one (the state directory, /var/lib/as9888 by default)";
	default:
		return NULL;
	}
}

void remedy_socket(int errnum, const char *path, char *buf, size_t size)
{
	struct group *gr;
	struct stat st;

	switch (errnum) {
	case EACCES:
	case EPERM:
		if (stat(path, &st)) {
			snprintf(buf, size, "run as root, or ask for SocketGroup");
			break;
		}
		gr = getgrgid(st.st_gid);
		if (st.st_gid && (st.st_mode & 0020) && gr)
			snprintf(buf, size,
				 "run as root, or ask to be added to group %s (the socket's SocketGroup=)",
				 gr->gr_name);
		else
			snprintf(buf, size,
				 "run as root, or ask for SocketGroup: a drop-in for as9888-calibd.socket with SocketGroup=GROUP, and you in that group");
		break;
	case ENOENT:
	case ECONNREFUSED:
		snprintf(buf, size,
			 "the daemon is not running: systemctl enable --now as9888-calibd.socket (or start as9888-calibd daemon), or give its socket with --socket");
		break;
	default:
		snprintf(buf, size, "is the daemon running, and is this its socket (--socket)?");
		break;
	}
}
