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
# BusyBox init or sysvinit: the init script as S45as9888-calibd (after the
# modules, before the consumers), and the restore on hotplug through mdev's
# line or eudev's rule (contrib/sysvinit/)
AS9888_CALIBD_CONF_OPTS += -Dsystemd=false -Dsysvinit=true
define AS9888_CALIBD_INSTALL_INIT_SYSV
	mv $(TARGET_DIR)/etc/init.d/as9888-calibd \
		$(TARGET_DIR)/etc/init.d/S45as9888-calibd
	sed -i 's|/etc/init.d/as9888-calibd hotplug|/etc/init.d/S45as9888-calibd hotplug|' \
		$(TARGET_DIR)/etc/init.d/S45as9888-calibd
endef
ifeq ($(BR2_ROOTFS_DEVICE_CREATION_DYNAMIC_MDEV),y)
define AS9888_CALIBD_MDEV_LINE
	grep -q as9888-calibd $(TARGET_DIR)/etc/mdev.conf || \
		sed -i "1i $$(sed -n 's|/etc/init.d/as9888-calibd|/etc/init.d/S45as9888-calibd|; /^-SUBSYSTEM/p' \
			$(@D)/contrib/sysvinit/mdev.conf)" $(TARGET_DIR)/etc/mdev.conf
endef
AS9888_CALIBD_POST_INSTALL_TARGET_HOOKS += AS9888_CALIBD_MDEV_LINE
endif
ifeq ($(BR2_ROOTFS_DEVICE_CREATION_DYNAMIC_EUDEV),y)
define AS9888_CALIBD_EUDEV_RULE
	sed 's|/etc/init.d/as9888-calibd|/etc/init.d/S45as9888-calibd|' \
		$(@D)/contrib/sysvinit/61-as9888-calibd-hotplug.rules \
		>$(TARGET_DIR)/lib/udev/rules.d/61-as9888-calibd-hotplug.rules
endef
AS9888_CALIBD_POST_INSTALL_TARGET_HOOKS += AS9888_CALIBD_EUDEV_RULE
endif
endif

$(eval $(meson-package))
