# SPDX-License-Identifier: GPL-2.0
# The same chip on the adapter's SPI controller, through as9888_spi.
# The driver holds RSTN (a module reference on the GPIO provider): unload it
# first, as on a real board.
plan 22
check "as9888_i2c unloads" rmmod as9888_i2c
check "adapter unloads" rmmod as9888_sim
check_not "no IIO device with the adapter gone" iio_dev
check "as9888_spi loads" insmod $MODDIR/as9888_spi.ko
check "adapter loads with spi=1" insmod $MODDIR/as9888_sim.ko spi=1
check "SPI: as9888-accel and as9888-magn IIO devices appear" wait_dev 5
C=$(client)
check "SPI: $C bound to as9888_spi" test -e /sys/bus/spi/drivers/as9888_spi/$C
eq "SPI: both devices are children of $C" \
	"$(basename "$(dirname "$(readlink -f $DEV)")") $(basename "$(dirname "$(readlink -f $MDEV)")")" "$C $C"
set_unit "temperature = 25" "offset = 40 -25 60" "noise = 0"
wait_dev 5
set_cal 40 -25 60 25000
near "SPI: accel x compensated: 0" "$(cat $DEV/in_accel_x_raw)" 0 3
near "SPI: accel z compensated: 1 g = 1024" "$(cat $DEV/in_accel_z_raw)" 1024 3
near "SPI: magn x from the ambient field (67)" "$(cat $MDEV/in_magn_x_raw)" 67 1
echo 1 > $MDEV/selftest 2>/dev/null
eq "SPI: selftest passes" "$(cat $MDEV/selftest)" pass
T=$(dr_trig)
if capture "$T" 2 /tmp/buf3; then
	S=$(samples /tmp/buf3)
	M=$((CAP_M1 - CAP_M0))
	check "SPI data-ready trigger: at least 20 samples ($S)" test "$S" -ge 20
	check "SPI data-ready trigger: timestamps strictly increasing" monotonic /tmp/buf3
	if [ $M -gt 0 ]; then
		TPS=$(echo "$((CAP_T1 - CAP_T0)) $M" | awk '{ printf "%.2f", $1 / $2 }')
		diag "AS9888-METRIC spi_transfers_per_sample=$TPS spi_rate_hz=$(period_us /tmp/buf3 | awk '{ printf "%.1f", 1e6 / $1 }')"
	fi
else
	nok_for 2 "SPI: buffer enable with the data-ready trigger"
fi
if buf_start $MDEV "$T" /tmp/buf3m magn_x magn_y magn_z timestamp; then
	check "SPI: magn buffer on the data-ready trigger: 20 samples (stall: 60 s)" \
		wait_grow /tmp/buf3m $((20 * 16))
	buf_stop $MDEV $BUF_PID /tmp/buf3m
	check "SPI: magn samples: timestamps strictly increasing" monotonic /tmp/buf3m
else
	nok_for 2 "SPI: magn buffer enable with the data-ready trigger"
fi
kmsg_mark 90-wia
set_unit "fault = wia"
check "SPI: unknown WIA: the driver binds" wait_dev 5
check "SPI: unknown WIA: the magn device too" test -n "$MDEV"
check "SPI: unknown WIA: the probe names the ID read and the one expected" \
	kmsg_since 90-wia "WIA reads 0x47, expected 0x48"
check "SPI: as9888_spi unloads" rmmod as9888_spi
check "SPI: adapter unloads (SPI controller removed)" rmmod as9888_sim
insmod $MODDIR/as9888_i2c.ko
insmod $MODDIR/as9888_sim.ko
check "back on I2C" wait_dev 5
