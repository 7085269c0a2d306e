# SPDX-License-Identifier: GPL-2.0
# The data-ready trigger never stalls (issue 24, point 5): while buffers run
# on it, the test stops and restarts them (each device alone and beside the
# other), changes their rates, reads _raw of the other device, and puts the
# system to sleep, each with the INT1 edges delivered at once, a few ms late
# (within a period), later than a period, and later than the trigger's 1 s
# watchdog (the adapter's delay_int1_us). After each step the buffer must
# deliver samples again: no sample for 30 s is a stall (the clients of the
# bench wait 60 s; the driver's own waits are 1 s and 2 s plus two periods).
# Throughout, the trigger's reenable op only re-arms: no sample is started
# from an interrupt thread (the adapter's irq_thread_starts; the edges
# later than a period make every reenable find its next sample due).
plan 66
set_unit "temperature = 25" "noise = 0"
wait_dev 5
T=$(dr_trig)
ACC=$DEV
MAG=$MDEV
check "stall: data-ready trigger registered" test -n "$T"

# st_flow NAME FILE N: FILE grows by N samples (16 bytes each) within 30 s
st_flow() {
	_sf_w=$(($(wc -c < "$2") + 16 * $3)); _sf_i=0
	while [ "$(wc -c < "$2")" -lt $_sf_w ]; do
		if [ $_sf_i -ge 300 ]; then
			nok "$1: samples flow" "no $3 samples in 30 s: $(wc -c < "$2") bytes, want $_sf_w"
			dmesg | grep -i as9888 | grep -v as9888_sim | tail -n 5 | sed 's/^/# /'
			return 1
		fi
		sleep 0.1; _sf_i=$((_sf_i + 1))
	done
	ok "$1: samples flow"
}
# accelerometer and magnetometer captures, 16 bytes a sample
acc_on() { buf_start $ACC "$T" /tmp/st-acc accel_x accel_y accel_z timestamp && ACC_PID=$BUF_PID; }
acc_off() { buf_stop $ACC "$ACC_PID" /tmp/st-acc; }
mag_on() { buf_start $MAG "$T" /tmp/st-mag magn_x magn_y magn_z timestamp && MAG_PID=$BUF_PID; }
mag_off() { buf_stop $MAG "$MAG_PID" /tmp/st-mag; }
# restart DIR N: buffer off and on again N times, as fast as sysfs goes
restart() {
	_rs_i=0; _rs_ok=0
	while [ $_rs_i -lt $2 ]; do
		echo 0 > "$1/buffer/enable"
		echo 1 > "$1/buffer/enable" && _rs_ok=$((_rs_ok + 1))
		_rs_i=$((_rs_i + 1))
	done
	[ $_rs_ok = $2 ]
}
# raw_reads FILE N: N reads of a _raw attribute succeed
raw_reads() {
	_rr_i=0
	while [ $_rr_i -lt $2 ]; do
		cat "$1" > /dev/null || return 1
		_rr_i=$((_rr_i + 1))
	done
}
CAN_SLEEP=0
if [ -w /sys/power/pm_test ] && grep -qw freeze /sys/power/state; then
	CAN_SLEEP=1
	echo devices > /sys/power/pm_test
	[ -w /sys/module/suspend/parameters/pm_test_delay ] &&
		echo 0 > /sys/module/suspend/parameters/pm_test_delay
fi

echo 100 > $ACC/sampling_frequency
echo 100 > $MAG/sampling_frequency
kmsg_mark 74-stall
ITS0=$(stat_get irq_thread_starts)
# For the log (DECISIONS, "gaps of up to a second"): the longest gap
# between two samples while both buffers run undisturbed for 5 s
acc_on
mag_on
sleep 5
diag "AS9888-METRIC trigger_steady_longest_gap_ms=$(max_gap_ms /tmp/st-acc)" \
	"(accelerometer; magnetometer $(max_gap_ms /tmp/st-mag) ms;" \
	"$(samples /tmp/st-acc) and $(samples /tmp/st-mag) samples at 100 Hz)"
mag_off
acc_off
for D in 0 3000 15000; do
	echo $D > $SIM/delay_int1_us
	W="edges ${D} us late"
	acc_on
	st_flow "$W, accelerometer alone" /tmp/st-acc 20
	check "$W: accelerometer restarted 20 times" restart $ACC 20
	st_flow "$W, accelerometer restarted" /tmp/st-acc 20
	mag_on
	st_flow "$W, magnetometer beside the accelerometer" /tmp/st-mag 10
	check "$W: magnetometer restarted 20 times beside the accelerometer" restart $MAG 20
	st_flow "$W, accelerometer while the magnetometer restarts" /tmp/st-acc 20
	st_flow "$W, magnetometer restarted" /tmp/st-mag 10
	check "$W: accelerometer restarted 20 times beside the magnetometer" restart $ACC 20
	st_flow "$W, magnetometer while the accelerometer restarts" /tmp/st-mag 10
	st_flow "$W, accelerometer restarted beside the magnetometer" /tmp/st-acc 20
	for f in 50 1 100 20 100; do
		echo $f > $ACC/sampling_frequency
		echo $f > $MAG/sampling_frequency
	done
	st_flow "$W, accelerometer after rate changes" /tmp/st-acc 20
	st_flow "$W, magnetometer after rate changes" /tmp/st-mag 10
	mag_off
	check "$W: magnetometer _raw beside the accelerometer's buffer" \
		raw_reads $MAG/in_magn_x_raw 20
	st_flow "$W, accelerometer after magnetometer reads" /tmp/st-acc 20
	acc_off
	mag_on
	check "$W: accelerometer _raw beside the magnetometer's buffer" \
		raw_reads $ACC/in_accel_z_raw 20
	st_flow "$W, magnetometer after accelerometer reads" /tmp/st-mag 10
	acc_on
	if [ $CAN_SLEEP = 1 ]; then
		check "$W: system sleep with both buffers running" \
			sh -c "echo freeze > /sys/power/state"
		st_flow "$W, accelerometer after resume" /tmp/st-acc 20
		st_flow "$W, magnetometer after resume" /tmp/st-mag 10
	else
		# as 67-pm-faults: the bench's kernels have CONFIG_PM_DEBUG
		nok_for 3 "$W: system sleep with both buffers running" \
			"/sys/power/pm_test and freeze available (CONFIG_PM_DEBUG)"
	fi
	mag_off
	acc_off
done

# Edges later than the watchdog: every sample is aborted and started again
# before its edge comes; the late edge then fires the trigger on the sample
# started after it, so the buffer still gets about one sample a second
# the edges this part delays (the counter holds earlier files' too)
DELAYED0=$(stat_get irqs_delayed)
echo 1500000 > $SIM/delay_int1_us
acc_on
st_flow "edges 1.5 s late (beyond the watchdog), accelerometer" /tmp/st-acc 3
check "edges 1.5 s late: accelerometer restarted 5 times" restart $ACC 5
st_flow "edges 1.5 s late, accelerometer restarted" /tmp/st-acc 3
echo 0 > $SIM/delay_int1_us
st_flow "edges on time again, accelerometer" /tmp/st-acc 50
acc_off
check "edges were delayed (by this part)" test $(($(stat_get irqs_delayed) - DELAYED0)) -gt 0
eq "no sample started from an interrupt thread (reenable only re-arms)" \
	$(($(stat_get irq_thread_starts) - ITS0)) 0
[ $CAN_SLEEP = 1 ] && echo none > /sys/power/pm_test
check "stall: the test's mark still in the kernel log" \
	sh -c "dmesg | grep -q 'as9888-bench: mark 74-stall'"
check_not "stall: the driver logged no stall" kmsg_since 74-stall 'trigger stalled'
