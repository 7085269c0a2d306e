// SPDX-License-Identifier: GPL-2.0
/* The AS9888 IIO driver's interfaces as the daemon uses them (iio.h). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "iio.h"
#include "session.h"

/* Beyond any adjusted reading: 4096 * (255 + 128) / 256 */
#define IIO_SELFTEST_ABS_MAX	8192.0


const char *iio_sysfs_root(void)
{
	const char *root = getenv("AS9888_SYSFS");

	return root && *root ? root : "/sys";
}

int iio_read_attr(const char *dir, const char *name, char *buf, size_t size)
{
	char path[IIO_PATH_MAX];
	ssize_t n;
	int fd;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	n = read(fd, buf, size - 1);
	close(fd);
	if (n < 0)
		return -errno;
	while (n > 0 && buf[n - 1] == '\n')
		n--;
	buf[n] = '\0';

	return (int)n;
}

int iio_write_attr(const char *dir, const char *name, const char *value)
{
	char path[IIO_PATH_MAX];
	size_t len = strlen(value);
	ssize_t n;
	int fd;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	fd = open(path, O_WRONLY | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	n = write(fd, value, len);
	if (n < 0)
		n = -errno;
	close(fd);

	return n < 0 ? (int)n : (size_t)n == len ? 0 : -EIO;
}

static bool is_as9888(const char *dir)
{
	char name[IIO_ATTR_MAX];

	return iio_read_attr(dir, "name", name, sizeof(name)) > 0 &&
	       !strcmp(name, IIO_DEVICE_NAME);
}

/* The first AS9888 iio:deviceN directly below @dir */
static int scan(const char *dir, char *out, size_t size)
{
	struct dirent *de;
	DIR *d = opendir(dir);
	int ret = -ENOENT;

	if (!d)
		return -ENOENT;
	while ((de = readdir(d))) {
		if (strncmp(de->d_name, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX)))
			continue;
		snprintf(out, size, "%s/%s", dir, de->d_name);
		if (is_as9888(out)) {
			ret = 0;
			break;
		}
	}
	closedir(d);

	return ret;
}

int iio_find_device(const char *devpath, char *out, size_t size)
{
	char dir[IIO_PATH_MAX];
	const char *base;

	if (!devpath) {
		snprintf(dir, sizeof(dir), "%s/bus/iio/devices", iio_sysfs_root());
		return scan(dir, out, size);
	}
	if (strstr(devpath, "/.."))
		return -ENOENT;
	snprintf(dir, sizeof(dir), "%s%s", iio_sysfs_root(), devpath);
	base = strrchr(dir, '/');
	if (base && !strncmp(base + 1, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX))) {
		if (!is_as9888(dir))
			return -ENOENT;
		snprintf(out, size, "%s", dir);
		return 0;
	}

	return scan(dir, out, size);
}

int iio_read_eeprom(const char *dir, uint8_t eeprom[AS9888_EEPROM_LEN])
{
	const char *base = strrchr(dir, '/');
	char path[IIO_PATH_MAX];
	ssize_t n;
	int fd;

	if (!base || strncmp(base + 1, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX)))
		return -EINVAL;
	snprintf(path, sizeof(path), "%s/../%s-eeprom%s/nvmem", dir,
		 IIO_DEVICE_NAME, base + 1 + strlen(IIO_DEVICE_PREFIX));
	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return -errno;
	n = read(fd, eeprom, AS9888_EEPROM_LEN);
	close(fd);
	if (n < 0)
		return -errno;

	return n == AS9888_EEPROM_LEN ? 0 : -EIO;
}

int iio_restore(const char *record_path, const char *dir)
{
	uint8_t eeprom[AS9888_EEPROM_LEN];
	struct calib_record rec;
	int ret;

	if (session_load_record(record_path, &rec))
		return -EINVAL;
	ret = iio_read_eeprom(dir, eeprom);
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s: cannot read the EEPROM: %s\n",
			dir, strerror(-ret));
		return ret;
	}
	if (memcmp(eeprom, rec.eeprom, AS9888_EEPROM_LEN)) {
		fprintf(stderr, "as9888-calibd: %s belongs to chip %016llx, %s is chip %016llx; nothing applied\n",
			record_path, (unsigned long long)record_fingerprint(rec.eeprom),
			dir, (unsigned long long)record_fingerprint(eeprom));
		return -ENODEV;
	}

	return iio_apply_record(dir, &rec);
}

int iio_apply_record(const char *dir, const struct calib_record *rec)
{
	static const char *const bias[AS9888_AXES] = {
		"in_accel_x_calibbias", "in_accel_y_calibbias", "in_accel_z_calibbias",
	};
	char want[IIO_ATTR_MAX], got[IIO_ATTR_MAX];
	struct as9888_eeprom ee;
	int axis, ret;

	as9888_eeprom_decode(rec->eeprom, &ee);
	for (axis = 0; axis < AS9888_AXES; axis++) {
		snprintf(want, sizeof(want), "%d",
			 as9888_dac2lin(ee.axis[axis].ga, rec->dac[axis]));
		ret = iio_write_attr(dir, bias[axis], want);
		if (!ret)
			ret = iio_read_attr(dir, bias[axis], got, sizeof(got)) < 0 ? -EIO :
			      strcmp(want, got) ? -EIO : 0;
		if (ret) {
			fprintf(stderr, "as9888-calibd: %s/%s: cannot set %s: %s\n",
				dir, bias[axis], want, strerror(-ret));
			return ret;
		}
	}

	snprintf(want, sizeof(want), "%d %d %d %d %d %d %d",
		 rec->level_mean_q16[0], rec->level_mean_q16[1],
		 rec->level_mean_q16[2], rec->t_level_mdegc, rec->gravity[0],
		 rec->gravity[1], rec->gravity[2]);
	ret = iio_write_attr(dir, "in_accel_calibration", want);
	if (!ret)
		ret = iio_read_attr(dir, "in_accel_calibration", got, sizeof(got)) < 0 ?
		      -EIO : strcmp(want, got) ? -EIO : 0;
	if (ret) {
		fprintf(stderr, "as9888-calibd: %s/in_accel_calibration: cannot set \"%s\": %s\n",
			dir, want, strerror(-ret));
		return ret;
	}

	return 0;
}

int iio_parse_selftest(const char *s, bool *pass, int32_t adj_q8[AS9888_AXES])
{
	char verdict[8], tail;
	double v[AS9888_AXES];
	int axis;

	if (sscanf(s, "%7s %lf %lf %lf %c", verdict, &v[0], &v[1], &v[2],
		   &tail) != 4)
		return -EINVAL;
	if (!strcmp(verdict, "pass"))
		*pass = true;
	else if (!strcmp(verdict, "fail"))
		*pass = false;
	else
		return -EINVAL;
	for (axis = 0; axis < AS9888_AXES; axis++) {
		/* 1/1000 rounding is finer than 1/256: the Q8 value is exact */
		if (!(v[axis] > -IIO_SELFTEST_ABS_MAX &&
		      v[axis] < IIO_SELFTEST_ABS_MAX))
			return -EINVAL;
		adj_q8[axis] = (int32_t)(v[axis] * AS9888_Q8_ONE +
					 (v[axis] < 0 ? -0.5 : 0.5));
	}

	return 0;
}
