#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The magnetometer's calibration as userspace sees it: show (text and
# JSON), the daemon's "magn" request, recalibrate keeping the section, a
# format 1 record saying it has none. Output is TAP.
set -u

calibd=${1:?usage: magn.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
here=$(cd "$(dirname "$0")" && pwd)
if [ -z "${AS9888_IN_NETNS:-}" ]; then
	# the daemon listens to uevents: none of the host's may reach it
	if [ "$(id -u)" -eq 0 ] && unshare --net true 2>/dev/null; then
		AS9888_IN_NETNS=1 exec unshare --net "$0" "$calibd"
	fi
	echo "1..0 # SKIP needs root for a private network namespace"
	exit 77
fi

work=$(mktemp -d /tmp/as9888-magn-XXXXXX)
export ASAN_OPTIONS=detect_leaks=1
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
# shellcheck source=../lib/tap.sh
. "$here/../lib/tap.sh"
TAP_SHOW="$work/err"
# no driver here: an empty sysfs
mkdir -p "$work/sys"
export AS9888_SYSFS=$work/sys

rec=$work/state/calibration
sim=(--sim-clock virtual --unit /dev/null)
"$calibd" factory-test "${sim[@]}" --record "$rec" >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }

run show --record "$rec"
check "format 1: show has no magnetometer part" eval '[ $rc -eq 0 ] && ! says Magnetometer out'
"$here/magn_inject.py" "$rec"
check "the injected record is format 2" grep -q "^format = as9888-calibration 2$" "$rec"

run show --record "$rec"
check "show prints the magnetometer's calibration and the driver's part" eval '[ $rc -eq 0 ] &&
	says "^Magnetometer, learned 2026-11-23T00:00:00Z from 300 samples (coverage 0.875)" out &&
	says "hard iron b \[uT\] *30.000 *-45.500 *100.250" out &&
	says "driver calibbias \[LSB\] *-100 *149 *-341" out &&
	says "driver calibscale *1.020000 *0.985000 *1.003000" out'
run show --json --record "$rec"
check "show --json: the magnetometer object, HAL bias W*b" python3 - "$work/out" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["magnetometer"]
b, W = d["hard_iron"], d["soft_iron"]
assert b == [30.0, -45.5, 100.25], b
assert d["calibbias"] == [-100, 149, -341], d
hal = [sum(W[i][j] * b[j] for j in range(3)) for i in range(3)]
assert all(abs(hal[i] - d["hal_bias"][i]) < 1e-5 for i in range(3)), (hal, d)
R = d["residual_matrix"]
assert all(abs(R[i][j] - W[i][j] / W[j][j]) < 1e-6 for i in range(3) for j in range(3))
PY

sock=$work/sock
"$calibd" daemon "${sim[@]}" --record "$rec" --socket "$sock" 2>"$work/log" &
pid=$!
for _ in $(seq 200); do [ -S "$sock" ] && break; sleep 0.05; done
out=$("$calibd" request magn --socket "$sock")
check "request magn: the calibration, exit status 0" eval 'grep -q "^Magnetometer, learned" <<<"$out" &&
	grep -q "HAL bias" <<<"$out" && grep -q "^exit status 0" <<<"$out"'
out=$("$calibd" request magn --json --socket "$sock")
check "request magn --json: one JSON object" python3 -c '
import json, sys
d = json.loads(sys.argv[1])
assert d["field"] == 48.512 and d["samples"] == 300, d' "$out"

# recalibrate (the accelerometer) keeps the magnetometer's section
grep '^magn_' "$rec" >"$work/magn-before"
run recalibrate "${sim[@]}" --record "$rec"
grep '^magn_' "$rec" >"$work/magn-after"
check "recalibrate keeps the magnetometer's calibration" eval '[ $rc -eq 0 ] &&
	cmp -s "$work/magn-before" "$work/magn-after" &&
	grep -q "^format = as9888-calibration 2$" "$rec" &&
	grep -q "^magn_" "$rec.previous"'

# rollback brings a format 1 record back: "magn" says there is none
"$calibd" factory-test "${sim[@]}" --record "$rec" >/dev/null
out=$("$calibd" request magn --socket "$sock" 2>&1)
check "request magn on a format 1 record: exit status 1, says to run magn-calibrate" eval '
	grep -q "no magnetometer calibration" <<<"$out" && grep -q "magn-calibrate" <<<"$out" &&
	grep -q "^exit status 1" <<<"$out"'

kill "$pid"
wait "$pid" 2>/dev/null
pid=
tap_end
