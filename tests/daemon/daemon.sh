#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The long-running daemon: calibration applied when an AS9888 IIO device
# appears (kernel uevents, here sent by the test into a private network
# namespace, against a sysfs tree laid out like the driver's), requests on
# the socket (status, check, recalibrate, rollback; bad ones refused;
# concurrent ones serialised), the socket's permissions, idle cost, clean
# stop on SIGTERM. Output is TAP; prints the idle CPU and memory figures and
# the time from device appearance to calibration applied.
set -u

calibd=${1:?usage: daemon.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
if [ -z "${AS9888_IN_NETNS:-}" ]; then
	# uevents sent by the test must reach nobody else: a network namespace
	if [ "$(id -u)" -eq 0 ] && unshare --net true 2>/dev/null; then
		AS9888_IN_NETNS=1 exec unshare --net "$0" "$calibd"
	fi
	echo "1..0 # SKIP needs root for a private network namespace"
	exit 77
fi

work=$(mktemp -d /tmp/as9888-daemon-XXXXXX)
export ASAN_OPTIONS=detect_leaks=1
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
tap_plan 15
TAP_SHOW="$work/log"

# uevent MESSAGE-FIELDS...: multicast a kernel-style uevent (group 1)
uevent() {
	python3 - "$@" <<'PY'
import socket, sys
msg = b"\0".join(a.encode() for a in sys.argv[1:]) + b"\0"
s = socket.socket(socket.AF_NETLINK, socket.SOCK_DGRAM, 15)
s.bind((0, 0))
s.sendto(msg, (0, 1))
PY
}

# a sysfs tree like the driver's, as in test_uevent_iio.c
sys=$work/sys
bus=$sys/devices/i2c/1-000c
dev=$bus/iio:device0
# with the chip's magnetometer device beside its accelerometer's
mkdir -p "$dev" "$bus/iio:device2" "$bus/as9888-eeprom0" "$sys/bus/iio/devices" \
	"$sys/devices/i2c/1-0050/iio:device1"
ln -s ../../../devices/i2c/1-000c/iio:device0 "$sys/bus/iio/devices/iio:device0"
ln -s ../../../devices/i2c/1-000c/iio:device2 "$sys/bus/iio/devices/iio:device2"
printf 'as9888-accel\n' >"$dev/name"
printf 'as9888-magn\n' >"$bus/iio:device2/name"
printf 'bmc150_accel\n' >"$sys/devices/i2c/1-0050/iio:device1/name"
printf '\x9a\x71\x15\x5c\x80\x85\x7b\x1c\x63\xa2\x38\xe6\x9c\x0d\x8f\x8c\x04\x65\xc3\x88\x50' \
	>"$bus/as9888-eeprom0/nvmem"
# the driver's state after probe, but for a calibbias no record here
# gives (4711), so that applying one shows
reset_attrs() {
	for a in x y z; do
		printf '4711\n' >"$dev/in_accel_${a}_calibbias"
	done
}
reset_attrs
export AS9888_SYSFS=$sys

rec=$work/state/calibration
sock=$work/sock
"$calibd" factory-test --sim-clock virtual --record "$rec" --unit /dev/null >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }

"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$sock" 2>"$work/log" &
pid=$!
for _ in $(seq 100); do [ -S "$sock" ] && break; sleep 0.05; done

# every axis' calibbias written
applied() {
	[ "$(cat "$dev/in_accel_x_calibbias")" != 4711 ] &&
		[ "$(cat "$dev/in_accel_y_calibbias")" != 4711 ] &&
		[ "$(cat "$dev/in_accel_z_calibbias")" != 4711 ]
}
wait_applied() {
	for _ in $(seq 200); do applied && return 0; sleep 0.01; done
	return 1
}

check "daemon up, socket mode 0660" test "$(stat -c %a "$sock")" = 660
check "calibration applied to the device present at start" wait_applied

reset_attrs
t0=$(date +%s%N)
uevent "add@/devices/i2c/1-000c/iio:device0" "ACTION=add" \
	"DEVPATH=/devices/i2c/1-000c/iio:device0" "SUBSYSTEM=iio" "DEVTYPE=iio_device"
wait_applied; rc=$?
t1=$(date +%s%N)
check "device added (module reload): calibration applied without being asked" test $rc -eq 0
echo "# appearance to calibration applied: $(sed -n 's/.*applied to .*iio:device0 in \([0-9]*\) us/\1/p' "$work/log" | tail -1) us in the daemon, $(( (t1 - t0) / 1000 )) us seen by the test (python start-up included)"
# the default unit has no offset at 25 degC; at t_RT (23.75 degC) Kote
# makes it -3.0, -12.3 and 5.4 LSB: about 12, 48 and -21 as calibbias
# (-offset / St_RT * 1024), and the level test's noise gives 13, 48, -20
check "calibbias set from the record's level test" \
	test "$(for a in x y z; do cat "$dev/in_accel_${a}_calibbias"; echo; done | tr '\n' ' ')" = "13 48 -20 "

reset_attrs
uevent "bind@/devices/i2c/1-000c" "ACTION=bind" "DEVPATH=/devices/i2c/1-000c" \
	"SUBSYSTEM=i2c" "DRIVER=as9888_i2c"
uevent "add@/devices/i2c/1-000c/iio:device0" "ACTION=add" \
	"DEVPATH=/devices/i2c/1-000c/iio:device0" "SUBSYSTEM=iio" "DEVTYPE=iio_device"
check "driver rebound (bind, then the IIO device's add): calibration applied" wait_applied

reset_attrs
uevent "add@/devices/i2c/1-0050/iio:device1" "ACTION=add" \
	"DEVPATH=/devices/i2c/1-0050/iio:device1" "SUBSYSTEM=iio" "DEVTYPE=iio_device"
# the chip's magnetometer device has no calibration: it applies nothing
uevent "add@/devices/i2c/1-000c/iio:device2" "ACTION=add" \
	"DEVPATH=/devices/i2c/1-000c/iio:device2" "SUBSYSTEM=iio" "DEVTYPE=iio_device"
uevent "remove@/devices/i2c/1-000c/iio:device0" "ACTION=remove" "SUBSYSTEM=iio" "DEVTYPE=iio_device"
sleep 0.3
check "other devices, the magnetometer device and removals leave it alone" eval '! applied'

out=$("$calibd" request status --socket "$sock")
check "request status" eval 'grep -q "^Chip 676f64b435a720ba" <<<"$out" && grep -q "^exit status 0" <<<"$out"'
out=$("$calibd" request check --json --socket "$sock")
check "request check --json" python3 -c "import json,sys; d=json.loads(sys.argv[1]); assert d['advisable'] is False" "$out"
out=$(printf 'recalibrate --force\n' | python3 -c "
import socket, sys
s = socket.socket(socket.AF_UNIX); s.connect('$sock'); s.sendall(sys.stdin.buffer.read())
print(s.recv(4096).decode())")
check "a request with unknown words is refused" grep -q "^error" <<<"$out"
out=$("$calibd" request reboot --socket "$sock")
check "an unknown request is refused" grep -q 'unknown request "reboot"' <<<"$out"

"$calibd" request recalibrate --socket "$sock" >"$work/r1" &
r1=$!
"$calibd" request recalibrate --socket "$sock" >"$work/r2" &
r2=$!
wait $r1 $r2
check "two recalibrations at once both complete" \
	eval 'grep -q "^exit status 0" "$work/r1" && grep -q "^exit status 0" "$work/r2"'
# both in the log, each start after the other's end (no log: no pass)
check "and ran one after the other" python3 - "$work/log" <<'PY'
import sys
busy = False
starts = ends = 0
for line in open(sys.argv[1]):
    if "recalibrate requested" in line:
        assert not busy, "a second recalibration started before the first's end"
        busy = True
        starts += 1
    elif "recalibrate done" in line:
        assert busy, "a recalibration ended that had not started"
        busy = False
        ends += 1
assert starts == 2 and ends == 2, "%d starts and %d ends logged, not 2 and 2" % (starts, ends)
PY
out=$("$calibd" request rollback --socket "$sock")
check "request rollback" grep -q "^exit status 0" <<<"$out"

# idle: no CPU time, no wake-ups (of a daemon that is still running)
idle=$(proc_idle "$pid" 3)
rss=$(awk '/^VmRSS/ { print $2 }' "/proc/$pid/status" 2>/dev/null)
echo "# idle for 3 s: ${idle% *} CPU ticks, ${idle#* } wake-ups, RSS ${rss} kB"
check "idle: no CPU time and no wake-ups" test "$idle" = "0 0"

kill -TERM "$pid"
wait "$pid"; rc=$?
pid=
check "SIGTERM: clean exit, socket removed" \
	eval '[ $rc -eq 0 ] && [ ! -e "$sock" ] && grep -q "stopped: calibration applied 3 times, 0 failures" "$work/log"'

tap_end
