# SPDX-License-Identifier: GPL-2.0
# Injected faults give clean errors (no hang, no splat: the host checks the
# log), and the device goes away cleanly afterwards.

# timed_read FILE: prints the value, or "ERR"; never blocks more than 10 s
timed_read() {
	timeout 10 cat "$1" 2>/dev/null || echo ERR
}

set_unit "fault = no_drdy"
if wait_dev 5; then
	eq "no_drdy: a raw read fails instead of hanging" "$(timed_read $DEV/in_accel_x_raw)" ERR
	eq "no_drdy: a magn raw read fails instead of hanging" "$(timed_read $MDEV/in_magn_x_raw)" ERR
	eq "no_drdy: selftest write fails" \
		"$(timeout 10 sh -c "echo 1 > $MDEV/selftest" 2>/dev/null && echo OK || echo ERR)" ERR
else
	ok "no_drdy: probe refused the unit"
fi

set_unit "fault = nak" "noise = 0"
wait_dev 5
errs=0; good=0; i=0
while [ $i -lt 40 ]; do
	v=$(timed_read $DEV/in_accel_x_raw)
	if [ "$v" = ERR ]; then errs=$((errs + 1)); else good=$((good + 1)); fi
	i=$((i + 1))
done
diag "nak: $good good reads, $errs failed"
check "nak: most reads succeed ($good of 40)" test $good -ge 20
check "nak: the adapter saw NAKs" test "$(stat_get bus_naks)" -gt 0

set_unit "fault = int1_open" "noise = 0"
if wait_dev 5; then
	v=$(timed_read $DEV/in_accel_x_raw)
	diag "int1_open: raw read gives '$v'"
	check "int1_open: a raw read returns (value or error) within 10 s" test -n "$v"
else
	ok "int1_open: probe refused the unit"
fi

set_unit "fault = eeprom_blank"
if wait_dev 5; then
	diag "eeprom_blank: device probed, calibbias $(timed_read $DEV/in_accel_x_calibbias)"
	ok "eeprom_blank: probe completed (driver accepts a blank EEPROM)"
else
	ok "eeprom_blank: probe refused the unit"
fi

set_unit "noise = 1"
check "healthy unit after the faults" wait_dev 5
