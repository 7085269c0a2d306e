# SPDX-License-Identifier: GPL-2.0
#
# The AS9888 IIO drivers as out-of-tree modules, built through the
# repository's top-level Kbuild exactly as dkms.conf builds them
# (as9888_core, as9888_i2c, as9888_spi; no KUnit module).
# Prefer the driver in the kernel tree (drivers/iio/imu/as9888) when the
# BSP carries it.
#
# EXAMPLE, NOT BUILT HERE: no bitbake runs in this project's CI. The same
# make command is tested by scripts/dkms-check.sh and scripts/kernel-build.sh.

SUMMARY = "ALSEN AS9888 IIO drivers (out of tree)"
LICENSE = "GPL-2.0-only"
LIC_FILES_CHKSUM = "file://COPYING;md5=b234ee4d69f5fce4486a80fdaf4a4263"

AS9888_GIT_URI ??= "git://git.example.com/as9888.git;protocol=https;branch=main"
SRC_URI = "${AS9888_GIT_URI}"
# pinned (reproducible): the commit this recipe was written for
SRCREV = "c5ead2ee31db033c92c0ac05b8362c419d56eb37"
S = "${WORKDIR}/git"

inherit module

# no Makefile of our own: run the kernel's, with our Kbuild as M=
AS9888_KCONFIG = "CONFIG_AS9888=m CONFIG_AS9888_I2C=m CONFIG_AS9888_SPI=m CONFIG_AS9888_KUNIT_TEST="
MAKE_TARGETS = "-C ${STAGING_KERNEL_DIR} M=${S} ${AS9888_KCONFIG} modules"
MODULES_INSTALL_TARGET = "-C ${STAGING_KERNEL_DIR} M=${S} ${AS9888_KCONFIG} modules_install"

RPROVIDES:${PN} += "kernel-module-as9888-i2c"
