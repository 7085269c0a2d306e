// SPDX-License-Identifier: GPL-2.0
/* A sysfs tree laid out like the AS9888 driver's (fake_sysfs.h). */
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "fake_sysfs.h"

const uint8_t fake_example_eeprom[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

void fake_put_bytes(const char *dir, const char *name, const void *data,
		    size_t len)
{
	char path[1024];
	int fd;

	assert_true(snprintf(path, sizeof(path), "%s/%s", dir, name) < (int)sizeof(path));
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	assert_true(fd >= 0);
	assert_int_equal(write(fd, data, len), (ssize_t)len);
	close(fd);
}

void fake_put(const char *dir, const char *name, const char *text)
{
	fake_put_bytes(dir, name, text, strlen(text));
}

void fake_get(const char *dir, const char *name, char *buf, size_t size)
{
	char path[1024];
	ssize_t n;
	int fd;

	assert_true(snprintf(path, sizeof(path), "%s/%s", dir, name) < (int)sizeof(path));
	fd = open(path, O_RDONLY);
	assert_true(fd >= 0);
	n = read(fd, buf, size - 1);
	assert_true(n >= 0);
	buf[n] = '\0';
	close(fd);
}

void fake_mkdir(const char *dir, const char *sub)
{
	char cmd[1100];

	assert_true(snprintf(cmd, sizeof(cmd), "mkdir -p '%s/%s'", dir, sub) <
		    (int)sizeof(cmd));
	assert_int_equal(system(cmd), 0);
}

void fake_reset_calibration(const struct fake_sysfs *f)
{
	fake_put(f->dev, "in_accel_x_calibbias", "0\n");
	fake_put(f->dev, "in_accel_y_calibbias", "0\n");
	fake_put(f->dev, "in_accel_z_calibbias", "0\n");
}

void fake_magn_calibration(const struct fake_sysfs *f, bool present)
{
	static const char *const attr[][2] = {
		{ "calibbias", "0\n" }, { "calibscale", "1.000000\n" },
	};
	char name[64], path[1024];
	int axis, i;

	for (axis = 0; axis < 3; axis++) {
		for (i = 0; i < 2; i++) {
			snprintf(name, sizeof(name), "in_magn_%c_%s",
				 "xyz"[axis], attr[i][0]);
			snprintf(path, sizeof(path), "%s/%s", f->magn, name);
			if (present)
				fake_put(f->magn, name, attr[i][1]);
			else
				unlink(path);
		}
	}
}

/* iio:device@n of the bus device 1-000c, named @name, with its bus link */
static void add_iio_device(const struct fake_sysfs *f, unsigned int n,
			   const char *name, char *dir, size_t size)
{
	char link[1024], target[128], text[64];

	assert_true(snprintf(dir, size, "%s/devices/i2c/1-000c/iio:device%u",
			     f->root, n) < (int)size);
	fake_mkdir(dir, ".");
	snprintf(link, sizeof(link), "%s/bus/iio/devices/iio:device%u", f->root, n);
	snprintf(target, sizeof(target), "../../../devices/i2c/1-000c/iio:device%u", n);
	assert_int_equal(symlink(target, link), 0);
	snprintf(text, sizeof(text), "%s\n", name);
	fake_put(dir, "name", text);
}

/* rename @from to @to, both below @root */
static void fake_rename(const char *root, const char *from, const char *to)
{
	char a[1024], b[1024];

	snprintf(a, sizeof(a), "%s/%s", root, from);
	snprintf(b, sizeof(b), "%s/%s", root, to);
	assert_int_equal(rename(a, b), 0);
}

void fake_magn_present(const struct fake_sysfs *f, bool present)
{
	static const char *const moved[][2] = {
		{ "devices/i2c/1-000c/iio:device1", "gone-magn" },
		{ "bus/iio/devices/iio:device1", "gone-magn-link" },
	};
	size_t i;

	for (i = 0; i < sizeof(moved) / sizeof(moved[0]); i++)
		fake_rename(f->root, moved[i][present], moved[i][!present]);
}

int fake_sysfs_setup(void **state)
{
	struct fake_sysfs *f = calloc(1, sizeof(*f));
	char path[1024];

	assert_non_null(f);
	snprintf(f->root, sizeof(f->root), "/tmp/as9888-sysfs-XXXXXX");
	assert_non_null(mkdtemp(f->root));
	fake_mkdir(f->root, "devices/i2c/1-000c/as9888-eeprom0");
	fake_mkdir(f->root, "bus/iio/devices");
	add_iio_device(f, 0, "as9888-accel", f->dev, sizeof(f->dev));
	add_iio_device(f, 1, "as9888-magn", f->magn, sizeof(f->magn));
	fake_reset_calibration(f);
	snprintf(path, sizeof(path), "%s/devices/i2c/1-000c/as9888-eeprom0",
		 f->root);
	fake_put_bytes(path, "nvmem", fake_example_eeprom,
		       sizeof(fake_example_eeprom));
	setenv("AS9888_SYSFS", f->root, 1);
	*state = f;

	return 0;
}

int fake_sysfs_teardown(void **state)
{
	struct fake_sysfs *f = *state;
	char cmd[128];
	int ret;

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", f->root);
	ret = system(cmd);
	free(f);

	return ret;
}
