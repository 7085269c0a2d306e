# SPDX-License-Identifier: GPL-2.0
SUMMARY = "ALSEN AS9888 factory test, accelerometer calibration and boot restore"
DESCRIPTION = "as9888-calibd runs the factory test of the AS9888 sensor, \
               writes the accelerometer's calibration record and applies it to the \
               kernel driver whenever the sensor's IIO device appears. A product build: \
               no simulator, no tests; libgpiod only for the raw backend's pins \
               (PACKAGECONFIG gpiod)."

SECTION = "console/tools"

require include/as9888-source.inc

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
# boot is uncalibrated (the restore then warns).
AS9888_STATEDIR ??= "${localstatedir}/lib/as9888"
EXTRA_OEMESON += "-Dstatedir=${AS9888_STATEDIR}"
# sysvinit distros: the init script (update-rc.d), and eudev's rule for
# the restore on hotplug (not with systemd: restore@ does it there)
EXTRA_OEMESON += "-Dsysvinit=${@bb.utils.contains('DISTRO_FEATURES', 'sysvinit', 'true', 'false', d)}"

PACKAGECONFIG ??= ""
PACKAGECONFIG[gpiod] = "-Dlibgpiod=enabled,-Dlibgpiod=disabled,libgpiod"

INITSCRIPT_NAME = "as9888-calibd"
INITSCRIPT_PARAMS = "start 45 2 3 4 5 . stop 55 0 1 6 ."

# the socket starts the daemon (the service has no [Install]: enabling it
# would start it at every boot); the restore template is started by udev
SYSTEMD_SERVICE:${PN} = "as9888-calibd.socket"
SYSTEMD_AUTO_ENABLE = "enable"

do_install:append() {
    if ${@bb.utils.contains('DISTRO_FEATURES', 'sysvinit', 'true', 'false', d)} && \
       ! ${@bb.utils.contains('DISTRO_FEATURES', 'systemd', 'true', 'false', d)}; then
        install -D -m 0644 ${S}/contrib/sysvinit/61-as9888-calibd-hotplug.rules \
            ${D}${nonarch_base_libdir}/udev/rules.d/61-as9888-calibd-hotplug.rules
    fi
}

FILES:${PN} += "${nonarch_base_libdir}/udev/rules.d \
                ${nonarch_libdir}/tmpfiles.d \
                ${systemd_system_unitdir}"

# the kernel driver: as9888-mod (or the driver in your kernel tree, with
# recipes-kernel/linux/files/as9888.cfg)
RRECOMMENDS:${PN} += "kernel-module-as9888-i2c"
