// SPDX-License-Identifier: GPL-2.0
/* Where the kernel's file systems are (iio_root.h). */
#include <stdlib.h>

#include "iio_root.h"

/* $@name when set and not empty, else @fallback */
static const char *root_from_env(const char *name, const char *fallback)
{
	const char *root = getenv(name);

	return root && *root ? root : fallback;
}

const char *iio_sysfs_root(void)
{
	return root_from_env("AS9888_SYSFS", "/sys");
}

const char *iio_debugfs_root(void)
{
	return root_from_env("AS9888_DEBUGFS", "/sys/kernel/debug");
}

const char *iio_dev_root(void)
{
	return root_from_env("AS9888_DEVDIR", "/dev");
}
