# SPDX-License-Identifier: GPL-2.0
# Wrong WIA fails probe cleanly; the device comes back with a good unit.
set_unit "fault = wia"
sleep 0.5
C=$(client)
check_not "wrong WIA: no IIO device" iio_dev
check_not "wrong WIA: no magn IIO device either" iio_dev_named as9888-magn
check "wrong WIA: client $C exists but is not bound" \
	sh -c "test -e /sys/bus/i2c/devices/$C && ! test -e /sys/bus/i2c/devices/$C/driver"
check "wrong WIA: probe error in the log" sh -c "dmesg | grep -qi 'as9888.*\(WIA\|ID\|0x47\)'"
set_unit "noise = 1"
check "good unit: device probes again" wait_dev 5
