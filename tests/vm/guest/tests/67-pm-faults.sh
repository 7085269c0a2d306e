# SPDX-License-Identifier: GPL-2.0
# Power management error paths, with the adapter's supply failing on
# purpose (fail_supply_off, fail_supply_on):
#  - runtime suspend whose power-off fails: the driver restores the
#    registers (RSTN was pulsed), the device stays active and usable, and
#    it suspends normally the next time. A driver that returns the
#    regulator's error instead of -EAGAIN leaves the device in the runtime
#    PM error state (runtime_status "error"): every later access fails.
#  - system resume whose power-up fails: the device is left runtime
#    suspended, and the next access powers it up and measures. A driver
#    that stays in its "system sleep" state after the failed resume
#    answers every later measurement with -EBUSY.
# Runs on its own too (AS9888_VM_ONLY=67-pm-faults): loads the modules.
plan 24
load_driver
load_sim
set_unit "temperature = 25" "noise = 0"
wait_dev 10
PF=$(pm_dir)

# pf_spent KNOB: up to 30 s for the adapter's KNOB to count down to 0
pf_spent() {
	_i=0
	while [ $_i -lt 300 ]; do
		[ "$(cat $SIM/$1)" = 0 ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}
# pf_z: the accelerometer's z reading, empty when the read fails
pf_z() { cat $DEV/in_accel_z_raw 2>/dev/null; }
pf_regs() { cat $SIM/regs; }

# --- runtime suspend: the supply cannot be switched off -----------------------
echo 60000 > $PF/autosuspend_delay_ms
near "active: z reads about 1 g" "$(pf_z)" 1024 64
_r0=$(pf_regs)
_p0=$(stat_get chip_power_offs)
_s0=$(stat_get chip_resets)
echo 1 > $SIM/fail_supply_off
echo 200 > $PF/autosuspend_delay_ms
check "failed power-off: the driver tried to switch the supply off" \
	pf_spent fail_supply_off
# hold the device active again while its state is inspected
echo 60000 > $PF/autosuspend_delay_ms
eq "failed power-off: the device stays active (not in the runtime PM error state)" \
	"$(cat $PF/runtime_status)" active
eq "failed power-off: the supply stayed on" "$(stat_get chip_power_offs)" "$_p0"
eq "failed power-off: RSTN was pulsed" "$(stat_get chip_resets)" $((_s0 + 1))
eq "failed power-off: every trim, DAC and INTxEN register restored" \
	"$(pf_regs)" "$_r0"
near "failed power-off: z still reads about 1 g" "$(pf_z)" 1024 64
echo 200 > $PF/autosuspend_delay_ms
check "failed power-off: the next autosuspend succeeds" wait_runtime suspended
eq "failed power-off: then the supply goes off" \
	"$(stat_get chip_power_offs)" $((_p0 + 1))
echo 60000 > $PF/autosuspend_delay_ms
near "after the next suspend: z reads about 1 g" "$(pf_z)" 1024 64

# --- system resume: the supply cannot be switched on --------------------------
# "on" holds a runtime PM reference over the sleep: the device is in use,
# so pm_runtime_force_resume() powers it up at resume (an unused device
# would stay suspended until its next use)
if [ -w /sys/power/pm_test ] && grep -qw freeze /sys/power/state; then
	echo on > $PF/control
	near "in use: z reads about 1 g" "$(pf_z)" 1024 64
	echo devices > /sys/power/pm_test
	[ -w /sys/module/suspend/parameters/pm_test_delay ] &&
		echo 1 > /sys/module/suspend/parameters/pm_test_delay
	kmsg_mark 67-resume
	_p0=$(stat_get chip_power_offs)
	echo 1 > $SIM/fail_supply_on
	check "failed power-up: system sleep and resume" \
		sh -c "echo freeze > /sys/power/state"
	echo none > /sys/power/pm_test
	# (at least once: a regulator core that switches vid on while vdd
	# fails switches it off again)
	check "failed power-up: the supply went off in sleep" \
		test "$(stat_get chip_power_offs)" -ge $((_p0 + 1))
	eq "failed power-up: resume tried to switch the supply on" \
		"$(cat $SIM/fail_supply_on)" 0
	check "failed power-up: the resume error is reported" \
		kmsg_since 67-resume 'failed to resume'
	eq "failed power-up: the device is left runtime suspended" \
		"$(cat $PF/runtime_status)" suspended
	_z=$(pf_z)
	near "failed power-up: the next read powers the chip up and measures (z about 1 g)" \
		"$_z" 1024 64
	eq "failed power-up: the device is active again" \
		"$(cat $PF/runtime_status)" active
	check "failed power-up: the magnetometer measures too" \
		sh -c "cat $MDEV/in_magn_x_raw > /dev/null"
	echo auto > $PF/control

	# A buffer on the data-ready trigger over a failed power-up: the
	# trigger is not restarted on the unpowered chip (no sample whose
	# edge never comes, no watchdog warning); disabled and enabled
	# again, the buffer powers the chip up and gets samples.
	T=$(dr_trig)
	echo 100 > $DEV/sampling_frequency
	SE=$(se_dir $DEV)
	for c in in_accel_x in_accel_y in_accel_z in_timestamp; do
		echo 1 > $SE/${c}_en
	done
	echo "$T" > $DEV/trigger/current_trigger
	echo 1024 > $DEV/buffer/length
	check "buffer over a failed power-up: enabled on $T" \
		sh -c "echo 1 > $DEV/buffer/enable"
	echo devices > /sys/power/pm_test
	kmsg_mark 67-watchdog
	echo 1 > $SIM/fail_supply_on
	check "buffer over a failed power-up: system sleep and resume" \
		sh -c "echo freeze > /sys/power/state"
	echo none > /sys/power/pm_test
	eq "buffer over a failed power-up: resume tried to switch the supply on" \
		"$(cat $SIM/fail_supply_on)" 0
	sleep 2
	echo 0 > $DEV/buffer/enable
	timeout 5 cat /dev/iio:device${DEV##*iio:device} > /dev/null
	echo "" > $DEV/trigger/current_trigger
	check_not "buffer over a failed power-up: no watchdog restart on the unpowered chip" \
		kmsg_since 67-watchdog 'edge .* after a sample started'
	if capture "$T" 1 /tmp/pf.bin; then
		check "buffer enabled again: at least 50 samples in 1 s ($(samples /tmp/pf.bin))" \
			test "$(samples /tmp/pf.bin)" -ge 50
	else
		nok "buffer enabled again after the failed power-up"
	fi
else
	nok_for 14 "system sleep: /sys/power/pm_test and freeze available (CONFIG_PM_DEBUG)"
fi
echo 2000 > $PF/autosuspend_delay_ms
