# SPDX-License-Identifier: GPL-2.0
# Concurrent users while the accel device's buffer runs on the data-ready
# trigger: raw reads and oversampling_ratio writes fail with EBUSY
# (documented in Documentation/iio/as9888.rst), a second open of the
# character device fails with EBUSY, scale and calibration reads succeed;
# calibbias writes succeed, taken between two samples (a restore under a
# client that holds the buffer), and the samples move by the calibbias
# written, each compensated for the DAC it was measured with;
# the capture keeps its rate and loses no sample. (The selftest is the
# magn device's now: beside the accel buffer it runs, 73-split.sh; under
# the magn device's own buffer it is refused, 58-bad-input.sh.) First, a
# calibbias write with nothing running costs the DAC write and its
# read-back only: the driver knows the chip is in power-down.
plan 16
set_unit "temperature = 25" "noise = 0"
wait_dev 5
set_cal 0 0 0 25000
T=$(dr_trig)
N=${DEV##*iio:device}
SE=$DEV/scan_elements
for f in $SE/*_en; do echo 0 > $f; done
for c in in_accel_x in_accel_y in_accel_z in_timestamp; do echo 1 > $SE/${c}_en; done
echo 100 > $DEV/sampling_frequency
echo "$T" > $DEV/trigger/current_trigger
echo 4096 > $DEV/buffer/length
b0=$(cat $DEV/in_accel_x_calibbias)
# (powered throughout: no runtime resume's transfers in the count)
PWR=$(readlink -f $DEV)/../power/control
echo on > $PWR
x0=$(stat_get bus_transfers)
echo $b0 > $DEV/in_accel_x_calibbias
eq "a calibbias write with no measurement running: 2 bus transfers (DAC write, read-back)" \
	$(($(stat_get bus_transfers) - x0)) 2
echo auto > $PWR
lp0=$(cat $DEV/in_accel_oversampling_ratio)
cal0=$(cal_get)
cat $SIM/stats > /tmp/cc-stats0
echo 1 > $DEV/buffer/enable
cat /dev/iio:device$N > /tmp/cc.bin &
READER=$!
sleep 0.2
t0=$(uptime_s)

# second reader of the character device
if cat /dev/iio:device$N > /tmp/cc2.bin 2>/tmp/cc2.err; then
	nok "second open of /dev/iio:device$N fails"
else
	check "second open of /dev/iio:device$N fails with EBUSY" grep -qi busy /tmp/cc2.err
fi

# three background sysfs readers, 10 raw reads each: result lines "ok"/"busy"/"other"
for r in x y z; do
	(
		i=0
		while [ $i -lt 10 ]; do
			if v=$(cat $DEV/in_accel_${r}_raw 2>/tmp/cc-r$r.err); then
				echo "ok $v"
			elif grep -qi busy /tmp/cc-r$r.err; then
				echo busy
			else
				echo "other $(cat /tmp/cc-r$r.err)"
			fi
			i=$((i + 1))
		done > /tmp/cc-r$r.out
	) &
	eval "R$r=\$!"
done
# and scale and calibration reads: the driver's state, no measurement
sc_ok=0; i=0
while [ $i -lt 10 ]; do
	v=$(cat $DEV/in_accel_scale 2>/dev/null) && [ "$v" = $G_SCALE ] && sc_ok=$((sc_ok + 1))
	[ "$(cal_get)" = "$cal0" ] && sc_ok=$((sc_ok + 1))
	i=$((i + 1))
done
# writes while buffering
cb_ok=0; cb_back=0; lp_busy=0; i=0
while [ $i -lt 3 ]; do
	# 200 more each time (about one DAC code, 2048 / (gain + 16) chip
	# counts), away from the end of the range
	cb=$((b0 + (i + 1) * 200 * (1 - 2 * (b0 > 0))))
	if echo $cb 2>/tmp/cc-w.err > $DEV/in_accel_x_calibbias; then
		cb_ok=$((cb_ok + 1))
		[ "$(cat $DEV/in_accel_x_calibbias)" = $cb ] && cb_back=$((cb_back + 1))
	else
		diag "calibbias $cb while buffering: $(cat /tmp/cc-w.err)"
	fi
	sleep 0.1
	echo 4 2>/tmp/cc-w.err > $DEV/in_accel_oversampling_ratio ||
		{ grep -qi busy /tmp/cc-w.err && lp_busy=$((lp_busy + 1)); }
	i=$((i + 1))
done
wait $Rx $Ry $Rz
sleep 1
t1=$(uptime_s)
cat $SIM/stats > /tmp/cc-stats1
echo 0 > $DEV/buffer/enable
# the reader drains what is left, then blocks on the empty buffer
sleep 0.5
kill $READER 2>/dev/null
wait $READER 2>/dev/null
echo "" > $DEV/trigger/current_trigger

eq "3 x 10 raw reads while buffering: all EBUSY" \
	"$(cat /tmp/cc-rx.out /tmp/cc-ry.out /tmp/cc-rz.out | sort | uniq -c | sed 's/^ *//')" "30 busy"
eq "10 scale and 10 calibration reads while buffering succeed" $sc_ok 20
eq "3 calibbias writes while buffering succeed" $cb_ok 3
eq "3 calibbias writes while buffering read back" $cb_back 3
eq "3 oversampling_ratio writes while buffering: EBUSY" $lp_busy 3
eq "calibbias: the last value written while buffering stays" \
	"$(cat $DEV/in_accel_x_calibbias)" "$cb"
echo $b0 > $DEV/in_accel_x_calibbias
eq "oversampling_ratio unchanged" "$(cat $DEV/in_accel_oversampling_ratio)" "$lp0"

S=$(samples /tmp/cc.bin)
M=$(($(sed -n 's/^chip_measurements //p' /tmp/cc-stats1) - $(sed -n 's/^chip_measurements //p' /tmp/cc-stats0)))
E=$(echo "$t0 $t1" | awk '{ printf "%d", ($2 - $1) * 100 }')
diag "capture: $S samples, $M measurements; about $E expected from 100 Hz over the busy part"
# (a busy host slows the TCG guest: half the rate is still no stall; that
# no sample is lost is the next check)
check "capture: at least half of the samples 100 Hz gives while busy ($S vs $E)" test $((S * 2)) -ge "$E"
check "capture: every measurement of the window reached the reader ($S >= $M - 2)" test $S -ge $((M - 2))
check "capture: timestamps strictly increasing" monotonic /tmp/cc.bin
eq "capture: every z sample 1 g (1024 +- 4)" "$(zbad /tmp/cc.bin)" 0
# calibbias moved x three times during the capture, 200 each time, and the
# DAC with it: 200 * St_RT / St(25) LSB a step at 25 degC (datasheet 6.4,
# from the EEPROM). Each sample is compensated for the calibbias and DAC
# it was measured with: x is k steps from 0 g (+- 4), k = 0..3, and k
# never goes back
D=$(ee_bytes | awk -v s=$((1 - 2 * (b0 > 0))) '{ r = int($3 / 8) % 32; if (r >= 16) r -= 32
	k = -0.428125 + 0.04375 * int($17 / 32)
	printf "%.3f", s * 200 / (1 + k / 100 * (25 - (176 - 136 - r) / 1.6)) }')
eq "capture: every x sample k steps of $D LSB from 0 g (+- 4), k = 0..3 in order" \
	"$(od -A n -t d2 -v /tmp/cc.bin | awk -v d="$D" 'NF == 8 { q = $1 / d; k = int(q + 0.5)
		e = $1 - k * d; if (e < 0) e = -e
		if (k < 0 || k > 3 || e > 4 || k < last) bad++; else last = k }
		END { print bad + 0 }')" 0
P=$(period_us /tmp/cc.bin)
period_ok "capture under load at 100 Hz" "$P" 10000
check "device usable after the capture" test -n "$(cat $DEV/in_accel_x_raw)"
