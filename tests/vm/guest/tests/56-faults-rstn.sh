# SPDX-License-Identifier: GPL-2.0
# rstn_open: the reset line is not connected, reset pulses do nothing.
# The datasheet checks RSTN only in the factory function test (section 7,
# D11: INT1EN reads back 0x00 after a pulse), which is the daemon's job;
# the driver pulses RSTN at probe without checking it. The chip has just
# been powered on, so it is in its reset state anyway and probe works:
# assert that, and that the pulse really had no effect on this unit.
plan 11
set_unit "temperature = 25" "noise = 0"
check "healthy unit probes" wait_dev 5
# at least one: RSTN is also held low while runtime PM has the supplies
# off, so a power-up after probe is one more pulse
r=$(stat_get chip_resets)
check "healthy unit: the probe's reset pulse took effect ($r resets)" test "$r" -ge 1
z_ok=$(cat $DEV/in_accel_z_raw)

n0=$(dmesg | wc -l)
set_unit "temperature = 25" "noise = 0" "fault = rstn_open"
check "rstn_open: device probes" wait_dev 5
eq "rstn_open: the reset pulse had no effect" "$(stat_get chip_resets)" 0
echo on > "$(pm_dir)/control"
eq "rstn_open: RSTN still requested by the driver, deasserted while powered" \
	"$(rstn_out)" hi
echo auto > "$(pm_dir)/control"
eq "rstn_open: z reads as on the healthy unit" "$(cat $DEV/in_accel_z_raw)" "$z_ok"
eq "rstn_open: the trim is loaded (REF3 = 0x18 | EREF3[2:0])" \
	"$(sed -n 's/^0x32 //p' $SIM/regs)" "$(printf '0x%02x' $((0x18 | (0x15 & 7))))"
check "rstn_open: selftest passes" sh -c "echo 1 > $MDEV/selftest && grep -q '^pass' $MDEV/selftest"
rebind
check "rstn_open: unbind/bind works" wait_dev 5
D=$(dmesg | tail -n +$((n0 + 1)) | grep -i as9888)
[ -n "$D" ] && echo "$D" | sed 's/^/# /'
eq "rstn_open: no driver message in the log" "$D" ""
set_unit "noise = 1"
check "healthy unit after rstn_open" wait_dev 5
