################################################################################
#
# as9888-calibd
#
# EXAMPLE, NOT BUILT HERE: no Buildroot runs in this project's CI. What is
# tested is the build with exactly these meson flags (tests/install/
# install.sh checks that AS9888_CALIBD_CONF_OPTS holds the flags it builds
# with). Set AS9888_CALIBD_SITE to your copy of the repository.
#
################################################################################

AS9888_CALIBD_VERSION = 0.1.0
AS9888_CALIBD_SITE ?= $(call github,example,as9888,v$(AS9888_CALIBD_VERSION))
AS9888_CALIBD_LICENSE = GPL-2.0
AS9888_CALIBD_LICENSE_FILES = COPYING

# the product flags (tests/install/install.sh builds with the same)
AS9888_CALIBD_CONF_OPTS = -Dsimulator=false -Dtests=disabled

ifeq ($(BR2_PACKAGE_LIBGPIOD),y)
AS9888_CALIBD_DEPENDENCIES += libgpiod
AS9888_CALIBD_CONF_OPTS += -Dlibgpiod=enabled
else
AS9888_CALIBD_CONF_OPTS += -Dlibgpiod=disabled
endif

ifeq ($(BR2_INIT_SYSTEMD),y)
AS9888_CALIBD_CONF_OPTS += -Dsystemd=true
# the socket starts the daemon; udev starts as9888-calibd-restore@
define AS9888_CALIBD_INSTALL_INIT_SYSTEMD
	mkdir -p $(TARGET_DIR)/usr/lib/systemd/system-preset
	echo "enable as9888-calibd.socket" \
		>$(TARGET_DIR)/usr/lib/systemd/system-preset/80-as9888-calibd.preset
endef
else
AS9888_CALIBD_CONF_OPTS += -Dsystemd=false
endif

$(eval $(meson-package))
