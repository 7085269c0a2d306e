# SPDX-License-Identifier: GPL-2.0
# Wrong WIA fails probe cleanly; the device comes back with a good unit.
plan 5
kmsg_mark 50-wia
set_unit "fault = wia"
sleep 0.5
C=$(client)
check_not "wrong WIA: no IIO device" iio_dev
check_not "wrong WIA: no magn IIO device either" iio_dev_named as9888-magn
check "wrong WIA: client $C exists but is not bound" \
	sh -c "test -e /sys/bus/i2c/devices/$C && ! test -e /sys/bus/i2c/devices/$C/driver"
# the adapter's wrong ID is 0x47 (tests/model/as9888_model.h), the AS9888's 0x48
check "wrong WIA: the probe error names the ID read and the one expected" \
	kmsg_since 50-wia "$C: .*WIA reads 0x47, not an AS9888 (0x48)"
set_unit "noise = 1"
check "good unit: device probes again" wait_dev 5
