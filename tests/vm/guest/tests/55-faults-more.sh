# SPDX-License-Identifier: GPL-2.0
# Injected faults give clean errors (no hang, no splat: the host checks the
# log), and the device goes away cleanly afterwards.
plan 11

# timed_read FILE: prints the value; "ERR" when the read fails; "HANG"
# when it did not return within 10 s and timeout stopped it (a hang is
# never taken for the error the check wants)
timed_read() {
	_tr_v=$(timeout 10 cat "$1" 2>/dev/null)
	case $? in
	0) echo "$_tr_v" ;;
	124 | 137 | 143) echo HANG ;;
	*) echo ERR ;;
	esac
}
# timed_write VALUE FILE: "OK", "ERR" or "HANG", as timed_read
timed_write() {
	timeout 10 sh -c "echo $1 > $2" 2>/dev/null
	case $? in
	0) echo OK ;;
	124 | 137 | 143) echo HANG ;;
	*) echo ERR ;;
	esac
}
# no_drdy: the chip never finishes a measurement; the driver probes (the
# probe measures nothing) and every measurement times out
set_unit "fault = no_drdy"
check "no_drdy: the unit probes" wait_dev 5
eq "no_drdy: a raw read fails instead of hanging" "$(timed_read $DEV/in_accel_x_raw)" ERR
eq "no_drdy: a magn raw read fails instead of hanging" "$(timed_read $MDEV/in_magn_x_raw)" ERR
eq "no_drdy: selftest write fails" "$(timed_write 1 $MDEV/selftest)" ERR

set_unit "fault = nak" "noise = 0"
wait_dev 5
# the adapter's NAKs counted from here (its counter holds earlier files' too)
NAKS0=$(stat_get bus_naks)
errs=0; good=0; i=0
while [ $i -lt 40 ]; do
	v=$(timed_read $DEV/in_accel_x_raw)
	if is_int "$v"; then good=$((good + 1)); else errs=$((errs + 1)); fi
	i=$((i + 1))
done
diag "nak: $good good reads, $errs failed"
check "nak: most reads succeed ($good of 40)" test $good -ge 20
check "nak: the adapter NAKed these reads" test $(($(stat_get bus_naks) - NAKS0)) -gt 0

# int1_open: the sample is ready but its edge never comes: the driver
# fails the read (EIO) after its grace for a late edge, and says why
set_unit "fault = int1_open" "noise = 0"
wait_dev 5
kmsg_mark 55-int1_open
v=$(timed_read $DEV/in_accel_x_raw)
diag "int1_open: raw read gives '$v'"
eq "int1_open: a raw read fails within 10 s" "$v" ERR
check "int1_open: the driver names the INT1 line" \
	kmsg_since 55-int1_open "sample ready but no INT1 edge: check the INT1 line"

# eeprom_blank: a blank factory EEPROM is unusable: the probe is refused
# and the log says what was wrong
kmsg_mark 55-eeprom_blank
set_unit "fault = eeprom_blank"
check_not "eeprom_blank: the probe is refused (no device)" wait_dev 5
check "eeprom_blank: the log says the EEPROM is blank" \
	kmsg_since 55-eeprom_blank "EEPROM blank (all bytes 0xff)"

set_unit "noise = 1"
check "healthy unit after the faults" wait_dev 5
