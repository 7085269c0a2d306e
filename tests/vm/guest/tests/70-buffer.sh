# SPDX-License-Identifier: GPL-2.0
# Buffered capture with the driver's data-ready trigger and an hrtimer
# trigger: sample counts, monotonic timestamps, values, bus transfers.
plan 19
set_unit "temperature = 25" "noise = 0"
wait_dev 5
set_cal 0 0 0 25000

T=$(dr_trig)
check "driver registers its data-ready trigger" test -n "$T"
echo 100 > $DEV/sampling_frequency 2>/dev/null || echo 100 > $DEV/in_sampling_frequency 2>/dev/null
P100=""
if capture "$T" 2 /tmp/buf1; then
	S=$(samples /tmp/buf1)
	diag "data-ready trigger: $S samples in 2 s, measurements $((CAP_M1 - CAP_M0)), transfers $((CAP_T1 - CAP_T0))"
	check "data-ready trigger: at least 20 samples in 2 s ($S)" test "$S" -ge 20
	P=$(period_us /tmp/buf1)
	diag "data-ready trigger: mean sample period $P us"
	# TCG adds latency to every wake-up; the driver schedules each
	# measurement a period after the previous one was due, so lateness
	# does not add up
	period_ok "data-ready trigger at 100 Hz" "$P" 10000
	P100=$P
	check "data-ready trigger: timestamps strictly increasing" monotonic /tmp/buf1
	eq "data-ready trigger: every z sample 1 g (1024 +- 4)" "$(zbad /tmp/buf1)" 0
	M=$((CAP_M1 - CAP_M0))
	if [ $M -gt 0 ]; then
		TPS=$(echo "$((CAP_T1 - CAP_T0)) $M" | awk '{ printf "%.2f", $1 / $2 }')
		diag "AS9888-METRIC transfers_per_sample=$TPS rate_hz=$(echo "$P" | awk '{ printf "%.1f", 1e6 / $1 }')"
		check "bus transfers per buffered sample $TPS <= 2 (MS write + burst read)" \
			awk "BEGIN { exit !($TPS <= 2.02) }"
	else
		nok "measurements during the capture"
	fi
else
	nok_for 5 "buffer enable with the data-ready trigger"
fi

# The accelerometer alone above 100 Hz (t_ACC = 1.2 ms, issue 24): the
# rates the guest delivers go to the log (README, "Measured"). Under TCG
# on a busy host a guest does not keep 400 Hz (nor the hrtimer trigger its
# 50 Hz): never faster than asked, and faster than the 100 Hz capture
# above, which ran under the same load
for f in 200 400; do
	echo $f > $DEV/sampling_frequency
	if capture "$T" 2 /tmp/buf-$f; then
		P=$(period_us /tmp/buf-$f)
		diag "AS9888-METRIC accel_only_${f}hz_delivered_hz=$(echo "$P" | awk '{ if ($1) printf "%.1f", 1e6 / $1 }') period_us=$P samples=$(samples /tmp/buf-$f)"
		check "accelerometer alone at $f Hz: mean period $P us, not under $((900000 / f)) us" \
			test "${P:-0}" -ge $((900000 / f))
		check "accelerometer alone at $f Hz: faster than at 100 Hz ($P < ${P100:-none} us)" \
			test "${P:-0}" -gt 0 -a "${P:-0}" -lt "${P100:-0}"
		check "accelerometer alone at $f Hz: timestamps strictly increasing" monotonic /tmp/buf-$f
	else
		nok_for 3 "buffer enable at $f Hz"
	fi
done
# the magnetometer on the trigger limits the accelerometer to its 100 Hz
buf_start $MDEV "$T" /tmp/buf-magn magn_x magn_y magn_z timestamp
eq "accelerometer asked 400 Hz reads 100 Hz while the magnetometer buffers" \
	"$(cat $DEV/sampling_frequency)" 100
check "magnetometer samples flow beside it" wait_grow /tmp/buf-magn 160
buf_stop $MDEV $BUF_PID /tmp/buf-magn
eq "accelerometer back at 400 Hz when the magnetometer stops" \
	"$(cat $DEV/sampling_frequency)" 400
echo 100 > $DEV/sampling_frequency

mkdir -p /sys/kernel/config/iio/triggers/hrtimer/as9888t0
for t in /sys/bus/iio/devices/trigger*; do
	[ "$(cat $t/name)" = as9888t0 ] && echo 50 > $t/sampling_frequency
done
if capture as9888t0 2 /tmp/buf2; then
	S=$(samples /tmp/buf2)
	diag "hrtimer trigger 50 Hz: $S samples in 2 s"
	check "hrtimer trigger: at least 10 samples ($S)" test "$S" -ge 10
	P=$(period_us /tmp/buf2)
	diag "hrtimer trigger: mean sample period $P us"
	period_ok "hrtimer trigger at 50 Hz" "$P" 20000
	check "hrtimer trigger: timestamps strictly increasing" monotonic /tmp/buf2
	eq "hrtimer trigger: every z sample 1 g (1024 +- 4)" "$(zbad /tmp/buf2)" 0
else
	nok_for 4 "buffer enable with an hrtimer trigger"
fi
