# SPDX-License-Identifier: GPL-2.0
# The magnetometer is measured (SLCT2.MEN) only when the magn device asks
# for it: a magnetometer channel read, or its buffer running; never for the
# accel device, whatever it scans. Counted by the chip model.
plan 17
set_unit "temperature = 25" "noise = 0"
wait_dev 5
T=$(dr_trig)
echo 100 > $DEV/sampling_frequency
# snap: "measurements magn_measurements" now
snap() { cat $SIM/stats | awk '$1 == "chip_measurements" { m = $2 } $1 == "chip_magn_measurements" { g = $2 } END { print m, g }'; }
# scan "ACCEL_CHANNELS" "MAGN_CHANNELS": buffered capture of 1 s on the
# data-ready trigger, the accel device with the first list, the magn device
# with the second (an empty list: that device's buffer stays off); sets SA
# and SM (samples of each), DM (measurements), DG (magnetometer
# measurements)
scan() {
	SA=0; SM=0
	set -- "$1" "$2" $(snap)
	# the magn device first, so that with both every measurement of the
	# window is one it asked for
	# (a buffer that does not start is a check more: plan_more)
	[ -z "$2" ] || buf_start $MDEV "$T" /tmp/magn-m.bin $2 ||
		{ plan_more 1; nok "magn buffer enable ($2)"; }
	PM=$BUF_PID
	[ -z "$1" ] || buf_start $DEV "$T" /tmp/magn-a.bin $1 ||
		{ plan_more 1; nok "accel buffer enable ($1)"; }
	PA=$BUF_PID
	sleep 1
	[ -z "$1" ] || { _za=$(scan_bytes $DEV); echo 0 > $DEV/buffer/enable; }
	[ -z "$2" ] || { _zm=$(scan_bytes $MDEV); echo 0 > $MDEV/buffer/enable; }
	_a=$(snap)
	if [ -n "$1" ]; then
		buf_drain $DEV $PA /tmp/magn-a.bin
		SA=$(($(wc -c < /tmp/magn-a.bin) / _za))
	fi
	if [ -n "$2" ]; then
		buf_drain $MDEV $PM /tmp/magn-m.bin
		SM=$(($(wc -c < /tmp/magn-m.bin) / _zm))
	fi
	DM=$((${_a% *} - $3))
	DG=$((${_a#* } - $4))
}

scan "accel_x accel_y accel_z timestamp" ""
diag "accel only: $SA samples, $DM measurements, $DG with the magnetometer"
check "accel-only capture: samples arrive ($SA)" test $SA -ge 40
eq "accel-only capture: no magnetometer measurement" $DG 0
scan "all" ""
diag "every scan element of as9888-accel: $SA samples, $DM measurements, $DG with the magnetometer"
check "all of as9888-accel's scan elements: samples arrive ($SA)" test $SA -ge 40
eq "all of as9888-accel's scan elements: no magnetometer measurement" $DG 0
scan "accel_x temp timestamp" "magn_y timestamp"
diag "accel + temp on as9888-accel, magn_y on as9888-magn: $SA + $SM samples, $DM measurements, $DG with the magnetometer"
check "both devices: accel samples arrive ($SA)" test $SA -ge 40
check "both devices: magn samples arrive ($SM)" test $SM -ge 40
near "both devices: every measurement includes the magnetometer" $DG $DM 0
near "both devices: one magnetometer measurement per magn sample" $DG $SM 2
scan "" "magn_x timestamp"
near "magn_x alone: one magnetometer measurement per sample ($SM)" $DG $SM 2
check "magn_x alone: samples arrive ($SM)" test $SM -ge 40

# single reads
sysfs_magn() {
	set -- $(snap)
	cat $_f > /dev/null
	_a=$(snap)
	echo "$((${_a% *} - $1)) $((${_a#* } - $2))"
}
for _f in $DEV/in_accel_x_raw $DEV/in_accel_y_raw $DEV/in_accel_z_raw $DEV/in_temp_raw; do
	eq "${_f##*/}: one measurement, without the magnetometer" "$(sysfs_magn)" "1 0"
done
for _f in $MDEV/in_magn_x_raw $MDEV/in_magn_y_raw $MDEV/in_magn_z_raw; do
	eq "${_f##*/}: one measurement, with the magnetometer" "$(sysfs_magn)" "1 1"
done
for f in $(se_dir $DEV)/*_en $(se_dir $MDEV)/*_en; do echo 0 > $f; done
