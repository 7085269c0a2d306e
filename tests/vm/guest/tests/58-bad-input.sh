# SPDX-License-Identifier: GPL-2.0
# Every writable attribute of the IIO device rejects bad input and keeps
# its value. The attributes are found by listing; one without an entry in
# bad_values() fails the test, so a new attribute needs its bad input here.
#
# Booleans are parsed by kstrtobool(), which looks at the first character
# ("1abc" is 1) like every sysfs boolean, so their junk starts the string.
# Empty input is the newline that echo writes.
set_unit "temperature = 25" "noise = 0"
wait_dev 5
# values that differ from the defaults, so that a change shows
set_cal 12.5 -3.25 0.000016 30000
echo 4 > $DEV/in_accel_oversampling_ratio
OVF=99999999999999999999

# bad_values ATTR: one bad value per line for ATTR (relative to $DEV);
# status 2: the attribute has its own checks below
bad_values() {
	case "$1" in
	in_accel_[xyz]_calibbias)
		printf '%s\n' "" abc 68 -68 1.5 $OVF 4294967297 "1 2" 5abc "5 junk" ;;
	in_accel_[xyz]_caliboffset)
		# decimal, up to 6 places, |v| <= 8192 chip LSB
		printf '%s\n' "" abc 8192.000001 -8192.000001 8193 -9000 1.0000001 \
			"1." ".5" "-.5" "1.2.3" "--1" "+1" "- 1" 1e3 0x10 "1 2" 5abc \
			"5 junk" 1.5x $OVF 4294967296 4294967297.5 "1,5" nan ;;
	in_accel_calibtemp)
		# integer mdegC, -30000..85000 (the valid TMPS range)
		printf '%s\n' "" abc 85001 -30001 90000 -40000 25000.5 $OVF \
			4294992296 "25000 1" 25000abc "25 000" 0x61a8x ;;
	in_accel_oversampling_ratio)
		printf '%s\n' "" abc 0 2 3 8 16 -1 -4 1.5 4.0001 $OVF "1 4" 4abc ;;
	scan_elements/*_en | buffer0/*_en | buffer/enable | buffer0/enable)
		printf '%s\n' "" abc 2 -1 $OVF x1 ;;
	sampling_frequency)
		printf '%s\n' "" abc 0 3 1000 -5 100.5 $OVF "100 200" 100abc ;;
	selftest)
		printf '%s\n' "" 0 2 abc -1 $OVF x ;;
	buffer/length | buffer0/length)
		printf '%s\n' "" abc -1 $OVF "1 2" 5abc 1.5 ;;
	buffer/watermark | buffer0/watermark)
		printf '%s\n' "" abc 0 -1 $OVF "1 2" 5abc 999999 ;;
	trigger/current_trigger)
		# the IIO core takes any unknown name as "no trigger": below
		return 2 ;;
	current_timestamp_clock)
		printf '%s\n' "" abc "realtime junk" monotonic_rawx ;;
	power/control)
		printf '%s\n' "" abc onn "on x" ;;
	power/autosuspend_delay_ms)
		printf '%s\n' "" abc $OVF "1 2" 5abc 1.5 ;;
	uevent)
		printf '%s\n' "" abc "addx" ;;
	# info attributes without a write_raw case: every write fails
	in_*_raw | in_*_scale | in_*_offset)
		printf '%s\n' "" 0 1 -1 abc $OVF 1.5 ;;
	*)
		return 1 ;;
	esac
}

# try ATTR: write every bad value; prints the values that were accepted
try() {
	bad_values "$1" | while IFS= read -r v; do
		echo "$v" > "$DEV/$1" 2>/dev/null && echo "'$v'"
	done
}

W=$(cd $DEV && find . -perm -200 -type f | sed 's|^\./||' | sort)
diag "writable attributes: $(echo $W)"
check "at least 40 writable attributes found ($(echo "$W" | wc -l))" test "$(echo "$W" | wc -l)" -ge 40
for f in $W; do
	bad_values "$f" > /dev/null
	case $? in
	0) ;;
	2) continue ;;
	*) nok "$f: covered by the bad-input table"; continue ;;
	esac
	before=$(cat "$DEV/$f" 2>&1)
	acc=$(try "$f")
	after=$(cat "$DEV/$f" 2>&1)
	if [ -n "$acc" ]; then
		nok "$f: every bad write rejected" "accepted: $(echo $acc)"
	elif [ "$after" != "$before" ]; then
		nok "$f: every bad write rejected, value unchanged" "'$before' became '$after'"
	else
		ok "$f: $(bad_values "$f" | wc -l) bad writes rejected, value unchanged"
	fi
done

# current_trigger: an unknown name detaches the trigger, like "" (IIO core)
T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
echo "$T" > $DEV/trigger/current_trigger
echo as9888-nosuch > $DEV/trigger/current_trigger
eq "current_trigger: an unknown name leaves no trigger (IIO core)" \
	"$(cat $DEV/trigger/current_trigger)" ""

# While the buffer runs, valid writes that would change it are refused too
SE=$DEV/scan_elements
for f in $SE/*_en; do echo 0 > $f; done
echo 1 > $SE/in_accel_x_en
echo "$T" > $DEV/trigger/current_trigger
echo 1 > $DEV/buffer/enable
# busy ATTR VALUE: the write fails and the value stays
busy() {
	_b=$(cat "$DEV/$1")
	if echo "$2" > "$DEV/$1" 2>/dev/null; then
		nok "buffer on: '$2' > $1 refused"
	else
		eq "buffer on: '$2' > $1 refused, value unchanged" "$(cat "$DEV/$1")" "$_b"
	fi
}
busy scan_elements/in_accel_x_en 0
busy scan_elements/in_magn_x_en 1
busy buffer0/in_accel_y_en 1
busy buffer/length 64
busy trigger/current_trigger ""
# (calibbias is taken between two samples: 72-concurrency)
busy in_accel_oversampling_ratio 1
busy selftest 1
echo 0 > $DEV/buffer/enable
echo "" > $DEV/trigger/current_trigger
echo 1 > $DEV/in_accel_oversampling_ratio
eq "oversampling_ratio: the values available" \
	"$(cat $DEV/in_accel_oversampling_ratio_available)" "1 4"
set_cal 0 0 0 25000
