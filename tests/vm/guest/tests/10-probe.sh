# SPDX-License-Identifier: GPL-2.0
# Probe on the adapter: modules, IIO device, GPIO lines, mount matrix.
check "driver modules load" load_driver
check "adapter module loads" load_sim
check "as9888 IIO device appears" wait_dev 5
eq "name is as9888" "$(cat $DEV/name 2>/dev/null)" as9888
C=$(client)
check "i2c client $C bound to as9888_i2c" test -e /sys/bus/i2c/drivers/as9888_i2c/$C
G=$(cat /sys/kernel/debug/gpio 2>/dev/null)
for l in AS9888_RSTN AS9888_INT1 AS9888_INT2; do
	check "GPIO line $l named" sh -c "echo '$G' | grep -q '$l'"
done
check "RSTN requested as reset by the driver, output high (deasserted)" \
	sh -c "echo '$G' | grep 'AS9888_RSTN' | grep -q 'reset.*out hi'"
eq "accel mount matrix from the software node" \
	"$(cat $DEV/in_accel_mount_matrix 2>/dev/null)" "0, 1, 0; -1, 0, 0; 0, 0, 1"
N=$(ls /sys/bus/nvmem/devices/ 2>/dev/null | grep as9888-eeprom | head -n1)
if [ -n "$N" ]; then
	E=$(od -A n -t x1 /sys/bus/nvmem/devices/$N/nvmem | tr -s ' \n' ' ' | sed 's/^ //; s/ $//')
	eq "NVMEM $N holds the unit's EEPROM" "$E" \
		"9a 71 15 5c 80 85 7b 1c 63 a2 38 e6 9c 0d 8f 8c 04 65 c3 88 50"
else
	nok "NVMEM provider as9888-eeprom<N> registered"
fi
