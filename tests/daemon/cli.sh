#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# as9888-calibd as a user meets it: commands, exit codes, messages, the JSON
# reports, restore refusing foreign or corrupt records, bad input refused
# with nothing lost. Output is TAP.
set -u

calibd=${1:?usage: cli.sh PATH-TO-as9888-calibd [PATH-TO-clock_preload.so]}
preload=${2:-}
work=$(mktemp -d /tmp/as9888-cli-XXXXXX)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
# shellcheck source=../lib/record.sh
. "$(dirname "$0")/../lib/record.sh"
tap_plan 63
json() { python3 -c "import json,sys; d=json.load(open('$work/out')); sys.exit(0 if ($1) else 1)"; }

rec=$work/state/calibration
vt="--sim-clock virtual"

run help
check "help exits 0 and lists the commands" \
	test $rc -eq 0 -a -n "$(grep -e factory-test "$work/out")"
run frobnicate
check "unknown command: exit 2 with a message" eval '[ $rc -eq 2 ] && says "unknown command" err'
for bad in "--samples 9" "--samples 4097" "--samples ten" "--fluctuation -1" \
	   "--gravity up" "--permissible-error 0" "--backend i2c" "--sim-clock fast" \
	   "--temperature 20" "--bogus" "extra"; do
	# shellcheck disable=SC2086
	run factory-test $vt --record "$rec" $bad
	check "factory-test $bad: exit 2, message, nothing written" \
		eval '[ $rc -eq 2 ] && [ -s "$work/err" ] && [ ! -e "$rec" ]'
done

run factory-test --backend raw --i2c-dev "$work/no-such-i2c" --record "$rec"
check "raw backend without the bus: exit 1 naming the device" \
	eval '[ $rc -eq 1 ] && says "cannot open $work/no-such-i2c" err && [ ! -e "$rec" ]'
run factory-test --backend raw --unit "$work/x" --record "$rec"
check "raw backend with a sim option: exit 2" test $rc -eq 2
run factory-test --backend sim --int1-line 3 --record "$rec"
check "sim backend with a raw option: exit 2" test $rc -eq 2
run factory-test --backend raw --i2c-address 0x10 --record "$rec"
check "raw backend, address outside 0x0c..0x0f: exit 2" test $rc -eq 2
# numbers with something before them (strtoul() skips blanks and takes a sign)
for bad in " 1" "+660" " 0660" "-1"; do
	# bounded: a daemon that takes the mode serves until killed
	timeout -s KILL 30 "$calibd" daemon --backend sim --socket "$work/never.sock" \
		--socket-mode "$bad" --record "$rec" >"$work/out" 2>"$work/err"
	rc=$?
	check "daemon --socket-mode \"$bad\": exit 2, named, no socket" \
		eval '[ $rc -eq 2 ] && says "socket-mode takes an octal mode" err && [ ! -e "$work/never.sock" ]'
	rm -f "$work/never.sock"
done
run factory-test --backend raw --i2c-address " 0x0c" --record "$rec"
check "raw backend, address \" 0x0c\": exit 2" eval '[ $rc -eq 2 ] && [ ! -e "$rec" ]'

run factory-test $vt --record "$rec" --json
check "factory-test --json: pass, exit 0" test $rc -eq 0
check "JSON report has the documented fields" json \
	"d['result'] == 'pass' and d['failed_step'] is None and len(d['steps']) > 40 and \
	 all(set(s) >= {'step','name','measured','limits','result'} for s in d['steps']) and \
	 d['calibration']['dac'] == [13, 143, 140] and len(d['calibration']['level_mean']) == 3 and \
	 len(d['calibration']['offset']) == 3 and d['calibration']['gravity'] == [0, 0, -1] and \
	 d['calibration']['samples'] == 10 and abs(d['calibration']['t_level'] - 25) < 1"
check "record written with mode 0644 in a 0755 directory" \
	test "$(stat -c %a "$rec")" = 644 -a "$(stat -c %a "$(dirname "$rec")")" = 755
cp "$rec" "$work/good"
check "the report states the backend" json "d['backend'] == 'sim'"
check "a record made on the simulator says so (source = simulator)" \
	grep -qx "source = simulator" "$rec"

# A clock outside 1970-9999 (issue 25, point 7): time() made to say so by
# clock_preload.so; recalibrate and factory-test refuse to store a record
# that show, restore and rollback would then reject, and say why
if [ -n "$preload" ]; then
	for t in 253402300800 -86400; do
		cp "$work/good" "$work/clock-rec"
		AS9888_TEST_TIME=$t LD_PRELOAD=$preload ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0 \
			"$calibd" recalibrate $vt --record "$work/clock-rec" >"$work/out" 2>"$work/err"
		rc=$?
		check "recalibrate with the clock at $t s: FAIL at step 4-1 naming the clock, record unchanged, no previous" \
			eval '[ $rc -eq 1 ] && says "FAIL at step 4-1" out && says "the system clock is outside 1970-9999, set it first" out &&
			      cmp -s "$work/clock-rec" "$work/good" && [ ! -e "$work/clock-rec.previous" ] &&
			      "$calibd" show --record "$work/clock-rec" >/dev/null'
		AS9888_TEST_TIME=$t LD_PRELOAD=$preload ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0 \
			"$calibd" factory-test $vt --record "$work/clock-new" >"$work/out" 2>"$work/err"
		rc=$?
		check "factory-test with the clock at $t s: FAIL at step 4-1, no record written" \
			eval '[ $rc -eq 1 ] && says "FAIL at step 4-1" out && [ ! -e "$work/clock-new" ]'
	done
	AS9888_TEST_TIME=253402300799 LD_PRELOAD=$preload ASAN_OPTIONS=detect_leaks=1:verify_asan_link_order=0 \
		"$calibd" factory-test $vt --record "$work/clock-new" >/dev/null 2>&1
	check "the clock at the last second of 9999: a valid record (the limit is the format's)" \
		eval '"$calibd" show --record "$work/clock-new" >/dev/null && grep -q "^created = 9999-12-31T23:59:59Z" "$work/clock-new"'
else
	check "clock_preload.so given (the second argument)" false
fi

# No --backend: the driver, else the raw bus, else a failure; never the simulator
mkdir -p "$work/sys"
AS9888_SYSFS=$work/sys run factory-test --record "$work/none/cal"
check "factory-test without --backend, no driver, no bus: exit 1, says what to install, no record" \
	eval '[ $rc -eq 1 ] && says "no AS9888 found" err && says "install the driver" err && \
	      says "the driver is not bound: load as9888_i2c or as9888_spi" err && \
	      says "modprobe i2c-dev" err && says "backend sim" err && [ ! -e "$work/none/cal" ] && \
	      ! says "pass" out'
AS9888_SYSFS=$work/sys run restore --record "$rec"
check "restore without --backend, no driver, no bus: exit 1, nothing done" \
	eval '[ $rc -eq 1 ] && says "no AS9888 found" err'
run restore --backend raw --i2c-dev "$work/no-such-i2c" --record "$rec"
check "restore of a simulator record on a real backend: refused before the bus is opened" \
	eval '[ $rc -eq 1 ] && says "written by a factory test on the simulator" err && \
	      says "nothing applied" err && ! says "no-such-i2c" err'
run restore --backend iio --record "$rec"
check "restore of a simulator record through the driver: refused" \
	eval '[ $rc -eq 1 ] && says "on the simulator" err'
# a record from before the source key: still valid, taken as a chip's
grep -v '^source = ' "$rec" > "$work/old-format"
record_reseal "$work/old-format"
run restore --backend raw --i2c-dev "$work/no-such-i2c" --record "$work/old-format"
check "a record without source reads as a chip's: restore goes on to the bus" \
	eval '[ $rc -eq 1 ] && says "no-such-i2c" err && ! says "simulator" err'
run show --record "$work/old-format"
check "a record without source: show reads it" test $rc -eq 0

run show --record "$rec" --temperature 60 --json
check "show --json: temperature and axes" json \
	"d['temperature'] == 60 and set(d['axes']) == {'x','y','z'} and \
	 abs(d['axes']['x']['sensitivity'] - 219.649) < 0.01 and \
	 abs(d['axes']['x']['offset'] - (d['record']['level_mean'][0] + 2.4 * 35)) < 0.01"
run show --record "$rec" --temperature 86
check "show --temperature 86: exit 2" test $rc -eq 2

run restore $vt --record "$rec"
check "restore: exit 0, quiet" eval '[ $rc -eq 0 ] && [ ! -s "$work/out" ] && [ ! -s "$work/err" ]'

printf 'eeprom = 9a 71 15 5c 81 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 50\n' >"$work/other.unit"
run restore $vt --record "$rec" --unit "$work/other.unit"
check "restore on another chip: refused, exit 1" \
	eval '[ $rc -eq 1 ] && says "belongs to chip" err && says "nothing applied" err'

sed 's/^samples = 10$/samples = 11/' "$work/good" >"$rec"
run restore $vt --record "$rec"
check "restore of an edited record: checksum refused" \
	eval '[ $rc -eq 1 ] && says "checksum mismatch" err'
head -c 100 "$work/good" >"$rec"
run restore $vt --record "$rec"
check "restore of a truncated record: refused" eval '[ $rc -eq 1 ] && says "not a valid record" err'
rm -f "$rec"
run restore $vt --record "$rec"
check "restore without a record: exit 1 naming the file" eval '[ $rc -eq 1 ] && says "$rec" err'
ln -s "$work/good" "$rec"
run restore $vt --record "$rec"
check "restore through a symlink: refused" eval '[ $rc -eq 1 ] && says "symbolic link" err'
run factory-test $vt --record "$rec"
check "factory-test over a symlink: refused, link kept" \
	eval '[ $rc -eq 1 ] && [ -L "$rec" ] && cmp -s "$work/good" "$(readlink "$rec")"'
rm -f "$rec"
cp "$work/good" "$rec"

printf 'fault = selftest_weak\n' >"$work/weak.unit"
run factory-test $vt --record "$rec" --unit "$work/weak.unit" --json
check "failing unit: exit 1, failed_step 2-21, old record kept" \
	eval '[ $rc -eq 1 ] && cmp -s "$work/good" "$rec"' 
check "failing unit: JSON says fail at 2-21" json \
	"d['result'] == 'fail' and d['failed_step'] == '2-21' and d['calibration'] is None"

printf 'up = 0 0 1\nnoise = lots\n' >"$work/bad.unit"
run factory-test $vt --record "$rec" --unit "$work/bad.unit"
check "bad unit file: exit 1 with file and line" eval '[ $rc -eq 1 ] && says "bad.unit:2" err'

mkfifo "$work/fifo.unit"
timeout 60 "$calibd" factory-test $vt --record "$rec" --unit "$work/fifo.unit" >"$work/out" 2>"$work/err"
rc=$?
check "a FIFO as --unit: refused at once, not waited on" \
	eval '[ $rc -eq 1 ] && says "fifo.unit: not a unit file" err'
run show --record "$rec" --samples 10
check "an option a command does not take is named, not its value" \
	eval '[ $rc -eq 2 ] && says "show does not take --samples" err'

run restore --record "$rec" --device relative/iio:device0
check "restore --device relative/...: exit 2, an absolute sysfs path asked for" \
	eval '[ $rc -eq 2 ] && says "takes the absolute sysfs path" err'
run restore --record "$rec" --backend sim --device /sys/x
check "restore --backend sim --device: exit 2, --device is for the driver" \
	eval '[ $rc -eq 2 ] && says "is for --backend iio" err'
run restore --record "$rec" --device
check "restore --device without a value: exit 2" \
	eval '[ $rc -eq 2 ] && says "needs a value" err'
run factory-test $vt --record "$rec" --device /sys/x
check "--device is restore's: factory-test does not take it" \
	eval '[ $rc -eq 2 ] && says "factory-test does not take --device" err'


# Errors a new integrator meets say what failed, why and what to do
run show --record "$work/none/cal"
check "no record yet: exit 1, says to run the factory test first" \
	eval '[ $rc -eq 1 ] && says "cannot open $work/none/cal: No such file or directory: no record yet: run factory-test first" err'
AS9888_SYSFS=$work/sys run factory-test --backend iio --record "$work/none/cal"
check "--backend iio and no driver bound: exit 1, says to load it or use the raw backend" \
	eval '[ $rc -eq 1 ] && says "no as9888-accel IIO device: the driver is not bound: load as9888_i2c (or as9888_spi)" err && \
	      says "or use --backend raw" err && [ ! -e "$work/none/cal" ]'
# the chip's magnetometer device alone is not the device calibrated
magn=$work/sys-magn/devices/i2c/1-000c/iio:device1
mkdir -p "$magn" "$work/sys-magn/bus/iio/devices"
ln -s ../../../devices/i2c/1-000c/iio:device1 "$work/sys-magn/bus/iio/devices/iio:device1"
printf 'as9888-magn\n' >"$magn/name"
AS9888_SYSFS=$work/sys-magn run factory-test --backend iio --record "$work/none/cal"
check "--backend iio with only the magnetometer device (as9888-magn): exit 1, no as9888-accel device" \
	eval '[ $rc -eq 1 ] && says "no as9888-accel IIO device: the driver is not bound" err && [ ! -e "$work/none/cal" ]'
# a user who may not: nobody when run as root, else this user against
# modes that shut out even the owner
if [ "$(id -u)" -eq 0 ] && id nobody >/dev/null 2>&1; then
	as_user() { setpriv --reuid nobody --regid "$(id -g nobody)" --clear-groups "$@"; }
else
	as_user() { "$@"; }
fi
chmod 0711 "$work"
mkdir -m 0555 "$work/rootdir"
as_user "$calibd" factory-test $vt --record "$work/rootdir/cal" >"$work/out" 2>"$work/err"
rc=$?
check "record directory not writable: exit 1, permission denied: run as root" \
	eval '[ $rc -eq 1 ] && says "$work/rootdir/cal.lock: Permission denied: run as root" err && [ ! -e "$work/rootdir/cal" ]'
as_user "$calibd" daemon --backend sim --socket "$work/rootdir/sock" --record "$work/rootdir/cal" >"$work/out" 2>"$work/err"
rc=$?
check "daemon, socket directory not writable: exit 1, permission denied: run the daemon as root" \
	eval '[ $rc -eq 1 ] && says "cannot listen on $work/rootdir/sock: Permission denied: run the daemon as root" err'
python3 -c 'import socket, sys, time
s = socket.socket(socket.AF_UNIX)
s.bind(sys.argv[1])
s.listen()
time.sleep(120)' "$work/sock" &
listener=$!
for _ in $(seq 100); do [ -S "$work/sock" ] && break; sleep 0.1; done
if [ "$(id -u)" -eq 0 ]; then
	chgrp users "$work/sock" && chmod 0660 "$work/sock"
	group_remedy="run as root, or ask to be added to group users (the socket's SocketGroup=)"
else
	chmod 0 "$work/sock"
	group_remedy="run as root, or ask for SocketGroup"
fi
as_user "$calibd" request status --socket "$work/sock" >"$work/out" 2>"$work/err"
rc=$?
check "socket permission denied: exit 1, run as root or ask for SocketGroup (naming the group)" \
	eval '[ $rc -eq 1 ] && says "cannot reach the daemon at $work/sock: Permission denied: $group_remedy" err'
kill "$listener"
wait "$listener" 2>/dev/null
run request status --socket "$work/no-daemon.sock"
check "no daemon: exit 1, says to start it" \
	eval '[ $rc -eq 1 ] && says "the daemon is not running: systemctl enable --now as9888-calibd.socket" err'

tap_end
