# SPDX-License-Identifier: GPL-2.0
#
# as9888-calibd for a Yocto/OpenEmbedded BSP layer: the calibration daemon,
# its man page, the systemd units, the udev rule that restores the
# calibration when the AS9888 IIO device appears, and the tmpfiles.d entry.
# A product build: no simulator, no tests (no cmocka); libgpiod only for the
# raw backend's pins (PACKAGECONFIG "gpiod", off by default).
#
# EXAMPLE, NOT BUILT HERE: no bitbake runs in this project's CI. What is
# tested is the build with exactly these meson flags (tests/install/
# install.sh checks that EXTRA_OEMESON below holds the flags it builds with).
# Set AS9888_GIT_URI in your layer (or a .bbappend); SRCREV is pinned to
# the commit this recipe was written for: move it with PV.

SUMMARY = "ALSEN AS9888 factory test, accelerometer calibration and boot restore"
HOMEPAGE = "${AS9888_GIT_URI}"
LICENSE = "GPL-2.0-only"
LIC_FILES_CHKSUM = "file://COPYING;md5=b234ee4d69f5fce4486a80fdaf4a4263"

AS9888_GIT_URI ??= "git://git.example.com/as9888.git;protocol=https;branch=main"
SRC_URI = "${AS9888_GIT_URI}"
SRCREV = "c5ead2ee31db033c92c0ac05b8362c419d56eb37"
S = "${WORKDIR}/git"

inherit meson pkgconfig systemd update-rc.d

# the product flags (tests/install/install.sh builds with the same;
# -Dlibgpiod=disabled comes from PACKAGECONFIG below)
EXTRA_OEMESON = "-Dsimulator=false -Dtests=disabled"
# the layout of the image
EXTRA_OEMESON += "-Dsystemdsystemunitdir=${systemd_system_unitdir} \
                  -Dudevrulesdir=${nonarch_base_libdir}/udev/rules.d \
                  -Dtmpfilesdir=${nonarch_libdir}/tmpfiles.d \
                  -Dsystemd=${@bb.utils.contains('DISTRO_FEATURES', 'systemd', 'true', 'false', d)}"
# Where the calibration record lives. With a read-only rootfs
# (IMAGE_FEATURES read-only-rootfs: volatile-binds puts /var/lib on a
# tmpfs) or an A/B update, point it at the persistent partition, e.g.
# AS9888_STATEDIR = "/persist/as9888" with /persist in fstab; else every
# boot is uncalibrated (the restore then warns in the journal).
AS9888_STATEDIR ??= "${localstatedir}/lib/as9888"
EXTRA_OEMESON += "-Dstatedir=${AS9888_STATEDIR}"
# sysvinit distros: the init script (update-rc.d), and eudev's rule for
# the restore on hotplug (not with systemd: restore@ does it there)
EXTRA_OEMESON += "-Dsysvinit=${@bb.utils.contains('DISTRO_FEATURES', 'sysvinit', 'true', 'false', d)}"
INITSCRIPT_NAME = "as9888-calibd"
INITSCRIPT_PARAMS = "start 45 2 3 4 5 . stop 55 0 1 6 ."
do_install:append() {
	if ${@bb.utils.contains('DISTRO_FEATURES', 'sysvinit', 'true', 'false', d)} && \
	   ! ${@bb.utils.contains('DISTRO_FEATURES', 'systemd', 'true', 'false', d)}; then
		install -D -m 0644 ${S}/contrib/sysvinit/61-as9888-calibd-hotplug.rules \
			${D}${nonarch_base_libdir}/udev/rules.d/61-as9888-calibd-hotplug.rules
	fi
}

PACKAGECONFIG ??= ""
PACKAGECONFIG[gpiod] = "-Dlibgpiod=enabled,-Dlibgpiod=disabled,libgpiod"

# the socket starts the daemon (the service has no [Install]: enabling it
# would start it at every boot); the restore template is started by udev
SYSTEMD_SERVICE:${PN} = "as9888-calibd.socket"
SYSTEMD_AUTO_ENABLE = "enable"

FILES:${PN} += "${nonarch_base_libdir}/udev/rules.d ${sysconfdir}/init.d \
                ${nonarch_libdir}/tmpfiles.d \
                ${systemd_system_unitdir}"

# the kernel driver: as9888-mod_0.1.0.bb (or the driver in your kernel tree)
RRECOMMENDS:${PN} += "kernel-module-as9888-i2c"
