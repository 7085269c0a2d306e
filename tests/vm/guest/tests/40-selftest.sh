# SPDX-License-Identifier: GPL-2.0
# Self-test passes on a healthy unit, fails on selftest_weak. selftest is an
# attribute of the magnetometer device (as9888-magn): it reads one word
# (none, pass, fail); the adjusted readings of the last test are in debugfs
# iio/iio:deviceM/selftest_readings ("X Y Z", 3 decimals, or none), M the
# magn device's number.
plan 8
set_unit "noise = 0"
wait_dev 5
RD=/sys/kernel/debug/iio/${MDEV##*/}/selftest_readings
check_not "no selftest attribute on the accel device" test -e $DEV/selftest
eq "selftest before the first test: none" "$(cat $MDEV/selftest)" none
eq "selftest_readings before the first test: none" "$(cat $RD 2>&1)" none
check "selftest runs on a healthy unit" sh -c "echo 1 > $MDEV/selftest"
eq "selftest passes on a healthy unit (one word)" "$(cat $MDEV/selftest)" pass
r=$(cat $RD 2>&1); diag "selftest_readings: $r"
# windows of the application note: X and Y -100..100, Z 300..1000
check "selftest_readings: three values with 3 decimals within the windows" \
	sh -c "echo '$r' | awk 'NF == 3 && \$0 ~ /^-?[0-9]+\\.[0-9][0-9][0-9] -?[0-9]+\\.[0-9][0-9][0-9] -?[0-9]+\\.[0-9][0-9][0-9]\$/ &&
		\$1 >= -100 && \$1 <= 100 && \$2 >= -100 && \$2 <= 100 && \$3 >= 300 && \$3 <= 1000 { ok = 1 } END { exit !ok }'"
set_unit "fault = selftest_weak"
wait_dev 5
RD=/sys/kernel/debug/iio/${MDEV##*/}/selftest_readings
echo 1 > $MDEV/selftest 2>/dev/null
eq "selftest fails on selftest_weak" "$(cat $MDEV/selftest)" fail
r=$(cat $RD 2>&1); diag "selftest_readings: $r"
check "selftest_readings: Z below the window (generator about 150)" \
	sh -c "echo '$r' | awk 'NF == 3 && \$3 < 300 { ok = 1 } END { exit !ok }'"
