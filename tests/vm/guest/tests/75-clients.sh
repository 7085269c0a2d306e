# SPDX-License-Identifier: GPL-2.0
# Real clients written by others: libgpiod's tools, the kernel's tools/iio.
plan 11
set_unit "temperature = 25" "noise = 0"
wait_dev 5
D=$(gpiodetect 2>&1)
diag "gpiodetect: $(echo "$D" | grep as9888)"
check "gpiodetect: as9888-sim-gpio with 3 lines" \
	sh -c "echo '$D' | grep -q 'as9888-sim-gpio.*(3 lines)'"
CHIP=$(echo "$D" | grep as9888-sim-gpio | cut -d' ' -f1)
I=$(gpioinfo "$CHIP" 2>&1)
echo "$I" | sed 's/^/# /'
check "gpioinfo: line 0 AS9888_RSTN, output, used by reset, active-low" \
	sh -c "echo '$I' | grep 'line *0:' | grep 'AS9888_RSTN' | grep '\"reset\"' | grep output | grep -q active-low"
check "gpioinfo: line 1 AS9888_INT1, input" \
	sh -c "echo '$I' | grep 'line *1:' | grep 'AS9888_INT1' | grep -q input"
check "gpioinfo: line 2 AS9888_INT2, input, unused" \
	sh -c "echo '$I' | grep 'line *2:' | grep 'AS9888_INT2' | grep -q unused"
L=$(lsiio 2>&1)
echo "$L" | sed 's/^/# /'
check "lsiio: the as9888-accel device" sh -c "echo '$L' | grep -q 'Device [0-9]*: as9888-accel\$'"
check "lsiio: the as9888-magn device" sh -c "echo '$L' | grep -q 'Device [0-9]*: as9888-magn\$'"
check "lsiio: its data-ready trigger" sh -c "echo '$L' | grep -q 'Trigger [0-9]*: as9888-dev'"
T=$(dr_trig)
# -a: every channel of the device, as iio-sensor-proxy 3.7+ enables every
# scan element: on as9888-accel that costs no magnetometer measurement
mg0=$(stat_get chip_magn_measurements)
G=$(timeout 20 iio_generic_buffer -n as9888-accel -t "$T" -c 5 -a 2>&1)
mg1=$(stat_get chip_magn_measurements)
echo "$G" | tail -n 6 | sed 's/^/# /'
check "iio_generic_buffer: 5 scans of as9888-accel with the data-ready trigger" \
	sh -c "test \$(echo '$G' | grep -c '^[-0-9. ]*[0-9] *\$') -ge 5"
eq "iio_generic_buffer -a on as9888-accel: no magnetometer measurement" "$mg1" "$mg0"
G=$(timeout 20 iio_generic_buffer -n as9888-magn -t "$T" -c 5 -a 2>&1)
echo "$G" | tail -n 6 | sed 's/^/# /'
check "iio_generic_buffer: 5 scans of as9888-magn with the data-ready trigger" \
	sh -c "test \$(echo '$G' | grep -c '^[-0-9. ]*[0-9] *\$') -ge 5"
check "iio_generic_buffer: as9888-magn measured the magnetometer" \
	test "$(stat_get chip_magn_measurements)" -ge $((mg1 + 5))
