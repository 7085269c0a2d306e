# SPDX-License-Identifier: GPL-2.0
# as9888-calibd: a factory record made for this unit, restored through the
# driver (restore --backend iio), also after a driver reload; a record of
# another chip is refused.
load_sim
load_driver
U="temperature = 25
offset = 40 -25 60
noise = 0.5
seed = 7"
printf '%s\n' "$U" > /tmp/unit.txt
printf '%s\n' "$U" > $SIM/unit
wait_dev 5
CALIBD=/bin/as9888-calibd
check "factory test (sim backend, same unit) writes a record" \
	sh -c "$CALIBD factory-test --backend sim --sim-clock virtual --unit /tmp/unit.txt --record /tmp/rec > /tmp/ft.log 2>&1"
tail -n 3 /tmp/ft.log | sed 's/^/# /'
eq "no calibration before restore" "$(cat $DEV/in_accel_calibration)" none
check "restore --backend iio" sh -c "$CALIBD restore --backend iio --record /tmp/rec > /tmp/r.log 2>&1"
sed 's/^/# /' /tmp/r.log
CAL=$(cat $DEV/in_accel_calibration)
diag "in_accel_calibration: $CAL"
check "in_accel_calibration set: 7 fields, Z vertical" \
	sh -c "echo '$CAL' | awk 'NF == 7 && \$5 == 0 && \$6 == 0 && (\$7 == -1 || \$7 == 1) { ok = 1 } END { exit !ok }'"
B="$(cat $DEV/in_accel_x_calibbias) $(cat $DEV/in_accel_y_calibbias) $(cat $DEV/in_accel_z_calibbias)"
diag "calibbias after restore: $B"
rmmod as9888_i2c; insmod $MODDIR/as9888_i2c.ko; wait_dev 5
eq "driver reload forgets the calibration" "$(cat $DEV/in_accel_calibration)" none
check "restore after the reload" sh -c "$CALIBD restore --backend iio --record /tmp/rec > /tmp/r.log 2>&1"
eq "same calibration after reload + restore" "$(cat $DEV/in_accel_calibration)" "$CAL"
eq "same calibbias after reload + restore" \
	"$(cat $DEV/in_accel_x_calibbias) $(cat $DEV/in_accel_y_calibbias) $(cat $DEV/in_accel_z_calibbias)" "$B"
# A record of another chip (ET2 differs)
printf '%s\neeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 52\n' "$U" > /tmp/other.txt
$CALIBD factory-test --backend sim --sim-clock virtual --unit /tmp/other.txt --record /tmp/rec2 > /tmp/ft2.log 2>&1
echo none > $DEV/in_accel_calibration
if $CALIBD restore --backend iio --record /tmp/rec2 > /tmp/r2.log 2>&1; then
	nok "restore refuses another chip's record"
else
	ok "restore refuses another chip's record"
fi
eq "nothing applied from another chip's record" "$(cat $DEV/in_accel_calibration)" none
