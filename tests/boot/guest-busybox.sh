#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The boot test's third boot: the same Debian image with BusyBox init as
# PID 1 (no systemd, no udev; tests/boot/busybox/: inittab, rcS, mdev.conf)
# and the record written by the factory boot. BusyBox init runs this as
# the first consumer, after rcS (sysinit) has finished. Checks that the
# package's init script (/etc/init.d/as9888-calibd, as Buildroot's
# S45as9888-calibd) applied the record before that; after a rebind, that
# mdev's hotplug line applies it again with the daemon stopped, and the
# daemon with it running; start|stop|restart|status; and that a board
# without a record gets one warning in syslog and keeps booting.
# Prints "BOOTTEST plan N" (the checks it makes: the host fails a run that
# made another number; a check added here adds one), "BOOTTEST ok|not ok -
# what" lines and "BOOTTEST done", then powers the machine off.
set -u
# shellcheck source=tests/boot/lib.sh
. /usr/local/lib/as9888-boottest/lib.sh
init=/etc/init.d/as9888-calibd
msgs=/run/messages
# syslog lines of as9888-calibd matching $1
logged() { grep -c "as9888-calibd.*$1" "$msgs" 2>/dev/null || true; }
wait_logged() {	# TEXT COUNT: until more than COUNT lines match
	for _ in $(seq 50); do [ "$(logged "$1")" -gt "$2" ] && return 0; sleep 0.2; done
	return 1
}
status_is() { "$init" status >/dev/null; [ $? -eq "$1" ]; }

# the first consumer: read the state before anything else happens
if applied; then first=yes; else first=no; fi
echo "BOOTTEST plan 14"
echo "BOOTTEST phase busybox, kernel $(uname -r), PID 1: $(readlink /proc/1/exe) ($(tr '\0' ' ' </proc/1/cmdline))"
check "PID 1 is BusyBox init, no systemd, no udev" \
	eval '[ "$(readlink -f /proc/1/exe)" = "$(readlink -f /bin/busybox)" ] && [ ! -d /run/systemd/system ] &&
	      ! pidof systemd-udevd >/dev/null'
check "the AS9888 IIO device is there (driver from DKMS)" \
	eval 'dev >/dev/null && modinfo -n as9888_i2c | grep -q /updates/dkms/'
check "calibration applied before the first consumer read the sensor (by the init script at start)" \
	eval '[ "$first" = yes ] && [ "$(logged "start: calibration applied from $rec")" -eq 1 ]'
check "status: the daemon runs (exit 0)" status_is 0
check "request status through the daemon's own socket" \
	eval 'as9888-calibd request status >/tmp/st.log 2>&1'
sed 's/^/BOOTTEST # /' /tmp/st.log | head -3

# a rebind with the daemon running: mdev's line and the daemon apply it
h0=$(logged "hotplug .*: calibration applied")
d0=$(logged "calibration applied to")
rebind
check "rebind: applied again" wait_applied
check "rebind: by mdev's hotplug line" wait_logged "hotplug .*: calibration applied" "$h0"
check "rebind: and by the daemon (uevents without udev)" wait_logged "calibration applied to" "$d0"

# stop, then a rebind: mdev alone applies it
check "stop (exit 0), then status says stopped (exit 3)" eval '"$init" stop && status_is 3'
h0=$(logged "hotplug .*: calibration applied")
rebind
check "rebind with the daemon stopped: applied by mdev's hotplug line" \
	eval 'wait_applied && [ "$(logged "hotplug .*: calibration applied")" -gt "$h0" ]'
check "start (exit 0): status running" eval '"$init" start >/dev/null && status_is 0'
p1=$(cat /run/as9888-calibd.pid)
check "restart: a new daemon (status running)" \
	eval '"$init" restart >/dev/null && status_is 0 && [ "$(cat /run/as9888-calibd.pid)" != "$p1" ]'

# a board without a record: one warning, start goes on
"$init" stop >/dev/null
mv "$rec" /tmp/calibration.saved
w0=$(logged "no calibration record at $rec")
"$init" start >/tmp/start.log 2>&1
rc=$?
check "no record: start exits 0 and starts the daemon" eval '[ $rc -eq 0 ] && status_is 0'
check "no record: one warning in syslog, saying what to run" \
	eval '[ "$(logged "no calibration record at $rec")" -eq $((w0 + 1)) ] &&
	      grep "no calibration record at $rec" "$msgs" | tail -n1 | grep -q "warn.*Run as9888-calibd factory-test --backend iio on this board"'
grep "no calibration record" "$msgs" | tail -n1 | sed 's/^/BOOTTEST # syslog: /'
mv /tmp/calibration.saved "$rec"
"$init" restart >/dev/null
grep as9888-calibd "$msgs" | tail -n 8 | sed 's/^/BOOTTEST # syslog: /'
echo "BOOTTEST done"
sync
mount -o remount,ro / 2>/dev/null
/bin/busybox poweroff -f
