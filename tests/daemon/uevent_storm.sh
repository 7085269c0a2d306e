#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Quiet when nothing happens: a storm of 1000 real kernel uevents of
# another subsystem (`change` written to the loopback interface's uevent
# file) wakes the daemon 0 times, because its netlink socket carries a
# socket filter that drops them in the kernel. Wake-ups are counted as
# daemon.sh counts them (voluntary context switches of the daemon).
# Controls, so that 0 means something: a plain listener in the same place
# receives the storm's 1000 uevents, and 100 iio uevents (not an
# appearance: change) do wake the daemon. Runs in a private network and
# mount namespace, with sysfs mounted there: the loopback device's uevents
# are that namespace's, nobody else sees them. Output is TAP.
set -u

calibd=${1:?usage: uevent_storm.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
storm=${AS9888_STORM:-1000}
if [ -z "${AS9888_IN_NETNS:-}" ]; then
	if [ "$(id -u)" -eq 0 ] && unshare --net --mount true 2>/dev/null; then
		AS9888_IN_NETNS=1 exec unshare --net --mount --propagation private "$0" "$calibd"
	fi
	echo "1..0 # SKIP needs root for a private network and mount namespace"
	exit 77
fi

work=$(mktemp -d /tmp/as9888-storm-XXXXXX)
pid=
listener=
cleanup() {
	[ -n "$pid" ] && kill "$pid" 2>/dev/null
	[ -n "$listener" ] && kill "$listener" 2>/dev/null
	umount "$work/netsys" 2>/dev/null
	rm -rf "$work"
}
trap cleanup EXIT
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
tap_plan 6
TAP_SHOW="$work/log"

# this namespace's sysfs: its /class/net/lo is our loopback device
mkdir "$work/netsys"
mount -t sysfs sysfs "$work/netsys" || { echo "Bail out! cannot mount sysfs"; exit 1; }
lo_uevent=$work/netsys/class/net/lo/uevent

# the daemon against a sysfs tree like the driver's (as daemon.sh)
sys=$work/sys
bus=$sys/devices/i2c/1-000c
dev=$bus/iio:device0
mkdir -p "$dev" "$bus/as9888-eeprom0" "$sys/bus/iio/devices"
ln -s ../../../devices/i2c/1-000c/iio:device0 "$sys/bus/iio/devices/iio:device0"
printf 'as9888-accel\n' >"$dev/name"
printf '\x9a\x71\x15\x5c\x80\x85\x7b\x1c\x63\xa2\x38\xe6\x9c\x0d\x8f\x8c\x04\x65\xc3\x88\x50' \
	>"$bus/as9888-eeprom0/nvmem"
for a in x y z; do
	printf '0\n' >"$dev/in_accel_${a}_calibbias"
done
export AS9888_SYSFS=$sys
rec=$work/state/calibration
sock=$work/sock
"$calibd" factory-test --sim-clock virtual --record "$rec" --unit /dev/null >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }
"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$sock" 2>"$work/log" &
pid=$!
for _ in $(seq 200); do [ -S "$sock" ] && break; sleep 0.05; done
check "daemon up" test -S "$sock"

# a plain uevent listener (no filter) beside it, counting what arrives
python3 - "$work/heard" <<'PY' &
import socket, sys
s = socket.socket(socket.AF_NETLINK, socket.SOCK_DGRAM, 15)
# root: past rmem_max (SO_RCVBUFFORCE), so a lagging listener loses nothing
s.setsockopt(socket.SOL_SOCKET, getattr(socket, "SO_RCVBUFFORCE", 33), 8 << 20)
s.bind((0, 1))
open(sys.argv[1] + ".ready", "w").close()
n = 0
while True:
    m = s.recv(8192)
    if b"\0SUBSYSTEM=net\0" in m and b"@/devices/virtual/net/lo\0" in m:
        n += 1
        with open(sys.argv[1], "w") as f:
            f.write(str(n))
PY
listener=$!
for _ in $(seq 200); do [ -e "$work/heard.ready" ] && break; sleep 0.05; done

switches() { awk '/^voluntary_ctxt_switches/ { print $2 }' "/proc/$pid/status"; }
settle() {	# until the daemon's count stands still for 1 s
	local a b
	b=$(switches)
	for _ in $(seq 30); do
		sleep 1
		a=$b; b=$(switches)
		[ "$a" = "$b" ] && return 0
	done
	return 1
}
settle

w0=$(switches)
for _ in $(seq "$storm"); do echo change >"$lo_uevent"; done
# the listener may lag on a busy machine: up to a minute
for _ in $(seq 600); do [ "$(cat "$work/heard" 2>/dev/null)" = "$storm" ] && break; sleep 0.1; done
sleep 0.5
w1=$(switches)
heard=$(cat "$work/heard" 2>/dev/null || echo 0)
echo "# $storm loopback uevents: the plain listener heard $heard, the daemon woke $((w1 - w0)) times"
check "the storm's uevents reached this namespace ($heard of $storm heard by a plain listener)" \
	test "$heard" -eq "$storm"
check "$storm unrelated uevents: 0 wake-ups of the daemon" test $((w1 - w0)) -eq 0

# control: iio uevents that are not an appearance do reach it
w0=$(switches)
python3 - <<'PY'
import socket
s = socket.socket(socket.AF_NETLINK, socket.SOCK_DGRAM, 15)
s.bind((0, 0))
for i in range(100):
    p = b"/devices/i2c/1-000c/iio:device0"
    s.sendto(b"change@" + p + b"\0ACTION=change\0DEVPATH=" + p +
             b"\0SUBSYSTEM=iio\0DEVTYPE=iio_device\0SEQNUM=%d\0" % i, (0, 1))
    if i % 10 == 9:
        import time; time.sleep(0.02)
PY
sleep 0.5
w1=$(switches)
echo "# 100 iio change uevents: the daemon woke $((w1 - w0)) times"
check "iio uevents still wake it (the count measures wake-ups)" test $((w1 - w0)) -gt 0
check "and it is still serving" eval '"$calibd" request status --socket "$sock" >"$work/status" 2>&1'

kill -TERM "$pid"
wait "$pid"; rc=$?
pid=
check "SIGTERM: clean exit" test $rc -eq 0

tap_end
