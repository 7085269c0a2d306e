# SPDX-License-Identifier: GPL-2.0
# Runtime PM: the adapter switches the chip's supply off when the driver
# runtime-suspends (registers back to their reset values); after resume
# the DAC (from calibbias), the trim and INT1EN are back in the chip and
# the calibration (calibbias) is unchanged.
# System sleep is tested in 66-pm-wiring (pm_test=devices with freeze).
plan 27
set_unit "temperature = 25" "noise = 0"
wait_dev 5
PM=$(readlink -f $DEV)/../power
status() { cat $PM/runtime_status; }
# wait_status STATE: up to 30 s (autosuspend after 1 s; more is a stall)
wait_status() {
	_i=0
	while [ $_i -lt 300 ]; do
		[ "$(status)" = "$1" ] && return 0
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}
regs() { cat $SIM/regs; }
reg() { sed -n "s/^$1 //p" $SIM/regs; }
# On a busy machine a check can take longer than the autosuspend delay:
# hold keeps the device active while a state is inspected, release lets it
# suspend 1 s after its last use
hold() { echo 60000 > $PM/autosuspend_delay_ms; }
release() { echo 1000 > $PM/autosuspend_delay_ms; }

delay0=$(cat $PM/autosuspend_delay_ms)
eq "autosuspend delay is the driver's 2000 ms" "$delay0" 2000
hold

# the unit's calibration, then 600 less on x and 400 more on z: 152 and
# 101 chip LSB, which the driver puts into the DAC (3 and 2 codes)
set_cal 0 0 0 25000
c0=$(cal_get)
bx=$(echo $c0 | cut -d' ' -f1)
by=$(echo $c0 | cut -d' ' -f2)
bz=$(echo $c0 | cut -d' ' -f3)
put_cal $((bx - 600)) $by $((bz + 400))
cal=$(cal_get)
eq "calibration loaded" "$cal" "$((bx - 600)) $by $((bz + 400))"
x0=$(cat $DEV/in_accel_x_raw)
z0=$(cat $DEV/in_accel_z_raw)
# -600 * St_RT / St(25) = -600 * 260 / 258.609, and half a chip LSB (2 LSB)
# of the chip's own rounding
near "x reads -603 with that calibration and the DAC moved" "$x0" -603 4
po0=$(stat_get chip_power_offs)
r0=$(regs)
da_x=$(reg 0x37)
diag "chip registers while active: $(echo $r0)"
eq "active: the chip's AXDA holds the DAC its calibbias gives (DACopt)" \
	"$da_x" "$(bias_dac "$cal" | cut -d' ' -f1)"
eq "active: INT1EN set" "$(reg 0x02)" 0x01
release

check "runtime_status reaches suspended" wait_status suspended
eq "suspend switched the chip's supply off once" "$(stat_get chip_power_offs)" $((po0 + 1))
eq "suspended: the chip lost its DAC (AXDA at reset value 0x80)" "$(reg 0x37)" 0x80
eq "suspended: the chip lost INT1EN" "$(reg 0x02)" 0x00
# calibbias, the calibration, the scale and sampling_frequency come from
# the driver's state: reading them does not resume the device
eq "calibbias readable while suspended" "$(cal_get)" "$cal"
eq "scale readable while suspended" "$(cat $DEV/in_accel_scale)" $G_SCALE
eq "still suspended after those reads" "$(status)" suspended
# An INT1 edge that belongs to no measurement (the pin of the unpowered
# chip, a glitch) is not the driver's: it returns IRQ_NONE, so the kernel's
# spurious-interrupt detector counts it (issue 24, nit of point 9)
IRQN=$(awk -v n="$(basename "$(readlink -f $DEV/..)")" '$NF == n { sub(":", "", $1); print $1 }' /proc/interrupts)
# the count and time of the last edge no handler claimed: the kernel
# restarts the count at 1 when the one before is over 100 ms old, so the
# pair, not the count, tells that one more came
unhandled() { sed -n 's/^\(last_\)\{0,1\}unhandled //p' /proc/irq/$IRQN/spurious | tr '\n' ' '; }
if [ -n "$IRQN" ] && [ -r /proc/irq/$IRQN/spurious ]; then
	u0=$(unhandled)
	echo 1 > $SIM/glitch_int1
	_i=0
	while [ "$(unhandled)" = "$u0" ] && [ $_i -lt 50 ]; do sleep 0.1; _i=$((_i + 1)); done
	check_not "suspended: an INT1 edge of no measurement is not handled (IRQ_NONE)" \
		test "$(unhandled)" = "$u0"
	eq "suspended: the stray edge does not resume the device" "$(status)" suspended
else
	nok_for 2 "the interrupt of the device in /proc/interrupts and its spurious file" "irq '$IRQN'"
fi

hold
x1=$(cat $DEV/in_accel_x_raw)
eq "a raw read resumes the device" "$(status)" active
eq "after resume: every trim, DAC and INT1EN register as before the suspend" "$(regs)" "$r0"
eq "after resume: x raw unchanged (DAC reloaded)" "$x1" "$x0"
eq "after resume: z raw unchanged" "$(cat $DEV/in_accel_z_raw)" "$z0"
eq "after resume: calibbias unchanged" "$(cal_get)" "$cal"
release

# A calibbias write while suspended resumes, writes the chip, suspends again
check "suspended again" wait_status suspended
echo $((bx - 200)) > $DEV/in_accel_x_calibbias
eq "calibbias written while suspended reads back" "$(cat $DEV/in_accel_x_calibbias)" $((bx - 200))
check "suspended after the write" wait_status suspended
hold
cat $DEV/in_temp_raw > /dev/null
eq "after another power cycle the chip's AXDA is the DAC the new calibbias gives" \
	"$(reg 0x37)" "$(bias_dac "$((bx - 200)) $by $((bz + 400))" | cut -d' ' -f1)"
# the chip's output moved by two DAC steps (46.5 chip LSB each): the
# driver accounts for them, x reads -200 * 260 / 258.609
near "x compensated after the cycle with the new DAC: -201" \
	"$(cat $DEV/in_accel_x_raw)" -201 4
release

put_cal $c0

# The data-ready trigger works after a power cycle
check "suspended before the capture" wait_status suspended
T=$(dr_trig)
echo 100 > $DEV/sampling_frequency
if capture "$T" 1 /tmp/pm.bin; then
	check "capture after a power cycle: at least 50 samples in 1 s ($(samples /tmp/pm.bin))" \
		test "$(samples /tmp/pm.bin)" -ge 50
	eq "capture after a power cycle: every z sample 1 g" "$(zbad /tmp/pm.bin)" 0
else
	nok_for 2 "buffer enable after a power cycle"
fi

echo "$delay0" > $PM/autosuspend_delay_ms
