#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Crash safety of the record save: inject a failure (an error return, or
# SIGKILL as a stand-in for a power cut) into every system call of the save
# path in turn, with strace, and check what is on disk afterwards: the
# record path holds either the complete old record or a complete new one,
# never a torn one, and a failed save reports failure and leaves no
# temporary file. Output is TAP.
set -u

calibd=${1:?usage: save_inject.sh PATH-TO-as9888-calibd}
command -v strace >/dev/null || { echo "1..0 # SKIP strace is not installed"; exit 77; }

work=$(mktemp -d /tmp/as9888-inject-XXXXXX)
trap 'rm -rf "$work"' EXIT
rec=$work/cal
export ASAN_OPTIONS=detect_leaks=0

run() {
	"$calibd" factory-test --sim-clock virtual --record "$rec" "$@"
}

run >/dev/null || { echo "Bail out! factory test does not pass"; exit 1; }
cp "$rec" "$work/old"

n=0
fail=0
hits=0
ok() { n=$((n + 1)); echo "ok $n - $*"; }
not_ok() { n=$((n + 1)); fail=$((fail + 1)); echo "not ok $n - $*"; }

for action in error kill; do
	for call in openat fchmod write fsync close renameat rename renameat2; do
		for when in 1 2 3; do
			case $action in
			error) inject="$call:error=EIO:when=$when" ;;
			kill) inject="$call:signal=KILL:when=$when" ;;
			esac
			cp "$work/old" "$rec"
			rm -f "$rec.new"
			# a different sample count makes the new record differ
			strace -f -qq -o "$work/trace" -P "$rec" -P "$rec.new" -P "$work" \
				-e trace=openat,fchmod,write,fsync,close,rename,renameat,renameat2 \
				-e inject="$inject" \
				"$calibd" factory-test --sim-clock virtual --samples 12 \
				--record "$rec" >"$work/out" 2>"$work/stderr" &
			wait $! 2>/dev/null
			rc=$?
			if ! grep -qE 'INJECTED|killed by SIGKILL' "$work/trace"; then
				continue	# the save makes fewer such calls
			fi
			hits=$((hits + 1))
			what="$action at $call #$when"
			if cmp -s "$rec" "$work/old"; then
				state=old
			elif "$calibd" show --record "$rec" >/dev/null 2>&1 &&
			     grep -q '^samples = 12$' "$rec"; then
				state=new
			else
				not_ok "$what: record torn or missing"
				continue
			fi
			if [ "$action" = error ] && [ $rc -eq 0 ] && [ $state = old ]; then
				not_ok "$what: save failed but the command reported success"
			elif [ "$action" = error ] && [ -e "$rec.new" ]; then
				not_ok "$what: temporary file left behind"
			elif [ "$action" = error ] && [ $rc -ne 0 ] &&
			     ! grep -qE '^4-1 +fail store calibration record: cannot' "$work/out"; then
				not_ok "$what: no reason given"
			else
				ok "$what: $state record intact (exit $rc)"
			fi
		done
	done
done

# a stale temporary left by a killed save does not block the next save
run --samples 13 >/dev/null && grep -q '^samples = 13$' "$rec" && [ ! -e "$rec.new" ] &&
	ok "save after an interrupted one" || not_ok "save after an interrupted one"

if [ $hits -lt 10 ]; then
	not_ok "only $hits injection points were reached"
fi
echo "1..$n"
echo "# $hits injection points, $fail failures"
[ $fail -eq 0 ]
