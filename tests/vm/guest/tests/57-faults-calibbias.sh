# SPDX-License-Identifier: GPL-2.0
# A calibbias write whose bus transfer fails (issue 38, item D) changes
# nothing: the attribute reads the calibbias kept, the driver's register
# cache (what compensates every sample, read through direct_reg_access)
# and the chip (the adapter's regs, read without a bus transfer) hold its
# offset DAC value, and _raw reads as before. Once with the write failing
# (the driver writes the old value back), once with the write back failing
# too (the cache must hold the old value all the same; the driver says the
# chip may not); then once more after a runtime suspend, whose resume
# writes the register cache to the chip. regmap caches a value before its
# bus write and, when a raw write fails on the bus, drops the register
# from its cache (a value that reads back wrong stays there): before the
# fix, resume then did not restore that DAC register at all, and the chip
# ran with its reset value under the calibbias kept.
plan 20
set_unit "temperature = 23.75" "offset = 40 -25 60" "noise = 0"
wait_dev 5
# the device stays powered: a runtime resume would spend the failures on
# its register restore instead of the calibbias write
echo on > "$(pm_dir)/control"
set_cal 40 -25 60
CAL0=$(cal_get)
DAC0=$(dac_get)
RAW0=$(accel_mean 2)
# chip_dac: the offset DAC registers as the chip holds them
chip_dac() { echo $(sed -n 's/^0x3[789] //p' $SIM/regs); }
X0=${CAL0%% *}
kmsg_mark 57-calibbias
for N in 1 2; do
	W="calibbias write, $N transfer(s) failing"
	echo $N > $SIM/fail_next
	check_not "$W: the write fails" \
		sh -c "echo $((X0 + 2000)) > $DEV/in_accel_x_calibbias"
	eq "$W: every failure spent on it" "$(cat $SIM/fail_next)" 0
	echo 0 > $SIM/fail_next
	eq "$W: calibbias reads the old values" "$(cal_get)" "$CAL0"
	eq "$W: the driver's cache holds the old DAC values" "$(dac_get)" "$DAC0"
	eq "$W: the chip holds the old DAC values" "$(chip_dac)" "$DAC0"
	accel_near "$W: _raw as before" "$(accel_mean 2)" "$RAW0" 1
done
check "the failed write back was logged" \
	kmsg_since 57-calibbias 'may hold'
# Runtime PM cuts the supplies and writes the cache back on resume: the
# DAC the chip runs with afterwards is the cache's
echo auto > "$(pm_dir)/control"
check "after the failed writes: runtime suspended" wait_runtime suspended
accel_near "after a runtime suspend: _raw as before" "$(accel_mean 2)" "$RAW0" 1
eq "after a runtime suspend: the chip holds the old DAC values" "$(chip_dac)" "$DAC0"
echo on > "$(pm_dir)/control"
# the bus works again: the same write goes through and moves x
check "calibbias write on a working bus" \
	sh -c "echo $((X0 + 2000)) > $DEV/in_accel_x_calibbias"
eq "calibbias reads the new x" "$(cal_get | cut -d' ' -f1)" $((X0 + 2000))
# (the test's premise: this write changes the DAC, so a failed one that
# left the new value in the cache would show above)
check_not "the new x moved the DAC" test "$(dac_get)" = "$DAC0"
eq "the chip holds the DAC values of the cache" "$(chip_dac)" "$(dac_get)"
put_cal $CAL0
echo auto > "$(pm_dir)/control"
