// SPDX-License-Identifier: GPL-2.0
/*
 * Kernel uevent parsing and the IIO restore path against a sysfs tree laid
 * out like the driver's (iio:deviceN with its attributes, the NVMEM
 * provider beside it, the bus/iio/devices symlink).
 */
#include <errno.h>
#include <fcntl.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "iio.h"
#include "record.h"
#include "uevent.h"

static void parse_iio_add(void **state)
{
	static const char msg[] =
		"add@/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0\0"
		"ACTION=add\0DEVPATH=/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0\0"
		"SUBSYSTEM=iio\0DEVTYPE=iio_device\0MAJOR=250\0MINOR=0\0SEQNUM=1234";
	struct uevent ev;

	assert_int_equal(uevent_parse(msg, sizeof(msg), &ev), 0);
	assert_string_equal(ev.action, "add");
	assert_string_equal(ev.devpath, "/devices/platform/i2c-sim/i2c-1/1-000c/iio:device0");
	assert_string_equal(ev.subsystem, "iio");
	assert_string_equal(ev.devtype, "iio_device");
	assert_true(uevent_is_appearance(&ev));
}

static void parse_bind(void **state)
{
	static const char msg[] = "bind@/devices/x/1-000c\0ACTION=bind\0"
				  "SUBSYSTEM=i2c\0DRIVER=as9888_i2c\0";
	static const char other[] = "bind@/devices/x/1-0050\0ACTION=bind\0"
				    "SUBSYSTEM=i2c\0DRIVER=at24\0";
	struct uevent ev;

	/* a bind is followed by the IIO device's own add: not counted twice */
	assert_int_equal(uevent_parse(msg, sizeof(msg), &ev), 0);
	assert_string_equal(ev.driver, "as9888_i2c");
	assert_false(uevent_is_appearance(&ev));
	assert_int_equal(uevent_parse(other, sizeof(other), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
}

static void parse_not_appearance(void **state)
{
	static const char remove[] = "remove@/devices/x/iio:device0\0"
				     "SUBSYSTEM=iio\0DEVTYPE=iio_device\0";
	static const char trigger[] = "add@/devices/x/trigger0\0"
				      "SUBSYSTEM=iio\0DEVTYPE=iio_trigger\0";
	struct uevent ev;

	assert_int_equal(uevent_parse(remove, sizeof(remove), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
	assert_int_equal(uevent_parse(trigger, sizeof(trigger), &ev), 0);
	assert_false(uevent_is_appearance(&ev));
}

static void parse_garbage(void **state)
{
	static const char udev[] = "libudev\0\xfe\xed\xca\xfe";
	struct uevent ev;
	char big[600];

	assert_int_equal(uevent_parse(udev, sizeof(udev), &ev), -EINVAL);
	assert_int_equal(uevent_parse("add", 3, &ev), -EINVAL);
	assert_int_equal(uevent_parse("@x\0", 3, &ev), -EINVAL);
	assert_int_equal(uevent_parse("", 0, &ev), -EINVAL);
	/* over-long fields are cut, never overflow */
	memset(big, 'a', sizeof(big));
	memcpy(big, "add@/", 5);
	big[400] = '\0';
	memcpy(big + 401, "SUBSYSTEM=", 10);
	assert_int_equal(uevent_parse(big, sizeof(big), &ev), 0);
	assert_int_equal(strlen(ev.devpath), sizeof(ev.devpath) - 1);
	assert_int_equal(strlen(ev.subsystem), sizeof(ev.subsystem) - 1);
}

static const uint8_t example[AS9888_EEPROM_LEN] = {
	0x9a, 0x71, 0x15, 0x5c, 0x80, 0x85, 0x7b, 0x1c, 0x63, 0xa2, 0x38,
	0xe6, 0x9c, 0x0d, 0x8f, 0x8c, 0x04, 0x65, 0xc3, 0x88, 0x50,
};

static char root[64], devdir[256];

static void put(const char *dir, const char *name, const void *data, size_t len)
{
	char path[1024];
	int fd;

	assert_true(snprintf(path, sizeof(path), "%s/%s", dir, name) < (int)sizeof(path));
	fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	assert_true(fd >= 0);
	assert_int_equal(write(fd, data, len), (ssize_t)len);
	close(fd);
}

static void get(const char *dir, const char *name, char *buf, size_t size)
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

/* $root/devices/i2c/1-000c/{iio:device0,as9888-eeprom0}, bus/iio/devices/iio:device0 -> */
static int make_tree(void **state)
{
	char path[1024];

	snprintf(root, sizeof(root), "/tmp/as9888-sysfs-XXXXXX");
	assert_non_null(mkdtemp(root));
	snprintf(devdir, sizeof(devdir), "%s/devices/i2c/1-000c/iio:device0", root);
	snprintf(path, sizeof(path), "mkdir -p '%s' '%s/devices/i2c/1-000c/as9888-eeprom0' '%s/bus/iio/devices'",
		 devdir, root, root);
	assert_int_equal(system(path), 0);
	snprintf(path, sizeof(path), "%s/bus/iio/devices/iio:device0", root);
	assert_int_equal(symlink("../../../devices/i2c/1-000c/iio:device0", path), 0);
	put(devdir, "name", "as9888\n", 7);
	put(devdir, "in_accel_x_calibbias", "0\n", 2);
	put(devdir, "in_accel_y_calibbias", "0\n", 2);
	put(devdir, "in_accel_z_calibbias", "0\n", 2);
	put(devdir, "in_accel_calibration", "none\n", 5);
	snprintf(path, sizeof(path), "%s/devices/i2c/1-000c/as9888-eeprom0", root);
	put(path, "nvmem", example, sizeof(example));
	setenv("AS9888_SYSFS", root, 1);
	return 0;
}

static int remove_tree(void **state)
{
	char cmd[128];

	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", root);
	return system(cmd);
}

static void write_record(const char *path, const uint8_t *eeprom)
{
	struct calib_record rec = {
		.dac = { 0x0f, 0x8e, 0x8c },
		.level_mean_q16 = { -26214, 6553, 258 * 65536 + 6554 },
		.t_level_mdegc = 24583,
		.gravity = { 0, 0, -1 },
		.samples = 16,
		.created = 1795305600,
	};
	char buf[RECORD_MAX_SIZE];
	int len;

	memcpy(rec.eeprom, eeprom, AS9888_EEPROM_LEN);
	len = record_format(&rec, buf, sizeof(buf));
	assert_true(len > 0);
	put(root, path, buf, (size_t)len);
}

static void find_device(void **state)
{
	char dir[IIO_PATH_MAX], want[IIO_PATH_MAX];

	assert_int_equal(iio_find_device(NULL, dir, sizeof(dir)), 0);
	snprintf(want, sizeof(want), "%s/bus/iio/devices/iio:device0", root);
	assert_string_equal(dir, want);
	assert_int_equal(iio_find_device("/devices/i2c/1-000c/iio:device0", dir,
					 sizeof(dir)), 0);
	assert_string_equal(dir, devdir);
	/* a bind of the bus device finds the IIO device below it */
	assert_int_equal(iio_find_device("/devices/i2c/1-000c", dir, sizeof(dir)), 0);
	assert_string_equal(dir, devdir);
	assert_int_equal(iio_find_device("/devices/i2c/1-000d", dir, sizeof(dir)),
			 -ENOENT);
	assert_int_equal(iio_find_device("/devices/i2c/1-000c/../1-000c", dir,
					 sizeof(dir)), -ENOENT);
}

static void restore_applies(void **state)
{
	char path[256], buf[128];

	write_record("cal", example);
	snprintf(path, sizeof(path), "%s/cal", root);
	assert_int_equal(iio_restore(path, devdir), 0);
	/* X: EAXGA 0x1c, DAC 0x0f -> linear -15; Y polarity: 0x8e -> -14 */
	get(devdir, "in_accel_x_calibbias", buf, sizeof(buf));
	assert_string_equal(buf, "-15");
	get(devdir, "in_accel_y_calibbias", buf, sizeof(buf));
	assert_string_equal(buf, "-14");
	get(devdir, "in_accel_z_calibbias", buf, sizeof(buf));
	assert_string_equal(buf, "12");
	get(devdir, "in_accel_calibration", buf, sizeof(buf));
	assert_string_equal(buf, "-26214 6553 16914842 24583 0 0 -1");
}

static void restore_refuses_other_chip(void **state)
{
	uint8_t other[AS9888_EEPROM_LEN];
	char path[256], buf[128];

	memcpy(other, example, sizeof(other));
	other[AS9888_EE_EHC(0)] ^= 1;
	put(devdir, "in_accel_calibration", "none\n", 5);
	write_record("other", other);
	snprintf(path, sizeof(path), "%s/other", root);
	assert_int_equal(iio_restore(path, devdir), -ENODEV);
	get(devdir, "in_accel_calibration", buf, sizeof(buf));
	assert_string_equal(buf, "none\n");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(parse_iio_add),
		cmocka_unit_test(parse_bind),
		cmocka_unit_test(parse_not_appearance),
		cmocka_unit_test(parse_garbage),
		cmocka_unit_test(find_device),
		cmocka_unit_test(restore_applies),
		cmocka_unit_test(restore_refuses_other_chip),
	};

	return cmocka_run_group_tests_name("uevent-iio", tests, make_tree, remove_tree);
}
