# SPDX-License-Identifier: GPL-2.0
# The magnetometer is measured (SLCT2.MEN) only when a magnetometer channel
# is read or in the buffer's scan: counted by the chip model.
set_unit "temperature = 25" "noise = 0"
wait_dev 5
T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
N=${DEV##*iio:device}
SE=$DEV/scan_elements
echo 100 > $DEV/sampling_frequency
# snap: "measurements magn_measurements" now
snap() { cat $SIM/stats | awk '$1 == "chip_measurements" { m = $2 } $1 == "chip_magn_measurements" { g = $2 } END { print m, g }'; }
# scan CHANNELS...: buffered capture of 1 s with these channels; sets
# S (samples), DM (measurements), DG (magnetometer measurements)
scan() {
	for f in $SE/*_en; do echo 0 > $f; done
	_sz=0
	for c in "$@"; do
		echo 1 > $SE/in_${c}_en
		_sz=$((_sz + $(cat $SE/in_${c}_type | sed 's/.*:[su]\([0-9]*\)\/\([0-9]*\).*/\2/') / 8))
	done
	# the timestamp is aligned to 8 bytes
	_sz=$(((_sz + 7) / 8 * 8))
	echo "$T" > $DEV/trigger/current_trigger
	echo 1024 > $DEV/buffer/length
	set -- $(snap)
	echo 1 > $DEV/buffer/enable
	sleep 1
	echo 0 > $DEV/buffer/enable
	_a=$(snap)
	timeout 3 cat /dev/iio:device$N > /tmp/magn.bin
	echo "" > $DEV/trigger/current_trigger
	S=$(($(wc -c < /tmp/magn.bin) / _sz))
	DM=$((${_a% *} - $1))
	DG=$((${_a#* } - $2))
}

scan accel_x accel_y accel_z timestamp
diag "accel only: $S samples, $DM measurements, $DG with the magnetometer"
check "accel-only capture: samples arrive ($S)" test $S -ge 40
eq "accel-only capture: no magnetometer measurement" $DG 0
scan accel_x magn_y temp timestamp
diag "accel + magn_y: $S samples, $DM measurements, $DG with the magnetometer"
check "capture with magn_y: samples arrive ($S)" test $S -ge 40
near "capture with magn_y: every measurement includes the magnetometer" $DG $DM 0
near "capture with magn_y: one magnetometer measurement per sample" $DG $S 2
scan magn_x timestamp
near "magn_x alone: one magnetometer measurement per sample ($S)" $DG $S 2

# single reads
sysfs_magn() {
	set -- $(snap)
	cat $DEV/$_f > /dev/null
	_a=$(snap)
	echo "$((${_a% *} - $1)) $((${_a#* } - $2))"
}
for _f in in_accel_x_raw in_accel_y_raw in_accel_z_raw in_temp_raw; do
	eq "$_f: one measurement, without the magnetometer" "$(sysfs_magn)" "1 0"
done
for _f in in_magn_x_raw in_magn_y_raw in_magn_z_raw; do
	eq "$_f: one measurement, with the magnetometer" "$(sysfs_magn)" "1 1"
done
for f in $SE/*_en; do echo 0 > $f; done
