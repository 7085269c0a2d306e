#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# In the Debian guest of scripts/boot-debian.sh, after multi-user.target.
# The phase comes from the kernel command line (as9888.phase=):
#  factory  a board fresh from assembly: no record yet; it must boot clean
#           (no failed unit, the restore unit skipped), then the factory
#           test runs through the driver and writes the record.
#           The daemon, asked before there is a record, says to run the
#           factory test and keeps running.
#  boot     the record exists: the calibration must have been applied by
#           as9888-calibd-restore@ before multi-user.target, with the
#           driver a DKMS module and the adapter loaded at boot; then a
#           rebind, a late instantiation and the driver module loaded
#           after boot are applied again, and the socket answers
#           "request status" for a user in SocketGroup.
# Prints "BOOTTEST ok|not ok - what" lines and "BOOTTEST done".
set -u
phase=$(sed -n 's/.*as9888\.phase=\([a-z]*\).*/\1/p' /proc/cmdline)
rec=/var/lib/as9888/calibration
n=0
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
# the driver's calibbias after probe is 0 0 0; a record's is not
applied() {
	local d
	d=$(dev) || return 1
	[ "$(cat "$d/in_accel_x_calibbias" "$d/in_accel_y_calibbias" \
		"$d/in_accel_z_calibbias" | tr '\n' ' ')" != "0 0 0 " ]
}
wait_applied() { for _ in $(seq 150); do applied && return 0; sleep 0.2; done; return 1; }
mono() { systemctl show -P "$2" "$1"; }
# gone_and_back WHAT WHAT-GONE REMOVE ADD: REMOVE takes the device away, and
# restore@ (BindsTo= the device) must stop with it; ADD brings it back, and
# restore@ must run again for it and apply the record
gone_and_back() {
	local u t1 u2 t2
	u=$(restore_unit)
	t1=$(mono "$u" ExecMainStartTimestampMonotonic)
	check "$2: command ok" eval "$3"
	sleep 1
	check "$2, restore@ stopped with it" \
		eval '! dev && [ "$(mono "$u" ActiveState)" = inactive ]'
	sleep 1
	check "$1: command ok" eval "$4"
	wait_dev
	check "$1: applied again" wait_applied
	sleep 1
	u2=$(restore_unit)
	t2=$(mono "$u2" ExecMainStartTimestampMonotonic)
	echo "BOOTTEST # restore@ started at $t1 us, and after it at $t2 us"
	check "$1: restore@ ran again for the device" \
		eval '[ "$t2" -gt "$t1" ] && [ "$(mono "$u2" ExecMainStatus)" = 0 ]'
}
restore_unit() { systemctl list-units --all --plain --no-legend 'as9888-calibd-restore@*' | awk '{ print $1; exit }'; }

echo "BOOTTEST phase $phase, kernel $(uname -r), systemd $(systemctl --version | awk 'NR == 1 { print $2 }')"
check "the AS9888 IIO device is there (driver from DKMS, adapter at boot)" wait_dev
check "its magnetometer device (as9888-magn) beside it, below the same bus device" \
	eval 'm=$(dev as9888-magn) && [ "$(dirname "$m")" = "$(dirname "$(dev)")" ]'
check "one restore unit: the magnetometer device starts none" \
	eval '[ "$(systemctl list-units --all --plain --no-legend "as9888-calibd-restore@*" | wc -l)" -eq 1 ]'
check "driver modules from the DKMS tree" eval 'modinfo -n as9888_i2c | grep -q /updates/dkms/'
# (multi-user.target is reached: this unit is ordered after it)
failed=$(systemctl --failed --plain --no-legend | awk '{ print $1 }' | grep -v as9888-boottest | tr '\n' ' ')
check "no failed unit (${failed:-none})" test -z "$failed"

case $phase in
factory)
	u=$(restore_unit)
	check "no record: restore unit $u skipped by its condition, not failed" \
		eval '[ -n "$u" ] && [ "$(mono "$u" ConditionResult)" = no ] && [ "$(mono "$u" Result)" = success ]'
	check "no record: request status (SocketGroup user) says to run the factory test" \
		eval '! runuser -u tester -- as9888-calibd request status >/tmp/st0.log 2>&1 && grep -q "no record yet: run factory-test first" /tmp/st0.log'
	sed 's/^/BOOTTEST # /' /tmp/st0.log | head -3
	check "and the daemon keeps running" systemctl is-active -q as9888-calibd.service
	check "factory test through the driver writes the record" \
		eval 'as9888-calibd factory-test --backend iio --record "$rec" >/tmp/ft.log 2>&1'
	tail -5 /tmp/ft.log | sed 's/^/BOOTTEST # /'
	check "record written" test -s "$rec"
	;;
boot)
	u=$(restore_unit)
	echo "BOOTTEST # restore unit: $u"
	check "calibration applied at boot" applied
	check "by as9888-calibd-restore@ (ran, succeeded)" \
		eval '[ -n "$u" ] && [ "$(mono "$u" ExecMainStatus)" = 0 ] && [ "$(mono "$u" ActiveState)" = active ]'
	r=$(mono "$u" ActiveEnterTimestampMonotonic)
	m=$(mono multi-user.target ActiveEnterTimestampMonotonic)
	echo "BOOTTEST # restore done at ${r} us, multi-user.target at ${m} us (monotonic)"
	check "before multi-user.target" test "$r" -gt 0 -a "$r" -lt "$m"
	check "the daemon runs (socket-activated or started)" \
		eval 'systemctl start as9888-calibd.service && systemctl is-active -q as9888-calibd.service'

	# rebind: the driver comes back with its defaults; restore@ (BindsTo)
	# and the daemon apply the record again
	d=$(dev); i2c=$(basename "$(readlink -f "$d/..")")
	sleep 1
	c0=$(journalctl -q -o cat -u as9888-calibd.service | grep -c "calibration applied to")
	echo "$i2c" >/sys/bus/i2c/drivers/as9888_i2c/unbind
	sleep 1
	echo "$i2c" >/sys/bus/i2c/drivers/as9888_i2c/bind
	wait_dev
	check "rebind: applied again" wait_applied
	# the daemon too: kernel uevents reach its private network namespace
	# (PrivateNetwork=yes) through the socket filter
	daemon_applied() { journalctl -q -o cat -u as9888-calibd.service | grep -c "calibration applied to"; }
	check "rebind: the daemon applied it too (uevent through PrivateNetwork= and the filter)" \
		eval 'for _ in $(seq 50); do [ "$(daemon_applied)" -gt "$c0" ] && break; sleep 0.2; done; [ "$(daemon_applied)" -gt "$c0" ]'
	journalctl -q -o cat -u as9888-calibd.service | tail -6 | sed 's/^/BOOTTEST # daemon: /'

	# a late probe: the adapter removes the device and instantiates it
	# again (debugfs "present"), as a deferred probe would; restore@
	# (BindsTo= the device) stops and runs again
	gone_and_back "device instantiated late" "device removed: no device" \
		"echo 0 >/sys/kernel/debug/as9888_sim/present" \
		"echo 1 >/sys/kernel/debug/as9888_sim/present"
	# the driver module loaded after boot: the device appears when it
	# binds, restore@ runs for it
	gone_and_back "driver module loaded after boot" \
		"driver module unloaded: no device" \
		"modprobe -r as9888_i2c && ! lsmod | grep -q '^as9888_i2c '" \
		"modprobe as9888_i2c"

	check "request status as a user in SocketGroup" \
		eval 'runuser -u tester -- as9888-calibd request status >/tmp/st.log 2>&1'
	sed 's/^/BOOTTEST # /' /tmp/st.log | head -5
	check "and refused for a user outside it, told to ask for group as9888" \
		eval '! runuser -u nobody -- as9888-calibd request status >/tmp/st1.log 2>&1 &&
		      grep -q "Permission denied: run as root, or ask to be added to group as9888" /tmp/st1.log'
	sed 's/^/BOOTTEST # /' /tmp/st1.log | head -2
	;;
esac
echo "BOOTTEST done"
