# SPDX-License-Identifier: GPL-2.0
# The program real users' devices run (issue 12): Debian 12's
# iio-sensor-proxy 3.0 with its own udev rule, systemd-udevd and the system
# bus, and monitor-sensor as the client. udev tags the accel device
# (as9888-accel) as the rule says, and leaves the magn device (as9888-magn)
# untagged: iio-sensor-proxy finds one accelerometer, the accel device; iio-sensor-proxy reads raw x scale (it never reads _offset) through
# the mount matrix and turns it into the screen orientation that GNOME and
# Phosh rotate to. At -20, 25 and 70 degC (set live) the unit is stepped
# through the four screen postures and flat; each "Accelerometer orientation
# changed" line must name the orientation worked out here from the mount
# matrix with iio-sensor-proxy's rule (35 degrees off the screen plane;
# flat changes nothing). No compass, no light sensor. Waits are for stalls
# only: a line has 60 s to come.
O=/tmp/proxy
mkdir -p $O /run/udev /run/dbus
# Processes started here, stopped at the end whatever happens
PIDS=""
stop_all() {
	for p in $PIDS; do kill $p 2>/dev/null; done
	for p in $PIDS; do wait $p 2>/dev/null; done
	killall systemd-udevd dbus-daemon 2>/dev/null
	rm -rf /run/dbus/* /run/udev/*
}

set_unit "temperature = 25" "noise = 0.5" "seed = 11"
wait_dev 5
sed 's/^/# client: /' /tests/clients.txt

# udevd as the system runs it, then the coldplug of the iio devices
/lib/systemd/systemd-udevd --daemon 2>$O/udevd.err
udevadm trigger --action=add --subsystem-match=iio
udevadm settle --timeout=60
udevadm info -q property -p "${DEV#/sys}" > $O/props 2>&1
T=$(sed -n 's/^IIO_SENSOR_PROXY_TYPE=//p' $O/props)
diag "udev: as9888-accel: IIO_SENSOR_PROXY_TYPE=$T"
check "udev tags the accel device iio-poll-accel (80-iio-sensor-proxy.rules)" \
	sh -c "echo '$T' | grep -qw iio-poll-accel"
check "udev tags the accel device iio-buffer-accel" sh -c "echo '$T' | grep -qw iio-buffer-accel"
check "udev: no compass or light tag on the accel device" sh -c "! echo '$T' | grep -q -e compass -e als"
check "udev asks systemd for iio-sensor-proxy.service" \
	grep -q '^SYSTEMD_WANTS=iio-sensor-proxy.service' $O/props
udevadm info -q property -p "${MDEV#/sys}" > $O/mprops 2>&1
MT=$(sed -n 's/^IIO_SENSOR_PROXY_TYPE=//p' $O/mprops)
diag "udev: as9888-magn: IIO_SENSOR_PROXY_TYPE=$MT"
check "udev knows the magn device" grep -q "^DEVPATH=.*/${MDEV##*/}\$" $O/mprops
check "udev: the magn device is not tagged as an accelerometer" \
	sh -c "! echo '$MT' | grep -q accel"
check "udev: the magn device has no compass or light tag either" \
	sh -c "! echo '$MT' | grep -q -e compass -e als"

dbus-daemon --system --fork --print-pid > $O/dbus.pid 2>$O/dbus.err
check "the system bus runs" test -S /run/dbus/system_bus_socket
# as its unit runs it (Type=dbus, ExecStart=/usr/sbin/iio-sensor-proxy)
G_MESSAGES_DEBUG=all /usr/sbin/iio-sensor-proxy > $O/isp.log 2>&1 &
PIDS="$PIDS $!"
monitor-sensor > $O/ms.out 2>&1 &
PIDS="$PIDS $!"

# wait_line PATTERN: until monitor-sensor has printed a line matching it
# after the first $SEEN lines; sets SEEN to that line's number
SEEN=0
wait_line() {
	_i=0
	while [ $_i -lt 600 ]; do
		_w=$(awk -v from=$SEEN -v pat="$1" 'NR > from && $0 ~ pat { print NR; exit }' $O/ms.out)
		[ -n "$_w" ] && { SEEN=$_w; return 0; }
		sleep 0.1; _i=$((_i + 1))
	done
	return 1
}
check "monitor-sensor finds iio-sensor-proxy" wait_line '^\+\+\+ iio-sensor-proxy appeared'
check "it has an accelerometer" wait_line '^=== Has accelerometer'
check "it has no ambient light sensor" grep -q '^=== No ambient light sensor' $O/ms.out
check "it has no compass (the magnetometer has no tilt-compensated heading channel)" \
	sh -c "! grep -q -e '^=== Has compass' -e '^+++ Compass appeared' $O/ms.out"
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
	{ sed 's/^/# dbus: /' $O/dbus.err; sed 's/^/# isp: /' $O/isp.log | tail -n 20; }

# The posture ("up": the direction gravity pushes the chip, as its
# accelerometer reads it) that puts the device, through the mount matrix
# M (device = M x chip), in the screen posture whose device-frame reading
# is V: chip = M^T V. M is read from the driver.
M=$(cat $DEV/in_accel_mount_matrix)
diag "mount matrix: $M"
up_for() {
	echo "$M; $*" | tr ',;' '  ' | awk '{ for (i = 1; i <= 3; i++)
		printf "%d%s", $i * $10 + $(i + 3) * $11 + $(i + 6) * $12, i < 3 ? " " : "\n" }'
}
# iio-sensor-proxy's rule on the device frame, whose readings it takes in
# the Windows convention (the vector points where gravity pulls: -1 g on Y
# when the device stands in its normal posture; this driver, as IIO
# accelerometers do, reads +1 g on the axis that points up, so a board's
# mount matrix carries the sign, see README): X beyond 35 degrees from the
# screen plane: right-up (X reads -g) or left-up; else Y beyond 35
# degrees: normal (Y reads -g) or bottom-up; else (flat) no change
printf '%s\n' "normal:0 -1 0" "left-up:1 0 0" "bottom-up:0 1 0" "right-up:-1 0 0" > $O/steps
# without the service and its client there is nothing to step through
grep -q '^=== Has accelerometer' $O/ms.out || { stop_all; return 0 2>/dev/null || exit 0; }
for t in -20 25 70; do
	sim_temp $t
	while IFS=: read name v; do
		sim_up $(up_for $v)
		if wait_line "orientation changed: $name\$"; then
			ok "$t degC: device $name (chip up $(up_for $v)): monitor-sensor says $name"
		else
			nok "$t degC: device $name (chip up $(up_for $v)): monitor-sensor says $name" \
				"saw: $(tail -n 3 $O/ms.out | tr '\n' '|'); raw now $(cat $DEV/in_accel_x_raw $DEV/in_accel_y_raw $DEV/in_accel_z_raw | tr '\n' ' ')"
			grep -e "Accel read" -e "quirk applied" $O/isp.log | tail -n 2 | sed 's/^/# isp: /'
			SEEN=$(wc -l < $O/ms.out)
		fi
	done < $O/steps
	# flat: no orientation change; the last one stays
	sim_up $(up_for 0 0 -1)
	sleep 3
	eq "$t degC: flat: no orientation change (right-up stays)" \
		"$(awk -v from=$SEEN 'NR > from && /orientation changed/' $O/ms.out)" ""
done

# what the poll driver read: raw x scale, once per 700 ms, without _offset
check "iio-sensor-proxy polled in_accel_*_raw (iio-poll-accel)" \
	grep -q "Accel read from IIO" $O/isp.log
stop_all
check "iio-sensor-proxy, monitor-sensor, udevd and dbus-daemon stopped" \
	sh -c "! pidof iio-sensor-proxy monitor-sensor systemd-udevd dbus-daemon >/dev/null"
sim_temp 25
sim_up 0 0 1
