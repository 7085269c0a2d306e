#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
# TAP helpers and device helpers for the guest tests (busybox sh).
T_N=0
T_PASS=0
T_FAIL=0
T_SKIP=0
SIM=/sys/kernel/debug/as9888_sim
MODDIR=/lib/modules/as9888
# record_reseal, record_add_magn: tests/lib/record.sh, shipped by vm-run.sh
# shellcheck source=tests/lib/record.sh
. /tests/record.sh

diag() { echo "# $*"; }
# plan N: the number of checks (ok, not ok, skip) this test file makes, at
# its top. run-all.sh reports planned and made after the file, and the host
# fails a file that made another number. A count that depends on what the
# file finds (a loop over the devices present, a branch that checks more)
# is planned as the number the bench's fixed setup gives. A branch that
# cannot make its checks fails every one of them (nok_for N), so the plan
# never goes down; a branch that adds failures says so with plan_more N,
# next to the checks it adds, with the reason.
T_PLAN=""
T_FILE0=0
plan() { T_PLAN=$1; }
plan_more() { T_PLAN=$((T_PLAN + $1)); }
# bail_rest REASON: the rest of this file cannot run (what it needs is not
# there): every planned check not made yet fails with REASON (at least
# one), so that the count stays true. The file then returns.
bail_rest() {
	_bl_i=$((T_N - T_FILE0))
	nok "$1 (so the file's remaining checks are failed)"
	_bl_i=$((_bl_i + 1))
	while [ $_bl_i -lt "${T_PLAN:-0}" ]; do
		nok "not made: planned check $((_bl_i + 1)) of $T_PLAN ($1)"
		_bl_i=$((_bl_i + 1))
	done
}
# nok_for N NAME REASON: a branch that cannot make its N checks fails
# them all (NAME with REASON, then N - 1 "not made"), so that the file's
# plan stays what it declared at its top
nok_for() {
	if [ -n "${3:-}" ]; then nok "$2" "$3"; else nok "$2"; fi
	_nf_i=1
	while [ $_nf_i -lt "$1" ]; do
		nok "not made: check $((_nf_i + 1)) of $1 after '$2'"
		_nf_i=$((_nf_i + 1))
	done
}
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
# skip NAME REASON: a check that could not be made here. TAP "# SKIP": not a
# pass (T_SKIP, and the host counts it apart), not a failure
skip() {
	T_N=$((T_N + 1)); T_SKIP=$((T_SKIP + 1))
	echo "ok $T_N - $1 # SKIP $2"
}
# check NAME COMMAND...: ok if the command succeeds
check() {
	_ck_n="$1"; shift
	if "$@"; then ok "$_ck_n"; else nok "$_ck_n" "failed: $*"; fi
}
# check_not NAME COMMAND...: ok if the command fails (shell functions allowed)
check_not() {
	_cn_n="$1"; shift
	if "$@"; then nok "$_cn_n" "succeeded: $*"; else ok "$_cn_n"; fi
}
# eq NAME GOT WANT
eq() {
	if [ "$2" = "$3" ]; then ok "$1"; else nok "$1" "got '$2', want '$3'"; fi
}
# is_int VALUE: an optionally signed decimal integer
is_int() {
	case $1 in
	'' | - | *[!0-9-]* | ?*-*) return 1 ;;
	esac
}
# near NAME GOT WANT TOL (integers; GOT that is not one fails)
near() {
	if is_int "$2" && is_int "$3"; then
		_d=$(($2 - $3)); [ $_d -lt 0 ] && _d=$((-_d))
	else
		_d=""
	fi
	if [ -n "$_d" ] && [ $_d -le $4 ]; then ok "$1"; else
		nok "$1" "got '$2', want $3 +- $4"; fi
}

# uptime_s: seconds since boot, as /proc/uptime gives them (10 ms
# resolution); ms_now: the same in whole milliseconds. For wall times.
uptime_s() { cut -d' ' -f1 /proc/uptime; }
ms_now() { awk '{ printf "%d", $1 * 1000 }' /proc/uptime; }

# kmsg_mark NAME: a line "as9888-bench: mark NAME" in the kernel log (at
# KERN_INFO: not on the console); kmsg_since NAME PATTERN: a kernel message
# after the last such mark matches PATTERN (grep). Only the messages of
# what ran since count, however full the log is.
kmsg_mark() { echo "<6>as9888-bench: mark $1" > /dev/kmsg; }
kmsg_since() {
	dmesg | awk -v m="as9888-bench: mark $1" 'index($0, m) { n = NR } { l[NR] = $0 }
		END { for (i = n + 1; n && i <= NR; i++) print l[i] }' | grep -q "$2"
}

load_driver() {
	for m in as9888_core as9888_i2c; do
		grep -q "^$m " /proc/modules || insmod $MODDIR/$m.ko || return 1
	done
}
load_sim() {
	grep -q "^as9888_sim " /proc/modules || insmod $MODDIR/as9888_sim.ko
}

# --- the chip's two IIO devices -------------------------------------------------
# The driver registers one IIO device per sensor, both children of the same
# bus device (the i2c client or spi device): "as9888-accel" (accelerometer,
# temperature, calibration, the chip's data-ready trigger "as9888-dev<N>",
# N = its device number) and "as9888-magn" (magnetometer, selftest).
ACCEL_NAME=as9888-accel
MAGN_NAME=as9888-magn
# iio_dev_named NAME: the first IIO device directory with that name
iio_dev_named() {
	for _dn_d in /sys/bus/iio/devices/iio:device*; do
		[ "$(cat "$_dn_d/name" 2>/dev/null)" = "$1" ] && { echo "$_dn_d"; return 0; }
	done
	return 1
}
# The accelerometer's IIO device directory of the AS9888, or empty
iio_dev() { iio_dev_named $ACCEL_NAME; }
# magn_of ACCEL_DIR: the magnetometer device of the same chip, the sibling
# named as9888-magn under the same bus device, as /sys/bus/iio/devices/...
magn_of() {
	_mo_p=$(readlink -f "$1") || return 1
	for _mo_d in "${_mo_p%/*}"/iio:device*; do
		[ "$(cat "$_mo_d/name" 2>/dev/null)" = $MAGN_NAME ] &&
			{ echo "/sys/bus/iio/devices/${_mo_d##*/}"; return 0; }
	done
	return 1
}
# dev_id DIR: the identity of a device directory (its kernfs inode, which a
# new device never shares with a removed one, unlike the device number)
dev_id() { stat -L -c %i "$1" 2>/dev/null; }
# dr_trig: the name of the chip's data-ready trigger, "as9888-dev<N>" with N
# the accel device's number, if such a trigger exists
dr_trig() {
	_dt_t=as9888-dev${DEV##*iio:device}
	grep -qx "$_dt_t" /sys/bus/iio/devices/trigger*/name 2>/dev/null && echo "$_dt_t"
}
# dev_stale: the chip's devices are about to be re-created (a new unit, an
# unbind/bind, a module reload): remember the present accel device, so that
# wait_dev waits for another one. set_unit and rebind call it; a test that
# re-creates the device by other means calls it first.
DEV_STALE=""
dev_stale() {
	_ds_d=$(iio_dev) && DEV_STALE=$(dev_id "$_ds_d") || DEV_STALE=""
}
# dev_ready ACCEL_DIR: the chip's devices are there and probed: a readable
# name on both, the same parent, the parent bound to its driver, and (INT1
# wired: sampling_frequency) the data-ready trigger registered
dev_ready() {
	_dr_m=$(magn_of "$1") || return 1
	[ "$(cat "$_dr_m/name" 2>/dev/null)" = $MAGN_NAME ] || return 1
	[ -e "$(readlink -f "$1")/../driver" ] || return 1
	if [ -e "$1/sampling_frequency" ]; then
		grep -qx "as9888-dev${1##*iio:device}" /sys/bus/iio/devices/trigger*/name 2>/dev/null ||
			return 1
	fi
	return 0
}
# wait_dev [SECONDS]: wait (default 10 s) for the chip's devices: sets DEV
# (accel) and MDEV (magn). After dev_stale, only a device other than the one
# remembered counts (a re-created device may reuse the number of the old).
# A timeout says on stderr (the console) what it waited for and what was
# there.
wait_dev() {
	_wd_i=0
	_wd_n=$((${1:-10} * 10))
	while [ $_wd_i -lt $_wd_n ]; do
		if _wd_a=$(iio_dev); then
			_wd_id=$(dev_id "$_wd_a")
			if [ -n "$_wd_id" ] && [ "$_wd_id" != "$DEV_STALE" ] && dev_ready "$_wd_a" &&
				[ "$(dev_id "$_wd_a")" = "$_wd_id" ]; then
				DEV=$_wd_a
				MDEV=$(magn_of "$_wd_a")
				DEV_STALE=""
				return 0
			fi
		fi
		sleep 0.1; _wd_i=$((_wd_i + 1))
	done
	_wd_have=""
	for _wd_d in /sys/bus/iio/devices/iio:device*; do
		[ -e "$_wd_d" ] && _wd_have="$_wd_have ${_wd_d##*/}=$(cat "$_wd_d/name" 2>/dev/null)(inode $(dev_id "$_wd_d"))"
	done
	echo "# wait_dev: no probed $ACCEL_NAME + $MAGN_NAME pair${DEV_STALE:+ other than the accel device of inode $DEV_STALE} within ${1:-10} s; present:${_wd_have:- none}" >&2
	# paths where every read and write fails
	DEV=/nonexistent-iio-device
	MDEV=/nonexistent-iio-device
	return 1
}
# chip_gone: neither of the chip's IIO devices is left, nor its trigger
chip_gone() {
	! iio_dev > /dev/null && ! iio_dev_named $MAGN_NAME > /dev/null &&
		! grep -q '^as9888-dev' /sys/bus/iio/devices/trigger*/name 2>/dev/null
}
# set_unit "key = value" ...: one line per argument; re-instantiates the chip
set_unit() {
	_u=""
	for l in "$@"; do _u="$_u$l
"; done
	dev_stale
	printf '%s' "$_u" > $SIM/unit
}
# bus_drv: the driver directory of the bus device (i2c or spi)
bus_drv() { readlink -f "$(readlink -f "$DEV")/../driver"; }
# rebind: unbind and bind the chip's bus device (DEV set by wait_dev); then
# wait_dev waits for the new devices
rebind() {
	_rb_b=$(bus_drv)
	_rb_c=$(basename "$(readlink -f "$DEV/..")")
	dev_stale
	echo "$_rb_c" > "$_rb_b/unbind" && echo "$_rb_c" > "$_rb_b/bind"
}
client() { cut -d' ' -f2 $SIM/bus; }
# raw_line GPIOINFO NAME: the number of the line AS9888_NAME in a listing
raw_line() { sed -n "s/^[[:space:]]*line *\([0-9]*\): *\"AS9888_$2\".*/\1/p" "$1"; }
# The daemon tests' healthy unit (80 and 82 to 86): a level board at
# 25 degC whose offsets the factory test trims away
HEALTHY_UNIT="temperature = 25
offset = 40 -25 60
noise = 0.5
seed = 7"
# daemon_fixture: /tmp/rec, the record of HEALTHY_UNIT from the factory
# test through the driver, as 80-daemon.sh leaves it; made here when 80 did
# not run (AS9888_VM_ONLY without it). Leaves the chip as that unit, the
# driver bound
daemon_fixture() {
	[ -s /tmp/rec ] && return 0
	diag "no /tmp/rec of 80-daemon.sh: the factory test through the driver on its unit makes it"
	load_sim
	load_driver
	dev_stale
	printf '%s\n' "$HEALTHY_UNIT" > $SIM/unit
	wait_dev 5 &&
		/bin/as9888-calibd factory-test --backend iio --record /tmp/rec > /tmp/fixture.log 2>&1 ||
		sed 's/^/# fixture: /' /tmp/fixture.log
}
# supply_settled: the kernel switches off every unused regulator once,
# 30 s after its late initcalls (drivers/regulator/core.c,
# regulator_init_complete, a delayed work item). With no driver bound, the
# chip's supply has no consumer: a raw-bus run at that moment loses the
# chip's power under it (the chip NAKs, INT1 stays low). Waits until that
# has happened: the kernel's "as9888-sim-supply: disabling" line, or, when
# the supply was in use or off then (no line), 45 s after the first
# "Freeing unused kernel" line, which comes right after the late initcalls
# (15 s for a work item late on a loaded guest). Without that line (the
# log wrapped, long after boot) it has happened.
SUPPLY_SETTLE_S=45
supply_settled() {
	_ss_t=$(dmesg | sed -n 's/^\[ *\([0-9]*\)\.[0-9]*\] Freeing unused kernel.*/\1/p' | head -n 1)
	[ -n "$_ss_t" ] || return 0
	_ss_end=$((_ss_t + SUPPLY_SETTLE_S))
	_ss_said=""
	while [ "$(cut -d. -f1 /proc/uptime)" -lt $_ss_end ] &&
		! dmesg | grep -q 'as9888-sim-supply: disabling'; do
		[ -n "$_ss_said" ] || diag "waiting for the kernel's switch-off of unused regulators (by uptime $_ss_end s) before the raw bus is used"
		_ss_said=1
		sleep 1
	done
}
# raw_find GPIOINFO: where the chip is for --backend raw, by name: the
# adapter as9888-sim-i2c (BUS), the as9888 client on it (CLIENT, ADDR), the
# GPIO chip as9888-sim-gpio (GCHIP, its lines listed into GPIOINFO) and its
# lines RSTN, INT1, INT2; RAW: the daemon's options for all of them, once the supply_settled
raw_find() {
	supply_settled
	BUS=""
	for _rf_n in /sys/bus/i2c/devices/i2c-*/name; do
		[ "$(cat "$_rf_n")" = as9888-sim-i2c ] && BUS=$(basename "$(dirname "$_rf_n")")
	done
	CLIENT=""
	for _rf_n in "/sys/bus/i2c/devices/${BUS#i2c-}"-*/name; do
		[ "$(cat "$_rf_n" 2>/dev/null)" = as9888 ] && CLIENT=$(basename "$(dirname "$_rf_n")")
	done
	ADDR=0x${CLIENT##*-00}
	GCHIP=$(gpiodetect | sed -n 's/^\([^ ]*\) \[as9888-sim-gpio\].*/\1/p')
	gpioinfo "$GCHIP" > "$1" 2>&1
	RSTN=$(raw_line "$1" RSTN)
	INT1=$(raw_line "$1" INT1)
	INT2=$(raw_line "$1" INT2)
	RAW="--backend raw --i2c-dev /dev/$BUS --i2c-address $ADDR --gpiochip $GCHIP --rstn-line $RSTN --int1-line $INT1 --int2-line $INT2"
}
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
# se_dir DIR: the scan elements directory of an IIO device
se_dir() { if [ -d "$1/scan_elements" ]; then echo "$1/scan_elements"; else echo "$1/buffer0"; fi; }
# scan_bytes DIR: the size of one scan with the elements enabled now, each
# element at an offset that is a multiple of its storage size, the scan a
# multiple of the largest one (the IIO core's layout)
scan_bytes() {
	for _sb_e in "$(se_dir "$1")"/*_en; do
		[ "$(cat "$_sb_e")" = 1 ] || continue
		echo "$(cat "${_sb_e%_en}_index") $(cat "${_sb_e%_en}_type")"
	done | sort -n | awk '{ split($2, a, "/"); b = int((a[2] + 0) / 8)
			off = int((off + b - 1) / b) * b + b; if (b > m) m = b }
		END { if (m) off = int((off + m - 1) / m) * m; print off + 0 }'
}
# buf_start DIR TRIGGER FILE ELEMENTS...: a buffered capture of DIR's IIO
# device on TRIGGER with these scan elements ("accel_x", ...; "all": every
# one the device has) into FILE, read by a background cat (BUF_PID).
# Fails if the buffer does not start.
buf_start() {
	_bs_dir=$1; _bs_trg=$2; _bs_out=$3; shift 3
	_bs_se=$(se_dir "$_bs_dir")
	for _bs_e in "$_bs_se"/*_en; do echo 0 > "$_bs_e"; done
	if [ "$1" = all ]; then
		for _bs_e in "$_bs_se"/*_en; do echo 1 > "$_bs_e"; done
	else
		for _bs_c in "$@"; do echo 1 > "$_bs_se/in_${_bs_c}_en"; done
	fi
	echo "$_bs_trg" > "$_bs_dir/trigger/current_trigger"
	echo 4096 > "$_bs_dir/buffer/length"
	: > "$_bs_out"
	echo 1 > "$_bs_dir/buffer/enable" || return 1
	# (the reader's errors, e.g. ENODEV when the device goes, in FILE.err)
	cat "/dev/iio:device${_bs_dir##*iio:device}" >> "$_bs_out" 2> "$_bs_out.err" &
	BUF_PID=$!
}
# buf_drain DIR PID FILE: after the buffer was turned off, the reader
# drains what is left (until FILE stops growing, at most 5 s), is stopped,
# and the trigger detached
buf_drain() {
	_bd_i=0; _bd_s=-1
	while [ $_bd_i -lt 50 ] && [ "$(wc -c < "$3")" != "$_bd_s" ]; do
		_bd_s=$(wc -c < "$3"); sleep 0.2; _bd_i=$((_bd_i + 1))
	done
	kill "$2" 2>/dev/null
	wait "$2" 2>/dev/null
	echo "" > "$1/trigger/current_trigger"
}
# buf_stop DIR PID FILE: buffer off, then buf_drain
buf_stop() {
	echo 0 > "$1/buffer/enable"
	buf_drain "$@"
}
# wait_grow FILE BYTES: until FILE holds BYTES more than now; 60 s without
# that is a stall (fails)
wait_grow() {
	_wg_w=$(($(wc -c < "$1") + $2)); _wg_i=0
	while [ "$(wc -c < "$1")" -lt $_wg_w ]; do
		[ $_wg_i -ge 600 ] && return 1
		sleep 0.1; _wg_i=$((_wg_i + 1))
	done
}
# samples FILE; monotonic FILE; zbad FILE
samples() { echo $(($(wc -c < "$1") / 16)); }
monotonic() {
	od -A n -t d8 -v "$1" | awk 'NF == 2 { if (n++ && $2 <= last) bad++; last = $2 }
		END { exit (n < 2 || bad) }'
}
# the longest time between two samples of a capture, in milliseconds;
# "none" for a capture of fewer than two samples (there is no gap to give)
max_gap_ms() {
	od -A n -t d8 -v "$1" | awk 'NF == 2 { if (n++ && $2 - last > gap) gap = $2 - last; last = $2 }
		END { if (n > 1) printf "%d", gap / 1000000; else printf "none" }'
}
# mean timestamp difference in microseconds
period_us() {
	od -A n -t d8 -v "$1" | awk 'NF == 2 { if (!n++) first = $2; last = $2 }
		END { if (n > 1) printf "%d", (last - first) / (n - 1) / 1000 }'
}
# z samples of a capture not within 1 g +- 4 LSB (a noiseless unit, Z up,
# calibrated with set_cal to its own offsets: only rounding is left, at
# most half a chip LSB = 2 LSB, and the rounding of the output)
# period_ok NAME PERIOD_US WANT_US: a trigger's mean period. Never more
# than 10% faster than asked (the driver's and the trigger's promise); on
# the slow side only a collapse fails (more than twice the period): under
# TCG on a busy host the guest cannot always keep the rate, and the rate
# reached goes to the log (AS9888-METRIC) instead
period_ok() {
	diag "AS9888-METRIC $(echo "$1" | tr -c 'a-zA-Z0-9\n' _)_period_us=$2 (asked $3)"
	if [ -n "$2" ] && [ "$2" -ge $(($3 * 9 / 10)) ] && [ "$2" -le $(($3 * 2)) ]; then
		ok "$1: mean period $2 us, asked $3 us (-10%, +100%)"
	else
		nok "$1: mean period $2 us, asked $3 us (-10%, +100%)"
	fi
}
# (an empty or missing capture prints "no samples", which no count equals)
zbad() {
	od -A n -t d2 -v "$1" 2>/dev/null | awk 'NF == 8 { n++; if ($3 < 1020 || $3 > 1028) bad++ }
		END { if (n) print bad + 0; else print "no samples" }'
}

# --- driver v2: compensated accelerometer data, 1024 LSB per g ---------------
# Every in_accel_*_raw and buffered accelerometer sample is
# rint((raw - Ot(t)) / St(t) * 1024) with the chip's raw reading, the offset
# and sensitivity at the temperature of the same measurement.
G_LSB=1024
# the scale in m/s^2 per LSB: 9.80665 / 1024
G_SCALE=0.009576806
# The calibration is in_accel_{x,y,z}_calibbias, output LSB (1/1024 g):
# minus the zero-g offset O at the EEPROM's reference temperature t_RT with
# the factory DAC value, -O / St_RT * 1024. The driver applies
# Ot(t) = Kote * (t - t_RT) + O and chooses the DAC from it.
#
# BIAS_AWK: awk functions over e[0..20], the EEPROM bytes: bias(i, o, t)
# is the calibbias (unrounded) of axis i's offset o chip LSB at t degC,
# moved to t_RT with Kote (datasheet 6.1, 6.3, 6.5, D4); trt() is t_RT
BIAS_AWK='function s5(v) { v = v % 32; return v >= 16 ? v - 32 : v }
	function trt() { return (176 - (136 + s5(int(e[2] / 8)))) / 1.6 }
	function kote(i,   d, dt) { d = (e[19] - e[20]) / 1.6
		if (e[19] < 40 || e[19] > 224 || e[20] < 40 || e[20] > 224 || d < 10 || d > 80) d = 35
		dt = int(e[7 + i] / 128) * 256 + e[10 + i]
		if (dt >= 256) dt -= 512
		return dt * 1.5 / d }
	function bias(i, o, t) { return -(o + kote(i) * (trt() - t)) / (256 + s5(e[16 + i] % 32)) * 1024 }'
# ee_bytes: the EEPROM of the device under test, 21 decimals, from the
# NVMEM provider beside the IIO device (both children of the bus device)
ee_bytes() {
	for _n in "$(readlink -f $DEV)"/../as9888-eeprom*/nvmem; do
		od -A n -t u1 -v "$_n" | tr -s ' \n' ' '
		break
	done
}
# put_cal BX BY BZ: write the calibbias values as they are
put_cal() {
	echo "$1" > $DEV/in_accel_x_calibbias &&
		echo "$2" > $DEV/in_accel_y_calibbias &&
		echo "$3" > $DEV/in_accel_z_calibbias
}
# set_cal OX OY OZ [T_MDEGC]: load a calibration given as the zero-g
# offset of each axis in chip LSB as the axis reads it with its factory DAC
# value, at T_MDEGC (default 25000): the calibbias values that stand for
# it, rounded. "offset = OX OY OZ" of a unit description is exactly that at
# 25 degC: set_cal with the unit's offsets is a perfect calibration (to a
# quarter chip LSB).
set_cal() {
	put_cal $(echo "$(ee_bytes) $1 $2 $3 ${4:-25000}" | awk "$BIAS_AWK"'
		{ for (i = 0; i < 21; i++) e[i] = $(i + 1)
		  for (i = 0; i < 3; i++) { b = bias(i, $(22 + i), $25 / 1000)
			printf "%d ", b < 0 ? b - 0.5 : b + 0.5 } }')
}
# cal_get: "BX BY BZ", the calibbias values as the driver reads them back
cal_get() {
	echo $(cat $DEV/in_accel_x_calibbias $DEV/in_accel_y_calibbias \
		$DEV/in_accel_z_calibbias 2>&1)
}
# cal_near NAME GOT WANT [TOL]: two calibrations of three values agree
# within TOL output LSB (default 0.501: the driver's integers against the
# unrounded double-precision reference of rec_cal)
cal_near() {
	if echo "$2 | $3" | awk -v t="${4:-0.501}" '{ if (NF != 7) exit 1
		for (i = 1; i <= 3; i++) { d = $i - $(i + 4); if (d > t || d < -t) exit 1 } }'; then
		ok "$1"
	else
		nok "$1" "got '$2', want '$3'"
	fi
}
# dac_get: the offset DAC registers AXDA..AZDA (0x37..0x39) the chip runs
# with, through the IIO core's debugfs register access (which prints
# "0x%X"), as "0xnn 0xnn 0xnn"
dac_get() {
	_d=/sys/kernel/debug/iio/${DEV##*/}/direct_reg_access
	for _r in 0x37 0x38 0x39; do
		echo $_r > $_d && printf '0x%02x\n' $(($(cat $_d)))
	done | tr '\n' ' ' | sed 's/ $//'
}
# bias_dac "BX BY BZ": the DAC register values the driver chooses for
# these calibbias values: the application note's DACopt (6.6, D5) for the
# offset they stand for at t_RT, from the factory DAC, clamped; double
# precision
bias_dac() {
	echo "$(ee_bytes) $1" | awk "$BIAS_AWK"'
		function rint(x,   f) { f = int(x); if (x < 0 && f != x) f--
			if (x - f > 0.5 || (x - f == 0.5 && f % 2)) f++; return f }
		function lin(ga, da) { l = da >= 128 ? da - 128 : -da
			return int(ga / 64) % 2 ? -l : l }
		{ for (i = 0; i < 21; i++) e[i] = $(i + 1)
		  for (i = 0; i < 3; i++) { ga = e[7 + i] % 128
			o = -$(22 + i) * (256 + s5(e[16 + i] % 32)) / 1024
			l = lin(ga, e[13 + i]) - rint((ga % 64 + 16) / 2048 * o)
			if (l > 67) l = 67
			if (l < -67) l = -67
			if (int(ga / 64) % 2) l = -l
			printf "%s0x%02x", i ? " " : "", (l >= 0 ? 128 + l : -l) }
		  printf "\n" }'
}
# is_dec VALUE: a decimal number (optionally signed, with a fraction)
is_dec() {
	echo "$1" | awk '{ exit !(NR == 1 && $0 ~ /^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)$/) }'
}
# within NAME GOT WANT TOL: decimals, |GOT - WANT| <= TOL (a GOT that is
# not a number fails: awk would take it for 0)
within() {
	if is_dec "$2" && awk "BEGIN { d = ($2) - ($3); exit !(d <= $4 && d >= -($4)) }"; then
		ok "$1"
	else
		nok "$1" "got '$2', want $3 +- $4"
	fi
}
# accel_mean N: the mean of N sysfs reads of in_accel_{x,y,z}_raw, "X Y Z"
accel_mean() {
	_i=0
	while [ $_i -lt $1 ]; do
		echo $(cat $DEV/in_accel_x_raw $DEV/in_accel_y_raw $DEV/in_accel_z_raw)
		_i=$((_i + 1))
	done | awk 'NF == 3 { for (i = 1; i <= 3; i++) s[i] += $i; n++ }
		END { if (n) printf "%.3f %.3f %.3f\n", s[1] / n, s[2] / n, s[3] / n }'
}
# accel_near NAME "X Y Z" "WX WY WZ" TOL: every axis within TOL
accel_near() {
	if echo "$2 $3" | awk -v t="$4" '{ if (NF != 6) exit 1
		for (i = 1; i <= 3; i++) { d = $i - $(i + 3); if (d > t || d < -t) exit 1 } }'; then
		ok "$1"
	else
		nok "$1" "got '$2', want '$3' +- $4"
	fi
}
# rec_cal FILE: the calibration a factory record implies, as cal_get prints
# it but unrounded: Ot_L = A + St(t_L) * G per axis (datasheet 6.3-6.5),
# moved from the record's DAC to the factory DAC (6.6: one linear code
# moves the output by 2048 / (gain + 16) LSB), then to t_RT with Kote, as
# calibbias. Double precision, independent of the driver's fixed point.
rec_cal() {
	awk "$BIAS_AWK"'
		function h(s) { return (index("0123456789abcdef", substr(s, 1, 1)) - 1) * 16 + index("0123456789abcdef", substr(s, 2, 1)) - 1 }
		function lin(ga, da) { l = da >= 128 ? da - 128 : -da
			return int(ga / 64) % 2 ? -l : l }
		/^eeprom = / { for (i = 0; i < 21; i++) e[i] = h($(3 + i)) }
		/^dac = / { for (i = 0; i < 3; i++) da[i] = h($(3 + i)) }
		/^level_mean = / { for (i = 0; i < 3; i++) a[i] = $(3 + i) }
		/^t_level = / { tl = $3 }
		/^gravity = / { for (i = 0; i < 3; i++) g[i] = $(3 + i) }
		END {
			for (i = 0; i < 3; i++) {
				gtd = e[16 + i]; ga = e[7 + i] % 128
				kste = -0.428125 + 0.04375 * int(gtd / 32)
				st = (256 + s5(gtd % 32)) * (1 + kste / 100 * (tl - trt()))
				shift = (lin(ga, e[13 + i]) - lin(ga, da[i])) * 2048 / (ga % 64 + 16)
				printf "%s%.4f", i ? " " : "", bias(i, a[i] + st * g[i] + shift, tl)
			}
			printf "\n"
		}' "$1"
}

# The adapter's live environment (no new chip, no new device): the next
# measurement sees it
sim_temp() { echo "$1" > $SIM/temperature; }
sim_up() { echo "$*" > $SIM/up; }
sim_noise() { echo "$1" > $SIM/noise; }
# tmps_of DEGC: the TMPS code of an integer temperature, rint(176 - 1.6 t)
tmps_of() { awk -v t="$1" 'BEGIN { v = 176 - 1.6 * t; printf "%d", v < 0 ? v - 0.5 : v + 0.5 }'; }

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

# --- RSTN and runtime PM ------------------------------------------------------
# rstn_out: "hi" or "lo", the level the driver drives RSTN at now
rstn_out() {
	grep 'AS9888_RSTN' /sys/kernel/debug/gpio | grep -o 'out [a-z]*' | cut -d' ' -f2
}
# pm_dir: the runtime PM directory of the bus device (DEV set by wait_dev)
pm_dir() { echo "$(dirname "$(readlink -f $DEV)")/power"; }
# wait_runtime STATE: the bus device's runtime_status reaches STATE within
# 30 s (autosuspend is 2 s; more is a stall)
wait_runtime() {
	_wr_i=0
	while [ $_wr_i -lt 300 ]; do
		[ "$(cat "$(pm_dir)/runtime_status")" = "$1" ] && return 0
		sleep 0.1; _wr_i=$((_wr_i + 1))
	done
	diag "runtime_status $(cat "$(pm_dir)/runtime_status"), waited for $1"
	return 1
}

# --- iio-sensor-proxy (76-sensor-proxy: Debian 12's 3.0; 76-sensor-proxy-37:
# Debian 13's 3.7) ---------------------------------------------------------------
# The test sets O (its output directory) and PIDS (the processes it starts,
# which sp_stop stops); monitor-sensor writes $O/ms.out, iio-sensor-proxy
# $O/isp.log.
# sp_diag NAME: stdin as diagnostics "# NAME: ...", GLib's message prefix
# "** (prog:pid): DEBUG: 11:21:05.548: " shortened to "DEBUG " (the host
# takes "BUG:" in the serial log for a kernel splat)
sp_diag() {
	sed -e 's/^\*\* ([^)]*): \([A-Za-z-]*\)[ *]*: [0-9:.]*: /\1 /' \
		-e 's/^\([A-Za-z-]*\)[ *]*: [0-9:.]*: /\1 /' -e "s/^/# $1: /"
}
# sp_stop: stop PIDS, udevd and the system bus, and forget their state
sp_stop() {
	for _sp_p in $PIDS; do kill $_sp_p 2>/dev/null; done
	for _sp_p in $PIDS; do wait $_sp_p 2>/dev/null; done
	PIDS=""
	killall systemd-udevd dbus-daemon 2>/dev/null
	rm -rf /run/dbus/* /run/udev/*
}
# sp_udev: systemd-udevd as the system runs it, the coldplug of the iio
# devices, and the checks of what the iio-sensor-proxy rule in force made
# of the accel device (as9888-accel: tagged iio-poll-accel and
# iio-buffer-accel, systemd asked for the service) and of the magn device
# (as9888-magn: untagged)
sp_udev() {
	/lib/systemd/systemd-udevd --daemon 2>$O/udevd.err
	udevadm trigger --action=add --subsystem-match=iio
	udevadm settle --timeout=60
	udevadm info -q property -p "${DEV#/sys}" > $O/props 2>&1
	_sp_t=$(sed -n 's/^IIO_SENSOR_PROXY_TYPE=//p' $O/props)
	diag "udev: as9888-accel: IIO_SENSOR_PROXY_TYPE=$_sp_t"
	check "udev tags the accel device iio-poll-accel (80-iio-sensor-proxy.rules)" \
		sh -c "echo '$_sp_t' | grep -qw iio-poll-accel"
	check "udev tags the accel device iio-buffer-accel" sh -c "echo '$_sp_t' | grep -qw iio-buffer-accel"
	check "udev: no compass or light tag on the accel device" \
		sh -c "! echo '$_sp_t' | grep -q -e compass -e als"
	check "udev asks systemd for iio-sensor-proxy.service" \
		grep -q '^SYSTEMD_WANTS=iio-sensor-proxy.service' $O/props
	udevadm info -q property -p "${MDEV#/sys}" > $O/mprops 2>&1
	_sp_t=$(sed -n 's/^IIO_SENSOR_PROXY_TYPE=//p' $O/mprops)
	diag "udev: as9888-magn: IIO_SENSOR_PROXY_TYPE=$_sp_t"
	check "udev knows the magn device" grep -q "^DEVPATH=.*/${MDEV##*/}\$" $O/mprops
	check "udev: the magn device is not tagged as an accelerometer" \
		sh -c "! echo '$_sp_t' | grep -q accel"
	check "udev: the magn device has no compass or light tag either" \
		sh -c "! echo '$_sp_t' | grep -q -e compass -e als"
}
# sp_wait_line PATTERN: until monitor-sensor has printed a line matching it
# after the first $SEEN lines (120 s of the guest's clock: a stall); sets
# SEEN to that line's number. The bound is time, not a number of looks: on
# a loaded host each look (an awk) is slow. A diagnostic every 15 s tells
# the host's stall watchdog that the wait is bounded and still running.
SEEN=0
sp_wait_line() {
	_sp_t0=$(cut -d. -f1 /proc/uptime)
	_sp_said=0
	while :; do
		_sp_w=$(awk -v from=$SEEN -v pat="$1" 'NR > from && $0 ~ pat { print NR; exit }' $O/ms.out)
		[ -n "$_sp_w" ] && { SEEN=$_sp_w; return 0; }
		_sp_s=$(($(cut -d. -f1 /proc/uptime) - _sp_t0))
		[ $_sp_s -ge 120 ] && return 1
		if [ $_sp_s -ge $((_sp_said + 15)) ]; then
			_sp_said=$_sp_s
			diag "waiting for monitor-sensor's '$1' ($_sp_s s of 120)" >&2
		fi
		sleep 0.1
	done
}
# sp_client: monitor-sensor's first lines: the service, an accelerometer,
# no light sensor, no compass (the magnetometer has no tilt-compensated
# heading channel)
sp_client() {
	check "monitor-sensor finds iio-sensor-proxy" sp_wait_line '^\+\+\+ iio-sensor-proxy appeared'
	check "it has an accelerometer" sp_wait_line '^=== Has accelerometer'
	check "it has no ambient light sensor" grep -q '^=== No ambient light sensor' $O/ms.out
	check "it has no compass (the magnetometer has no tilt-compensated heading channel)" \
		sh -c "! grep -q -e '^=== Has compass' -e '^+++ Compass appeared' $O/ms.out"
}
# sp_up_for X Y Z: the posture ("up": the direction gravity pushes the
# chip, as its accelerometer reads it) that puts the device, through the
# mount matrix M (device = M x chip, from the driver), in the screen
# posture whose device-frame reading is X Y Z: chip = M^T V
sp_up_for() {
	echo "$(cat $DEV/in_accel_mount_matrix); $*" | tr ',;' '  ' | awk '{ for (i = 1; i <= 3; i++)
		printf "%d%s", $i * $10 + $(i + 3) * $11 + $(i + 6) * $12, i < 3 ? " " : "\n" }'
}
# sp_postures: at -20, 25 and 70 degC (set live) the unit is stepped
# through the four screen postures and flat; each "Accelerometer
# orientation changed" line must name the orientation worked out here from
# the mount matrix with iio-sensor-proxy's rule, on the device frame, whose
# readings it takes in the Windows convention (the vector points where
# gravity pulls: -1 g on Y when the device stands in its normal posture;
# this driver, as IIO accelerometers do, reads +1 g on the axis that points
# up, so a board's mount matrix carries the sign, see README): X beyond 35
# degrees from the screen plane: right-up (X reads -g) or left-up; else Y
# beyond 35 degrees: normal (Y reads -g) or bottom-up; else (flat) no
# change. A line has 120 s to come (sp_wait_line).
sp_postures() {
	diag "mount matrix: $(cat $DEV/in_accel_mount_matrix)"
	printf '%s\n' "normal:0 -1 0" "left-up:1 0 0" "bottom-up:0 1 0" "right-up:-1 0 0" > $O/steps
	for _sp_c in -20 25 70; do
		sim_temp $_sp_c
		while IFS=: read _sp_name _sp_v; do
			sim_up $(sp_up_for $_sp_v)
			if sp_wait_line "orientation changed: $_sp_name\$"; then
				ok "$_sp_c degC: device $_sp_name (chip up $(sp_up_for $_sp_v)): monitor-sensor says $_sp_name"
			else
				nok "$_sp_c degC: device $_sp_name (chip up $(sp_up_for $_sp_v)): monitor-sensor says $_sp_name" \
					"saw: $(tail -n 3 $O/ms.out | tr '\n' '|'); raw now $(cat $DEV/in_accel_x_raw $DEV/in_accel_y_raw $DEV/in_accel_z_raw | tr '\n' ' ')"
				grep -e "Accel read" -e "quirk applied" $O/isp.log | tail -n 2 | sp_diag isp
				SEEN=$(wc -l < $O/ms.out)
			fi
		done < $O/steps
		# flat: no orientation change; the last one stays
		sim_up $(sp_up_for 0 0 -1)
		sleep 3
		eq "$_sp_c degC: flat: no orientation change (right-up stays)" \
			"$(awk -v from=$SEEN 'NR > from && /orientation changed/' $O/ms.out)" ""
	done
}

# --- the magnetometer's calibration (88-magn-calib, 89-magn-restore) ----------
# mg ATTR: "X Y Z" of the magn device's in_magn_{x,y,z}_ATTR (an error as
# its message)
mg() { echo $(for _mg_a in x y z; do cat $MDEV/in_magn_${_mg_a}_$1 2>&1; done); }
# magn_board [KEY = VALUE...]: a unit (tests/model/as9888_unit.h; the
# accelerometer's noise and the like as arguments) with a magnetic world:
# level, sensor axes on East-North-Up, Earth 48 uT inclined 60 degrees
# down, declination 30 degrees, so the true field in the sensor frame is
# 48 * (cos 60 sin 30, cos 60 cos 30, -sin 60) = MAGN_TRUE (uT); hard iron
# MAGN_HARD and a diagonal soft iron MAGN_SOFT (the chip reads S B + h)
MAGN_TRUE="12.000 20.785 -41.569"
MAGN_HARD="150.000 -80.000 60.000"
MAGN_SOFT="1.08 0 0 0 0.93 0 0 0 1.02"
# its calibscale, 1 / diag(S) to the micro
MAGN_CALIBSCALE="0.925926 1.075269 0.980392"
magn_board() {
	set_unit "temperature = 25" "orientation = 1 0 0 0" \
		"earth = 48 60 30" "hard_iron = $MAGN_HARD" "soft_iron = $MAGN_SOFT" "$@"
}
# magn_iron on|off: the board's hard and soft iron, live (adapter knobs);
# off: none. The magnetometer's self-test reads the field too, so a
# factory test runs with it off (in a low field, as the note asks)
magn_iron() {
	if [ "$1" = on ]; then
		echo "$MAGN_HARD" > $SIM/hard_iron && echo "$MAGN_SOFT" > $SIM/soft_iron
	else
		echo "0 0 0" > $SIM/hard_iron && echo "1 0 0 0 1 0 0 0 1" > $SIM/soft_iron
	fi
}
# magn_bias_of "BX BY BZ": rint(-b / s) per axis (b in uT), s the axis' uT
# per LSB, 0.3 * (EHC + 128) / 256 with the EHC bytes of the chip's EEPROM
magn_bias_of() {
	echo "$1 $(ee_bytes | awk '{ print $5, $6, $7 }')" | awk '{ for (i = 1; i <= 3; i++) {
		v = -$i * 256 / (0.3 * ($(i + 3) + 128))
		printf "%s%d", (i > 1 ? " " : ""), v < 0 ? v - 0.5 : v + 0.5 } }'
}
# magn_is_field "RX RY RZ" TOL_UT: RAW x in_magn_*_scale (gauss) x 100 is
# MAGN_TRUE within TOL_UT uT on every axis
magn_is_field() {
	echo "$1 $(mg scale) $MAGN_TRUE" | awk -v t="$2" '{ if (NF != 9) exit 1
		for (i = 1; i <= 3; i++) { d = $i * $(i + 3) * 100 - $(i + 6)
			if (d > t || d < -t) exit 1 } }'
}
# magn_field_near NAME "RX RY RZ" TOL_UT: a check of magn_is_field
magn_field_near() {
	if magn_is_field "$2" "$3"; then
		ok "$1"
	else
		nok "$1" "raw '$2' x scale '$(mg scale)' is not $MAGN_TRUE uT within $3 uT"
	fi
}
