# SPDX-License-Identifier: GPL-2.0
# The long-running daemon in a real kernel: it applies the record to the
# device present at start, and again by itself after a module reload and an
# unbind/bind (real kernel uevents); the driver's offsets then match
# "as9888-calibd show" at the die temperature; requests work; SIGTERM stops
# it. Needs /tmp/rec and the unit of 80-daemon.sh.
CALIBD=/bin/as9888-calibd
SOCK=/tmp/calibd.sock

# the calibration the record gives, as the driver reads it back
want_cal() { cat $DEV/in_accel_calibration; }
# wait up to 5 s for the driver to hold the record's level data
wait_cal() {
	_i=0
	while [ $_i -lt 50 ]; do
		wait_dev 1 && [ "$(cat $DEV/in_accel_calibration)" = "$CAL" ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}

wait_dev 5
echo none > $DEV/in_accel_calibration
$CALIBD daemon --backend iio --record /tmp/rec --socket $SOCK 2>/tmp/daemon.log &
DPID=$!
check "daemon applies the record to the device present at start" wait_cal

echo none > $DEV/in_accel_calibration
rmmod as9888_i2c; insmod $MODDIR/as9888_i2c.ko
check "module reload: the daemon applies the record without being asked" wait_cal

C=$(client)
echo none > $DEV/in_accel_calibration
echo "$C" > /sys/bus/i2c/drivers/as9888_i2c/unbind
echo "$C" > /sys/bus/i2c/drivers/as9888_i2c/bind
check "unbind/bind: the daemon applies the record again" wait_cal
grep "applied to" /tmp/daemon.log | tail -n 3 | sed 's/^/# /'

# the driver's offsets against "show" at the die temperature
wait_dev 5
RAW=$(cat $DEV/in_temp_raw)
T=$(( (RAW + $(cat $DEV/in_temp_offset)) * $(cat $DEV/in_temp_scale) ))
TC=$(echo "$T" | awk '{ printf "%.3f", $1 / 1000 }')
$CALIBD show --record /tmp/rec --temperature "$TC" --json > /tmp/show.json
for a in x y z; do
	WANT=$(sed -n "s/.*\"$a\": {\"sensitivity\": [-0-9.]*, \"offset\": \([-0-9.]*\)}.*/\1/p" /tmp/show.json)
	GOT=$(cat $DEV/in_accel_${a}_offset)
	check "in_accel_${a}_offset $GOT = -(show's offset $WANT) at $TC degC" \
		awk "BEGIN { d = $GOT + $WANT; exit !(d < 0.001 && d > -0.001) }"
	WSCALE=$(sed -n "s/.*\"$a\": {\"sensitivity\": \([-0-9.]*\),.*/\1/p" /tmp/show.json)
	GSCALE=$(cat $DEV/in_accel_${a}_scale)
	check "in_accel_${a}_scale $GSCALE = 9.80665 / $WSCALE" \
		awk "BEGIN { d = $GSCALE - 9.80665 / $WSCALE; exit !(d < 1e-6 && d > -1e-6) }"
done

check "request status over the socket" sh -c "$CALIBD request status --socket $SOCK | grep -q '^Chip '"
kill -TERM $DPID
_i=0
while kill -0 $DPID 2>/dev/null && [ $_i -lt 50 ]; do sleep 0.1; _i=$((_i + 1)); done
check_not "SIGTERM stops the daemon" kill -0 $DPID
check "it stopped cleanly, each appearance applied once" \
	grep -q "stopped: calibration applied 3 times, 0 failures" /tmp/daemon.log
