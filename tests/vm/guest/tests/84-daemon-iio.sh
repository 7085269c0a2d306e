# SPDX-License-Identifier: GPL-2.0
# as9888-calibd's test engine through the bound driver (--backend iio):
# the full factory test on a healthy unit, its record put in effect, the
# same DAC values as the register engine finds on the same unit, the
# calibration the record implies and compensated readings of 0, 0 and 1 g;
# check,
# recalibrate after a "shock" and rollback, also as daemon requests; every
# fault fails at its step; the device's attributes are left as found.
plan 56
CALIBD=/bin/as9888-calibd
mkdir -p /tmp/iio

# json_field FILE KEY: a top-level string or number of the JSON report
json_field() {
	sed -n "s/^  \"$2\": \"*\([^\",]*\)\"*,*\$/\1/p" "$1" | head -n 1
}
# record_dac FILE: the record's DAC line
record_dac() { sed -n 's/^dac = //p' "$1"; }
# state: every attribute the test may change, one line each
state() {
	for a in in_accel_x_calibbias in_accel_y_calibbias in_accel_z_calibbias \
		in_accel_oversampling_ratio sampling_frequency \
		trigger/current_trigger buffer/length; do
		echo "$a=$(cat $DEV/$a)"
	done
	SE=$DEV/scan_elements
	[ -d "$SE" ] || SE=$DEV/buffer0
	for e in $SE/*_en; do echo "$(basename $e)=$(cat $e)"; done
	# the magn device: the daemon runs its selftest
	for a in sampling_frequency trigger/current_trigger buffer/length buffer/enable; do
		echo "magn $a=$(cat $MDEV/$a)"
	done
	for e in $(se_dir $MDEV)/*_en; do echo "magn $(basename $e)=$(cat $e)"; done
}
# nak_end_ok: the run of the nak fault ($GOT its end) passed, ended at 4-1,
# or its first failure is at the step $GOT and is an interface's failure
# (no limits: a read or write the NAK broke), not a judgment of the chip's
# data (which has limits)
nak_end_ok() {
	[ "$GOT" = pass ] || [ "$GOT" = 4-1 ] ||
		grep '"step": .*"result": "fail"' /tmp/iio/ft.json | head -n 1 |
		grep -q "\"step\": \"$GOT\".*\"limits\": \"\""
}
ft_iio() {
	_t0=$(ms_now)
	$CALIBD factory-test --backend iio --json "$@" > /tmp/iio/ft.json 2> /tmp/iio/ft.err
	FT_RC=$?
	FT_WALL_MS=$(( $(ms_now) - _t0 ))
}

load_driver
load_sim
printf '%s\n' "$HEALTHY_UNIT" > /tmp/iio/unit.txt
dev_stale
printf '%s\n' "$HEALTHY_UNIT" > $SIM/unit
wait_dev 5

# Leave odd settings in place: the test must put every one of them back
echo 10 > $DEV/sampling_frequency
echo 4 > $DEV/in_accel_oversampling_ratio
echo 3 > $DEV/in_accel_x_calibbias
echo 1 > $(se_dir $MDEV)/in_magn_x_en
echo 1 > $(se_dir $DEV)/in_temp_en
BEFORE=$(state)

rm -f /tmp/iio/rec
ft_iio --record /tmp/iio/rec
diag "factory-test --backend iio: exit $FT_RC, report $(json_field /tmp/iio/ft.json duration_ms) ms, wall $FT_WALL_MS ms"
diag "factory test duration (iio backend): $(json_field /tmp/iio/ft.json duration_ms) ms"
eq "factory test through the driver passes" "$FT_RC $(json_field /tmp/iio/ft.json result)" "0 pass"
[ "$FT_RC" = 0 ] || sed 's/^/# /' /tmp/iio/ft.err
check "the report judges D11's INT1 through the data-ready trigger" \
	grep -q '"INT1 pin check (D11)", "measured": "\([0-9]*\) of \1 samples from as9888-dev[0-9]*".*"pass"' /tmp/iio/ft.json
check "the device ID (WIA) is read through debugfs and judged" \
	grep -q '"device ID (WIA)", "measured": "0x48 (/sys/kernel/debug/iio/iio:device[0-9]*/direct_reg_access)".*"pass"' /tmp/iio/ft.json
check "RSTN and INT2 checks are reported as skipped, not passed" \
	sh -c "grep -q '\"RSTN pin check (D11)\".*\"skip\"' /tmp/iio/ft.json &&
	       grep -q '\"INT2 pin check (D11)\".*\"skip\"' /tmp/iio/ft.json"
check "self-test judged from the driver's readings" \
	grep -q '"self-test Z after adjustment", "measured": "[0-9]*\.[0-9]*".*"pass"' /tmp/iio/ft.json
check "record written" test -s /tmp/iio/rec
AFTER=$(state)
CAL=$(cal_get)
diag "calibbias x y z: $CAL; the record's DACopt (at t_L) $(record_dac /tmp/iio/rec), the chip's DAC $(dac_get)"
cal_near "the new calibration is in effect: what the record implies" "$CAL" "$(rec_cal /tmp/iio/rec)"
eq "the DAC the chip runs with: DACopt of the calibbias' offset at t_RT" \
	"$(dac_get)" "$(bias_dac "$CAL")"
# everything but the DAC and the calibration as it was
eq "the other attributes are as they were found" \
	"$(echo "$AFTER" | grep -v -e calib)" \
	"$(echo "$BEFORE" | grep -v -e calib)"
set_cal 0 0 0 25000
check "restore of that record" $CALIBD restore --backend iio --record /tmp/iio/rec
eq "restore of that record gives the same calibration" "$(cal_get)" "$CAL"

# Compensated readings (16 reads each, noise 0.5 chip LSB): 0 on the level
# axes, 1 g on Z, with and without the low-pass filter
A=$(accel_mean 16)
diag "compensated readings, oversampling_ratio 4: $A"
accel_near "compensated readings, oversampling_ratio 4: 0 0 1 g" "$A" "0 0 $G_LSB" 4
echo 1 > $DEV/in_accel_oversampling_ratio
A=$(accel_mean 16)
diag "compensated readings, oversampling_ratio 1: $A"
accel_near "compensated readings, oversampling_ratio 1: 0 0 1 g" "$A" "0 0 $G_LSB" 4

# The register engine on the same unit finds the same DAC values
$CALIBD factory-test --backend sim --sim-clock virtual --unit /tmp/iio/unit.txt \
	--record /tmp/iio/rec-sim > /dev/null 2>&1
eq "same DACopt as the register engine on this unit" \
	"$(record_dac /tmp/iio/rec)" "$(record_dac /tmp/iio/rec-sim)"

# Field repair through the driver
check "check: no recalibration needed right after the factory test" \
	sh -c "$CALIBD check --backend iio --record /tmp/iio/rec | grep -q 'No recalibration needed'"
# a shock moves X by 20 LSB (the chip is re-instantiated: restore first)
set_unit "temperature = 25" "offset = 60 -25 60" "noise = 0.5" "seed = 7"
wait_dev 5
check "restore after the re-probe" $CALIBD restore --backend iio --record /tmp/iio/rec
# 20 chip LSB on X = 20 / 258.6 * 1024 = 79 LSB
A=$(accel_mean 16)
diag "compensated readings after the shock, old calibration: $A"
within "after the shock: x reads the 20 chip LSB of the shock (79 LSB)" "${A%% *}" 79 8
$CALIBD check --backend iio --record /tmp/iio/rec > /tmp/iio/check.txt 2>&1
sed 's/^/# /' /tmp/iio/check.txt
check "check: recalibration advisable after the shock" grep -q 'advisable' /tmp/iio/check.txt
OLD_CAL=$(cal_get)
check "recalibrate through the driver" \
	sh -c "$CALIBD recalibrate --backend iio --record /tmp/iio/rec > /tmp/iio/recal.txt 2>&1"
tail -n 2 /tmp/iio/recal.txt | sed 's/^/# /'
check "the previous record is kept" test -s /tmp/iio/rec.previous
accel_near "after recalibrating: compensated readings 0 0 1 g" "$(accel_mean 16)" "0 0 $G_LSB" 4
check "check after recalibrating: no recalibration needed" \
	sh -c "$CALIBD check --backend iio --record /tmp/iio/rec | grep -q 'No recalibration needed'"
check "rollback through the driver" $CALIBD rollback --backend iio --record /tmp/iio/rec
eq "rollback puts the earlier calibration back in effect" \
	"$(cal_get)" "$OLD_CAL"

# The same through the daemon's socket
$CALIBD daemon --backend iio --record /tmp/iio/rec --socket /tmp/iio/sock 2>/tmp/iio/daemon.log &
DPID84=$!
_i=0
while [ ! -S /tmp/iio/sock ] && [ $_i -lt 50 ]; do sleep 0.1; _i=$((_i + 1)); done
check "request check through the daemon" \
	sh -c "$CALIBD request check --socket /tmp/iio/sock | grep -q 'advisable'"
check "request recalibrate through the daemon" \
	sh -c "$CALIBD request recalibrate --socket /tmp/iio/sock > /tmp/iio/req.txt 2>&1"
check "request check afterwards: no recalibration needed" \
	sh -c "$CALIBD request check --socket /tmp/iio/sock | grep -q 'No recalibration needed'"
kill -TERM $DPID84
_i=0
while kill -0 $DPID84 2>/dev/null && [ $_i -lt 50 ]; do sleep 0.1; _i=$((_i + 1)); done
check_not "SIGTERM stops the daemon" kill -0 $DPID84

# Each fault fails the test at its step (or is out of the driver's sight)
for f in "no_drdy 2-4" "int1_open 2-4" "int2_open pass" "rstn_open pass" \
	"stuck_x 3-23" "saturate_z 3-12" "selftest_weak 2-21" "eeprom_blank nodev" \
	"wia 1-4" "nak any"; do
	set -- $f
	set_unit "fault = $1"
	if ! wait_dev 3; then
		eq "$1: no device to test (probe refused the unit)" nodev "$2"
		continue
	fi
	S0=$(state)
	rm -f /tmp/iio/frec
	ft_iio --record /tmp/iio/frec
	GOT=$(json_field /tmp/iio/ft.json failed_step)
	[ -n "$GOT" ] && [ "$GOT" != null ] || GOT=$(json_field /tmp/iio/ft.json result)
	[ -n "$GOT" ] || GOT="exit $FT_RC: $(head -c 200 /tmp/iio/ft.err)"
	diag "$1: $GOT, exit $FT_RC, $FT_WALL_MS ms: $(grep '"step": .*"result": "fail"' /tmp/iio/ft.json | head -n 1 | cut -c1-300)"
	# nak: every 50th transfer fails, wherever it falls: the test passes
	# (the NAK fell where the driver retries), ends at 4-1 (it fell on
	# applying the record) or stops at its first failure, which must be
	# a read or write the NAK broke, at the step failed_step names
	if [ "$2" != any ]; then
		eq "$1: the test ends at $2" "$GOT" "$2"
	else
		check "$1: ends as a NAK can end it (pass, 4-1, or an interface failure first at $GOT)" \
			nak_end_ok
	fi
	if [ "$GOT" = pass ]; then
		check "$1: passed, the record written" test -s /tmp/iio/frec
		eq "$1: passed, attributes as found but for the new calibration" \
			"$(state | grep -v -e calib)" \
			"$(echo "$S0" | grep -v -e calib)"
	elif [ "$GOT" = 4-1 ]; then
		# nak: the test passed, the NAK fell on applying its record
		# ("written but not applied"): none of it applied
		check "$1: 4-1, the record written" test -s /tmp/iio/frec
		eq "$1: 4-1, not applied: every attribute as found" "$(state)" "$S0"
	else
		check_not "$1: no record written" test -e /tmp/iio/frec
		eq "$1: failed, every attribute as found" "$(state)" "$S0"
	fi
done

set_unit "temperature = 25"
wait_dev 5
