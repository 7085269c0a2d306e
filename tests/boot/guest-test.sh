#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# In the Debian guest of scripts/boot-debian.sh, after multi-user.target.
# The phase comes from the kernel command line (as9888.phase=):
#  factory  a board fresh from assembly: no record yet; it must boot clean
#           (no failed unit, the restore units skipped), then the factory
#           test runs through the driver and writes the record, and
#           magn-calibrate, the board turned by the adapter's tumble,
#           adds the magnetometer's calibration (<record>.magn, the
#           record left format 1).
#           The daemon, asked before there is a record, says to run the
#           factory test and keeps running.
#  boot     the record exists: the calibration must have been applied by
#           as9888-calibd-restore@ before multi-user.target, the
#           accelerometer's and the magnetometer's each by its device's
#           own instance, with the
#           driver a DKMS module and the adapter loaded at boot; then a
#           rebind, a late instantiation and the driver module loaded
#           after boot are applied again, and the socket answers
#           "request status" for a user in SocketGroup.
# Prints "BOOTTEST plan N" (the checks this phase makes: the host fails a
# phase that made another number), "BOOTTEST ok|not ok - what" lines and
# "BOOTTEST done". A check added here adds one to its phase's plan.
set -u
phase=$(sed -n 's/.*as9888\.phase=\([a-z]*\).*/\1/p' /proc/cmdline)
# shellcheck source=tests/boot/lib.sh
. /usr/local/lib/as9888-boottest/lib.sh
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
# restore_unit [NAME]: the restore@ instance of the IIO device NAME
# (default the accelerometer's), named by the device's sysfs path
restore_unit() {
	local d
	d=$(dev "${1:-}") || d=/sys/none
	echo "as9888-calibd-restore@$(systemd-escape --path "$d").service"
}
# speed_run NAME ARGS...: one factory test (record /root/speed.rec, not the
# board's); appends its report's duration (ms) to /root/NAME.times when it
# passed, says why when it did not
speed_run() {
	local n=$1 d
	shift
	as9888-calibd factory-test "$@" --json --record /root/speed.rec \
		>/root/"$n".json 2>/root/"$n".err &&
		grep -q '^  "result": "pass"' /root/"$n".json &&
		d=$(sed -n 's/^  "duration_ms": \([0-9.]*\),*$/\1/p' /root/"$n".json) &&
		[ -n "$d" ] && { echo "$d" >>/root/"$n".times; return 0; }
	echo "BOOTTEST # $n failed: $(head -c 200 /root/"$n".err)"
	grep '"result": "fail"' /root/"$n".json | head -n 1 | cut -c1-200 | sed 's/^ */BOOTTEST # /'
	return 1
}
# speed_rounds N: the factory test on the raw bus (the driver unloaded,
# the chip powered again by the adapter) and through the driver, N rounds
# interleaved, on this stock kernel; prints the best of each and the ratio
# (what tests/vm/guest/tests/83-factory-speed.sh measures on the debug
# kernels)
speed_rounds() {
	local sim=/sys/kernel/debug/as9888_sim bus="" chip="" n addr client gi raw i r rounds=$1 best_raw best_iio
	modprobe i2c-dev
	for n in /sys/bus/i2c/devices/i2c-*/name; do
		[ "$(cat "$n")" = as9888-sim-i2c ] && bus=$(basename "$(dirname "$n")")
	done
	client=$(basename "$(readlink -f "$(dev)/..")")
	addr=0x${client##*-00}
	chip=$(gpiodetect | sed -n 's/^\([^ ]*\) \[as9888-sim-gpio\].*/\1/p')
	gi=$(gpioinfo "$chip")
	line() { echo "$gi" | sed -n "s/^[[:space:]]*line *\([0-9]*\): *\"AS9888_$1\".*/\1/p"; }
	raw="--backend raw --i2c-dev /dev/$bus --i2c-address $addr --gpiochip $chip --rstn-line $(line RSTN) --int1-line $(line INT1) --int2-line $(line INT2)"
	echo "BOOTTEST # raw: $raw"
	# the kernel switches unused regulators off once, 30 s after its late
	# initcalls: not under a raw-bus run (tests/vm/guest/lib.sh supply_settled)
	n=$(dmesg | sed -n 's/^\[ *\([0-9]*\)\.[0-9]*\] Freeing unused kernel.*/\1/p' | head -n 1)
	while [ -n "$n" ] && [ "$(cut -d. -f1 /proc/uptime)" -lt $((n + 45)) ] &&
		! dmesg | grep -q 'as9888-sim-supply: disabling'; do
		sleep 1
	done
	rm -f /root/raw.times /root/iio.times
	cat $sim/unit >/root/speed.unit
	for i in $(seq "$rounds"); do
		# the driver unloaded and kept off the chip: udev would load
		# and bind it again for the device the unit re-creates
		modprobe -r as9888_i2c
		echo 0 >/sys/bus/i2c/drivers_autoprobe
		# the unit written again: the chip powered on (the driver's
		# runtime PM had switched its supply off)
		cat /root/speed.unit >$sim/unit
		speed_run raw $raw
		echo 1 >/sys/bus/i2c/drivers_autoprobe
		modprobe as9888_i2c
		[ -e "/sys/bus/i2c/devices/$client/driver" ] ||
			echo "$client" >/sys/bus/i2c/drivers/as9888_i2c/bind
		# restore@ applies the board's record first: not during the test
		wait_dev && wait_applied
		speed_run iio --backend iio
	done
	echo 1 >/sys/bus/i2c/drivers_autoprobe
	best_raw=$(sort -n /root/raw.times 2>/dev/null | head -n 1)
	best_iio=$(sort -n /root/iio.times 2>/dev/null | head -n 1)
	r=$(awk -v i="$best_iio" -v r="$best_raw" 'BEGIN { if (i > 0 && r > 0) printf "%.2f", i / r }')
	echo "BOOTTEST # raw: $(tr '\n' ' ' </root/raw.times 2>/dev/null)ms; iio: $(tr '\n' ' ' </root/iio.times 2>/dev/null)ms"
	echo "BOOTTEST # AS9888-METRIC factory_iio_raw_ratio_stock_kernel=${r:-none} factory_raw_ms=${best_raw:-none} factory_iio_ms=${best_iio:-none} (kernel $(uname -r), best of $rounds each, report duration)"
	check "factory-test speed: --backend raw passed in every round" \
		eval '[ "$(wc -l </root/raw.times 2>/dev/null)" -eq "$rounds" ]'
	check "factory-test speed: --backend iio passed in every round" \
		eval '[ "$(wc -l </root/iio.times 2>/dev/null)" -eq "$rounds" ]'
}
# the magnetometer's calibration in the driver, as the factory phase saved it
magn_applied() { [ -s /root/magn-cal ] && [ "$(magn_cal)" = "$(cat /root/magn-cal)" ]; }

# the plan: 5 checks for every phase, then the phase's own
case $phase in
factory) echo "BOOTTEST plan $((5 + 12 + 2))" ;;
boot) echo "BOOTTEST plan $((5 + 11 + 2 * 5 + 6))" ;;
*)
	echo "BOOTTEST plan 1"
	bad "as9888.phase='$phase' on the kernel command line is not a phase (factory, boot)"
	echo "BOOTTEST done"
	exit 1
	;;
esac
echo "BOOTTEST phase $phase, kernel $(uname -r), systemd $(systemctl --version | awk 'NR == 1 { print $2 }')"
check "the AS9888 IIO device is there (driver from DKMS, adapter at boot)" wait_dev
check "its magnetometer device (as9888-magn) beside it, below the same bus device" \
	eval 'm=$(dev as9888-magn) && [ "$(dirname "$m")" = "$(dirname "$(dev)")" ]'
check "two restore units, one per IIO device (as9888-accel, as9888-magn)" \
	eval '[ "$(systemctl list-units --all --plain --no-legend "as9888-calibd-restore@*" | wc -l)" -eq 2 ] &&
	      systemctl cat "$(restore_unit)" "$(restore_unit as9888-magn)" >/dev/null 2>&1'
check "driver modules from the DKMS tree" eval 'modinfo -n as9888_i2c | grep -q /updates/dkms/'
# (multi-user.target is reached: this unit is ordered after it)
failed=$(systemctl --failed --plain --no-legend | awk '{ print $1 }' | grep -v as9888-boottest | tr '\n' ' ')
check "no failed unit (${failed:-none})" test -z "$failed"

case $phase in
factory)
	check "installed from the .debs: as9888-calibd and as9888-dkms" \
		eval '[ "$(dpkg-query -W -f="\${Status} " as9888-calibd as9888-dkms)" = "install ok installed install ok installed " ]'
	check "the socket enabled by the package, the daemon's service static (no [Install])" \
		eval '[ "$(systemctl is-enabled as9888-calibd.socket)" = enabled ] &&
		      [ "$(systemctl is-enabled as9888-calibd.service)" = static ]'
	u=$(restore_unit)
	check "no record: restore unit $u skipped by its ExecCondition=, not failed" \
		eval '[ -n "$u" ] && [ "$(mono "$u" Result)" = exec-condition ] && [ "$(mono "$u" ActiveState)" = inactive ]'
	m=$(restore_unit as9888-magn)
	check "no record: the magnetometer's restore unit skipped too" \
		eval '[ "$(mono "$m" Result)" = exec-condition ] && [ "$(mono "$m" ActiveState)" = inactive ]'
	warn=$(journalctl -b -q -p warning..warning -o cat | grep -c "no calibration record at $rec" || true)
	check "no record: one warning in the journal (priority warning), saying what to run" \
		eval '[ "$warn" -eq 1 ] &&
		      journalctl -b -q -p warning..warning -o cat -u "$u" | grep -q "factory trims only.*Run as9888-calibd factory-test --backend iio on this board"'
	journalctl -b -q -p warning..warning -o short-monotonic -u "$u" | sed 's/^/BOOTTEST # journal: /'
	check "no record: request status (SocketGroup user) says to run the factory test" \
		eval '! runuser -u tester -- as9888-calibd request status >/tmp/st0.log 2>&1 && grep -q "no record yet: run factory-test first" /tmp/st0.log'
	sed 's/^/BOOTTEST # /' /tmp/st0.log | head -3
	check "and the daemon keeps running" systemctl is-active -q as9888-calibd.service
	check "factory test through the driver writes the record" \
		eval 'as9888-calibd factory-test --backend iio --record "$rec" >/tmp/ft.log 2>&1'
	tail -5 /tmp/ft.log | sed 's/^/BOOTTEST # /'
	check "record written" test -s "$rec"
	# the factory test's speed on this stock kernel, raw bus against the
	# driver, before the board starts tumbling for magn-calibrate
	speed_rounds 5
	# the board's magnetic world (adapter knobs): hard and soft iron, a
	# little noise, and a tumble that turns it a degree a measurement;
	# magn-calibrate takes the field and the acceleration of each
	# measurement from both devices' buffers on the data-ready trigger
	# at 100 Hz, five measurements averaged a sample (with sysfs reads,
	# six measurements a sample, the compass gate refused such a run:
	# see docs/DECISIONS.md). The board then turns five degrees a sample:
	# learning takes a few hundred samples; a loaded host slows the
	# guest, not the turn a measurement, so --timeout 600 only stops a
	# session that stalls
	sim=/sys/kernel/debug/as9888_sim
	echo "48 60 3" >$sim/earth && echo "120 -80 45" >$sim/hard_iron &&
		echo "1.05 0.03 -0.02 0.03 0.95 0.04 -0.02 0.04 1.02" >$sim/soft_iron &&
		echo 0.3 >$sim/magn_noise && echo 1 >$sim/tumble
	check "magn-calibrate through the driver, the board tumbling: stored in <record>.magn, the record format 1" \
		eval 'as9888-calibd magn-calibrate --backend iio --timeout 600 --record "$rec" >/tmp/mc.log 2>&1 &&
		      grep -qx "format = as9888-magnetometer 1" "$rec.magn" &&
		      grep -qx "format = as9888-calibration 1" "$rec"'
	grep -E "^(samples: |Magnetometer calibrated|  field|the magnetometer reads)" /tmp/mc.log |
		sed 's/^/BOOTTEST # /'
	tail -2 /tmp/mc.log | sed 's/^/BOOTTEST # /'
	check "its samples from both devices' buffers on the data-ready trigger" \
		grep -q "^samples: both devices' buffers on as9888-dev" /tmp/mc.log
	echo 0 >$sim/tumble
	# saved only from a session that stored a calibration: the next
	# boots' checks compare with it
	grep -q "^magn_hard_iron = " "$rec.magn" && magn_cal >/root/magn-cal
	echo "BOOTTEST # the driver's magnetometer calibration: $(cat /root/magn-cal 2>/dev/null)"
	check "and applied to the driver (calibbias not the defaults)" \
		eval '[ -s /root/magn-cal ] && ! grep -q "^0 0 0 " /root/magn-cal'
	;;
boot)
	u=$(restore_unit)
	echo "BOOTTEST # restore unit: $u"
	check "calibration applied at boot" applied
	check "by as9888-calibd-restore@ (ran, succeeded)" \
		eval '[ -n "$u" ] && [ "$(mono "$u" ExecMainStatus)" = 0 ] && [ "$(mono "$u" ActiveState)" = active ]'
	mu=$(restore_unit as9888-magn)
	echo "BOOTTEST # the magnetometer's restore unit: $mu"
	check "the magnetometer's calibration (<record>.magn) applied at boot" magn_applied
	check "by the as9888-magn device's own restore@ (ran, succeeded; sandboxed to its directory)" \
		eval '[ "$(mono "$mu" ExecMainStatus)" = 0 ] && [ "$(mono "$mu" ActiveState)" = active ] &&
		      [ "$(systemctl show -P ReadWritePaths "$mu")" = "$(dev as9888-magn)" ]'
	check "before multi-user.target too" \
		eval '[ "$(mono "$mu" ActiveEnterTimestampMonotonic)" -gt 0 ] &&
		      [ "$(mono "$mu" ActiveEnterTimestampMonotonic)" -lt "$(mono multi-user.target ActiveEnterTimestampMonotonic)" ]'
	r=$(mono "$u" ActiveEnterTimestampMonotonic)
	m=$(mono multi-user.target ActiveEnterTimestampMonotonic)
	echo "BOOTTEST # restore done at ${r} us, multi-user.target at ${m} us (monotonic)"
	check "before multi-user.target" test "$r" -gt 0 -a "$r" -lt "$m"
	check "the daemon runs (socket-activated or started)" \
		eval 'systemctl start as9888-calibd.service && systemctl is-active -q as9888-calibd.service'

	# rebind: the driver comes back with its defaults; restore@ (BindsTo)
	# and the daemon apply the record again
	sleep 1
	c0=$(journalctl -q -o cat -u as9888-calibd.service | grep -c "calibration applied to")
	rebind
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

	# an upgrade (the same package with a higher version) keeps the record
	up=$(ls /root/debs-upgrade/as9888-calibd_*.deb)
	upver=$(dpkg-deb -f "$up" Version)
	sum0=$(sha256sum "$rec")
	t=$(date +%s)
	check "upgrade: apt install ./$(basename "$up")" \
		eval 'apt install -y "$up" >/tmp/up.log 2>&1 &&
		      [ "$(dpkg-query -W -f="\${Version}" as9888-calibd)" = "$upver" ]'
	tail -3 /tmp/up.log | sed 's/^/BOOTTEST # /'
	echo "BOOTTEST # the upgrade took $(( $(date +%s) - t )) s"
	check "upgrade: the record unchanged" eval '[ "$(sha256sum "$rec")" = "$sum0" ]'
	check "upgrade: the socket still enabled, the daemon answers" \
		eval 'systemctl is-enabled -q as9888-calibd.socket && as9888-calibd request status >/tmp/st2.log 2>&1'
	check "upgrade: a rebind is applied again" eval 'rebind && wait_applied'

	# purge: nothing of the packages left (the list of the image before they
	# were installed, less what booting creates: lib.sh, snapshot())
	t=$(date +%s)
	check "purge: apt purge as9888-calibd as9888-dkms" \
		eval 'apt purge -y as9888-calibd as9888-dkms >/tmp/purge.log 2>&1 &&
		      ! dpkg-query -W -f="\${Status}" as9888-calibd as9888-dkms 2>/dev/null | grep -q installed'
	echo "BOOTTEST # the purge took $(( $(date +%s) - t )) s"
	snapshot >/tmp/files-after
	LC_ALL=C comm -13 /root/files-before /tmp/files-after >/tmp/files-left
	check "purge: no file left behind ($(wc -l </tmp/files-left) new since before the install)" \
		test ! -s /tmp/files-left
	head -20 /tmp/files-left | sed 's/^/BOOTTEST # left: /'
	;;
*)
	bad "no checks for phase '$phase'"
	;;
esac
echo "BOOTTEST done"
