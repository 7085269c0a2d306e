# SPDX-License-Identifier: GPL-2.0
# libiio's own clients (iio_info, iio_attr, iio_readdev, Debian's
# libiio-utils 0.24) on the local backend: what they list, read, write and
# capture.
plan 50
set_unit "temperature = 25" "noise = 0"
wait_dev 5
set_cal 0 0 0 25000
I=$(iio_info 2>&1)
echo "$I" | grep -E 'context|as9888|channels found|: *\(input' | sed 's/^/# /'
has() { echo "$I" | grep -q "$1"; }
# section NAME: iio_info's lines of the device NAME (to the next device
# or trigger); in_accel NAME PATTERN: the section has the pattern
section() {
	echo "$I" | awk -v n="$1" '/^\t[^\t]/ { on = ($0 ~ ": " n " ") } on'
}
IA=$(section as9888-accel)
IM=$(section as9888-magn)
in_accel() { echo "$IA" | grep -q "$1"; }
in_magn() { echo "$IM" | grep -q "$1"; }
check "iio_info: local backend" has 'IIO context created with local backend'
check "iio_info: the as9888-accel device, buffer capable" has 'iio:device[0-9]*: as9888-accel (buffer capable)'
check "iio_info: the as9888-magn device, buffer capable" has 'iio:device[0-9]*: as9888-magn (buffer capable)'
check "iio_info: as9888-accel: 5 channels" in_accel '5 channels found'
check "iio_info: as9888-magn: 4 channels" in_magn '4 channels found'
# the accelerometer is compensated on 1024 LSB/g: s16 in 16 bits (libiio
# writes S when the value fills its storage)
for c in accel_x accel_y accel_z; do
	check "iio_info: as9888-accel: channel $c, s16 in 16 bits" in_accel "	$c:  (input, index: [0-2], format: le:S16/16>>0)"
done
for c in magn_x magn_y magn_z; do
	check "iio_info: as9888-magn: channel $c, s13 in 16 bits" in_magn "	$c:  (input, index: [0-2], format: le:s13/16>>0)"
done
check "iio_info: as9888-accel: channel temp, u8 in 16 bits, index 3" in_accel 'temp:  (input, index: 3, format: le:u8/16>>0)'
check "iio_info: as9888-accel: channel timestamp, s64, index 4" in_accel 'timestamp:  (input, index: 4, format: le:S64/64>>0)'
check "iio_info: as9888-magn: channel timestamp, s64, index 3" in_magn 'timestamp:  (input, index: 3, format: le:S64/64>>0)'
check_not "iio_info: as9888-accel has no magnetometer channel" in_accel 'magn_'
check_not "iio_info: as9888-magn has no accelerometer or temperature channel" \
	sh -c "echo '$IM' | grep -q -e 'accel_' -e 'temp:'"
for a in calibbias calibbias_available mount_matrix \
	oversampling_ratio oversampling_ratio_available raw scale; do
	check "iio_info: as9888-accel: accel attribute $a" in_accel "attr  [0-9]: $a value: "
done
check "iio_info: as9888-magn: device attribute selftest" in_magn 'attr  [0-9]: selftest value: none'
check_not "iio_info: as9888-accel: no selftest attribute" in_accel 'selftest'
check "iio_info: device attribute sampling_frequency_available as sysfs has it" \
	in_accel "sampling_frequency_available value: $(cat $DEV/sampling_frequency_available)"
check "iio_info: as9888-accel: current trigger is the chip's own" in_accel 'Current trigger: trigger[0-9]*(as9888-dev[0-9]*)'
check "iio_info: as9888-magn: current trigger is the chip's own too" in_magn 'Current trigger: trigger[0-9]*(as9888-dev[0-9]*)'
check_not "iio_info: no attribute read error on the as9888 devices" \
	sh -c "echo '$IA$IM' | grep -q ERROR"

A=$(iio_attr -c as9888-accel accel_z scale 2>&1)
eq "iio_attr: accel_z scale as sysfs has it" "$A" "$(cat $DEV/in_accel_scale)"
Z=$(iio_attr -c as9888-accel accel_z raw 2>&1)
near "iio_attr: accel_z raw 1 g = 1024" "$Z" 1024 3
eq "iio_attr: accel_x calibbias as sysfs has it" \
	"$(iio_attr -c as9888-accel accel_x calibbias 2>&1)" "$(cat $DEV/in_accel_x_calibbias)"
b0=$(cat $DEV/in_accel_y_calibbias)
W=$(iio_attr -c as9888-accel accel_y calibbias $((b0 + 4)) 2>&1)
eq "iio_attr: a write prints the value read back" "$W" $((b0 + 4))
eq "iio_attr: calibbias written through libiio reads back in sysfs" \
	"$(cat $DEV/in_accel_y_calibbias)" $((b0 + 4))
eq "iio_attr: and through libiio" "$(iio_attr -c as9888-accel accel_y calibbias 2>&1)" $((b0 + 4))
iio_attr -c as9888-accel accel_y calibbias 9999 >/dev/null 2>&1
eq "iio_attr: out-of-range calibbias 9999 leaves the value" "$(cat $DEV/in_accel_y_calibbias)" $((b0 + 4))
echo "$b0" > $DEV/in_accel_y_calibbias

# 50 scans of accel x/y/z + timestamp with the data-ready trigger: 16 bytes each
T=$(dr_trig)
mg0=$(stat_get chip_magn_measurements)
timeout 30 iio_readdev -t "$T" -s 50 -b 10 as9888-accel accel_x accel_y accel_z timestamp \
	> /tmp/readdev.bin 2>/tmp/readdev.err
rc=$?
# (its upper-case warning about high-speed mode is no kernel splat)
sed 's/^/# iio_readdev: /; s/WARNING:/warning:/' /tmp/readdev.err
eq "iio_readdev: exit status 0" $rc 0
eq "iio_readdev: 50 scans, 800 bytes" "$(wc -c < /tmp/readdev.bin)" 800
eq "iio_readdev: every z sample 1 g (1024 +- 4)" "$(zbad /tmp/readdev.bin)" 0
check "iio_readdev: timestamps strictly increasing" monotonic /tmp/readdev.bin
P=$(period_us /tmp/readdev.bin)
period_ok "iio_readdev at 100 Hz" "$P" 10000
eq "iio_readdev: the buffer is off afterwards" "$(cat $DEV/buffer/enable)" 0
# A channel subset: only the temperature, 2 bytes a scan
timeout 30 iio_readdev -t "$T" -s 20 -b 5 as9888-accel temp > /tmp/readdev-t.bin 2>/dev/null
eq "iio_readdev: 20 scans of temp alone, 40 bytes" "$(wc -c < /tmp/readdev-t.bin)" 40
# TMPS at 25 degC: 176 - 25 * 1.6 = 136
eq "iio_readdev: every temp sample is TMPS(25) = 136" \
	"$(od -A n -t u2 -v /tmp/readdev-t.bin | tr -s ' \n' '\n' | grep -v '^$' | sort -u)" 136
# every channel of as9888-accel (iio_readdev with no channel: all of them)
timeout 30 iio_readdev -t "$T" -s 20 -b 5 as9888-accel > /tmp/readdev-all.bin 2>/dev/null
eq "iio_readdev: 20 scans of every as9888-accel channel, 16 bytes each" "$(wc -c < /tmp/readdev-all.bin)" 320
eq "iio_readdev on as9888-accel, all channels: every z sample 1 g" "$(zbad /tmp/readdev-all.bin)" 0
eq "libiio's accel clients made no magnetometer measurement" "$(stat_get chip_magn_measurements)" "$mg0"
# the magnetometer: 20 scans of magn x/y/z + timestamp, 16 bytes each
timeout 30 iio_readdev -t "$T" -s 20 -b 5 as9888-magn magn_x magn_y magn_z timestamp \
	> /tmp/readdev-m.bin 2>/dev/null
eq "iio_readdev: 20 scans of as9888-magn, 320 bytes" "$(wc -c < /tmp/readdev-m.bin)" 320
# the ambient field of 20-channels.sh: x 67, y -16, z -136 (s13: sign from bit 12)
eq "iio_readdev: every magn sample is the ambient field (67 -16 -136 +- 1)" \
	"$(od -A n -t u2 -v /tmp/readdev-m.bin | awk 'function s13(v) { v = v % 8192; return v >= 4096 ? v - 8192 : v }
		NF == 8 { x = s13($1); y = s13($2); z = s13($3)
			if (x < 66 || x > 68 || y < -17 || y > -15 || z < -137 || z > -135) bad++ }
		END { print bad + 0 }')" 0
check "as9888-magn measured the magnetometer" \
	test "$(stat_get chip_magn_measurements)" -ge $((mg0 + 20))
echo "" > $DEV/trigger/current_trigger 2>/dev/null
