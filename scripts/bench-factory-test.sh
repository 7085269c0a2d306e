#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Factory test speed on the simulator: the wall time of steps 1-3 at N = 16
# in real time, next to the physical limit for the same N. The limit is the
# same run on the simulator's virtual clock, which advances only by what
# the chip and the bus need: the datasheet's mandatory waits (t_RSTL,
# t_BOOT, t_EEP, t_PD), the conversion times (t_MAG, t_ACC) and every
# transfer at 400 kHz. Target: real <= 1.2 x limit.
# Usage: bench-factory-test.sh PATH-TO-as9888-calibd [RUNS]
set -euo pipefail

calibd=${1:?usage: bench-factory-test.sh PATH-TO-as9888-calibd [RUNS]}
runs=${2:-7}
n=16
work=$(mktemp -d /tmp/as9888-bench-XXXXXX)
trap 'rm -rf "$work"' EXIT

duration() {
	"$calibd" factory-test --json --samples $n --record "$work/cal" "$@" |
		sed -n 's/^  "duration_ms": \(.*\),$/\1/p'
}

limit=$(duration --sim-clock virtual)
[ -n "$limit" ] || { echo "bench: the factory test did not run" >&2; exit 1; }
times=()
for _ in $(seq "$runs"); do
	times+=("$(duration)")
done
median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(( (runs + 1) / 2 ))p")
ratio=$(awk -v a="$median" -v b="$limit" 'BEGIN { printf "%.3f", a / b }')
conv=$(awk -v n=$n 'BEGIN { printf "%.1f", 2 * 7.3 + 2 * n * 1.2 }')
echo "factory-test N=$n: wall ${median} ms (median of $runs), physical limit ${limit} ms" \
     "(of which ${conv} ms conversions), ratio ${ratio} (target <= 1.2)"
echo "all runs (ms): ${times[*]}"
