#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Bounded libFuzzer run of the calibration record parser (clang from
# Debian). Usage: scripts/fuzz.sh [SECONDS] (default 60).
# The seed corpus lives in tests/fuzz/corpus/record; new inputs found go to
# a scratch corpus under the build directory (merge them into the seed
# corpus by hand with -merge=1 when they are worth keeping).
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
out=${AS9888_BUILD:-$top/build}/fuzz
clang=$(command -v clang-14 || command -v clang || true)
[ -n "$clang" ] || { echo "fuzz: clang is not installed (scripts/setup.sh installs it)" >&2; exit 1; }

mkdir -p "$out/corpus"
"$clang" -g -O1 -std=gnu11 -D_GNU_SOURCE \
	-fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
	-I"$top/tools/include" -I"$top/drivers/iio/imu/as9888" -I"$top/daemon/src" \
	"$top/tests/fuzz/record_fuzz.c" "$top/daemon/src/record.c" \
	"$top/drivers/iio/imu/as9888/as9888_calib.c" \
	-o "$out/record_fuzz"

"$out/record_fuzz" -max_total_time="$seconds" -max_len=4096 -timeout=5 \
	-print_final_stats=1 "$out/corpus" "$top/tests/fuzz/corpus/record" \
	2>"$out/fuzz.log" || { tail -40 "$out/fuzz.log" >&2; exit 1; }
runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/fuzz.log")
echo "fuzz: record parser: $runs inputs in ${seconds}s, no crash, corpus $(ls "$out/corpus" | wc -l) entries"
