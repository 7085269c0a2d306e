#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
# contrib/examples/as9888-compass on a fake sysfs: the heading it prints
# for known raw values, scales, residual matrices and mount matrices.
# TAP output.
set -u
exe=$1
t=$(mktemp -d) || exit 1
trap 'rm -rf "$t"' EXIT
n=0
fails=0

dev() {	# dev DIR NAME
	mkdir -p "$t/bus/iio/devices/$1"
	echo "$2" > "$t/bus/iio/devices/$1/name"
}

put() {	# put DIR ATTR VALUE
	echo "$3" > "$t/bus/iio/devices/$1/$2"
}

vec() {	# vec DIR TYPE X Y Z
	put "$1" "in_$2_x_raw" "$3"
	put "$1" "in_$2_y_raw" "$4"
	put "$1" "in_$2_z_raw" "$5"
}

check() {	# check WANT DESCRIPTION ARGS...
	want=$1 what=$2
	shift 2
	n=$((n + 1))
	got=$("$exe" --sysfs "$t" "$@" 2>&1)
	if [ "$got" = "$want" ]; then
		echo "ok $n - $what"
	else
		echo "not ok $n - $what: got '$got', want '$want'"
		fails=$((fails + 1))
	fi
}

echo "1..8"
check "as9888-compass: no as9888-accel and as9888-magn IIO devices under $t" \
	"no devices: says so"
dev iio:device0 as9888-accel
dev iio:device1 as9888-magn
put iio:device0 in_accel_scale 0.009576806
for a in x y z; do put iio:device1 "in_magn_${a}_scale" 0.003000; done
# level, +Y east: the field (-24, 0, -42) uT = (-0.24, 0, -0.42) G
vec iio:device0 accel 0 0 1024
vec iio:device1 magn -80 0 -140
check "heading 90.0" "level, facing east"
check "heading 100.0" "declination 10 deg east" --declination 10
# a cross term the driver cannot apply: R puts it right
vec iio:device1 magn -80 10 -140
check "heading 82.9" "cross term, no residual matrix: 7 deg off"
check "heading 90.0" "cross term, residual matrix applied" \
	--residual "1 0 0 0.125 1 0 0 0 1"
# the mount matrix turns the sensor by 90 deg: the device faces south
vec iio:device1 magn -80 0 -140
put iio:device0 in_accel_mount_matrix "0, -1, 0; 1, 0, 0; 0, 0, 1"
put iio:device1 in_magn_mount_matrix "0, -1, 0; 1, 0, 0; 0, 0, 1"
check "heading 180.0" "mount matrix"
# R is the sensor's: applied before the mount matrix, not after it
vec iio:device1 magn -80 10 -140
check "heading 180.0" "mount matrix and a cross term: R in the sensor frame" \
	--residual "1 0 0 0.125 1 0 0 0 1"
check "usage: as9888-compass [--sysfs DIR] [--declination DEG] [--residual \"r11 r12 r13 r21 r22 r23 r31 r32 r33\"]" \
	"a bad argument: usage" --residual "1 2 3"
[ $fails -eq 0 ]
