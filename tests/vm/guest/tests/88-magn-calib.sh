# SPDX-License-Identifier: GPL-2.0
# Magnetometer calibration in the driver (issue 28, point 3): on
# as9888-magn, in_magn_{x,y,z}_calibbias (chip LSB, -4096..4096, added to
# the count) and in_magn_{x,y,z}_calibscale (0.500000..2.000000, multiplies
# after the bias). Every reading, _raw and buffered, is
# rint((count + calibbias) * calibscale), ties to even, kept to
# -4095..4094 (beyond, like a chip overflow: -ERANGE, the rail in the
# buffer). Checked here:
#  - defaults and the _available ranges;
#  - calibbias moves _raw by exactly the written amount, calibscale
#    multiplies, in sysfs and in the buffer; a write while the buffer runs
#    reaches the samples after it;
#  - bad values fail with EINVAL and change nothing;
#  - the values survive runtime suspend (the supply off) and system sleep,
#    and start from the defaults on a new bind;
#  - overflow stays -ERANGE / the rail;
#  - a board with hard iron and a diagonal soft iron (the model's magnetic
#    world): the calibbias and calibscale that cancel them make raw x scale
#    the true field at -20, 25 and 70 degC and in the buffer (and without
#    them it is not).
# The unit: the built-in EEPROM (EHC X 0x80, Y 0x85, Z 0x7b), no noise; the
# magnetometer count of a field f uT is rint(f / 0.3 * 256 / (EHC + 128)).
# Waits are for stalls only (60 s without the samples waited for).
plan 64
load_driver
load_sim
set_unit "temperature = 25" "noise = 0" "field = 20 -5 -40"
check "as9888-accel and as9888-magn" wait_dev 5
T=$(dr_trig)
O=/tmp/magn-calib
mkdir -p $O

# mput ATTR VX VY VZ: write the three values
mput() {
	echo "$2" > $MDEV/in_magn_x_$1 && echo "$3" > $MDEV/in_magn_y_$1 &&
		echo "$4" > $MDEV/in_magn_z_$1
}
# werr FILE VALUE: the error message of writing VALUE, empty if accepted
werr() { (echo "$2" > "$1") 2>&1 | sed 's/.*: //'; }
# rerr FILE: the error message of reading FILE, or "value N"
rerr() {
	_re=$(cat "$1" 2>&1) && echo "value $_re" || echo "$_re" | sed 's/.*: //'
}
# mbuf FILE SCANS: SCANS magn scans (x y z + timestamp) on the data-ready
# trigger into FILE; fails on a stall
mbuf() {
	buf_start $MDEV "$T" "$1" magn_x magn_y magn_z timestamp &&
		wait_grow "$1" $(($2 * 16)) && buf_stop $MDEV $BUF_PID "$1"
}
# scans FILE [FROM]: the distinct "x y z" of the scans (from scan FROM on,
# default 1), with their counts: "N x y z; ..."
scans() {
	od -A n -t d2 -v "$1" | awk -v f="${2:-1}" 'NF == 8 && ++n >= f { c[$1 " " $2 " " $3]++ }
		END { for (k in c) printf "%d %s; ", c[k], k }'
}
# one_value FILE [FROM]: the scans agree: "x y z" of all of them
one_value() {
	_ov=$(scans "$@")
	case "$_ov" in
	*"; "*"; "*) echo "several: $_ov" ;;
	*) echo "$_ov" | sed 's/^[0-9]* //; s/; $//' ;;
	esac
}

# --- defaults, ranges ------------------------------------------------------------
eq "calibbias after probe: 0 0 0" "$(mg calibbias)" "0 0 0"
eq "calibscale after probe: 1 1 1" "$(mg calibscale)" "1.000000 1.000000 1.000000"
eq "calibbias_available: [-4096 1 4096] on every axis" "$(mg calibbias_available)" \
	"[-4096 1 4096] [-4096 1 4096] [-4096 1 4096]"
eq "calibscale_available: [0.500000 0.000001 2.000000] on every axis" \
	"$(mg calibscale_available)" \
	"[0.500000 0.000001 2.000000] [0.500000 0.000001 2.000000] [0.500000 0.000001 2.000000]"
eq "uncalibrated: the field 20 -5 -40 uT reads 67 -16 -136" "$(mg raw)" "67 -16 -136"
S0=$(mg scale)

# --- calibbias adds, calibscale multiplies after it (sysfs) -----------------
mput calibbias 100 -50 4096
eq "calibbias 100 -50 4096 reads back" "$(mg calibbias)" "100 -50 4096"
eq "calibbias 100 -50 4096: raw moves by exactly that: 167 -66 3960" "$(mg raw)" "167 -66 3960"
mput calibbias -4096 0 -4096
eq "calibbias -4096 0 -4096: -4029 -16 -4232 is beyond -4095: x -4029, y -16, z ERANGE" \
	"$(rerr $MDEV/in_magn_x_raw) $(rerr $MDEV/in_magn_y_raw) $(rerr $MDEV/in_magn_z_raw)" \
	"value -4029 value -16 Numerical result out of range"
mput calibbias 100 -50 0
mput calibscale 1.5 0.5 2
eq "calibscale 1.5 0.5 2 reads back" "$(mg calibscale)" "1.500000 0.500000 2.000000"
# 167 * 1.5 = 250.5 -> 250 (ties to even), -66 * 0.5 = -33, -136 * 2
eq "calibscale 1.5 0.5 2 after calibbias 100 -50 0: 250 -33 -272" "$(mg raw)" "250 -33 -272"
mput calibscale 0.500001 1.999999 0.75
# 83.500167 -> 84, -131.999934 -> -132, -102
eq "calibscale 0.500001 1.999999 0.75: 84 -132 -102" "$(mg raw)" "84 -132 -102"
eq "the scale does not change with the calibration" "$(mg scale)" "$S0"

# --- the buffer carries the same values ---------------------------------------
if [ -n "$T" ] && mbuf $O/b1.bin 20; then
	eq "buffer: every scan is the calibrated reading 84 -132 -102" \
		"$(one_value $O/b1.bin)" "84 -132 -102"
else
	nok "buffer: 20 calibrated magn scans (stall: 60 s)"
fi
# a write while the buffer runs: accepted, the samples after it carry it
if [ -n "$T" ] && buf_start $MDEV "$T" $O/b2.bin magn_x magn_y magn_z timestamp &&
	wait_grow $O/b2.bin $((5 * 16)); then
	eq "calibbias written while the buffer runs: accepted" \
		"$(werr $MDEV/in_magn_x_calibbias -67)" ""
	eq "calibscale written while the buffer runs: accepted" \
		"$(werr $MDEV/in_magn_z_calibscale 1)" ""
	n0=$(($(wc -c < $O/b2.bin) / 16 + 2))
	wait_grow $O/b2.bin $((10 * 16))
	buf_stop $MDEV $BUF_PID $O/b2.bin
	# x (67 + -67) * 0.500001 = 0, z -136
	eq "buffer: the scans after the writes are 0 -132 -136" \
		"$(one_value $O/b2.bin $n0)" "0 -132 -136"
else
	nok_for 3 "buffer while writing the calibration (stall: 60 s)"
fi
eq "sysfs after the buffer: 0 -132 -136" "$(mg raw)" "0 -132 -136"

# --- bad values: EINVAL, nothing changed ----------------------------------------
mput calibbias 7 -8 9
mput calibscale 1.25 0.8 1.000001
for v in 4097 -4097 99999 abc 1.5 ""; do
	eq "calibbias '$v': EINVAL" "$(werr $MDEV/in_magn_y_calibbias "$v")" "Invalid argument"
done
for v in 0.499999 2.000001 0 -1 -0.5 3 abc "1 2"; do
	eq "calibscale '$v': EINVAL" "$(werr $MDEV/in_magn_y_calibscale "$v")" "Invalid argument"
done
eq "after the bad writes: calibbias 7 -8 9" "$(mg calibbias)" "7 -8 9"
eq "after the bad writes: calibscale 1.25 0.8 1.000001" "$(mg calibscale)" \
	"1.250000 0.800000 1.000001"
# (67 + 7) * 1.25 = 92.5 -> 92, -24 * 0.8 = -19.2, -127.000127
W="92 -19 -127"
eq "after the bad writes: raw $W" "$(mg raw)" "$W"

# --- runtime suspend and system sleep keep the values ----------------------------
PMD=$(pm_dir)
p0=$(stat_get chip_power_offs)
echo 200 > $PMD/autosuspend_delay_ms
check "runtime suspend" wait_runtime suspended
check "runtime suspend: the chip's supply went off" test "$(stat_get chip_power_offs)" -gt "$p0"
eq "after runtime suspend: calibbias kept" "$(mg calibbias)" "7 -8 9"
eq "after runtime suspend: calibscale kept" "$(mg calibscale)" "1.250000 0.800000 1.000001"
eq "after runtime suspend: raw $W" "$(mg raw)" "$W"
echo 2000 > $PMD/autosuspend_delay_ms
if [ -w /sys/power/pm_test ] && grep -qw freeze /sys/power/state; then
	echo devices > /sys/power/pm_test
	[ -w /sys/module/suspend/parameters/pm_test_delay ] &&
		echo 1 > /sys/module/suspend/parameters/pm_test_delay
	p0=$(stat_get chip_power_offs)
	if [ -n "$T" ]; then
		buf_start $MDEV "$T" $O/b3.bin magn_x magn_y magn_z timestamp
		wait_grow $O/b3.bin $((3 * 16))
	fi
	check "system sleep and resume (freeze, pm_test devices)" \
		sh -c "echo freeze > /sys/power/state"
	echo none > /sys/power/pm_test
	check "system sleep: the chip's supply went off" test "$(stat_get chip_power_offs)" -gt "$p0"
	if [ -n "$T" ]; then
		n0=$(($(wc -c < $O/b3.bin) / 16 + 2))
		wait_grow $O/b3.bin $((10 * 16))
		buf_stop $MDEV $BUF_PID $O/b3.bin
	fi
	eq "after system sleep: the buffered scans are $W" "$(one_value $O/b3.bin $n0)" "$W"
	eq "after system sleep: calibbias kept" "$(mg calibbias)" "7 -8 9"
	eq "after system sleep: calibscale kept" "$(mg calibscale)" "1.250000 0.800000 1.000001"
	eq "after system sleep: raw $W" "$(mg raw)" "$W"
else
	bail_rest "system sleep: /sys/power/pm_test and freeze available (CONFIG_PM_DEBUG)"
	return 0
fi

# --- overflow: -ERANGE and the rail, whatever the calibration ------------------
# a calibrated value beyond -4095..4094: x (67 + 4096) * 2 = 8326
mput calibscale 2 1 1
mput calibbias 4096 0 0
eq "calibrated beyond the output range: x ERANGE, y z read" \
	"$(rerr $MDEV/in_magn_x_raw) $(rerr $MDEV/in_magn_y_raw) $(rerr $MDEV/in_magn_z_raw)" \
	"Numerical result out of range value -16 value -136"
if [ -n "$T" ] && mbuf $O/b4.bin 5; then
	eq "calibrated beyond the output range, buffer: x is the rail 4095" \
		"$(one_value $O/b4.bin)" "4095 -16 -136"
else
	nok "buffer beyond the output range (stall: 60 s)"
fi
# the chip overflows on x (HOFL): a calibbias that would bring the count
# back in range is not applied to a count at the rail
set_unit "temperature = 25" "noise = 0" "field = 2000 -5 -40"
check "overflowing unit: the devices" wait_dev 5
T=$(dr_trig)
mput calibbias -4096 10 0
eq "chip overflow on x: in_magn_x_raw ERANGE" "$(rerr $MDEV/in_magn_x_raw)" \
	"Numerical result out of range"
eq "chip overflow (HOFL): in_magn_y_raw ERANGE too, as before" "$(rerr $MDEV/in_magn_y_raw)" \
	"Numerical result out of range"
if [ -n "$T" ] && mbuf $O/b5.bin 5; then
	eq "chip overflow, buffer: x the rail 4095 (no calibbias), y calibrated -6" \
		"$(one_value $O/b5.bin)" "4095 -6 -136"
else
	nok "buffer with a chip overflow (stall: 60 s)"
fi

# --- a new bind starts from the defaults --------------------------------------------
set_unit "temperature = 25" "noise = 0" "field = 20 -5 -40"
check "normal unit again" wait_dev 5
mput calibbias 1 2 3
mput calibscale 1.1 1.2 1.3
rebind
check "rebound" wait_dev 5
eq "after a new bind: calibbias 0 0 0" "$(mg calibbias)" "0 0 0"
eq "after a new bind: calibscale 1 1 1" "$(mg calibscale)" "1.000000 1.000000 1.000000"
eq "after a new bind: raw 67 -16 -136" "$(mg raw)" "67 -16 -136"

# --- a calibrated board: raw x scale is the true field ---------------------------
# (lib.sh: MAGN_TRUE, the board's hard and soft iron). Two roundings of
# half an LSB (the count, the calibbias) times up to 1 / 0.93, and the
# final rint: 0.482 uT at most (Y: 0.306 uT x (1 / 0.93 + 0.5))
magn_board "noise = 0"
check "board with hard and soft iron" wait_dev 5
T=$(dr_trig)
check_not "uncalibrated: raw x scale is not the true field within 5 uT (the check can fail)" \
	magn_is_field "$(mg raw)" 5
WB=$(magn_bias_of "$MAGN_HARD")
mput calibbias $WB
mput calibscale $MAGN_CALIBSCALE
eq "calibbias $WB, calibscale $MAGN_CALIBSCALE written" "$(mg calibbias) $(mg calibscale)" \
	"$WB $MAGN_CALIBSCALE"
for t in -20 25 70; do
	sim_temp $t
	magn_field_near "calibrated, $t degC: raw x scale is $MAGN_TRUE uT (0.5 uT)" "$(mg raw)" 0.5
done
if [ -n "$T" ] && mbuf $O/b6.bin 10; then
	V=$(one_value $O/b6.bin)
	magn_field_near "calibrated, 70 degC, buffer: every scan ($V) is the true field (0.5 uT)" "$V" 0.5
else
	nok "calibrated board in the buffer: 10 scans (stall: 60 s)"
fi
sim_temp 25
