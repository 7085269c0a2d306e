# SPDX-License-Identifier: GPL-2.0
# Shared by the shell test scripts: TAP output and the command runner.
# Source it after setting $work (a scratch directory).

tap_n=0
tap_failed=0
tap_planned=

# tap_plan N: the number of checks the script makes, printed before the
# first: a script that stops early has made fewer, and fails (here in
# tap_end when it gets there, and in Meson's TAP parser when it does not)
tap_plan() {
	tap_planned=$1
	echo "1..$1"
}

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

# proc_idle PID SECONDS: "CPU-TICKS WAKE-UPS" of the live process PID over
# SECONDS; fails, saying so, when it is not alive at the start or the end
# (a dead process would read as perfectly idle)
proc_idle() {
	local c0 w0 c1 w1
	c0=$(awk '{ print $14 + $15 }' "/proc/$1/stat" 2>/dev/null)
	w0=$(awk '/^voluntary_ctxt_switches/ { print $2 }' "/proc/$1/status" 2>/dev/null)
	sleep "$2"
	c1=$(awk '{ print $14 + $15 }' "/proc/$1/stat" 2>/dev/null)
	w1=$(awk '/^voluntary_ctxt_switches/ { print $2 }' "/proc/$1/status" 2>/dev/null)
	if [ -z "$c0" ] || [ -z "$w0" ] || [ -z "$c1" ] || [ -z "$w1" ] ||
		! kill -0 "$1" 2>/dev/null; then
		echo "# process $1 is not running: its idle cost cannot be measured" >&2
		return 1
	fi
	echo "$((c1 - c0)) $((w1 - w0))"
}

# the exit status: the checks made must be the plan declared by tap_plan
tap_end() {
	if [ -z "$tap_planned" ]; then
		echo "not ok $((tap_n + 1)) - the script declared no plan (tap_plan N)"
		echo "1..$((tap_n + 1))"
		return 1
	fi
	if [ "$tap_n" -ne "$tap_planned" ]; then
		echo "# planned $tap_planned checks, made $tap_n"
		return 1
	fi
	[ "$tap_failed" -eq 0 ]
}
