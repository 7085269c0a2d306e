#!/bin/sh
# SPDX-License-Identifier: GPL-2.0
# Runs every /tests/tests/*.sh in order in one shell (they share lib.sh's
# counters) and prints the TAP plan at the end. After each file, its own
# plan and the checks it made ("# AS9888-PLAN <file> planned=P made=M"),
# which the host compares.
. /tests/lib.sh
# cpu_times: the guest's uptime, and its CPU time in user space, in the
# kernel and idle (/proc/stat, in USER_HZ ticks), so a file's share of a
# host core shows (a TCG guest's idle time is the host's), and what a
# file's time goes to
cpu_times() {
	awk '{ printf "uptime %s s, ", $1 }' /proc/uptime
	awk '$1 == "cpu" { printf "user %.2f s, system %.2f s, idle %.2f s", ($2 + $3) / 100, ($4 + $7 + $8) / 100, ($5 + $6) / 100 }' /proc/stat
}
# /tests/only (from AS9888_VM_ONLY on the host): run only these files
for t in /tests/tests/*.sh; do
	if [ -s /tests/only ] && ! grep -qx "$(basename "$t" .sh)" /tests/only; then
		continue
	fi
	# (the file's name kept apart: a test file may use $t for itself)
	RA_FILE=$(basename "$t" .sh)
	diag "--- $RA_FILE.sh ($(cpu_times))"
	# the file's plan (lib.sh plan) against the checks it made, for the host
	T_PLAN=""
	T_FILE0=$T_N
	. "$t"
	diag "AS9888-PLAN $RA_FILE planned=${T_PLAN:-none} made=$((T_N - T_FILE0))"
done
leak_check
diag "--- end ($(cpu_times))"
echo "1..$T_N"
echo "# AS9888-VM-RESULT passed=$T_PASS failed=$T_FAIL skipped=$T_SKIP"
