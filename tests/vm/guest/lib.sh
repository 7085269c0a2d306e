#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
# TAP helpers and device helpers for the guest tests (busybox sh).
T_N=0
T_PASS=0
T_FAIL=0
SIM=/sys/kernel/debug/as9888_sim
MODDIR=/lib/modules/as9888

diag() { echo "# $*"; }
ok() {
	T_N=$((T_N + 1)); T_PASS=$((T_PASS + 1))
	echo "ok $T_N - $1"
}
nok() {
	T_N=$((T_N + 1)); T_FAIL=$((T_FAIL + 1))
	echo "not ok $T_N - $1"
	shift
	[ $# -gt 0 ] && diag "$*"
}
# check NAME COMMAND...: ok if the command succeeds
check() {
	_n="$1"; shift
	if "$@"; then ok "$_n"; else nok "$_n" "failed: $*"; fi
}
# check_not NAME COMMAND...: ok if the command fails (shell functions allowed)
check_not() {
	_n="$1"; shift
	if "$@"; then nok "$_n" "succeeded: $*"; else ok "$_n"; fi
}
# eq NAME GOT WANT
eq() {
	if [ "$2" = "$3" ]; then ok "$1"; else nok "$1" "got '$2', want '$3'"; fi
}
# near NAME GOT WANT TOL (integers)
near() {
	_d=$(($2 - $3)); [ $_d -lt 0 ] && _d=$((-_d))
	if [ -n "$2" ] && [ $_d -le $4 ]; then ok "$1"; else
		nok "$1" "got $2, want $3 +- $4"; fi
}

load_driver() {
	for m in as9888_calib as9888_core as9888_i2c; do
		grep -q "^$m " /proc/modules || insmod $MODDIR/$m.ko || return 1
	done
}
load_sim() {
	grep -q "^as9888_sim " /proc/modules || insmod $MODDIR/as9888_sim.ko
}

# The IIO device directory of the AS9888, or empty
iio_dev() {
	for d in /sys/bus/iio/devices/iio:device*; do
		[ -f "$d/name" ] && [ "$(cat "$d/name")" = as9888 ] && { echo "$d"; return 0; }
	done
	return 1
}
# wait_dev [SECONDS]: wait for the IIO device to appear
wait_dev() {
	_i=0
	while [ $_i -lt $((${1:-5} * 10)) ]; do
		DEV=$(iio_dev) && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	# a path where every read and write fails
	DEV=/nonexistent-iio-device
	return 1
}
# set_unit "key = value" ...: one line per argument; re-instantiates the chip
set_unit() {
	_u=""
	for l in "$@"; do _u="$_u$l
"; done
	printf '%s' "$_u" > $SIM/unit
}
client() { cut -d' ' -f2 $SIM/bus; }
stat_get() { sed -n "s/^$1 //p" $SIM/stats; }
# integer rounding of a decimal string times 1000 (e.g. "0.125" -> 125)
milli() {
	echo "$1" | awk '{ printf "%d", ($1 >= 0) ? $1 * 1000 + 0.5 : $1 * 1000 - 0.5 }'
}
# Buffered capture with the device's buffer (DEV set by wait_dev):
# capture TRIGGER SECONDS OUT: accel x/y/z + timestamp, 16 bytes a sample
capture() {
	N=${DEV##*iio:device}
	SE=$DEV/scan_elements
	[ -d "$SE" ] || SE=$DEV/buffer0
	for c in in_accel_x in_accel_y in_accel_z in_timestamp; do
		echo 1 > $SE/${c}_en
	done
	echo "$1" > $DEV/trigger/current_trigger
	echo 1024 > $DEV/buffer/length
	echo 1 > $DEV/buffer/enable || return 1
	# one read of the counters per snapshot, so that they agree
	cat $SIM/stats > /tmp/stats0
	sleep "$2"
	cat $SIM/stats > /tmp/stats1
	CAP_M0=$(sed -n 's/^chip_measurements //p' /tmp/stats0)
	CAP_T0=$(sed -n 's/^bus_transfers //p' /tmp/stats0)
	CAP_M1=$(sed -n 's/^chip_measurements //p' /tmp/stats1)
	CAP_T1=$(sed -n 's/^bus_transfers //p' /tmp/stats1)
	echo 0 > $DEV/buffer/enable
	# a disabled, drained buffer blocks a reader: stop it after 5 s
	timeout 5 cat /dev/iio:device$N > "$3"
	echo "" > $DEV/trigger/current_trigger
}
# samples FILE; monotonic FILE; zvals FILE
samples() { echo $(($(wc -c < "$1") / 16)); }
monotonic() {
	od -A n -t d8 -v "$1" | awk 'NF == 2 { if (n++ && $2 <= last) bad++; last = $2 }
		END { exit (n < 2 || bad) }'
}
# mean timestamp difference in microseconds
period_us() {
	od -A n -t d8 -v "$1" | awk 'NF == 2 { if (!n++) first = $2; last = $2 }
		END { if (n > 1) printf "%d", (last - first) / (n - 1) / 1000 }'
}
zbad() {
	od -A n -t d2 -v "$1" | awk 'NF == 8 { if ($3 < 248 || $3 > 268) bad++ } END { print bad + 0 }'
}

leak_check() {
	[ -f /sys/kernel/debug/kmemleak ] || { nok "kmemleak available"; return; }
	echo scan > /sys/kernel/debug/kmemleak
	sleep 6
	echo scan > /sys/kernel/debug/kmemleak
	_l=$(cat /sys/kernel/debug/kmemleak)
	if [ -z "$_l" ]; then ok "kmemleak: no leaks"; else
		echo "$_l" | head -40 | sed 's/^/# /'
		nok "kmemleak: no leaks"
	fi
}
