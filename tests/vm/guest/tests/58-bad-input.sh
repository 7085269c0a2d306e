# SPDX-License-Identifier: GPL-2.0
# Every writable attribute of the two IIO devices (as9888-accel and
# as9888-magn) rejects bad input and keeps its value. The attributes are found by listing; one without an entry in
# bad_values() fails the test, so a new attribute needs its bad input here.
#
# Booleans are parsed by kstrtobool(), which looks at the first character
# ("1abc" is 1) like every sysfs boolean, so their junk starts the string.
# Empty input is the newline that echo writes.
set_unit "temperature = 25" "noise = 0"
wait_dev 5
# values that differ from the defaults, so that a change shows
set_cal 12.5 -3.25 0.5 30000
echo 4 > $DEV/in_accel_oversampling_ratio
OVF=99999999999999999999

# bad_values ATTR: one bad value per line for ATTR (relative to the device);
# status 2: the attribute has its own checks below
bad_values() {
	case "$1" in
	in_accel_[xyz]_calibbias)
		# integer, 1/1024 g, |v| <= 8192
		printf '%s\n' "" abc 8193 -8193 9000 1.5 $OVF 4294967297 "1 2" 5abc \
			"5 junk" ;;
	in_magn_[xyz]_calibbias)
		# integer, chip LSB, |v| <= 4096
		printf '%s\n' "" abc 4097 -4097 9000 1.5 $OVF 4294967297 "1 2" 5abc \
			"5 junk" ;;
	in_magn_[xyz]_calibscale)
		# 0.5 .. 2 in millionths (a 7th decimal is dropped by the IIO
		# core: 2.0000001 is 2); no $OVF, which the core's fixed-point
		# parser would wrap
		printf '%s\n' "" abc 0 0.499999 2.000001 3 -1 -0.5 -1.5 99999.5 \
			"1 2" 1abc "1.5 x" 0.4999999 ;;
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

# try DIR ATTR: write every bad value; prints the values that were accepted
try() {
	bad_values "$2" | while IFS= read -r v; do
		echo "$v" > "$1/$2" 2>/dev/null && echo "'$v'"
	done
}
# writable DIR: the writable attributes of a device, relative to it
writable() { (cd "$1" && find . -perm -200 -type f | sed 's|^\./||' | sort); }

WA=$(writable $DEV)
WM=$(writable $MDEV)
# the plan: one check per writable attribute but current_trigger (checked
# apart, below), and 17 more
plan $((17 + $(printf '%s\n' $WA $WM | grep -vcx 'trigger/current_trigger')))
diag "writable attributes of as9888-accel: $(echo $WA)"
diag "writable attributes of as9888-magn: $(echo $WM)"
check "at least 40 writable attributes found on the two devices ($(echo "$WA" | wc -l) + $(echo "$WM" | wc -l))" \
	test $(($(echo "$WA" | wc -l) + $(echo "$WM" | wc -l))) -ge 40
check "the magn device's selftest among them" sh -c "echo '$WM' | grep -qx selftest"
for d in $DEV $MDEV; do
	n=$(cat $d/name)
	for f in $(writable $d); do
		bad_values "$f" > /dev/null
		case $? in
		0) ;;
		2) continue ;;
		*) nok "$n: $f: covered by the bad-input table"; continue ;;
		esac
		before=$(cat "$d/$f" 2>&1)
		acc=$(try "$d" "$f")
		after=$(cat "$d/$f" 2>&1)
		if [ -n "$acc" ]; then
			nok "$n: $f: every bad write rejected" "accepted: $(echo $acc)"
		elif [ "$after" != "$before" ]; then
			nok "$n: $f: every bad write rejected, value unchanged" "'$before' became '$after'"
		else
			ok "$n: $f: $(bad_values "$f" | wc -l) bad writes rejected, value unchanged"
		fi
	done
done

# current_trigger: an unknown name detaches the trigger, like "" (IIO core)
T=$(dr_trig)
for d in $DEV $MDEV; do
	echo "$T" > $d/trigger/current_trigger
	echo as9888-nosuch > $d/trigger/current_trigger
	eq "$(cat $d/name): current_trigger: an unknown name leaves no trigger (IIO core)" \
		"$(cat $d/trigger/current_trigger)" ""
done

# While a buffer runs, valid writes that would change it are refused too
# busy DIR ATTR VALUE: the write fails and the value stays
busy() {
	_b=$(cat "$1/$2")
	if echo "$3" > "$1/$2" 2>/dev/null; then
		nok "$(cat $1/name): buffer on: '$3' > $2 refused"
	else
		eq "$(cat $1/name): buffer on: '$3' > $2 refused, value unchanged" "$(cat "$1/$2")" "$_b"
	fi
}
# buffer_on DIR ELEMENT: DIR's buffer on the data-ready trigger with one
# element; buffer_off DIR
buffer_on() {
	for f in $(se_dir $1)/*_en; do echo 0 > $f; done
	echo 1 > $(se_dir $1)/in_$2_en
	echo "$T" > $1/trigger/current_trigger
	echo 1 > $1/buffer/enable
}
buffer_off() {
	echo 0 > $1/buffer/enable
	echo "" > $1/trigger/current_trigger
	for f in $(se_dir $1)/*_en; do echo 0 > $f; done
}
buffer_on $DEV accel_x
busy $DEV scan_elements/in_accel_x_en 0
busy $DEV scan_elements/in_temp_en 1
busy $DEV buffer0/in_accel_y_en 1
busy $DEV buffer/length 64
busy $DEV trigger/current_trigger ""
# (calibbias is taken between two samples: 72-concurrency)
busy $DEV in_accel_oversampling_ratio 1
buffer_off $DEV
# the magn device, its buffer on: the same, and its selftest
buffer_on $MDEV magn_x
busy $MDEV scan_elements/in_magn_x_en 0
busy $MDEV scan_elements/in_magn_y_en 1
busy $MDEV buffer0/in_magn_z_en 1
busy $MDEV buffer/length 64
busy $MDEV trigger/current_trigger ""
busy $MDEV selftest 1
buffer_off $MDEV
echo 1 > $DEV/in_accel_oversampling_ratio
eq "oversampling_ratio: the values available" \
	"$(cat $DEV/in_accel_oversampling_ratio_available)" "1 4"
set_cal 0 0 0 25000
