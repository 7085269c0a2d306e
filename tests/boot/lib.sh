# SPDX-License-Identifier: GPL-2.0
# shellcheck shell=bash
#
# Helpers of the boot test's guest scripts (guest-test.sh under systemd,
# guest-busybox.sh under BusyBox init): result lines, the AS9888 IIO
# device, and whether the record in $rec is applied to it.
rec=${rec:-/var/lib/as9888/calibration}
ok() { echo "BOOTTEST ok - $*"; }
bad() { echo "BOOTTEST not ok - $*"; }
check() { local what=$1; shift; if "$@"; then ok "$what"; else bad "$what"; fi; }

dev() {	# the sysfs directory of the IIO device named $1, default the accelerometer's
	local d
	for d in /sys/bus/iio/devices/iio:device*; do
		[ "$(cat "$d/name" 2>/dev/null)" = "${1:-as9888-accel}" ] && { readlink -f "$d"; return 0; }
	done
	return 1
}
wait_dev() { for _ in $(seq 100); do dev >/dev/null && return 0; sleep 0.2; done; return 1; }
# the magnetometer's calibbias and calibscale, x y z, on one line
magn_cal() {
	local d
	d=$(dev as9888-magn) || return 1
	cat "$d"/in_magn_[xyz]_calibbias "$d"/in_magn_[xyz]_calibscale | tr '\n' ' '
}
# the driver's calibbias after probe is 0 0 0; a record's is not. Once the
# factory phase saved the magnetometer's calibration (/root/magn-cal, a
# format 2 record), the magnetometer must hold it too
applied() {
	local d
	d=$(dev) || return 1
	[ "$(cat "$d/in_accel_x_calibbias" "$d/in_accel_y_calibbias" \
		"$d/in_accel_z_calibbias" | tr '\n' ' ')" != "0 0 0 " ] || return 1
	[ ! -s /root/magn-cal ] || [ "$(magn_cal)" = "$(cat /root/magn-cal)" ]
}
wait_applied() { for _ in $(seq 150); do applied && return 0; sleep 0.2; done; return 1; }
# rebind: the driver lets the device go and probes it again (defaults)
rebind() {
	local i2c
	i2c=$(basename "$(readlink -f "$(dev)/..")")
	echo "$i2c" >/sys/bus/i2c/drivers/as9888_i2c/unbind
	sleep 1
	echo "$i2c" >/sys/bus/i2c/drivers/as9888_i2c/bind
	wait_dev
}
# the image's files, as a sorted list (for "purge leaves nothing"): not
# what the kernel, the boot, logs, caches and package management keep
# (/proc /sys /dev /run /tmp /var/tmp /var/log /var/cache /var/lib/apt
# /var/lib/dpkg), nor the test's own /root, nor systemd's state of a boot
# (/var/lib/systemd but for the enablement records of deb-systemd-helper),
# nor dkms's signing key (/var/lib/dkms/mok.*, made on dkms's first build:
# dkms's, not the package's)
snapshot() {
	(cd / && find . -xdev \( -path ./proc -o -path ./sys -o -path ./dev -o -path ./run \
		-o -path ./tmp -o -path ./var/tmp -o -path ./var/log -o -path ./var/cache \
		-o -path ./var/lib/apt -o -path ./var/lib/dpkg -o -path ./root \) -prune -o -print) |
		sed 's|^\.||' |
		grep -Ev '^/var/lib/systemd/(random-seed|timers|catalog|coredump|linger|pstore|backlight|timesync)(/|$)|^/var/lib/dkms/mok\.(key|pub)$|^/etc/machine-id$' |
		LC_ALL=C sort
}
