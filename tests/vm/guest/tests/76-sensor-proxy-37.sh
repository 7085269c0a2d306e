# SPDX-License-Identifier: GPL-2.0
# iio-sensor-proxy 3.7, the version phones ship (issue 12), from Debian 13
# (trixie): installed in /opt/trixie with trixie's own loader and libraries
# (scripts/vm-run.sh, install_trixie), run as
#   /opt/trixie/lib64/ld-linux-x86-64.so.2 --library-path /opt/trixie/usr/lib/x86_64-linux-gnu \
#     /opt/trixie/usr/libexec/iio-sensor-proxy
# with trixie's udev rule, trixie's D-Bus policy and 3.7's monitor-sensor.
# Since 3.4 every claim is checked by polkit (net.hadess.SensorProxy.claim-
# sensor, allowed for the active local session only): trixie's polkitd runs
# too, with a rule that lets root claim, as a system without logind needs.
#
# What 3.7 does with this device (read from Debian's 3.7-3 source): the
# buffer driver (iio-buffer-accel) comes first. It looks for a trigger named
# "<device name>-dev<N>" or "<device name>-trigger", i.e. as9888-accel-dev<N>
# or as9888-accel-trigger, finds neither (the chip's trigger is
# as9888-dev<N>), warns "Could not find trigger name associated with ..." and
# writes no current_trigger; it enables every scan element and the buffer
# (length 128) on whatever trigger the device has: the driver's default,
# its data-ready trigger as9888-dev<N>. Discovery keeps it only if the
# buffer has data within 0.5 s, else it falls back to the poll driver. While
# a client holds the accelerometer the buffer stays on and the last scan is
# read every 700 ms; the last client's release turns the buffer off, the
# service's exit turns the scan elements off. All of that is asserted here,
# and the same orientation steps as 76-sensor-proxy (sp_postures). Last,
# with current_trigger cleared, the fallback: the buffer cannot be enabled
# without a trigger, and 3.7 polls.
plan 67
O=/tmp/proxy37
TX=/opt/trixie
TXLIB=$TX/usr/lib/x86_64-linux-gnu
mkdir -p $O /run/udev/rules.d /run/dbus
PIDS=""
# tx_exec PROGRAM ARGS...: a trixie program on trixie's loader and libraries
# only, in place of the shell that calls it: "(tx_exec ...) &" makes $! the
# program's own pid; tx PROGRAM ARGS...: the same in the foreground
tx_exec() {
	_tx_p=$1; shift
	exec $TX/lib64/ld-linux-x86-64.so.2 --library-path $TXLIB --argv0 "$_tx_p" "$TX$_tx_p" "$@"
}
tx() { (tx_exec "$@"); }

# (loaded by 10-probe in a full run)
load_sim
load_driver
set_unit "temperature = 25" "noise = 0.5" "seed = 11"
wait_dev 5
diag "client: trixie: $(tr '\n' ' ' < /tests/clients-trixie.txt)"
for f in lib64/ld-linux-x86-64.so.2 usr/libexec/iio-sensor-proxy usr/bin/monitor-sensor \
	usr/lib/polkit-1/polkitd usr/lib/udev/rules.d/80-iio-sensor-proxy.rules; do
	check "trixie's /$f is in /opt/trixie" test -e $TX/$f
done
check "the installed iio-sensor-proxy is 3.7 (trixie's package)" grep -q '^iio-sensor-proxy=3\.7' /tests/clients-trixie.txt

# trixie's udev rule in place of 3.0's (/run/udev/rules.d overrides
# /lib/udev/rules.d), then the coldplug and the tags
cp $TX/usr/lib/udev/rules.d/80-iio-sensor-proxy.rules /run/udev/rules.d/
sp_udev

# the system bus with trixie's policies only (net.hadess.SensorProxy,
# org.freedesktop.PolicyKit1), then polkitd
dbus-daemon --config-file=$TX/usr/share/dbus-1/system.conf --fork --print-pid > $O/dbus.pid 2>$O/dbus.err
check "the system bus runs (trixie's policies)" test -S /run/dbus/system_bus_socket
cat > /etc/polkit-1/rules.d/60-as9888-bench.rules <<'RULES'
// The bench has no logind session: let root claim sensors.
polkit.addRule(function(action, subject) {
	if (action.id == "net.hadess.SensorProxy.claim-sensor" && subject.user == "root")
		return polkit.Result.YES;
});
RULES
(tx_exec /usr/lib/polkit-1/polkitd --log-level=debug) > $O/polkitd.log 2>&1 &
PIDS="$PIDS $!"
_i=0
while [ $_i -lt 600 ] && ! grep -q 'Acquired the name org.freedesktop.PolicyKit1' $O/polkitd.log; do
	sleep 0.1; _i=$((_i + 1))
done
check "polkitd (trixie's) owns org.freedesktop.PolicyKit1" \
	grep -q 'Acquired the name org.freedesktop.PolicyKit1' $O/polkitd.log
grep -q 'Acquired the name' $O/polkitd.log || tail -n 10 $O/polkitd.log | sp_diag polkitd
check "polkit lets root claim a sensor (pkcheck net.hadess.SensorProxy.claim-sensor)" \
	tx /usr/bin/pkcheck --action-id net.hadess.SensorProxy.claim-sensor --process $$

# before the service: the buffer off, the driver's own trigger set
# the chip's data-ready trigger (lib.sh: dr_trig)
TRIG=as9888-dev${DEV##*iio:device}
eq "before iio-sensor-proxy: the accel buffer is off" "$(cat $DEV/buffer/enable)" 0
eq "before iio-sensor-proxy: current_trigger is the driver's default, $TRIG" \
	"$(cat $DEV/trigger/current_trigger)" "$TRIG"
G0=$(stat_get chip_magn_measurements)
diag "sampling_frequency before: $(cat $DEV/sampling_frequency 2>&1)"

# as its unit runs it (ExecStart=/usr/libexec/iio-sensor-proxy), -v: debug
(tx_exec /usr/libexec/iio-sensor-proxy -v) > $O/isp.log 2>&1 &
ISP=$!
PIDS="$PIDS $ISP"
SEEN=0
(tx_exec /usr/bin/monitor-sensor) > $O/ms.out 2>&1 &
MS=$!
PIDS="$PIDS $MS"
sp_client
sed 's/^/# monitor-sensor: /' $O/ms.out
grep -q '^=== Has accelerometer' $O/ms.out || {
	sp_diag dbus < $O/dbus.err
	tail -n 10 $O/polkitd.log | sp_diag polkitd
	tail -n 30 $O/isp.log | sp_diag isp
}

# what it runs on: trixie's loader and libraries, nothing of bookworm's
check "iio-sensor-proxy 3.7 runs (its version line)" grep -q 'Starting iio-sensor-proxy version 3\.7' $O/isp.log
awk '$6 ~ /\.so/ { print $6 }' /proc/$ISP/maps 2>/dev/null | sort -u > $O/maps
diag "iio-sensor-proxy (pid $ISP) maps $(wc -l < $O/maps) shared objects"
check "iio-sensor-proxy maps trixie's libc and GLib" \
	sh -c "grep -q '^$TXLIB/libc.so.6' $O/maps && grep -q '^$TXLIB/libglib-2.0.so.0' $O/maps"
check "iio-sensor-proxy maps no library from outside /opt/trixie" \
	sh -c "test -s $O/maps && ! grep -v '^$TX/' $O/maps"

# which driver it chose, and why
A=$(readlink -f $DEV)
grep -e 'trigger' -e 'Found' -e 'Buffer' -e 'ring buffer' $O/isp.log | sp_diag isp
check "3.7 finds no trigger named as9888-accel-dev<N> or as9888-accel-trigger (it says so)" \
	grep -q "Could not find trigger name associated with $A\$" $O/isp.log
check "3.7 found the accel device as an IIO buffer accelerometer" \
	grep -q "Found IIO buffer accelerometer at $A\$" $O/isp.log
check "3.7 chose the buffer driver for it" \
	grep -q "Found device $A of type accelerometer at IIO Buffer accelerometer" $O/isp.log
check_not "the buffer had data within 0.5 s at discovery (no fallback to polling)" \
	grep -q 'did not have data within' $O/isp.log
check_not "3.7 did not take it as a poll accelerometer" grep -q 'Found IIO poll accelerometer' $O/isp.log
eq "3.7 found no other accelerometer (not the magn device)" \
	"$(grep -o 'Found [A-Za-z0-9 ]*accelerometer at [^ ]*' $O/isp.log | grep -v " $A\$")" ""

# while monitor-sensor holds the accelerometer: the buffer runs on the
# driver's data-ready trigger, every scan element on
eq "held: buffer/enable is 1" "$(cat $DEV/buffer/enable)" 1
eq "held: current_trigger is still $TRIG (3.7 writes none)" "$(cat $DEV/trigger/current_trigger)" "$TRIG"
eq "held: buffer/length 128 (3.7's)" "$(cat $DEV/buffer/length)" 128
SE=$(se_dir $DEV)
eq "held: every scan element of as9888-accel on ($(ls $SE/*_en | wc -l))" \
	"$(cat $SE/*_en | sort -u)" 1
diag "sampling_frequency held: $(cat $DEV/sampling_frequency 2>&1)"
eq "held: the magn device's buffer is off" "$(cat $MDEV/buffer/enable)" 0

# without the service and its client there is nothing to step through: the
# checks that need them fail (bail_rest), not vanish
if ! grep -q '^=== Has accelerometer' $O/ms.out; then
	sp_stop
	rm -f /etc/polkit-1/rules.d/60-as9888-bench.rules
	bail_rest "monitor-sensor found no accelerometer through iio-sensor-proxy 3.7"
	return 0
fi
sp_postures

check "3.7 read the accelerometer from the buffer (Accel read from IIO)" grep -q 'Accel read from IIO' $O/isp.log
eq "held: buffer/enable still 1 after the steps" "$(cat $DEV/buffer/enable)" 1
eq "the whole run: no magnetometer measurement (every scan element of as9888-accel, none of as9888-magn)" \
	$(($(stat_get chip_magn_measurements) - G0)) 0

# the client goes: the last release turns the buffer off, the trigger stays
kill $MS; wait $MS 2>/dev/null
_i=0
while [ $_i -lt 100 ] && [ "$(cat $DEV/buffer/enable)" != 0 ]; do sleep 0.1; _i=$((_i + 1)); done
eq "released: buffer/enable back to 0" "$(cat $DEV/buffer/enable)" 0
eq "released: current_trigger still $TRIG" "$(cat $DEV/trigger/current_trigger)" "$TRIG"
# the service goes (SIGTERM, as systemd stops it): scan elements off
kill $ISP; wait $ISP 2>/dev/null
eq "iio-sensor-proxy stopped: every scan element off" "$(cat $SE/*_en | sort -u)" 0
eq "iio-sensor-proxy stopped: buffer off" "$(cat $DEV/buffer/enable)" 0

# Without a trigger (current_trigger cleared): the IIO core refuses to
# enable a triggered buffer, so 3.7's buffer driver fails to open the
# device and 3.7 falls back to its poll driver (in_accel_*_raw every 700 ms)
echo "" > $DEV/trigger/current_trigger
eq "no trigger: current_trigger cleared" "$(cat $DEV/trigger/current_trigger)" ""
_e=$(sh -c "echo 1 > $DEV/buffer/enable" 2>&1)
check "no trigger: the kernel refuses buffer/enable (${_e:-no error})" \
	sh -c "echo '$_e' | grep -q 'Invalid argument'"
(tx_exec /usr/libexec/iio-sensor-proxy -v) > $O/isp2.log 2>&1 &
ISP=$!
PIDS="$PIDS $ISP"
SEEN=$(wc -l < $O/ms.out)
(tx_exec /usr/bin/monitor-sensor) >> $O/ms.out 2>&1 &
MS=$!
PIDS="$PIDS $MS"
check "no trigger: monitor-sensor has an accelerometer" sp_wait_line '^=== Has accelerometer'
grep -e 'trigger' -e 'Found' -e 'buffer' $O/isp2.log | sp_diag isp
check "no trigger: 3.7 cannot enable the buffer (it says so)" \
	grep -q "Unable to enable ring buffer for $A\$" $O/isp2.log
check "no trigger: 3.7 falls back to the poll driver" \
	grep -q "Found device $A of type accelerometer at IIO Poll accelerometer" $O/isp2.log
sim_up $(sp_up_for 1 0 0)
check "no trigger: polled, the device left-up: monitor-sensor says left-up" sp_wait_line 'orientation changed: left-up$'
sim_up $(sp_up_for 0 -1 0)
check "no trigger: polled, the device normal: monitor-sensor says normal" sp_wait_line 'orientation changed: normal$'
eq "no trigger: held, the buffer stays off" "$(cat $DEV/buffer/enable)" 0
kill $MS $ISP; wait $MS $ISP 2>/dev/null
echo "$TRIG" > $DEV/trigger/current_trigger

sp_stop
rm -f /etc/polkit-1/rules.d/60-as9888-bench.rules
check "iio-sensor-proxy, monitor-sensor, polkitd, udevd and dbus-daemon stopped" \
	sh -c "! pidof systemd-udevd dbus-daemon >/dev/null && ! ls -l /proc/[0-9]*/exe 2>/dev/null | grep -q $TX/"
sim_temp 25
sim_up 0 0 1
