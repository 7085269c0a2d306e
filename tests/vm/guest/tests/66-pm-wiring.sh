# SPDX-License-Identifier: GPL-2.0
# Power management and wiring (issue 11, item 3), on the split driver (one
# IIO device per sensor, found by name here):
#  - system sleep (pm_test "devices": every device suspends and resumes)
#    while samples flow on the driver's data-ready trigger and on an
#    hrtimer trigger: no bus transfer reaches the unpowered chip, the
#    driver logs no error, samples flow again after resume;
#  - RSTN is low whenever the supply is off (the model counts
#    back-powering), and every power-up is a reset pulse;
#  - a lost INT1 edge and failed starts: the data-ready trigger recovers
#    (its watchdog) instead of stalling with the buffer enabled;
#  - wiring: a malformed interrupt specifier fails probe, INT1 level-high
#    works, and a board with INT2 alone samples on INT2.
# Waits are bounded but generous: a busy host slows the guest down.
# Runs on its own too (AS9888_VM_ONLY=66-pm-wiring): loads the modules.
plan 64
load_driver
load_sim
set_unit "temperature = 25" "noise = 0"

# pm_dev NAME: the IIO device directory named NAME, waiting up to 10 s
pm_dev() {
	_i=0
	while [ $_i -lt 100 ]; do
		for _d in /sys/bus/iio/devices/iio:device*; do
			[ -f "$_d/name" ] && [ "$(cat "$_d/name")" = "$1" ] &&
				{ echo "$_d"; return 0; }
		done
		sleep 0.1; _i=$((_i + 1))
	done
	echo /nonexistent-iio-device
	return 1
}
# pm_buf_on DEV TRIGGER: accel or magn x/y/z + timestamp into DEV's buffer
pm_buf_on() {
	_se=$1/scan_elements
	[ -d "$_se" ] || _se=$1/buffer0
	for _c in "$_se"/in_*_en; do
		echo 1 > "$_c"
	done
	echo "$2" > $1/trigger/current_trigger
	echo 4096 > $1/buffer/length
	echo 1 > $1/buffer/enable
}
# pm_buf_off DEV: stop, drain into /tmp/pm-drain, detach the trigger
pm_buf_off() {
	echo 0 > $1/buffer/enable
	timeout 5 cat /dev/iio:device${1##*iio:device} > /tmp/pm-drain
	echo "" > $1/trigger/current_trigger
}
# pm_flowing WHAT: chip measurements go on: 10 more within 20 s
pm_flowing() {
	_m0=$(stat_get chip_measurements)
	_i=0
	while [ $_i -lt 200 ]; do
		[ $(($(stat_get chip_measurements) - _m0)) -ge 10 ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	diag "$1: measurements stuck at $(stat_get chip_measurements)"
	return 1
}
# pm_log_sleep N: driver messages after line N of dmesg while the system
# was in sleep or on its way in or out ("PM: suspend entry" to "PM:
# suspend exit"): a measurement tried then finds no powered chip. A
# message after resume is a matter of the host's load (an INT1 edge
# delivered late), not of power management.
pm_log_sleep() {
	dmesg | tail -n +$(($1 + 1)) |
		sed -n '/PM: suspend entry/,/PM: suspend exit/p' |
		grep -i 'as9888' | grep -v 'as9888_sim'
}
# pm_log_since N: driver messages after line N of dmesg
pm_log_since() { dmesg | tail -n +$(($1 + 1)) | grep -i 'as9888' | grep -v 'as9888_sim'; }
# pm_wait_stat NAME VALUE: up to 20 s for a counter of stats to reach VALUE
pm_wait_stat() {
	_i=0
	while [ $_i -lt 200 ]; do
		[ "$(stat_get $1)" -ge "$2" ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}

ACC=$(pm_dev as9888-accel)
check "accelerometer device as9888-accel" test -d "$ACC"
MAG=$(pm_dev as9888-magn)
check "magnetometer device as9888-magn" test -d "$MAG"
PMD=$(readlink -f $ACC)/../power
T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
check "data-ready trigger registered" test -n "$T"
echo 100 > $ACC/sampling_frequency

# --- RSTN and runtime suspend -----------------------------------------------
# held active while the counters are taken
echo 60000 > $PMD/autosuspend_delay_ms
cat $ACC/in_accel_z_raw > /dev/null
_p0=$(stat_get chip_power_offs)
_r0=$(stat_get chip_resets)
echo 200 > $PMD/autosuspend_delay_ms
_i=0
while [ $_i -lt 300 ] && [ "$(cat $PMD/runtime_status)" != suspended ]; do
	sleep 0.1; _i=$((_i + 1))
done
eq "runtime suspend: the device suspends" "$(cat $PMD/runtime_status)" suspended
eq "runtime suspend: the supply went off" "$(stat_get chip_power_offs)" $((_p0 + 1))
eq "runtime suspend: RSTN low before the supply went off (no back-powering)" \
	"$(stat_get chip_backpowered)" 0
check "runtime suspend: RSTN held low while unpowered" \
	sh -c "grep 'AS9888_RSTN' /sys/kernel/debug/gpio | grep -q 'reset.*out lo'"
echo 60000 > $PMD/autosuspend_delay_ms
z=$(cat $ACC/in_accel_z_raw)
near "runtime resume: z reads about 1 g (factory calibration)" "$z" 1024 64
eq "runtime resume: a reset pulse with the power-up" "$(stat_get chip_resets)" $((_r0 + 1))
eq "runtime resume: no back-powering" "$(stat_get chip_backpowered)" 0
eq "no bus transfer reached the unpowered chip" "$(stat_get chip_unpowered_transfers)" 0

# --- system sleep while samples flow ----------------------------------------
# sleep_test WHAT: one system sleep ("freeze" with pm_test "devices": every
# device suspends, the kernel waits pm_test_delay s, every device resumes)
sleep_test() {
	_p0=$(stat_get chip_power_offs)
	_r0=$(stat_get chip_resets)
	_u0=$(stat_get chip_unpowered_transfers)
	_b0=$(stat_get chip_backpowered)
	_n0=$(dmesg | wc -l)
	check "$1: system sleep and resume" sh -c "echo freeze > /sys/power/state"
	eq "$1: the supply went off in sleep" "$(stat_get chip_power_offs)" $((_p0 + 1))
	eq "$1: no bus transfer reached the unpowered chip" \
		"$(stat_get chip_unpowered_transfers)" "$_u0"
	eq "$1: RSTN low while unpowered (no back-powering)" \
		"$(stat_get chip_backpowered)" "$_b0"
	eq "$1: resume pulsed reset" "$(stat_get chip_resets)" $((_r0 + 1))
	check "$1: samples flow again after resume" pm_flowing "$1"
	_l=$(pm_log_since $_n0)
	[ -n "$_l" ] && echo "$_l" | sed 's/^/# /'
	eq "$1: no driver message while the system sleeps" "$(pm_log_sleep $_n0)" ""
}

if [ -w /sys/power/pm_test ] && grep -qw freeze /sys/power/state; then
	echo devices > /sys/power/pm_test
	[ -w /sys/module/suspend/parameters/pm_test_delay ] &&
		echo 2 > /sys/module/suspend/parameters/pm_test_delay

	pm_buf_on $ACC "$T"
	pm_buf_on $MAG "$T"
	check "data-ready trigger: samples flow" pm_flowing "data-ready trigger"
	sleep_test "data-ready trigger, both buffers"
	pm_buf_off $MAG
	pm_buf_off $ACC
	check "data-ready trigger: samples captured" test -s /tmp/pm-drain

	mkdir -p /sys/kernel/config/iio/triggers/hrtimer/as9888pm
	for t in /sys/bus/iio/devices/trigger*; do
		[ "$(cat $t/name)" = as9888pm ] && echo 200 > $t/sampling_frequency
	done
	pm_buf_on $ACC as9888pm
	check "hrtimer trigger: samples flow" pm_flowing "hrtimer trigger"
	sleep_test "hrtimer trigger"
	pm_buf_off $ACC
	check "hrtimer trigger: samples captured" test -s /tmp/pm-drain

	# runtime suspend right after the buffer stops, the hrtimer running on
	echo 0 > $PMD/autosuspend_delay_ms
	_n0=$(dmesg | wc -l)
	_u0=$(stat_get chip_unpowered_transfers)
	pm_buf_on $ACC as9888pm
	sleep 1
	pm_buf_off $ACC
	sleep 1
	eq "buffer off, hrtimer on: runtime suspended" "$(cat $PMD/runtime_status)" suspended
	eq "buffer off, hrtimer on: no bus transfer to the unpowered chip" \
		"$(stat_get chip_unpowered_transfers)" "$_u0"
	eq "buffer off, hrtimer on: no driver message" "$(pm_log_since $_n0)" ""
	echo 60000 > $PMD/autosuspend_delay_ms
	echo none > /sys/power/pm_test
else
	nok_for 21 "system sleep: /sys/power/pm_test and freeze available (CONFIG_PM_DEBUG)"
fi

# --- the data-ready trigger recovers ----------------------------------------
# Failed starts, then a lost INT1 edge on a device probed afresh, so that
# each fails on its own when the driver does not recover from it.
pm_buf_on $ACC "$T"
check "watchdog: samples flow" pm_flowing "before the failed starts"
_n0=$(dmesg | wc -l)
echo 8 > $SIM/fail_next
_i=0
while [ $_i -lt 200 ] && [ "$(cat $SIM/fail_next)" != 0 ]; do
	sleep 0.1; _i=$((_i + 1))
done
eq "failed transfers: all 8 spent (the trigger kept trying)" "$(cat $SIM/fail_next)" 0
echo 0 > $SIM/fail_next
check "failed starts: samples flow again (within 20 s)" pm_flowing "after failed starts"
check "failed starts: the driver says so" \
	sh -c "dmesg | tail -n +$((_n0 + 1)) | grep -q 'cannot start a sample'"
pm_buf_off $ACC
check "failed starts: samples captured" test -s /tmp/pm-drain

# the same wiring again: the device is re-created on a chip powered afresh
echo int1 > $SIM/wiring
ACC=$(pm_dev as9888-accel)
PMD=$(readlink -f $ACC)/../power
T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
check "lost INT1 edge: a new device and its trigger" test -n "$T"
echo 100 > $ACC/sampling_frequency
pm_buf_on $ACC "$T"
check "lost INT1 edge: samples flow" pm_flowing "before the lost edge"
_n0=$(dmesg | wc -l)
_d0=$(stat_get irqs_dropped)
echo 1 > $SIM/drop_int1
check "lost INT1 edge: the adapter dropped one" pm_wait_stat irqs_dropped $((_d0 + 1))
check "lost INT1 edge: samples flow again (within 20 s)" pm_flowing "after a lost INT1 edge"
check "lost INT1 edge: the driver says so" \
	sh -c "dmesg | tail -n +$((_n0 + 1)) | grep -q 'no INT1 edge'"
pm_buf_off $ACC
check "lost INT1 edge: samples captured" test -s /tmp/pm-drain
echo 2000 > $PMD/autosuspend_delay_ms

# --- wiring -----------------------------------------------------------------
# pm_absent NAME: no IIO device NAME appears within 3 s
pm_absent() {
	sleep 3
	for _d in /sys/bus/iio/devices/iio:device*; do
		[ -f "$_d/name" ] && [ "$(cat "$_d/name")" = "$1" ] && return 1
	done
	return 0
}

# A malformed interrupt specifier: interrupt-names, but the interrupt
# cannot be got. Probe fails and says why; it does not poll in silence.
_n0=$(dmesg | wc -l)
echo bad > $SIM/wiring
check "bad interrupt specifier: no device (probe fails)" pm_absent as9888-accel
check "bad interrupt specifier: the driver names the interrupt" \
	sh -c "dmesg | tail -n +$((_n0 + 1)) | grep -q 'cannot get interrupt INT1'"

# pm_rewire WIRING WHAT: re-wire the device; sets ACC and T, checks that
# it probes with its trigger and reads 1 g, and starts 100 Hz sampling on
# its trigger, noting the adapter's counters (one read of stats: they move
# at 100 Hz)
pm_rewire() {
	_n1=$(dmesg | wc -l)
	echo "$1" > $SIM/wiring
	eq "$2: the adapter's wiring" "$(cat $SIM/wiring)" "$1"
	ACC=$(pm_dev as9888-accel)
	check "$2: device probes" test -d "$ACC"
	T=$(cat /sys/bus/iio/devices/trigger*/name | grep "^as9888-dev" | head -n1)
	check "$2: data-ready trigger registered" test -n "$T"
	near "$2: z raw reads about 1 g" "$(cat $ACC/in_accel_z_raw 2>/dev/null)" 1024 64
	echo 100 > $ACC/sampling_frequency
	_st0=$(cat $SIM/stats)
	pm_buf_on $ACC "$T"
	check "$2: samples flow on the data-ready trigger" pm_flowing "$2"
}
# pm_stat STATS NAME: counter NAME in STATS (a copy of the adapter's stats)
pm_stat() { echo "$1" | sed -n "s/^$2 //p"; }
# pm_counted WHAT: 1 s more of sampling, then stop; sets _m (measurements),
# _i (interrupts) and _s (samples captured) since pm_rewire
pm_counted() {
	sleep 1
	_st1=$(cat $SIM/stats)
	pm_buf_off $ACC
	_m=$(($(pm_stat "$_st1" chip_measurements) - $(pm_stat "$_st0" chip_measurements)))
	_i=$(($(pm_stat "$_st1" irqs) - $(pm_stat "$_st0" irqs)))
	_s=$(($(wc -c < /tmp/pm-drain) / 16))
	diag "$1: $_m measurements, $_i interrupts, $_s samples"
	check "$1: samples captured ($_s)" test "$_s" -ge 10
}

# INT1 as a level-high interrupt: the driver deasserts it (INT1ST) before
# it is unmasked again, so about one interrupt per sample, no storm (a
# line left high fires again each time it is unmasked: thousands a second)
pm_rewire int1-level "INT1 level-high"
pm_counted "INT1 level-high"
check "INT1 level-high: no interrupt storm ($_i for $_m measurements)" \
	test $_i -le $((2 * _m + 5))
eq "INT1 level-high: no driver message" "$(pm_log_since $_n1)" ""

# INT2 alone, the only interrupt the firmware names ("INT2" in
# interrupt-names; INT1 goes nowhere): the driver takes INT2 for data
# ready, enables it (INT2EN) and leaves INT1EN clear, and the trigger runs
# on INT2's edges. Without INT2 support such a board would poll: no
# trigger, and no interrupt at all.
# pm_reg REG: the chip's register REG ("0x03") as the adapter's regs shows it
pm_reg() { sed -n "s/^$1 //p" $SIM/regs; }
pm_rewire int2 "INT2 only"
_e1=$(pm_reg 0x02)
_e2=$(pm_reg 0x03)
pm_counted "INT2 only"
diag "INT2 only: INT1EN $_e1, INT2EN $_e2 while sampling"
eq "INT2 only: INT1EN clear while sampling" "$_e1" 0x00
check "INT2 only: INT2EN set while sampling ($_e2)" \
	test -n "$_e2" -a "$_e2" != 0x00
check "INT2 only: one interrupt per measurement ($_i for $_m)" \
	test $_i -ge $((_m / 2)) -a $_i -le $((_m + 5))
eq "INT2 only: no driver message" "$(pm_log_since $_n1)" ""

echo int1 > $SIM/wiring
ACC=$(pm_dev as9888-accel)
check "default wiring again: device probes" test -d "$ACC"
