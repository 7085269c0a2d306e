# SPDX-License-Identifier: GPL-2.0
# An unknown WIA is logged and the driver binds (a compatible part behind a
# fallback compatible); a good unit then binds without the message.
plan 6
kmsg_mark 50-wia
set_unit "fault = wia"
C=$(client)
check "unknown WIA: the driver binds" wait_dev 5
check "unknown WIA: the magn IIO device too" test -n "$MDEV"
check "unknown WIA: the accelerometer reads" sh -c "cat $DEV/in_accel_z_raw >/dev/null"
# the adapter's wrong ID is 0x47 (tests/model/as9888_model.h), the AS9888's 0x48
check "unknown WIA: the probe names the ID read and the one expected" \
	kmsg_since 50-wia "$C: .*WIA reads 0x47, expected 0x48"
kmsg_mark 50-good
set_unit "noise = 1"
check "good unit: device probes again" wait_dev 5
check_not "good unit: no WIA message" kmsg_since 50-good "WIA reads"
