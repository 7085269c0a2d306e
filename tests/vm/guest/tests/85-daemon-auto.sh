# SPDX-License-Identifier: GPL-2.0
# The long-running daemon in a real kernel: it applies the record to the
# device present at start, and again by itself after a module reload and an
# unbind/bind (real kernel uevents); the driver then holds the calibration
# the record implies (calibbias) and reads 0, 0 and 1 g;
# requests work; SIGTERM stops it. Uses /tmp/rec and the unit of
# 80-daemon.sh (daemon_fixture makes them when 80 did not run).
plan 9
CALIBD=/bin/as9888-calibd
SOCK=/tmp/calibd.sock

# the unit of 80-daemon.sh, which the record is for
daemon_fixture
load_sim
load_driver
dev_stale
printf '%s\n' "$HEALTHY_UNIT" > $SIM/unit
wait_dev 5
# the calibration the record gives, as the driver reads it back
$CALIBD restore --backend iio --record /tmp/rec > /dev/null 2>&1
CAL=$(cal_get)
cal_near "the record's calibration (restore)" "$CAL" "$(rec_cal /tmp/rec)"
# the calibration of a fresh probe: calibbias 0, zero offsets at t_RT
uncal() { set_cal 0 0 0 23750; }
# wait up to 10 s for the driver to hold the record's calibration
wait_cal() {
	_i=0
	while [ $_i -lt 100 ]; do
		wait_dev 1 && [ "$(cal_get)" = "$CAL" ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}

uncal
$CALIBD daemon --backend iio --record /tmp/rec --socket $SOCK 2>/tmp/daemon.log &
DPID=$!
check "daemon applies the record to the device present at start" wait_cal

uncal
dev_stale; rmmod as9888_i2c; insmod $MODDIR/as9888_i2c.ko
check "module reload: the daemon applies the record without being asked" wait_cal

uncal
rebind
check "unbind/bind: the daemon applies the record again" wait_cal
grep "applied to" /tmp/daemon.log | tail -n 3 | sed 's/^/# /'

# what clients see: the compensated readings on the constant scale
wait_dev 5
eq "in_accel_scale = 9.80665 / 1024" "$(cat $DEV/in_accel_scale)" $G_SCALE
A=$(accel_mean 16)
diag "compensated readings: $A"
accel_near "compensated readings after the daemon's re-apply: 0 0 1 g" "$A" "0 0 $G_LSB" 4

check "request status over the socket" sh -c "$CALIBD request status --socket $SOCK | grep -q '^Chip '"
kill -TERM $DPID
_i=0
while kill -0 $DPID 2>/dev/null && [ $_i -lt 50 ]; do sleep 0.1; _i=$((_i + 1)); done
check_not "SIGTERM stops the daemon" kill -0 $DPID
check "it stopped cleanly, each appearance applied once" \
	grep -q "stopped: calibration applied 3 times, 0 failures" /tmp/daemon.log
