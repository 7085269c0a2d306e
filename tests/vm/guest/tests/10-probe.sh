# SPDX-License-Identifier: GPL-2.0
# Probe on the adapter: modules, the two IIO devices (one per sensor, under
# the same bus device), the data-ready trigger named after the accel
# device, GPIO lines, mount matrices, NVMEM.
plan 21
check "driver modules load" load_driver
check "adapter module loads" load_sim
check "as9888-accel and as9888-magn IIO devices appear" wait_dev 5
eq "accel device name is as9888-accel" "$(cat $DEV/name 2>/dev/null)" as9888-accel
eq "magn device name is as9888-magn" "$(cat $MDEV/name 2>/dev/null)" as9888-magn
eq "both devices are children of the same bus device" \
	"$(dirname "$(readlink -f $MDEV)")" "$(dirname "$(readlink -f $DEV)")"
eq "one as9888-accel and one as9888-magn, no other as9888 device" \
	"$(cat /sys/bus/iio/devices/iio:device*/name | grep '^as9888' | sort | tr '\n' ' ')" \
	"as9888-accel as9888-magn "
eq "one data-ready trigger, as9888-dev<N> with N the accel device's number" \
	"$(cat /sys/bus/iio/devices/trigger*/name | grep '^as9888-dev')" "as9888-dev${DEV##*iio:device}"
C=$(client)
check "i2c client $C bound to as9888_i2c" test -e /sys/bus/i2c/drivers/as9888_i2c/$C
G=$(cat /sys/kernel/debug/gpio 2>/dev/null)
for l in AS9888_RSTN AS9888_INT1 AS9888_INT2; do
	check "GPIO line $l named" sh -c "echo '$G' | grep -q '$l'"
done
check "RSTN requested as reset by the driver" \
	sh -c "echo '$G' | grep 'AS9888_RSTN' | grep -q 'reset'"
# RSTN follows the supplies: released (high) while powered, held low while
# runtime PM has the supplies off (no back-powering, issue 11)
echo on > "$(pm_dir)/control"
eq "RSTN high (deasserted) while the chip is powered" "$(rstn_out)" hi
echo auto > "$(pm_dir)/control"
check "runtime PM switches the supplies off when unused" wait_runtime suspended
eq "RSTN low while the supplies are off" "$(rstn_out)" lo
eq "accel mount matrix from the software node" \
	"$(cat $DEV/in_accel_mount_matrix 2>/dev/null)" "0, 1, 0; -1, 0, 0; 0, 0, 1"
eq "magn mount matrix from the software node" \
	"$(cat $MDEV/in_magn_mount_matrix 2>/dev/null)" "0, 1, 0; -1, 0, 0; 0, 0, 1"
# The NVMEM provider "as9888-eeprom<M>", M numbered by the NVMEM core (not
# by the IIO device), is a child of the chip's bus device
N=$(ls /sys/bus/nvmem/devices/ 2>/dev/null | grep as9888-eeprom | head -n1)
if [ -n "$N" ]; then
	E=$(od -A n -t x1 /sys/bus/nvmem/devices/$N/nvmem | tr -s ' \n' ' ' | sed 's/^ //; s/ $//')
	eq "one NVMEM provider as9888-eeprom<M>" \
		"$(ls /sys/bus/nvmem/devices/ | grep -c '^as9888-eeprom')" 1
	eq "NVMEM $N is a child of the bus device" \
		"$(readlink -f /sys/bus/nvmem/devices/$N/..)" "$(readlink -f $DEV/..)"
	eq "NVMEM $N holds the unit's EEPROM" "$E" \
		"9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 50"
else
	nok_for 3 "NVMEM provider as9888-eeprom<M> registered"
fi
