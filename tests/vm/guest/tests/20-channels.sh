# SPDX-License-Identifier: GPL-2.0
# Every channel reads what the unit description implies. The accelerometer
# reads compensated values on 1024 LSB per g: with the calibration the
# unit implies (its offsets at 25 degC), 0 on the horizontal axes and 1024
# on the vertical one.
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
# After probe: no offset, at the factory room temperature t_RT of EREF3
# (0x15: TMPS 136 + 2 = 138, 23.75 degC)
eq "calibration after probe: zero offsets at t_RT" "$(cal_get)" \
	"0.000000 0.000000 0.000000 23750"
# Uncalibrated, the unit's offsets show: X reads (40 - Ot(25)) / St(25) * 1024
# with Ot(25) = Kote (2.4 LSB/degC) * (25 - 23.75) = 3 and
# St(25) = 260 * (1 - 0.428125 / 100 * 1.25) = 258.609: 146.5
near "uncalibrated: accel x shows the unit's offset (146.5)" "$(cat $DEV/in_accel_x_raw)" 147 1
# A rounding of the chip's output is at most 0.5 chip LSB, i.e. 2 LSB here,
# plus the rounding of the output: 3
check "caliboffset and calibtemp written" set_cal 40 -25 60 25000
eq "the calibration reads back" "$(cal_get)" "40.000000 -25.000000 60.000000 25000"
near "calibrated: accel x = 0 (horizontal)" "$(cat $DEV/in_accel_x_raw)" 0 3
near "calibrated: accel y = 0 (horizontal)" "$(cat $DEV/in_accel_y_raw)" 0 3
near "calibrated: accel z = 1024 (vertical, up)" "$(cat $DEV/in_accel_z_raw)" 1024 3
# caliboffset is in chip LSB: 10.5 more reads -10.5 / 258.609 * 1024 = -41.6
echo 50.5 > $DEV/in_accel_x_caliboffset
eq "caliboffset takes decimals" "$(cat $DEV/in_accel_x_caliboffset)" 50.500000
near "caliboffset +10.5 chip LSB moves x by -41.6 LSB" "$(cat $DEV/in_accel_x_raw)" -42 3
echo 40 > $DEV/in_accel_x_caliboffset
# calibtemp: the offsets hold at that temperature, Kote moves them from
# there: at calibtemp 35000 X's offset at 25 degC is 40 - 24, so x reads
# 24 / 258.609 * 1024 = 95
echo 35000 > $DEV/in_accel_calibtemp
near "calibtemp 35 degC: x reads Kote * 10 degC (95 LSB)" "$(cat $DEV/in_accel_x_raw)" 95 3
echo 25000 > $DEV/in_accel_calibtemp

set_unit "temperature = 25" "up = 1 0 0" "offset = 0 0 0" "noise = 0"
wait_dev 5
set_cal 0 0 0 25000
near "posture x up: accel x = 1024" "$(cat $DEV/in_accel_x_raw)" 1024 3
near "posture x up: accel z = 0" "$(cat $DEV/in_accel_z_raw)" 0 3

# Magnetometer: field 20 -5 -40 uT (default), raw = rint(f / 0.3 * 256 / (EHC + 128))
# EHC = 0x80 0x85 0x7b -> 66.67, -16.33(-16), -136.1(-136)
near "magn x raw from the ambient field" "$(cat $DEV/in_magn_x_raw)" 67 1
near "magn z raw from the ambient field" "$(cat $DEV/in_magn_z_raw)" -136 1
