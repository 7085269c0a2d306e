// SPDX-License-Identifier: GPL-2.0
/* The magnetometer calibration for applications (as9888_magn.h). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/un.h>
#include <unistd.h>

#include "as9888_magn.h"
#include "common/magn_cal.h"
#include "common/record.h"
#include "common/request.h"

#define NT_PER_UT	1000.0
#define MICRO		1000000.0
/* The longest as9888_magn_feed() waits for the daemon, each way */
#define FEED_TIMEOUT_S	1

static int read_text(const char *path, char *buf, size_t size, size_t *len,
		     char *err, size_t errlen)
{
	/* O_NONBLOCK: a FIFO put at the path must not hold a HAL's thread */
	int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY);
	struct stat st;
	ssize_t n;
	int ret;

	if (fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "%s: %s", path, strerror(-ret));
		return ret;
	}
	if (fstat(fd, &st) || !S_ISREG(st.st_mode)) {
		close(fd);
		snprintf(err, errlen, "%s: not a regular file (a record is one)", path);
		return -EINVAL;
	}
	n = read(fd, buf, size);
	ret = n < 0 ? -errno : 0;
	close(fd);
	if (ret) {
		snprintf(err, errlen, "%s: %s", path, strerror(-ret));
		return ret;
	}
	if ((size_t)n == size) {
		snprintf(err, errlen, "%s: larger than any record", path);
		return -EINVAL;
	}
	*len = (size_t)n;

	return 0;
}

/*
 * <@magn_file>.previous into @m when it is of @rec (its generation): after
 * a change of both cut between the two files, what the daemon's recovery
 * puts back in <record>.magn. 0 or -errno.
 */
static int read_previous(const char *magn_file, const struct calib_record *rec,
			 struct calib_magn *m)
{
	char file[PATH_MAX], buf[RECORD_MAX_SIZE + 1], why[256];
	size_t len = 0;
	int ret;

	if ((size_t)snprintf(file, sizeof(file), "%s%s", magn_file,
			     RECORD_PREVIOUS_SUFFIX) >= sizeof(file))
		return -ENAMETOOLONG;
	ret = read_text(file, buf, sizeof(buf), &len, why, sizeof(why));

	return ret ? ret : record_magn_of(rec, buf, len, m, why, sizeof(why));
}

/*
 * The magnetometer's file beside the record (<@path>.magn), when there is
 * one: @rec->magn is what it holds, judged as the daemon judges it
 * (record_magn_of(): valid, the record's chip, the record's generation).
 * Read here with read_text(), not the daemon's store: an application has
 * no trust policy of the daemon's to apply, and must never block on the
 * path. 0, or -errno with why in @err.
 */
static int read_magn_file(const char *path, struct calib_record *rec,
			  char *err, size_t errlen)
{
	char file[PATH_MAX], buf[RECORD_MAX_SIZE + 1], why[256];
	struct calib_magn m;
	size_t len = 0;
	int ret;

	if (snprintf(file, sizeof(file), "%s%s", path, RECORD_MAGN_SUFFIX) >=
	    (int)sizeof(file)) {
		snprintf(err, errlen, "%s: path too long", path);
		return -ENAMETOOLONG;
	}
	ret = read_text(file, buf, sizeof(buf), &len, err, errlen);
	if (ret == -ENOENT)
		return 0;
	if (ret)
		return ret;
	ret = record_magn_of(rec, buf, len, &m, why, sizeof(why));
	/*
	 * A change of both cut between the two files: the previous one is the
	 * record's, and what the daemon's recovery puts back (read-only here)
	 */
	if (ret == -ESTALE && !read_previous(file, rec, &m))
		ret = 0;
	if (ret == -EXDEV)
		snprintf(err, errlen, "%s belongs to another chip than %s (%s): not used",
			 file, path, why);
	else if (ret)
		snprintf(err, errlen, "%s is %s: not used", file, why);
	else
		rec->magn = m;

	return ret ? -EINVAL : 0;
}

int as9888_magn_load(const char *path, struct as9888_magn_calibration *cal,
		     char *err, size_t errlen)
{
	char buf[RECORD_MAX_SIZE + 1], why[256];
	const struct calib_magn *m;
	struct calib_record rec;
	struct magn_driver_cal d;
	struct magn_user_cal u;
	size_t len = 0;
	int i, ret;

	ret = read_text(path, buf, sizeof(buf), &len, err, errlen);
	if (ret)
		return ret;
	if (record_parse(buf, len, &rec, why, sizeof(why))) {
		snprintf(err, errlen, "%s: not a valid record: %s", path, why);
		return -EINVAL;
	}
	ret = read_magn_file(path, &rec, err, errlen);
	if (ret)
		return ret;
	/* as restore: what a simulated chip learned fits no real one */
	if (rec.simulated) {
		snprintf(err, errlen, "%s was made on the simulator (source = simulator), not on this chip: not used; run as9888-calibd magn-calibrate on this unit",
			 path);
		return -EPERM;
	}
	m = &rec.magn;
	if (!m->present) {
		snprintf(err, errlen, "%s has no magnetometer calibration: run as9888-calibd magn-calibrate",
			 path);
		return -ENODATA;
	}
	if (magn_driver_split(m, rec.eeprom, &d)) {
		snprintf(err, errlen, "%s: the hard iron is beyond the driver's calibbias range",
			 path);
		return -ERANGE;
	}
	magn_user_split(m, rec.eeprom, &d, &u);
	memset(cal, 0, sizeof(*cal));
	for (i = 0; i < 3; i++) {
		cal->hard_iron_ut[i] = u.bias_ut[i];
		cal->calibbias[i] = d.calibbias[i];
		cal->calibscale[i] = d.calibscale_micro[i] / MICRO;
		cal->offset_ut[i] = u.offset_ut[i];
		cal->hal_bias_ut[i] = u.hal_bias_ut[i];
		memcpy(cal->soft_iron[i], u.soft[i], sizeof(cal->soft_iron[i]));
		memcpy(cal->rotation[i], u.rotation[i], sizeof(cal->rotation[i]));
		memcpy(cal->residual[i], u.residual[i], sizeof(cal->residual[i]));
	}
	cal->field_ut = m->field_nt / NT_PER_UT;
	cal->residual_ut = m->residual_nt / NT_PER_UT;
	cal->coverage = m->coverage_milli / 1000.0;
	cal->samples = m->samples;
	cal->learned = m->learned;

	return 0;
}

void as9888_magn_correct(const struct as9888_magn_calibration *cal, const double y[3],
			 double f[3])
{
	magn_affine(cal->residual, y, cal->offset_ut, f);
}

void as9888_magn_correct_uncalibrated(const struct as9888_magn_calibration *cal,
				      const double m[3], double f[3])
{
	magn_affine(cal->soft_iron, m, cal->hard_iron_ut, f);
}

int as9888_magn_feed(const char *socket_path, const double y[3],
		     const double accel[3], char *err, size_t errlen)
{
	struct sockaddr_un sa = { .sun_family = AF_UNIX };
	struct timeval limit = { .tv_sec = FEED_TIMEOUT_S };
	char line[REQUEST_LINE_MAX], reply[512];
	size_t have = 0;
	ssize_t n;
	int fd, len, status, ret = 0;

	len = snprintf(line, sizeof(line), "magn-feed %.3f %.3f %.3f %.0f %.0f %.0f\n",
		       y[0], y[1], y[2], accel[0], accel[1], accel[2]);
	if (len < 0 || (size_t)len >= sizeof(line)) {
		snprintf(err, errlen, "sample out of range");
		return -ERANGE;
	}
	if (strlen(socket_path) >= sizeof(sa.sun_path)) {
		snprintf(err, errlen, "%s: path too long", socket_path);
		return -ENAMETOOLONG;
	}
	strcpy(sa.sun_path, socket_path);
	fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	/* a HAL's sensor thread is never held up long by a busy daemon */
	if (fd < 0 ||
	    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof(limit)) ||
	    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof(limit)) ||
	    connect(fd, (struct sockaddr *)&sa, sizeof(sa)))
		ret = -errno;
	else if ((errno = 0, write(fd, line, (size_t)len)) != len)
		ret = errno ? -errno : -EIO;
	/* the reply: the daemon's output, then "exit status N" */
	while (!ret && (n = read(fd, reply + have, sizeof(reply) - 1 - have)) != 0) {
		if (n < 0) {
			ret = -errno;
			break;
		}
		have += (size_t)n;
		if (have == sizeof(reply) - 1) {
			/* keep the tail, where the status line is */
			memmove(reply, reply + have / 2, have - have / 2);
			have -= have / 2;
		}
	}
	if (fd >= 0)
		close(fd);
	if (ret) {
		snprintf(err, errlen, "%s: %s", socket_path, strerror(-ret));
		return ret;
	}
	reply[have] = '\0';
	status = request_reply_status(reply, have, &have);
	if (status < 0) {
		snprintf(err, errlen, "%s: the reply has no status line", socket_path);
		return -EIO;
	}
	if (status) {
		snprintf(err, errlen, "the daemon refused the sample (exit status %d)",
			 status);
		return -EIO;
	}

	return 0;
}

void as9888_magn_hal_bias(const struct as9888_magn_calibration *cal, double bias[3])
{
	memcpy(bias, cal->hal_bias_ut, sizeof(cal->hal_bias_ut));
}
