// SPDX-License-Identifier: GPL-2.0
/* The HAL tests' additions to the fake sysfs tree (hal_test_tree.h) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <unistd.h>

#include <cmocka.h>

#include "hal_test_tree.h"

static void channel(const char *dir, const char *name, int index, const char *type)
{
	char file[96], text[32];

	snprintf(file, sizeof(file), "scan_elements/%s_en", name);
	fake_put(dir, file, "0\n");
	snprintf(file, sizeof(file), "scan_elements/%s_index", name);
	snprintf(text, sizeof(text), "%d\n", index);
	fake_put(dir, file, text);
	snprintf(file, sizeof(file), "scan_elements/%s_type", name);
	snprintf(text, sizeof(text), "%s\n", type);
	fake_put(dir, file, text);
}

static void buffer(const char *dir, const char *rates)
{
	fake_mkdir(dir, "scan_elements");
	fake_mkdir(dir, "buffer");
	fake_mkdir(dir, "trigger");
	fake_put(dir, "buffer/enable", "0\n");
	fake_put(dir, "buffer/length", "8\n");
	fake_put(dir, "buffer/watermark", "1\n");
	fake_put(dir, "trigger/current_trigger", "\n");
	fake_put(dir, "current_timestamp_clock", "realtime\n");
	fake_put(dir, "sampling_frequency", "1\n");
	fake_put(dir, "sampling_frequency_available", rates);
}

void hal_tree_channels(const struct fake_sysfs *f)
{
	char trig[300];

	buffer(f->dev, "1 2 5 10 20 25 50 100 200 400\n");
	channel(f->dev, "in_accel_x", 0, "le:s16/16>>0");
	channel(f->dev, "in_accel_y", 1, "le:s16/16>>0");
	channel(f->dev, "in_accel_z", 2, "le:s16/16>>0");
	channel(f->dev, "in_temp", 3, "le:u8/16>>0");
	channel(f->dev, "in_timestamp", 4, "le:s64/64>>0");
	fake_put(f->dev, "in_accel_scale", "0.009576806\n");
	fake_put(f->dev, "in_accel_mount_matrix", "1, 0, 0; 0, 1, 0; 0, 0, 1\n");
	fake_put(f->dev, "in_accel_x_raw", "0\n");
	fake_put(f->dev, "in_accel_y_raw", "0\n");
	fake_put(f->dev, "in_accel_z_raw", "1024\n");

	buffer(f->magn, "1 2 5 10 20 25 50 100\n");
	channel(f->magn, "in_magn_x", 0, "le:s13/16>>0");
	channel(f->magn, "in_magn_y", 1, "le:s13/16>>0");
	channel(f->magn, "in_magn_z", 2, "le:s13/16>>0");
	channel(f->magn, "in_timestamp", 3, "le:s64/64>>0");
	fake_put(f->magn, "in_magn_x_scale", "0.003000\n");
	fake_put(f->magn, "in_magn_y_scale", "0.00305859\n");
	fake_put(f->magn, "in_magn_z_scale", "0.00294141\n");
	fake_put(f->magn, "in_magn_mount_matrix", "1, 0, 0; 0, 1, 0; 0, 0, 1\n");

	snprintf(trig, sizeof(trig), "%s/bus/iio/devices/trigger0", f->root);
	fake_mkdir(trig, ".");
	fake_put(trig, "name", "as9888-dev0\n");
}

void hal_tree_remove(const char *dir, const char *name)
{
	char path[1024];

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	assert_int_equal(unlink(path), 0);
}
