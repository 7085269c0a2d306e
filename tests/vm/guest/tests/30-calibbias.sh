# SPDX-License-Identifier: GPL-2.0
# in_accel_*_calibbias is the calibration, in output LSB (1/1024 g):
# minus the axis' zero-g offset at the EEPROM's reference temperature t_RT.
# Written, it moves in_accel_*_raw by exactly its value at t_RT and by
# value * St_RT / St(t) at another temperature t, as an offset in the chip
# does (docs/DECISIONS.md, "Driver v3: calibration ABI"). The driver
# realises it as the application note's DACopt for that offset (the chip's
# AxDA, visible through debugfs direct_reg_access) plus the compensation
# of the rest. A chip reading at its rail is not compensated: -ERANGE on
# sysfs, the output limit in the buffer.
#
# The unit: the built-in EEPROM (t_RT 23.75 degC, TMPS 138; X: St_RT 260,
# Kste -0.428125 %/degC, 2048 / 44 = 46.5 chip LSB per DAC code), no noise,
# temperatures set live through the adapter (no new chip, no new device).
plan 43
set_unit "temperature = 23.75" "offset = 40 -25 60" "noise = 0"
wait_dev 5
eq "calibbias after probe: 0 0 0" "$(cal_get)" "0 0 0"
eq "calibbias available range: +-8 g" "$(cat $DEV/in_accel_x_calibbias_available)" "[-8192 1 8192]"
eq "the DAC the chip runs with: the factory's (EAxDA)" "$(dac_get)" "0x0d 0x8f 0x8c"
for a in caliboffset calibtemp; do
	check_not "no in_accel_*_$a (removed: no driver-private calibration ABI)" \
		sh -c "ls $DEV | grep -q '^in_accel_.*$a'"
done

# moved NAME AXIS BIAS WANT TOL: write BIAS on AXIS (from 0), the reading
# moves by WANT +- TOL
moved() {
	put_cal 0 0 0
	_r0=$(cat $DEV/in_accel_$2_raw)
	echo "$3" > $DEV/in_accel_$2_calibbias
	_r1=$(cat $DEV/in_accel_$2_raw)
	if [ -n "$_r0" ] && [ -n "$_r1" ]; then
		near "$1: $2 moves by $4 (+- $5): $_r0 -> $_r1" $((_r1 - _r0)) "$4" "$5"
	else
		nok "$1: $2 readable" "'$_r0' '$_r1'"
	fi
}

# --- at t_RT: exactly the written amount -------------------------------------
# Within half a DAC step the DAC stays and the chip's output is the same:
# the move is exact
eq "at t_RT: TMPS 138" "$(cat $DEV/in_temp_raw)" 138
moved "t_RT" x 20 20 0
moved "t_RT" x -37 -37 0
moved "t_RT" z 55 55 0
moved "t_RT" y -80 -80 0
# A value that moves the DAC: the chip rounds its output anew (half a chip
# LSB either way, 2 LSB each, and the output's own rounding), the rest is
# exact
da0=$(dac_get)
moved "t_RT, DAC moved" x -600 -600 5
check_not "calibbias -600: the chip's DAC moved" test "$(dac_get)" = "$da0"

# --- at 70 degC: the same offset reads St_RT / St(70) times larger ----------
sim_temp 70
eq "at 70 degC: TMPS 64" "$(cat $DEV/in_temp_raw)" 64
# St(70) = 260 * (1 - 0.00428125 * 46.25) = 208.52: x 80 -> 99.75
W=$(ee_bytes | awk '{ s = $17 % 32; if (s >= 16) s -= 32
	k = -0.428125 + 0.04375 * int($17 / 32)
	r = (176 - (136 + (int($3 / 8) % 32 >= 16 ? int($3 / 8) % 32 - 32 : int($3 / 8) % 32))) / 1.6
	printf "%d", 80 / (1 + k / 100 * (70 - r)) + 0.5 }')
eq "St_RT / St(70) from the EEPROM: 80 reads as 100" "$W" 100
moved "70 degC" x 80 "$W" 1
# the calibbias is stateless: written at 70 degC, it reads at t_RT as if
# written there
echo 20 > $DEV/in_accel_x_calibbias
sim_temp 23.75
x1=$(cat $DEV/in_accel_x_raw)
echo 0 > $DEV/in_accel_x_calibbias
x0=$(cat $DEV/in_accel_x_raw)
eq "written at 70 degC, at t_RT x moves by exactly 20" "$((x1 - x0))" 20

# --- the DAC the chip runs with: the application note's DACopt -------------
# powered throughout, so that the chip's own registers can be read too
# (runtime suspend switches its supplies off, which resets them)
echo on > "$(pm_dir)/control"
for b in "0 0 0" "-146 146 -258" "-600 300 1200" "-8192 8192 -8192"; do
	put_cal $b
	eq "calibbias $b reads back" "$(cal_get)" "$b"
	eq "calibbias $b: DAC = DACopt of its offset at t_RT ($(bias_dac "$b"))" \
		"$(dac_get)" "$(bias_dac "$b")"
	eq "calibbias $b: the chip's AXDA holds it" \
		"$(sed -n 's/^0x37 //p' $SIM/regs)" "$(dac_get | cut -d' ' -f1)"
done
echo auto > "$(pm_dir)/control"
# the unit's own offsets: a calibrated unit reads 0 0 1 g
set_cal 40 -25 60 25000
eq "set_cal 40 -25 60 at 25 degC: calibbias -146 146 -258" "$(cal_get)" "-146 146 -258"
accel_near "calibrated: 0 0 1 g at t_RT" "$(accel_mean 4)" "0 0 1024" 3
sim_temp 70
# one chip LSB is 4.9 LSB at 70 degC: half of it and the roundings
accel_near "calibrated: 0 0 1 g at 70 degC" "$(accel_mean 4)" "0 0 1024" 4
sim_temp 23.75

# --- bad input: rejected, nothing changed (58-bad-input.sh has every attribute)
b=$(cat $DEV/in_accel_x_calibbias)
d=$(dac_get)
for v in abc 8193 -8193 1.5 "" 99999999999; do
	if echo "$v" > $DEV/in_accel_x_calibbias 2>/dev/null; then
		nok "calibbias '$v' rejected"
	else
		ok "calibbias '$v' rejected"
	fi
done
eq "calibbias unchanged after bad writes" "$(cat $DEV/in_accel_x_calibbias)" "$b"
eq "DAC unchanged after bad writes" "$(dac_get)" "$d"
if echo 0 > $MDEV/selftest 2>/dev/null; then nok "selftest '0' rejected (magn device)"; else ok "selftest '0' rejected (magn device)"; fi

# --- saturation: not compensated -----------------------------------------------
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0" "fault = saturate_z"
wait_dev 5
set_cal 40 -25 60 25000
err=$(cat $DEV/in_accel_z_raw 2>&1 >/dev/null)
case "$err" in
*"out of range"*) ok "saturated z: in_accel_z_raw fails with ERANGE ($err)" ;;
*) nok "saturated z: in_accel_z_raw fails with ERANGE" "got '$err', value '$(cat $DEV/in_accel_z_raw 2>/dev/null)'" ;;
esac
near "saturated z: x still reads 0" "$(cat $DEV/in_accel_x_raw)" 0 3
T=$(dr_trig)
SE=$(se_dir $DEV)
if [ -n "$T" ]; then
	for f in $SE/*_en; do echo 0 > $f; done
	echo 1 > $SE/in_accel_x_en
	echo 1 > $SE/in_accel_z_en
	echo "$T" > $DEV/trigger/current_trigger
	echo 64 > $DEV/buffer/length
	# (no file of an earlier run: a buffer that does not start reads 0 scans)
	rm -f /tmp/sat.bin
	if echo 1 > $DEV/buffer/enable; then
		timeout 30 head -c $((8 * 4)) /dev/iio:device${DEV##*iio:device} > /tmp/sat.bin
		echo 0 > $DEV/buffer/enable
	fi
	eq "saturated z in the buffer: 8 scans, z = 32767 (the output limit), x about 0" \
		"$(od -A n -t d2 -v /tmp/sat.bin | awk '{ for (i = 1; i < NF; i += 2) { n++
			if ($(i + 1) != 32767 || $i > 3 || $i < -3) bad++ } }
			END { printf "%d scans, %d bad", n, bad }')" "8 scans, 0 bad"
	echo "" > $DEV/trigger/current_trigger
	for f in $SE/*_en; do echo 0 > $f; done
else
	nok "data-ready trigger for the saturation capture"
fi
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
