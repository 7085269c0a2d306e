################################################################################
#
# as9888 (kernel modules)
#
# EXAMPLE, NOT BUILT HERE. kernel-module builds with the kernel's make and
# M= this source tree, as dkms.conf does; the CONFIG_AS9888* values stand
# in for Kconfig (see the top-level Kbuild).
#
################################################################################

AS9888_VERSION = 0.1.0
AS9888_SITE ?= $(call github,example,as9888,v$(AS9888_VERSION))
AS9888_LICENSE = GPL-2.0
AS9888_LICENSE_FILES = COPYING
AS9888_MODULE_MAKE_OPTS = CONFIG_AS9888=m CONFIG_AS9888_I2C=m \
	CONFIG_AS9888_SPI=m CONFIG_AS9888_KUNIT_TEST=

$(eval $(kernel-module))
$(eval $(generic-package))
