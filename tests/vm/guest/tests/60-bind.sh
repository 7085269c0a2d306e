# SPDX-License-Identifier: GPL-2.0
# unbind/bind loops and module reload.
set_unit "noise = 1"
wait_dev 5
C=$(client)
fails=0
i=0
while [ $i -lt 20 ]; do
	echo $C > /sys/bus/i2c/drivers/as9888_i2c/unbind || fails=$((fails + 1))
	iio_dev >/dev/null && fails=$((fails + 1))
	echo $C > /sys/bus/i2c/drivers/as9888_i2c/bind || fails=$((fails + 1))
	wait_dev 2 || fails=$((fails + 1))
	i=$((i + 1))
done
eq "20 unbind/bind cycles" $fails 0
near "reads after the cycles" "$(cat $DEV/in_accel_z_raw)" 259 10
fails=0
i=0
while [ $i -lt 5 ]; do
	rmmod as9888_i2c || fails=$((fails + 1))
	insmod $MODDIR/as9888_i2c.ko || fails=$((fails + 1))
	wait_dev 2 || fails=$((fails + 1))
	i=$((i + 1))
done
eq "5 reloads of as9888_i2c" $fails 0
