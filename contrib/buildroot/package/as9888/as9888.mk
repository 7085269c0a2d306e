################################################################################
#
# as9888
#
################################################################################

# the same commit as as9888-calibd
AS9888_VERSION = 5dde4d51a7080c62a7cffd2b167cfe94f60c27a7
AS9888_SITE = https://git.example.com/as9888.git
AS9888_SITE_METHOD = git
AS9888_LICENSE = GPL-2.0
AS9888_LICENSE_FILES = COPYING
# the kernel's make with M= this tree, as dkms.conf runs it; as9888_spi
# only where the kernel has SPI (the top-level Kbuild's default)
AS9888_MODULE_MAKE_OPTS = CONFIG_AS9888=m CONFIG_AS9888_I2C=m \
	CONFIG_AS9888_KUNIT_TEST=

# What the driver needs that has a prompt. IIO_TRIGGERED_BUFFER,
# IIO_KFIFO_BUF and REGMAP_I2C have none: Kconfig's AS9888 selects them
# in-tree; out of tree another driver of the kernel must select them.
define AS9888_LINUX_CONFIG_FIXUPS
	$(call KCONFIG_ENABLE_OPT,CONFIG_I2C)
	$(call KCONFIG_ENABLE_OPT,CONFIG_IIO)
	$(call KCONFIG_ENABLE_OPT,CONFIG_IIO_BUFFER)
	$(call KCONFIG_ENABLE_OPT,CONFIG_IIO_TRIGGER)
	$(call KCONFIG_ENABLE_OPT,CONFIG_NVMEM)
endef

$(eval $(kernel-module))
$(eval $(generic-package))
