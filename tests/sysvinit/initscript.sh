#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The SysV/BusyBox init script (daemon/sysvinit/as9888-calibd.in) under
# BusyBox ash with BusyBox's applets only on PATH, driving the built
# as9888-calibd: "start | cat" and "restart | cat" return (a background
# process holding the script's stdout would keep cat waiting for ever),
# the LSB exit codes (status 0/3, reload 3, an unknown action 2), stop
# stops the daemon. The template is configured here as Meson does it
# (@name@ substitution), with the run, state and configuration
# directories in a scratch directory, and the daemon on a fake sysfs.
# A hang is detected by a generous timeout (60 s) on each call; the time
# each call took is printed as a diagnostic, not judged. Output is TAP.
set -u

calibd=${1:?usage: initscript.sh PATH-TO-as9888-calibd PATH-TO-as9888-calibd.in}
template=${2:?usage: initscript.sh PATH-TO-as9888-calibd PATH-TO-as9888-calibd.in}
work=$(mktemp -d /tmp/as9888-initscript-XXXXXX)
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
HANG=60
tap_plan 12
TAP_SHOW="$work/err"

busybox=$(command -v busybox) || {
	echo "Bail out! busybox is not installed (Debian package busybox-static)"
	exit 1
}
# BusyBox's applets alone on PATH, as on a BusyBox root
mkdir -p "$work/bin" "$work/sbin" "$work/etc/init.d" "$work/etc/default" \
	"$work/run" "$work/state" "$work/sys"
"$busybox" --install -s "$work/bin" || {
	echo "Bail out! busybox --install failed"
	exit 1
}
ln -s "$(cd "$(dirname "$calibd")" && pwd)/$(basename "$calibd")" "$work/sbin/as9888-calibd"
init=$work/etc/init.d/as9888-calibd
sed -e "s|@sbindir@|$work/sbin|g" -e "s|@sysconfdir@|$work/etc|g" \
	-e "s|@statedir@|$work/state|g" -e "s|@rundir@|$work/run|g" "$template" >"$init"
chmod 0755 "$init"
grep -q '@[a-z]*@' "$init" && {
	echo "Bail out! $template has a @name@ this test does not configure"
	exit 1
}
cat >"$work/etc/default/as9888-calibd" <<EOT
AS9888_CALIBD_DAEMON_OPTS="--socket $work/run/as9888-calibd.sock"
EOT
export AS9888_SYSFS=$work/sys

cleanup() {
	local pid
	read -r pid 2>/dev/null <"$work/run/as9888-calibd.pid" &&
		kill "$pid" 2>/dev/null
	rm -rf "$work"
}
trap cleanup EXIT

# call ACTION: "busybox ash INIT ACTION | cat" with BusyBox's PATH; $rc is
# the script's status, or 124 when the script still ran after $HANG s, or
# cat still read after $HANG s (a process the script left behind holds
# the pipe); the output in $work/out
call() {
	local t0 t1 ash_rc cat_rc
	t0=$(date +%s.%N)
	timeout -k 5 "$HANG" env -i PATH="$work/bin" AS9888_SYSFS="$AS9888_SYSFS" \
		"$busybox" ash "$init" "$1" 2>&1 |
		timeout -k 5 "$HANG" cat >"$work/out"
	ash_rc=${PIPESTATUS[0]} cat_rc=${PIPESTATUS[1]}
	t1=$(date +%s.%N)
	rc=$ash_rc
	[ "$cat_rc" -eq 0 ] || rc=124
	cp "$work/out" "$work/err"
	echo "# $1 | cat: returned after $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s, status $ash_rc, cat's $cat_rc"
}

daemon_pid() {
	local pid
	read -r pid 2>/dev/null <"$work/run/as9888-calibd.pid" || return 1
	[ "$(cat "/proc/$pid/comm" 2>/dev/null)" = as9888-calibd ] || return 1
	echo "$pid"
}

call start
check "start | cat returns (within $HANG s) with status 0" [ "$rc" = 0 ]
check "start: the daemon runs, its socket is there" \
	eval 'pid1=$(daemon_pid) && [ -S "$work/run/as9888-calibd.sock" ]'
check "start without a record: the warning names the factory test" \
	grep -q "no calibration record at $work/state/calibration.*factory-test" "$work/out"
call status
check "status: 0 while running" [ "$rc" = 0 ]
call start
check "start again | cat: 0, already running" \
	eval '[ "$rc" = 0 ] && grep -q "already running" "$work/out"'
call restart
check "restart | cat returns (within $HANG s) with status 0" [ "$rc" = 0 ]
check "restart: a new daemon" eval 'pid2=$(daemon_pid) && [ "$pid2" != "${pid1:-}" ]'
call reload
check "reload: 3 (LSB: unimplemented), says to restart" \
	eval '[ "$rc" = 3 ] && grep -q "use restart" "$work/out"'
call frobnicate
check "an unknown action: 2 (LSB: invalid argument)" [ "$rc" = 2 ]
call stop
check "stop: 0, the daemon gone, no pid file" \
	eval '[ "$rc" = 0 ] && [ ! -d "/proc/${pid2:-0}" ] && [ ! -e "$work/run/as9888-calibd.pid" ]'
call status
check "status: 3 when stopped" [ "$rc" = 3 ]
call stop
check "stop when stopped: 0" [ "$rc" = 0 ]
tap_end
