# SPDX-License-Identifier: GPL-2.0
# Sourced by the daemon test scripts once $work (their scratch directory) is
# made: what they start in the background and add to pids is killed when
# they exit, and $work is removed.
pids=()
cleanup() {
	local p
	for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
	rm -rf "$work"
}
trap cleanup EXIT
