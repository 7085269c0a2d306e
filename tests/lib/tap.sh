# SPDX-License-Identifier: GPL-2.0
# Shared by the shell test scripts: TAP output and the command runner.
# Source it after setting $work (a scratch directory).

tap_n=0
tap_failed=0

# check WHAT CMD...: one TAP line for CMD's status; on failure the tail of
# the files named in $TAP_SHOW follows as diagnostics
check() {
	local what=$1
	shift
	tap_n=$((tap_n + 1))
	if "$@"; then
		echo "ok $tap_n - $what"
	else
		tap_failed=$((tap_failed + 1))
		echo "not ok $tap_n - $what"
		[ -z "${TAP_SHOW:-}" ] || tail -n 15 $TAP_SHOW 2>/dev/null | sed 's/^/# /'
	fi
}

# run CMD...: $rc, and $work/out and $work/err
run() {
	"$calibd" "$@" >"$work/out" 2>"$work/err"
	rc=$?
}

# says TEXT out|err
says() { grep -q -- "$1" "$work/$2"; }

# the plan line and the exit status
tap_end() {
	echo "1..$tap_n"
	[ "$tap_failed" -eq 0 ]
}
