# SPDX-License-Identifier: GPL-2.0
# calibbias moves the reading by the DAC step: 2048 / (GA[5:0] + 16) LSB.
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
b0=$(cat $DEV/in_accel_x_calibbias)
x0=$(cat $DEV/in_accel_x_raw)
# EAXGA = 0x1c: GA[5:0] = 28 -> 2048 / 44 = 46.545 LSB per code
if echo $((b0 + 2)) > $DEV/in_accel_x_calibbias; then
	eq "calibbias x reads back" "$(cat $DEV/in_accel_x_calibbias)" $((b0 + 2))
	x1=$(cat $DEV/in_accel_x_raw)
	near "calibbias +2 moves x by 2 DAC steps (93.1 LSB)" $((x1 - x0)) 93 1
else
	nok "calibbias x write accepted"
fi
# EAZGA = 0xa2: bit 6 polarity set, GA[5:0] = 34 -> 2048 / 50 = 40.96 LSB
bz=$(cat $DEV/in_accel_z_calibbias)
z0=$(cat $DEV/in_accel_z_raw)
echo $((bz - 3)) > $DEV/in_accel_z_calibbias
z1=$(cat $DEV/in_accel_z_raw)
near "calibbias -3 moves z by -3 DAC steps (-122.9 LSB, polarity bit set)" $((z1 - z0)) -123 1
echo "$b0" > $DEV/in_accel_x_calibbias
eq "calibbias x restored" "$(cat $DEV/in_accel_x_raw)" "$x0"

# Bad input: rejected, nothing changed
b=$(cat $DEV/in_accel_x_calibbias)
for v in abc 68 -68 1.5 "" 99999999999; do
	if echo "$v" > $DEV/in_accel_x_calibbias 2>/dev/null; then
		nok "calibbias '$v' rejected"
	else
		ok "calibbias '$v' rejected"
	fi
done
eq "calibbias unchanged after bad writes" "$(cat $DEV/in_accel_x_calibbias)" "$b"
c=$(cat $DEV/in_accel_calibration)
for v in garbage "1 2 3" "0 0 0 25000 0 0 0" "0 0 0 25000 1 1 0" "0 0 0 999999 0 0 1"; do
	if echo "$v" > $DEV/in_accel_calibration 2>/dev/null; then
		nok "in_accel_calibration '$v' rejected"
	else
		ok "in_accel_calibration '$v' rejected"
	fi
done
eq "in_accel_calibration unchanged after bad writes" "$(cat $DEV/in_accel_calibration)" "$c"
if echo 0 > $DEV/selftest 2>/dev/null; then nok "selftest '0' rejected"; else ok "selftest '0' rejected"; fi
