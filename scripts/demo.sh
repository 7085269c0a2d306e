#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The main job on the built-in simulated unit: build as9888-calibd, run the
# factory test (steps 1-4 of the application note) on the simulator in real
# time, then show the stored calibration at a few temperatures.
# Usage: scripts/demo.sh [extra factory-test options, e.g. --unit FILE]
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
build=${AS9888_BUILD:-$top/build}/release
"$top/scripts/setup.sh"
[ -f "$build/build.ninja" ] || meson setup "$build" "$top" --buildtype=release >/dev/null
ninja -C "$build" daemon/as9888-calibd >/dev/null

calibd=$build/daemon/as9888-calibd
record=${AS9888_BUILD:-$top/build}/demo/calibration
echo "== as9888-calibd factory-test --backend sim --record $record $*"
"$calibd" factory-test --backend sim --record "$record" "$@"
for t in -10 25 60; do
	echo
	echo "== as9888-calibd show --record $record --temperature $t"
	"$calibd" show --record "$record" --temperature "$t"
done
