# SPDX-License-Identifier: GPL-2.0
# calibbias is the chip's offset DAC: it moves the chip's own output by
# 2048 / (GA[5:0] + 16) chip LSB per code. The driver accounts for the DAC
# in use, so the compensated reading stays where it was, and no other
# attribute changes with it.
plan 17
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
set_cal 40 -25 60 25000
cal=$(cal_get)
b0=$(cat $DEV/in_accel_x_calibbias)
near "x reads 0" "$(cat $DEV/in_accel_x_raw)" 0 3
da0=$(sed -n 's/^0x37 //p' $SIM/regs)
# EAXGA = 0x1c: GA[5:0] = 28 -> 2048 / 44 = 46.545 chip LSB per code
if echo $((b0 + 2)) > $DEV/in_accel_x_calibbias; then
	eq "calibbias x reads back" "$(cat $DEV/in_accel_x_calibbias)" $((b0 + 2))
	check_not "calibbias +2: the chip's AXDA changed" \
		test "$(sed -n 's/^0x37 //p' $SIM/regs)" = "$da0"
	near "calibbias +2: x still compensated: 0 (the driver applies the DAC in use)" \
		"$(cat $DEV/in_accel_x_raw)" 0 3
else
	nok "calibbias x write accepted"
	plan_more -2	# (the two checks of the new value are not made)
fi
# EAZGA = 0xa2: GA[5:0] = 34 -> 2048 / 50 = 40.96 chip LSB per code
# (each reading rounds the chip's output anew: compare with 1 g, not with
# the reading before)
bz=$(cat $DEV/in_accel_z_calibbias)
near "z reads 1 g" "$(cat $DEV/in_accel_z_raw)" 1024 3
echo $((bz - 3)) > $DEV/in_accel_z_calibbias
near "calibbias -3 on z: z still 1 g" "$(cat $DEV/in_accel_z_raw)" 1024 3
eq "calibbias changes no other attribute (caliboffset, calibtemp)" "$(cal_get)" "$cal"
echo "$b0" > $DEV/in_accel_x_calibbias
echo "$bz" > $DEV/in_accel_z_calibbias
eq "calibbias x restored" "$(cat $DEV/in_accel_x_calibbias)" "$b0"
eq "calibbias x available range" "$(cat $DEV/in_accel_x_calibbias_available)" "[-67 1 67]"

# Bad input: rejected, nothing changed (58-bad-input.sh has every attribute)
b=$(cat $DEV/in_accel_x_calibbias)
for v in abc 68 -68 1.5 "" 99999999999; do
	if echo "$v" > $DEV/in_accel_x_calibbias 2>/dev/null; then
		nok "calibbias '$v' rejected"
	else
		ok "calibbias '$v' rejected"
	fi
done
eq "calibbias unchanged after bad writes" "$(cat $DEV/in_accel_x_calibbias)" "$b"
if echo 0 > $MDEV/selftest 2>/dev/null; then nok "selftest '0' rejected (magn device)"; else ok "selftest '0' rejected (magn device)"; fi
