# SPDX-License-Identifier: GPL-2.0
# Self-test passes on a healthy unit, fails on selftest_weak.
set_unit "noise = 0"
wait_dev 5
check "selftest runs on a healthy unit" sh -c "echo 1 > $DEV/selftest"
r=$(cat $DEV/selftest); diag "selftest: $r"
eq "selftest passes on a healthy unit" "${r%% *}" pass
set_unit "fault = selftest_weak"
wait_dev 5
echo 1 > $DEV/selftest 2>/dev/null
r=$(cat $DEV/selftest); diag "selftest: $r"
eq "selftest fails on selftest_weak" "${r%% *}" fail
