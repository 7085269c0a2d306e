# SPDX-License-Identifier: GPL-2.0
# Buffered capture with the driver's data-ready trigger and an hrtimer
# trigger: sample counts, monotonic timestamps, values, bus transfers.
set_unit "temperature = 25" "noise = 0"
wait_dev 5
N=${DEV##*iio:device}
SE=$DEV/scan_elements
[ -d "$SE" ] || SE=$DEV/buffer0

# capture TRIGGER SECONDS OUT: accel x/y/z + timestamp, 16 bytes a sample
capture() {
	for c in in_accel_x in_accel_y in_accel_z in_timestamp; do
		echo 1 > $SE/${c}_en
	done
	echo "$1" > $DEV/trigger/current_trigger
	echo 1024 > $DEV/buffer/length
	echo 1 > $DEV/buffer/enable || return 1
	CAP_M0=$(stat_get chip_measurements); CAP_T0=$(stat_get bus_transfers)
	sleep "$2"
	CAP_M1=$(stat_get chip_measurements); CAP_T1=$(stat_get bus_transfers)
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
zbad() {
	od -A n -t d2 -v "$1" | awk 'NF == 8 { if ($3 < 248 || $3 > 268) bad++ } END { print bad + 0 }'
}

T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
check "driver registers its data-ready trigger" test -n "$T"
echo 100 > $DEV/sampling_frequency 2>/dev/null || echo 100 > $DEV/in_sampling_frequency 2>/dev/null
if capture "$T" 2 /tmp/buf1; then
	S=$(samples /tmp/buf1)
	diag "data-ready trigger: $S samples in 2 s, measurements $((CAP_M1 - CAP_M0)), transfers $((CAP_T1 - CAP_T0))"
	check "data-ready trigger: at least 20 samples in 2 s ($S)" test "$S" -ge 20
	check "data-ready trigger: at most 2 s x 100 Hz + 5% ($S)" test "$S" -le 210
	check "data-ready trigger: timestamps strictly increasing" monotonic /tmp/buf1
	eq "data-ready trigger: every z sample near St(25) = 258" "$(zbad /tmp/buf1)" 0
	M=$((CAP_M1 - CAP_M0))
	if [ $M -gt 0 ]; then
		TPS=$(echo "$((CAP_T1 - CAP_T0)) $M" | awk '{ printf "%.2f", $1 / $2 }')
		diag "AS9888-METRIC transfers_per_sample=$TPS rate_hz=$(echo "$S" | awk '{ printf "%.1f", $1 / 2 }')"
		check "bus transfers per buffered sample $TPS <= 2 (MS write + burst read)" \
			awk "BEGIN { exit !($TPS <= 2.05) }"
	else
		nok "measurements during the capture"
	fi
else
	nok "buffer enable with the data-ready trigger"
fi

mkdir -p /sys/kernel/config/iio/triggers/hrtimer/as9888t0
echo 50 > /sys/bus/iio/devices/trigger*/sampling_frequency 2>/dev/null
for t in /sys/bus/iio/devices/trigger*; do
	[ "$(cat $t/name)" = as9888t0 ] && echo 50 > $t/sampling_frequency
done
if capture as9888t0 2 /tmp/buf2; then
	S=$(samples /tmp/buf2)
	diag "hrtimer trigger 50 Hz: $S samples in 2 s"
	check "hrtimer trigger: at least 10 samples ($S)" test "$S" -ge 10
	check "hrtimer trigger: timestamps strictly increasing" monotonic /tmp/buf2
	eq "hrtimer trigger: every z sample near St(25) = 258" "$(zbad /tmp/buf2)" 0
else
	nok "buffer enable with an hrtimer trigger"
fi
