#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
# Runs every /tests/tests/*.sh in order in one shell (they share lib.sh's
# counters) and prints the TAP plan at the end.
. /tests/lib.sh
for t in /tests/tests/*.sh; do
	diag "--- $(basename "$t")"
	. "$t"
done
leak_check
echo "1..$T_N"
echo "# AS9888-VM-RESULT passed=$T_PASS failed=$T_FAIL"
