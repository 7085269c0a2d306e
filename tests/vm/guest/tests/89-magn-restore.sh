# SPDX-License-Identifier: GPL-2.0
# The magnetometer's calibration from the record to the driver (issue 28,
# "Done when": the record round-trips, restore applies it, and a
# calibrated board's raw x scale is the true field at three temperatures
# and in the buffer).
# The board of lib.sh's magn_board: the true field MAGN_TRUE, hard iron
# MAGN_HARD, diagonal soft iron S (the chip reads S B + h). Its record is
# this chip's own (the factory test through the driver, format 1) with a
# magnetometer section added: b = MAGN_HARD, W = S^-1 (format 2, by
# tests/lib/record.sh's record_add_magn, as the host's tests add one).
#  - restore --backend iio writes calibbias = rint(-b / s) (s the axis'
#    uT per LSB from the EEPROM) and calibscale = diag(W), and _raw is
#    rint((count + calibbias) * calibscale) exactly;
#  - raw x scale is then the true field within 0.5 uT (two roundings of
#    half an LSB divided by S, and the final one) at -20, 25 and 70 degC,
#    in sysfs and in the buffer; without the calibration it is not;
#  - the daemon rewrites the record (recalibrate) as format 1, the
#    section unchanged in <record>.magn (issue 40 N6); a new bind starts
#    from the defaults and restore brings the values back; a format 1
#    record restores the defaults;
#  - magn-calibrate through the driver on the board tumbling two degrees
#    a measurement stores a calibration, its samples from both devices'
#    buffers on the data-ready trigger (five measurements a sample), and
#    leaves every buffer attribute as it found it.
plan 29
load_sim
load_driver
CALIBD=/bin/as9888-calibd
O=/tmp/magn-restore
mkdir -p $O
# the factory test's accelerometer needs its noise (a noiseless axis reads
# as stuck)
magn_board "offset = 40 -25 60" "noise = 0.5" "seed = 7"
check "as9888-accel and as9888-magn" wait_dev 5
T=$(dr_trig)

# calibrated "COUNTS" "BIASES" "SCALES": rint((count + bias) * scale), ties
# to even, in exact integer steps (the product in millionths is an integer)
calibrated() {
	echo "$1 $2 $3" | awk '{ for (i = 1; i <= 3; i++) { p = ($i + $(i + 3)) * int($(i + 6) * 1000000 + 0.5)
		q = p / 1000000; q = q < 0 ? -int(-q) : int(q); if (q * 1000000 > p) q--
		r = p - q * 1000000; if (r > 500000 || (r == 500000 && q % 2)) q++
		printf "%s%d", (i > 1 ? " " : ""), q } }'
}
W=$(echo $MAGN_CALIBSCALE | awk '{ printf "%s 0.000000 0.000000 0.000000 %s 0.000000 0.000000 0.000000 %s", $1, $2, $3 }')

C=$(mg raw)
diag "uncalibrated counts of the board: $C"
check_not "uncalibrated: raw x scale is not the true field within 5 uT (the check can fail)" \
	magn_is_field "$C" 5
# (the factory test's magnetometer self-test wants a low field)
magn_iron off
rm -f $O/rec
check "factory test through the driver writes this chip's record" \
	sh -c "$CALIBD factory-test --backend iio --record $O/rec > $O/ft.log 2>&1"
magn_iron on
cp $O/rec $O/rec2
record_add_magn $O/rec2 "magn_hard_iron=$MAGN_HARD" "magn_soft_iron=$W"
WB=$(magn_bias_of "$MAGN_HARD")

# --- restore applies the record's hard iron and the diagonal of W -----------
check "restore --backend iio of the format 2 record" \
	sh -c "$CALIBD restore --backend iio --record $O/rec2 > $O/r.log 2>&1"
sed 's/^/# /' $O/r.log
eq "restore: calibbias = rint(-b / s): $WB" "$(mg calibbias)" "$WB"
eq "restore: calibscale = diag(W): $MAGN_CALIBSCALE" "$(mg calibscale)" "$MAGN_CALIBSCALE"
R=$(calibrated "$C" "$WB" "$MAGN_CALIBSCALE")
eq "restore: raw = rint((count + calibbias) * calibscale) = $R" "$(mg raw)" "$R"

# --- raw x scale is the true field --------------------------------------------------
for t in -20 25 70; do
	sim_temp $t
	magn_field_near "restored, $t degC: raw x scale is $MAGN_TRUE uT (0.5 uT)" "$(mg raw)" 0.5
done
if [ -n "$T" ] && buf_start $MDEV "$T" $O/b.bin magn_x magn_y magn_z timestamp &&
	wait_grow $O/b.bin $((10 * 16)); then
	buf_stop $MDEV $BUF_PID $O/b.bin
	V=$(od -A n -t d2 -v $O/b.bin | awk 'NF == 8 { c[$1 " " $2 " " $3]++ }
		END { for (k in c) printf "%s|", k }')
	eq "restored, 70 degC, buffer: every scan the same reading" "$(echo "$V" | tr -cd '|')" "|"
	magn_field_near "restored, 70 degC, buffer: raw x scale (${V%|}) is the true field (0.5 uT)" \
		"${V%|}" 0.5
else
	nok "buffer: 10 magn scans (stall: 60 s)"
	nok "buffer: raw x scale is the true field"
fi
sim_temp 25

# --- the record round-trips through the daemon -------------------------------------
grep '^magn_' $O/rec2 > $O/magn-before
magn_iron off
check "recalibrate rewrites the record" \
	sh -c "$CALIBD recalibrate --backend iio --record $O/rec2 > $O/rc.log 2>&1"
magn_iron on
tail -n 3 $O/rc.log | sed 's/^/# /'
check "recalibrate: the record was rewritten (the previous one kept)" test -s $O/rec2.previous
eq "rewritten record: format 1, which every build reads" "$(sed -n 's/^format = //p' $O/rec2)" "as9888-calibration 1"
eq "rewritten record: the magnetometer's calibration unchanged, in its .magn file" \
	"$(grep '^magn_' $O/rec2.magn | grep -v '^magn_rotation')" \
	"$(grep . $O/magn-before || echo 'none: the record before had no magn_ lines')"
eq "after recalibrate: calibbias still $WB" "$(mg calibbias)" "$WB"

# --- a new bind: the defaults, and restore brings the values back -----------------
rebind
check "rebound" wait_dev 5
eq "new bind: calibbias 0 0 0" "$(mg calibbias)" "0 0 0"
eq "new bind: raw is the board's uncalibrated counts again" "$(mg raw)" "$C"
check "restore after the new bind" \
	sh -c "$CALIBD restore --backend iio --record $O/rec2 > $O/r.log 2>&1"
eq "restored after the new bind: calibbias $WB, calibscale $MAGN_CALIBSCALE" \
	"$(mg calibbias) $(mg calibscale)" "$WB $MAGN_CALIBSCALE"
magn_field_near "restored after the new bind: raw x scale is the true field (0.5 uT)" "$(mg raw)" 0.5
# a format 1 record holds no magnetometer calibration: the defaults
check "restore of the format 1 record" \
	sh -c "$CALIBD restore --backend iio --record $O/rec > $O/r.log 2>&1"
eq "format 1 record: the driver's defaults" "$(mg calibbias) $(mg calibscale)" \
	"0 0 0 1.000000 1.000000 1.000000"

# --- magn-calibrate through the driver: both buffers, five measurements a sample ---
# bufstate: both devices' buffer attributes and scan elements, one line
bufstate() {
	for _bs_d in $DEV $MDEV; do
		cat $_bs_d/buffer/enable $_bs_d/buffer/length $_bs_d/trigger/current_trigger \
			$_bs_d/sampling_frequency $_bs_d/scan_elements/*_en 2>&1
	done | tr '\n' ' '
}
# the trigger is named after the accelerometer device, which the rebind
# above may have renumbered
T=$(dr_trig)
if [ -n "$T" ]; then
	B0=$(bufstate)
	cp $O/rec $O/rec3
	# two degrees a measurement: learned in well under the 120 s (the
	# boot test turns it one, the sweep's slowest)
	echo 0.3 > $SIM/magn_noise && echo 2 > $SIM/tumble
	check "magn-calibrate --backend iio, the board tumbling two degrees a measurement: stored" \
		sh -c "$CALIBD magn-calibrate --backend iio --timeout 600 --record $O/rec3 > $O/mc.log 2>&1"
	echo 0 > $SIM/tumble && echo 0 > $SIM/magn_noise
	grep -E "^(samples: |Magnetometer calibrated|  field)" $O/mc.log | sed 's/^/# /'
	tail -n 2 $O/mc.log | sed 's/^/# /'
	check "its samples from both devices' buffers on $T at 100 Hz, 5 measurements a sample" \
		grep -q "^samples: both devices' buffers on $T at 100 Hz, .*, 5 measurements averaged a sample" $O/mc.log
	check "its progress lines name the turn to make in the device's axes (the driver's mount matrix)" \
		grep -q "to cover more: turn it about the device's [XYZ] axis, +[XYZ] toward [+-][XYZ], about [0-9]* deg" $O/mc.log
	eq "afterwards every buffer attribute as it was" "$(bufstate)" "$B0"
else
	nok_for 4 "magn-calibrate through both buffers" "no data-ready trigger"
fi
