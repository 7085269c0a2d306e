# SPDX-License-Identifier: GPL-2.0
# as9888-calibd's records restored through the driver (restore --backend
# iio). The record is made on this chip: the factory test through the
# driver (84-daemon-iio.sh tests that test itself). After a restore,
# calibbias holds what the record implies and the
# compensated readings are right (0 on the horizontal axes, 1 g on the
# vertical one); also after a driver reload. Refused, with nothing applied:
# a record of another chip, and a record of the simulator (source =
# simulator: a simulated calibration is never applied to a chip).
# Leaves /tmp/rec for 85 and 86 (lib.sh daemon_fixture).
plan 19
load_sim
load_driver
U=$HEALTHY_UNIT
mkdir -p /tmp/daemon
printf '%s\n' "$U" > /tmp/daemon/unit.txt
dev_stale
printf '%s\n' "$U" > $SIM/unit
wait_dev 5
CALIBD=/bin/as9888-calibd
CAL0=$(cal_get)
eq "no calibration after probe (calibbias 0: zero offsets at t_RT)" "$CAL0" "0 0 0"
rm -f /tmp/rec
check "factory test of this chip through the driver writes a record" \
	sh -c "$CALIBD factory-test --backend iio --record /tmp/rec > /tmp/ft.log 2>&1"
tail -n 3 /tmp/ft.log | sed 's/^/# /'
B="$(cal_get)"
D="$(dac_get)"
# start from the probe's state, DAC included
dev_stale; rmmod as9888_i2c; insmod $MODDIR/as9888_i2c.ko; wait_dev 5
eq "driver reload: the probe's calibration" "$(cal_get)" "$CAL0"
check "restore --backend iio" sh -c "$CALIBD restore --backend iio --record /tmp/rec > /tmp/r.log 2>&1"
sed 's/^/# /' /tmp/r.log
CAL=$(cal_get)
diag "calibbias x y z: $CAL (the record implies $(rec_cal /tmp/rec))"
cal_near "calibbias = what the record implies" "$CAL" "$(rec_cal /tmp/rec)"
eq "calibbias as the factory test left it (it applies its record)" "$CAL" "$B"
eq "the DAC as the factory test left it" "$(dac_get)" "$D"
# the mean of 16 reads (noise 0.5 chip LSB = 2 LSB rms: the mean is within
# about 1 LSB) and the rounding of the chip: within 4 LSB
A=$(accel_mean 16)
diag "compensated readings after restore: $A"
accel_near "compensated readings after restore: 0 0 1 g" "$A" "0 0 $G_LSB" 4
dev_stale; rmmod as9888_i2c; insmod $MODDIR/as9888_i2c.ko; wait_dev 5
eq "driver reload forgets the calibration" "$(cal_get)" "$CAL0"
check "restore after the reload" sh -c "$CALIBD restore --backend iio --record /tmp/rec > /tmp/r.log 2>&1"
eq "same calibration after reload + restore" "$(cal_get)" "$CAL"
eq "same DAC after reload + restore" "$(dac_get)" "$D"
accel_near "compensated readings after reload + restore: 0 0 1 g" "$(accel_mean 16)" "0 0 $G_LSB" 4

# A record of the simulator, for the same unit: refused
$CALIBD factory-test --backend sim --sim-clock virtual --unit /tmp/daemon/unit.txt --record /tmp/rec-sim > /tmp/ft-sim.log 2>&1
check "the simulator's record says so (source = simulator)" grep -qx "source = simulator" /tmp/rec-sim
put_cal $CAL0
$CALIBD restore --backend iio --record /tmp/rec-sim > /tmp/r2.log 2>&1
rc=$?
sed 's/^/# /' /tmp/r2.log
# refused for being the simulator's: exit status 1 and the reason said
check "restore refuses the simulator's record, saying why" \
	sh -c "[ $rc -eq 1 ] && grep -q 'was written by a factory test on the simulator (source = simulator), not on this chip' /tmp/r2.log"
eq "nothing applied from the simulator's record" "$(cal_get)" "$CAL0"

# A record of another chip (ET2 differs): made on that chip, refused on this one
dev_stale
printf '%s\neeprom = 9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 52\n' "$U" > $SIM/unit
wait_dev 5
rm -f /tmp/rec2
check "factory test of another chip" \
	sh -c "$CALIBD factory-test --backend iio --record /tmp/rec2 > /tmp/ft2.log 2>&1"
dev_stale
printf '%s\n' "$U" > $SIM/unit
wait_dev 5
$CALIBD restore --backend iio --record /tmp/rec2 > /tmp/r2.log 2>&1
rc=$?
sed 's/^/# /' /tmp/r2.log
# refused for being another chip's (its EEPROM's fingerprint): exit 1, said
check "restore refuses another chip's record, saying why" \
	sh -c "[ $rc -eq 1 ] && grep -q '/tmp/rec2 belongs to chip [0-9a-f]*, .* is chip [0-9a-f]*; nothing applied' /tmp/r2.log"
eq "nothing applied from another chip's record" "$(cal_get)" "$CAL0"
