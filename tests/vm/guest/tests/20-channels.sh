# SPDX-License-Identifier: GPL-2.0
# Every channel reads what the unit description implies. The accelerometer
# reads compensated values on 1024 LSB per g: with the calibration the
# unit implies (its offsets at 25 degC), 0 on the horizontal axes and 1024
# on the vertical one.
plan 33
set_unit "temperature = 31.25" "offset = 40 -25 60" "noise = 0"
check "device back after a new unit" wait_dev 5
raw=$(cat $DEV/in_temp_raw); off=$(cat $DEV/in_temp_offset); sc=$(cat $DEV/in_temp_scale)
mdeg=$(echo "$raw $off $sc" | awk '{ printf "%d", ($1 + $2) * $3 }')
diag "temp raw=$raw offset=$off scale=$sc -> $mdeg mdegC"
# TMPS = rint(176 - 1.6 * 31.25) = 126 -> 31250 mdegC; 1 LSB = 625 mdegC
near "temperature in millidegrees from (raw+offset)*scale" "$mdeg" 31250 625

set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
eq "accel scale: 9.80665 / 1024 m/s^2" "$(cat $DEV/in_accel_scale)" $G_SCALE
# After probe: calibbias 0, no offset at the factory room temperature
# t_RT of EREF3 (0x15: TMPS 136 + 2 = 138, 23.75 degC)
eq "calibration after probe: calibbias 0 (zero offsets at t_RT)" "$(cal_get)" "0 0 0"
# Uncalibrated, the unit's offsets show: X reads (40 - Ot(25)) / St(25) * 1024
# with Ot(25) = Kote (2.4 LSB/degC) * (25 - 23.75) = 3 and
# St(25) = 260 * (1 - 0.428125 / 100 * 1.25) = 258.609: 146.5
near "uncalibrated: accel x shows the unit's offset (146.5)" "$(cat $DEV/in_accel_x_raw)" 147 1
# A rounding of the chip's output is at most 0.5 chip LSB, i.e. 2 LSB here,
# plus the rounding of the output: 3
# The unit's offsets 40 -25 60 at 25 degC are 37, -37.3, 65.4 chip LSB at
# t_RT (Kote 2.4, 9.857, -4.286 LSB/degC): calibbias -37 / 260 * 1024 =
# -146, 37.3 / 261 * 1024 = 146, -65.4 / 259 * 1024 = -258
check "calibbias written" set_cal 40 -25 60 25000
eq "the calibration reads back" "$(cal_get)" "-146 146 -258"
near "calibrated: accel x = 0 (horizontal)" "$(cat $DEV/in_accel_x_raw)" 0 3
near "calibrated: accel y = 0 (horizontal)" "$(cat $DEV/in_accel_y_raw)" 0 3
near "calibrated: accel z = 1024 (vertical, up)" "$(cat $DEV/in_accel_z_raw)" 1024 3
# calibbias is in output LSB at t_RT: 42 more is 10.66 chip LSB less
# offset, which reads 10.66 / 258.609 * 1024 = 42.2 higher at 25 degC
echo -104 > $DEV/in_accel_x_calibbias
near "calibbias +42 moves x by 42.2 LSB at 25 degC" "$(cat $DEV/in_accel_x_raw)" 42 3
echo -146 > $DEV/in_accel_x_calibbias
# the offset follows the temperature by Kote from the EEPROM: the unit's
# offsets given as if at 35 degC stand for 40 - 24 at 25 degC, so x reads
# the other 24 chip LSB: 24 / 258.609 * 1024 = 95
set_cal 40 -25 60 35000
near "offsets given at 35 degC: x reads Kote * 10 degC (95 LSB)" "$(cat $DEV/in_accel_x_raw)" 95 3
set_cal 40 -25 60 25000

set_unit "temperature = 25" "up = 1 0 0" "offset = 0 0 0" "noise = 0"
wait_dev 5
set_cal 0 0 0 25000
near "posture x up: accel x = 1024" "$(cat $DEV/in_accel_x_raw)" 1024 3
near "posture x up: accel z = 0" "$(cat $DEV/in_accel_z_raw)" 0 3

# Magnetometer: field 20 -5 -40 uT (default), raw = rint(f / 0.3 * 256 / (EHC + 128))
# EHC = 0x80 0x85 0x7b -> 66.67, -16.33(-16), -136.1(-136)
near "magn x raw from the ambient field" "$(cat $MDEV/in_magn_x_raw)" 67 1
near "magn z raw from the ambient field" "$(cat $MDEV/in_magn_z_raw)" -136 1

# One IIO device per sensor: what each has, exactly (the ABI of
# Documentation/ABI; INT1 wired, so sampling_frequency on both)
# attrs DIR: the channel and device attributes (in_*, sampling_*,
# selftest), one line, sorted
attrs() { (cd "$1" && ls -d in_* sampling_* selftest 2>/dev/null | sort | tr '\n' ' '); }
# scan DIR: "element:index" of every scan element, by index
scan() {
	_se=$(se_dir "$1")
	for _i in "$_se"/*_index; do
		_c=${_i##*/}; echo "$(cat "$_i") ${_c%_index}"
	done | sort -n | awk '{ printf "%s:%s ", $2, $1 }'
}
eq "as9888-accel: its attributes, no magnetometer, no selftest" "$(attrs $DEV)" \
	"$(printf '%s\n' in_accel_mount_matrix in_accel_oversampling_ratio \
		in_accel_oversampling_ratio_available in_accel_scale \
		in_accel_x_calibbias in_accel_x_calibbias_available in_accel_x_raw \
		in_accel_y_calibbias in_accel_y_calibbias_available in_accel_y_raw \
		in_accel_z_calibbias in_accel_z_calibbias_available in_accel_z_raw \
		in_temp_offset in_temp_raw in_temp_scale \
		sampling_frequency sampling_frequency_available | sort | tr '\n' ' ')"
eq "as9888-accel: scan elements accel 0-2, temp 3, timestamp 4" "$(scan $DEV)" \
	"in_accel_x:0 in_accel_y:1 in_accel_z:2 in_temp:3 in_timestamp:4 "
eq "as9888-magn: its attributes, calibration, selftest, no accelerometer or temperature" "$(attrs $MDEV)" \
	"$(printf '%s\n' in_magn_mount_matrix in_magn_x_raw in_magn_x_scale in_magn_y_raw \
		in_magn_y_scale in_magn_z_raw in_magn_z_scale sampling_frequency \
		in_magn_x_calibbias in_magn_x_calibbias_available in_magn_x_calibscale \
		in_magn_x_calibscale_available in_magn_y_calibbias in_magn_y_calibbias_available \
		in_magn_y_calibscale in_magn_y_calibscale_available in_magn_z_calibbias \
		in_magn_z_calibbias_available in_magn_z_calibscale in_magn_z_calibscale_available \
		sampling_frequency_available selftest | sort | tr '\n' ' ')"
eq "as9888-magn: scan elements magn 0-2, timestamp 3" "$(scan $MDEV)" \
	"in_magn_x:0 in_magn_y:1 in_magn_z:2 in_timestamp:3 "
eq "as9888-magn: the scan type of the magnetometer, s13 in 16 bits" \
	"$(cat $(se_dir $MDEV)/in_magn_[xyz]_type | sort -u)" "le:s13/16>>0"
# each device has its own rate on the data-ready trigger (issue 24, point
# 4): a write on one does not retime the other
echo 100 > $DEV/sampling_frequency
echo 50 > $MDEV/sampling_frequency
eq "sampling_frequency on the magn device: 50" "$(cat $MDEV/sampling_frequency)" 50
eq "sampling_frequency on the magn device does not retime the accel device" \
	"$(cat $DEV/sampling_frequency)" 100
echo 100 > $MDEV/sampling_frequency
# the rates offered are the rates the chip delivers: t_MAG 7.3 ms for the
# magnetometer, t_ACC 1.2 ms for the accelerometer alone (4.8 ms with the
# low-pass filter), each plus t_PD and the bus
eq "magn rates up to 100 Hz" "$(cat $MDEV/sampling_frequency_available)" \
	"1 2 5 10 20 25 50 100"
_osr=$(cat $DEV/in_accel_oversampling_ratio)
echo 1 > $DEV/in_accel_oversampling_ratio
eq "accel rates without the filter up to 400 Hz" "$(cat $DEV/sampling_frequency_available)" \
	"1 2 5 10 20 25 50 100 125 200 250 400"
echo 400 > $DEV/sampling_frequency
echo 4 > $DEV/in_accel_oversampling_ratio
eq "accel rates with the filter up to 125 Hz" "$(cat $DEV/sampling_frequency_available)" \
	"1 2 5 10 20 25 50 100 125"
eq "accel at 400 Hz reads 125 Hz, the rate delivered, with the filter" \
	"$(cat $DEV/sampling_frequency)" 125
check_not "accel: 400 Hz refused with the filter" sh -c "echo 400 > $DEV/sampling_frequency"
echo 1 > $DEV/in_accel_oversampling_ratio
eq "accel at 400 Hz again without the filter" "$(cat $DEV/sampling_frequency)" 400
echo "$_osr" > $DEV/in_accel_oversampling_ratio
echo 100 > $DEV/sampling_frequency
# debugfs: selftest_readings moved to the magn device
check "debugfs: selftest_readings on the magn device" \
	test -e /sys/kernel/debug/iio/${MDEV##*/}/selftest_readings
check_not "debugfs: no selftest_readings on the accel device" \
	test -e /sys/kernel/debug/iio/${DEV##*/}/selftest_readings
for d in $DEV $MDEV; do
	check "debugfs: direct_reg_access on $(cat $d/name)" \
		test -e /sys/kernel/debug/iio/${d##*/}/direct_reg_access
done
