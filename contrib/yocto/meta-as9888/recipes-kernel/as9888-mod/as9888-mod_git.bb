# SPDX-License-Identifier: GPL-2.0
SUMMARY = "ALSEN AS9888 IIO drivers (out-of-tree modules)"
DESCRIPTION = "The AS9888 IIO drivers built through the repository's \
               top-level Kbuild, as dkms.conf builds them: as9888_core, as9888_i2c, and \
               as9888_spi where the kernel has SPI. Prefer the driver in the kernel tree \
               when the BSP carries it. The kernel needs IIO, its buffers, the triggered \
               buffer and regmap I2C (recipes-kernel/linux/files/as9888.cfg)."

SECTION = "kernel"

require include/as9888-source.inc

inherit module

# No Makefile of our own: the kernel's, with our Kbuild as M=. SPI glue
# and the KUnit module follow the kernel's configuration (Kbuild's
# defaults): as9888_spi only where CONFIG_SPI is set.
AS9888_KCONFIG = "CONFIG_AS9888=m CONFIG_AS9888_I2C=m CONFIG_AS9888_KUNIT_TEST="
# module.bbclass passes it to make (oelint-adv does not know it)
# nooelint: oelint.vars.mispell.unknown
MAKE_TARGETS = "-C ${STAGING_KERNEL_DIR} M=${S} ${AS9888_KCONFIG} modules"
MODULES_INSTALL_TARGET = "-C ${STAGING_KERNEL_DIR} M=${S} ${AS9888_KCONFIG} modules_install"

# what Kconfig's AS9888 and AS9888_I2C select: a kernel without them
# fails here, saying which, instead of in modpost
AS9888_KERNEL_NEEDS = "CONFIG_IIO CONFIG_IIO_BUFFER CONFIG_IIO_TRIGGERED_BUFFER CONFIG_I2C CONFIG_REGMAP_I2C"
do_configure:prepend() {
    missing=""
    for opt in ${AS9888_KERNEL_NEEDS}; do
        grep -qE "^$opt=[ym]\$" ${STAGING_KERNEL_BUILDDIR}/.config || missing="$missing $opt"
    done
    if [ -n "$missing" ]; then
        bbfatal "the kernel lacks$missing: add recipes-kernel/linux/files/as9888.cfg (or the options) to its configuration"
    fi
}

RPROVIDES:${PN} += "kernel-module-as9888-i2c"
