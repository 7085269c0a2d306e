################################################################################
#
# as9888-calibd
#
################################################################################

# the commit contrib/yocto/meta-as9888 pins (scripts/yocto-check.sh checks
# both name the same one)
AS9888_CALIBD_VERSION = 5dde4d51a7080c62a7cffd2b167cfe94f60c27a7
AS9888_CALIBD_SITE = https://git.example.com/as9888.git
AS9888_CALIBD_SITE_METHOD = git
AS9888_CALIBD_LICENSE = GPL-2.0
AS9888_CALIBD_LICENSE_FILES = COPYING

# the product flags (tests/install/install.sh builds with the same)
AS9888_CALIBD_CONF_OPTS = -Dsimulator=false -Dtests=disabled
AS9888_CALIBD_CONF_OPTS += \
	-Dstatedir=$(call qstrip,$(BR2_PACKAGE_AS9888_CALIBD_STATEDIR))

ifeq ($(BR2_PACKAGE_LIBGPIOD),y)
AS9888_CALIBD_DEPENDENCIES += libgpiod
AS9888_CALIBD_CONF_OPTS += -Dlibgpiod=enabled
else
AS9888_CALIBD_CONF_OPTS += -Dlibgpiod=disabled
endif

ifeq ($(BR2_INIT_SYSTEMD),y)
AS9888_CALIBD_CONF_OPTS += -Dsystemd=true -Dsysvinit=false
# the socket starts the daemon; udev starts as9888-calibd-restore@
define AS9888_CALIBD_INSTALL_INIT_SYSTEMD
	mkdir -p $(TARGET_DIR)/usr/lib/systemd/system-preset
	echo "enable as9888-calibd.socket" \
		>$(TARGET_DIR)/usr/lib/systemd/system-preset/80-as9888-calibd.preset
endef
else ifeq ($(BR2_INIT_BUSYBOX)$(BR2_INIT_SYSV),y)
# BusyBox init or SysV init: the init script as S45as9888-calibd (after
# the modules, before the consumers)
AS9888_CALIBD_CONF_OPTS += -Dsystemd=false -Dsysvinit=true
define AS9888_CALIBD_INSTALL_INIT_SYSV
	mv $(TARGET_DIR)/etc/init.d/as9888-calibd \
		$(TARGET_DIR)/etc/init.d/S45as9888-calibd
	sed -i 's|/etc/init.d/as9888-calibd hotplug|/etc/init.d/S45as9888-calibd hotplug|' \
		$(TARGET_DIR)/etc/init.d/S45as9888-calibd
endef
# mdev (BusyBox's, selected by BR2_ROOTFS_DEVICE_CREATION_DYNAMIC_MDEV):
# its hotplug line goes into busybox's /etc/mdev.conf once every package
# is installed (a finalize hook: the file belongs to busybox)
ifeq ($(BR2_ROOTFS_DEVICE_CREATION_DYNAMIC_MDEV),y)
define AS9888_CALIBD_MDEV_LINE
	grep -q S45as9888-calibd $(TARGET_DIR)/etc/mdev.conf || \
		sed -i "1i $$(sed -n 's|/etc/init.d/as9888-calibd|/etc/init.d/S45as9888-calibd|; /^-SUBSYSTEM/p' \
			$(@D)/contrib/sysvinit/mdev.conf)" $(TARGET_DIR)/etc/mdev.conf
endef
AS9888_CALIBD_TARGET_FINALIZE_HOOKS += AS9888_CALIBD_MDEV_LINE
endif
# eudev: a rule file of our own in its rules directory
ifeq ($(BR2_PACKAGE_EUDEV),y)
AS9888_CALIBD_DEPENDENCIES += eudev
define AS9888_CALIBD_EUDEV_RULE
	mkdir -p $(TARGET_DIR)/lib/udev/rules.d
	sed 's|/etc/init.d/as9888-calibd|/etc/init.d/S45as9888-calibd|' \
		$(@D)/contrib/sysvinit/61-as9888-calibd-hotplug.rules \
		>$(TARGET_DIR)/lib/udev/rules.d/61-as9888-calibd-hotplug.rules
endef
AS9888_CALIBD_POST_INSTALL_TARGET_HOOKS += AS9888_CALIBD_EUDEV_RULE
endif
else
# OpenRC or no init system: no unit and no script (the SysV script does not
# fit OpenRC); see the help text
AS9888_CALIBD_CONF_OPTS += -Dsystemd=false -Dsysvinit=false
endif

$(eval $(meson-package))
