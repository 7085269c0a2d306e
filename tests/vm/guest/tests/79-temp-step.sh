# SPDX-License-Identifier: GPL-2.0
# A temperature step while the buffer runs shows up in the next sample, not
# on the next open (issue 10, item 5): every buffered sample is compensated
# with the temperature measured in the same burst. The buffer stays open
# while the adapter's die temperature steps from 25 to 70 and then to -20
# degC; the samples are told apart by the temperature channel of the same
# scan (TMPS 136, 64, 208), not by timing. A noiseless unit calibrated with
# its own offsets: every sample, including the first one after each step,
# must read 0 0 1 g within TOL = 8 LSB (2 chip LSB; only rounding is left).
# An offset that stayed at its 25 degC value would put Y off by
# Kote x 45 degC = 443 chip LSB, about 1760 LSB, at 70 degC.
# Deadlines are for stalls only (60 s for 40 samples at 100 Hz).
plan 11
TOL=8
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
set_cal 40 -25 60 25000
N=${DEV##*iio:device}
T=$(dr_trig)
SE=$DEV/scan_elements
[ -d "$SE" ] || SE=$DEV/buffer0
for f in $SE/*_en; do echo 0 > $f; done
for c in in_accel_x in_accel_y in_accel_z in_temp in_timestamp; do echo 1 > $SE/${c}_en; done
echo 100 > $DEV/sampling_frequency
echo "$T" > $DEV/trigger/current_trigger
echo 4096 > $DEV/buffer/length
F=/tmp/step.bin

# wait_bytes N: until the capture holds N bytes; 60 s without reaching
# them is a stall
wait_bytes() {
	_i=0
	while [ "$(wc -c < $F)" -lt "$1" ]; do
		[ $_i -ge 600 ] && return 1
		sleep 0.1; _i=$((_i + 1))
	done
}
# wait_more SAMPLES WHAT: wait for SAMPLES more scans
wait_more() {
	_s=$(wc -c < $F)
	wait_bytes $((_s + $1 * 16)) || {
		plan_more 1	# (a check that only a stall makes)
		nok "$2: $1 more samples within 60 s" "stalled at $(wc -c < $F) bytes"
	}
}

mg0=$(stat_get chip_magn_measurements)
: > $F
echo 1 > $DEV/buffer/enable
cat /dev/iio:device$N >> $F &
READER=$!
wait_more 40 "25 degC"
sim_temp 70
wait_more 40 "70 degC"
sim_temp -20
wait_more 40 "-20 degC"
echo 0 > $DEV/buffer/enable
sleep 0.5
kill $READER 2>/dev/null
wait $READER 2>/dev/null
echo "" > $DEV/trigger/current_trigger
sim_temp 25
eq "accel and temp only: no magnetometer measurement" "$(stat_get chip_magn_measurements)" "$mg0"

# one line per scan: TMPS X Y Z
od -A n -t d2 -v $F | awk 'NF == 8 { print $4, $1, $2, $3 }' > /tmp/step.txt
diag "$(wc -l < /tmp/step.txt) scans; around the steps:"
awk '{ if (NR > 1 && $1 != last) { print "# " prev; print "# " $0 } last = $1; prev = $0 }' /tmp/step.txt
eq "the temperature channel shows the steps in order, once each" \
	"$(awk '{ if ($1 != last) { printf "%s%s", sep, $1; sep = " " } last = $1 } END { print "" }' /tmp/step.txt)" \
	"136 64 208"
for p in "25:136" "70:64" "-20:208"; do
	t=${p%%:*}; code=${p#*:}
	n=$(awk -v c=$code '$1 == c' /tmp/step.txt | wc -l)
	check "$t degC: at least 20 samples ($n)" test "$n" -ge 20
	bad=$(awk -v c=$code -v t=$TOL '$1 == c { d1 = $2; d2 = $3; d3 = $4 - 1024
		if (d1 > t || d1 < -t || d2 > t || d2 < -t || d3 > t || d3 < -t) bad++ }
		END { print bad + 0 }' /tmp/step.txt)
	eq "$t degC: every sample 0 0 1 g within $TOL LSB" "$bad" 0
	first=$(awk -v c=$code '$1 == c { print $2, $3, $4; exit }' /tmp/step.txt)
	accel_near "$t degC: the first sample at this temperature is compensated ($first)" \
		"$first" "0 0 $G_LSB" $TOL
done
