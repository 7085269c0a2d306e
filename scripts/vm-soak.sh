#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-soak.sh [RUNS] [6.1|7.2|all]
#
# The VM bench on a busy machine (issue 12, item 6): RUNS (default 3)
# back-to-back runs of scripts/vm-run.sh on the kernels named (default
# both), each with a CPU hog beside it (stress-ng with one CPU worker per
# core, "stress-ng --cpu N"), so that every guest test runs slower than on
# an idle machine. The bench has no total time budget, only its stall
# watchdog (AS9888_VM_STALL), so a slow run must still pass: this script
# proves it. Not part of scripts/test.sh (on two cores one run of one
# kernel takes 20 to 35 min beside the hog); the README names it.
#
# AS9888_SOAK_HOGS sets the hog's CPU workers (default: one per core). Set
# it to 0 for a second soak run at the same time, on its own AS9888_CACHE,
# beside the first one's hog: the two guests and one hog then share the
# cores, which loads the machine more than one soak alone.
#
# Prints, per run, the bench's own "<k>: N passed, N failed (T s in QEMU)"
# lines and the wall time of the run, then a summary line
# "vm-soak: R runs, F failed"; exit status 0 only when every run passed.
# Logs: $AS9888_CACHE/logs/vm-soak-<run>.log.
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

runs=${1:-3}
shift || true
case "$runs" in
'' | *[!0-9]*) die "RUNS must be a positive number, not '$runs'" ;;
esac
[ "$runs" -ge 1 ] || die "RUNS must be at least 1"

hogs=${AS9888_SOAK_HOGS:-$(nproc)}
case "$hogs" in
'' | *[!0-9]*) die "AS9888_SOAK_HOGS must be a number of CPU workers, not '$hogs'" ;;
esac
if [ "$hogs" -gt 0 ]; then
	ensure_pkgs stress-ng
	beside="beside stress-ng --cpu $hogs"
else
	beside="with no hog of its own (AS9888_SOAK_HOGS=0)"
fi
mkdir -p "$LOG_DIR"

hog_pid=
stop_hog() {
	[ -n "$hog_pid" ] || return 0
	kill "$hog_pid" 2>/dev/null || true
	wait "$hog_pid" 2>/dev/null || true
	hog_pid=
}
trap stop_hog EXIT

failed=0
for ((r = 1; r <= runs; r++)); do
	log="$LOG_DIR/vm-soak-$r.log"
	if [ "$hogs" -gt 0 ]; then
		stress-ng --cpu "$hogs" --quiet >/dev/null 2>&1 &
		hog_pid=$!
	fi
	t=$(now)
	if AS9888_VM_SOAK=1 "$AS9888_REPO/scripts/vm-run.sh" "$@" >"$log" 2>&1; then
		verdict=pass
	else
		verdict=FAIL
		failed=$((failed + 1))
	fi
	stop_hog
	log "run $r of $runs $beside: $verdict in $(since "$t") (log: $log)"
	grep -E '^(6\.1|7\.2): [0-9]+ passed' "$log" | sed 's/^/  /' || true
	[ "$verdict" = pass ] || grep -E 'not ok|stall|splat' "$log" | head -n 10 | sed 's/^/  /' || true
done

log "vm-soak: $runs runs, $failed failed"
[ "$failed" -eq 0 ]
