# SPDX-License-Identifier: GPL-2.0
# The program real users' devices run (issue 12): Debian 12's
# iio-sensor-proxy 3.0 with its own udev rule, systemd-udevd and the system
# bus, and monitor-sensor as the client. udev tags the accel device
# (as9888-accel) as the rule says, and leaves the magn device (as9888-magn)
# untagged: iio-sensor-proxy finds one accelerometer, the accel device; iio-sensor-proxy reads raw x scale (it never reads _offset) through
# the mount matrix and turns it into the screen orientation that GNOME and
# Phosh rotate to. At -20, 25 and 70 degC (set live) the unit is stepped
# through the four screen postures and flat (sp_postures in lib.sh). No
# compass, no light sensor. Waits are for stalls only: a line has 60 s to
# come. 76-sensor-proxy-37 runs Debian 13's 3.7 the same way.
plan 31
O=/tmp/proxy
mkdir -p $O /run/udev /run/dbus
# Processes started here, stopped at the end whatever happens (sp_stop)
PIDS=""

# (loaded by 10-probe in a full run)
load_sim
load_driver
set_unit "temperature = 25" "noise = 0.5" "seed = 11"
wait_dev 5
sed 's/^/# client: /' /tests/clients.txt

# udevd with 3.0's rule (/lib/udev/rules.d), the coldplug, the tags
sp_udev

dbus-daemon --system --fork --print-pid > $O/dbus.pid 2>$O/dbus.err
check "the system bus runs" test -S /run/dbus/system_bus_socket
# as its unit runs it (Type=dbus, ExecStart=/usr/sbin/iio-sensor-proxy)
G_MESSAGES_DEBUG=all /usr/sbin/iio-sensor-proxy > $O/isp.log 2>&1 &
PIDS="$PIDS $!"
SEEN=0
monitor-sensor > $O/ms.out 2>&1 &
PIDS="$PIDS $!"

sp_client
# "Found IIO poll accelerometer at <sysfs path>" (and the like): only the
# accel device
F=$(grep -o 'Found [A-Za-z0-9 ]*accelerometer at [^ ]*' $O/isp.log | sort -u)
echo "$F" | sed 's/^/# isp: /'
check "iio-sensor-proxy found the accel device as an accelerometer" \
	sh -c "echo '$F' | grep -q '/${DEV##*/}\$'"
eq "iio-sensor-proxy found no other accelerometer (not the magn device)" \
	"$(echo "$F" | grep -v "/${DEV##*/}\$" | grep .)" ""
sed 's/^/# monitor-sensor: /' $O/ms.out
grep -q '^=== Has accelerometer' $O/ms.out ||
	{ sp_diag dbus < $O/dbus.err; tail -n 20 $O/isp.log | sp_diag isp; }

# without the service and its client there is nothing to step through: the
# checks that need them fail (bail_rest), not vanish
if ! grep -q '^=== Has accelerometer' $O/ms.out; then
	sp_stop
	bail_rest "monitor-sensor found no accelerometer through iio-sensor-proxy 3.0"
	return 0
fi
sp_postures

# what the poll driver read: raw x scale, once per 700 ms, without _offset
check "iio-sensor-proxy polled in_accel_*_raw (iio-poll-accel)" \
	grep -q "Accel read from IIO" $O/isp.log
sp_stop
check "iio-sensor-proxy, monitor-sensor, udevd and dbus-daemon stopped" \
	sh -c "! pidof iio-sensor-proxy monitor-sensor systemd-udevd dbus-daemon >/dev/null"
sim_temp 25
sim_up 0 0 1
