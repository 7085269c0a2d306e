# SPDX-License-Identifier: GPL-2.0
# Unbind/bind cycles, reloads of as9888_i2c and of the whole driver
# (as9888_i2c and as9888_core), then a kmemleak scan: 10, 10 and 2 in the
# bench, 50, 50 and 5 at soak depth (scripts/vm-soak.sh; /tests/soak). A
# leak or a lost resource shows in the first cycles already; the depth
# finds the rarer races, at about 200 s a kernel.
plan 7
if [ -s /tests/soak ]; then
	N_BIND=50; N_I2C=50; N_CORE=5
else
	N_BIND=10; N_I2C=10; N_CORE=2
fi
set_unit "noise = 1"
wait_dev 5
C=$(client)
I2C_DRV=/sys/bus/i2c/drivers/as9888_i2c

# repeat N FUNCTION: run FUNCTION N times, print how many runs failed
# (in a subshell: wait_dev again afterwards for DEV). Every 10 runs a
# diagnostic on stderr tells the host's stall watchdog that the cycles
# advance: 50 reloads take minutes on a busy host, with no TAP line.
repeat() {
	_fails=0; _n=0
	while [ $_n -lt $1 ]; do
		$2 || _fails=$((_fails + 1))
		_n=$((_n + 1))
		[ $((_n % 10)) -ne 0 ] ||
			diag "$2: $_n of $1 done, $_fails failed (uptime $(uptime_s) s)" >&2
	done
	echo $_fails
}
# each cycle: both devices go away, and new ones come back
unbind_bind() {
	dev_stale
	echo $C > $I2C_DRV/unbind && chip_gone &&
		echo $C > $I2C_DRV/bind && wait_dev 5
}
reload_i2c() {
	dev_stale
	rmmod as9888_i2c && chip_gone &&
		insmod $MODDIR/as9888_i2c.ko && wait_dev 5
}
reload_driver() {
	dev_stale
	rmmod as9888_i2c && rmmod as9888_core &&
		! grep -qE '^as9888_(i2c|core) ' /proc/modules && chip_gone &&
		load_driver && wait_dev 5
}

t0=$(uptime_s)
eq "$N_BIND unbind/bind cycles" "$(repeat $N_BIND unbind_bind)" 0
wait_dev 5
# 1 g = 1024 LSB; uncalibrated (zero offset at t_RT = 23.75 degC) Z reads
# about 1043 at 25 degC: Kote -4.3 chip LSB/degC over 1.25 degC
near "reads after the cycles (z about 1 g)" "$(cat $DEV/in_accel_z_raw)" 1043 40
t1=$(uptime_s)
eq "$N_I2C reloads of as9888_i2c" "$(repeat $N_I2C reload_i2c)" 0
t2=$(uptime_s)
eq "$N_CORE reloads of as9888_i2c and as9888_core" "$(repeat $N_CORE reload_driver)" 0
wait_dev 5
near "reads after the reloads (z about 1 g)" "$(cat $DEV/in_accel_z_raw)" 1043 40
near "magn reads after the reloads (x from the ambient field, 67)" "$(cat $MDEV/in_magn_x_raw)" 67 3
t3=$(uptime_s)
echo "$t0 $t1 $t2 $t3" | awk '{ printf "# AS9888-METRIC bind_cycles_s=%.1f i2c_reloads_s=%.1f driver_reloads_s=%.1f\n", $2 - $1, $3 - $2, $4 - $3 }'
leak_check
