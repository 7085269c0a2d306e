# SPDX-License-Identifier: GPL-2.0
# Every channel reads what the unit description implies.
set_unit "temperature = 31.25" "offset = 40 -25 60" "noise = 0"
check "device back after a new unit" wait_dev 5
raw=$(cat $DEV/in_temp_raw); off=$(cat $DEV/in_temp_offset); sc=$(cat $DEV/in_temp_scale)
mdeg=$(echo "$raw $off $sc" | awk '{ printf "%d", ($1 + $2) * $3 }')
diag "temp raw=$raw offset=$off scale=$sc -> $mdeg mdegC"
# TMPS = rint(176 - 1.6 * 31.25) = 126 -> 31250 mdegC; 1 LSB = 625 mdegC
near "temperature in millidegrees from (raw+offset)*scale" "$mdeg" 31250 625

set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
eq "accel x raw = offset (horizontal)" "$(cat $DEV/in_accel_x_raw)" 40
eq "accel y raw = offset (horizontal)" "$(cat $DEV/in_accel_y_raw)" -25
# Z up: St(25) = (256 + 3) * (1 - 0.165625/100 * (25 - 23.75)) = 258.46; + 60
near "accel z raw = St(25) + offset (vertical)" "$(cat $DEV/in_accel_z_raw)" 318 1

set_unit "temperature = 25" "up = 1 0 0" "offset = 0 0 0" "noise = 0"
wait_dev 5
# X up: EAXGTD 0x04: St_RT = 260, index 0 (-0.428125 %/degC): St(25) = 258.6
near "posture x up: accel x raw = St(25)" "$(cat $DEV/in_accel_x_raw)" 259 1
near "posture x up: accel z raw = 0" "$(cat $DEV/in_accel_z_raw)" 0 0

# Magnetometer: field 20 -5 -40 uT (default), raw = rint(f / 0.3 * 256 / (EHC + 128))
# EHC = 0x80 0x85 0x7b -> 66.67, -16.33(-16), -136.1(-136)
near "magn x raw from the ambient field" "$(cat $DEV/in_magn_x_raw)" 67 1
near "magn z raw from the ambient field" "$(cat $DEV/in_magn_z_raw)" -136 1
