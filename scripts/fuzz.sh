#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Bounded libFuzzer runs of every parser that reads outside data (clang
# from Debian):
#   record      the calibration record as it is (checksum and all)
#   record_crc  the record with its checksum repaired, so that the key,
#               range and consistency checks are reached
#   unit        the simulated unit description (--unit)
#   request     the daemon's request line and the reply's status line
#   uevent      kernel uevent datagrams
#   iio_scan    the IIO buffer layout (scan_elements _index/_type) and samples
#   iio_value   the driver's attribute values: self-test verdict and
#               readings, integers
#   hal_text    the sensors HAL's configuration file, mount matrix, rates
#               and numbers (hal/)
# Usage: scripts/fuzz.sh [SECONDS [TARGET...]]: SECONDS (default 60) in
# all, shared equally by the targets (default: all of them).
# Seed corpora live in tests/fuzz/corpus/TARGET; new inputs found go to a
# scratch corpus under the build directory (merge them into the seed
# corpus by hand with -merge=1 when they are worth keeping). Prints, per
# target, the inputs run and the coverage reached.
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
all=(record record_crc unit request uevent iio_scan iio_value hal_text)
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")
per=$((seconds / ${#targets[@]}))
[ "$per" -ge 1 ] || per=1
out=${AS9888_BUILD:-$top/build}/fuzz
clang=$(command -v clang-14 || command -v clang || true)
[ -n "$clang" ] || { echo "fuzz: clang is not installed (scripts/setup.sh installs it)" >&2; exit 1; }

calib=("$top/drivers/iio/imu/as9888/as9888_calib.c")
flags=(-g -O1 -std=gnu11 -D_GNU_SOURCE
	-fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined)
# the userspace part of the arithmetic and the kconfig stand-in, where the
# tree has them
if [ -e "$top/lib/calib/as9888_calib_user.c" ]; then
	calib+=("$top/lib/calib/as9888_calib_user.c")
	flags+=(-I"$top/lib/calib")
fi
[ -e "$top/tools/include/linux/kconfig.h" ] &&
	flags+=(-include "$top/tools/include/linux/kconfig.h")
flags+=(-I"$top/tools/include" -I"$top/drivers/iio/imu/as9888"
	-I"$top/daemon/src" -I"$top/lib/iio" -I"$top/tests/model" -I"$top/tests/fuzz"
	-I"$top/hal/include" -I"$top/hal/src")
src=$top/daemon/src

# the sources each target is built from, besides tests/fuzz/TARGET_fuzz.c
sources() {
	case $1 in
	record|record_crc) echo "$src/common/record.c ${calib[*]}" ;;
	unit) echo "$top/tests/model/as9888_unit.c" ;;
	request) echo "$src/common/request.c" ;;
	uevent) echo "$src/service/uevent.c $src/service/uevent_filter.c" ;;
	iio_scan) echo "$top/lib/iio/iio_scan.c" ;;
	iio_value) echo "$src/chip/iio_value.c ${calib[*]}" ;;
	hal_text) echo "$top/hal/src/hal_config.c $top/hal/src/hal_layout.c $top/hal/src/hal_attr.c $top/hal/src/hal_stream.c $top/lib/iio/*.c" ;;
	*) echo "fuzz: unknown target $1 (${all[*]})" >&2; return 1 ;;
	esac
}

for t in "${targets[@]}"; do
	srcs=$(sources "$t")
	mkdir -p "$out/corpus/$t"
	# shellcheck disable=SC2086
	"$clang" "${flags[@]}" "$top/tests/fuzz/${t}_fuzz.c" $srcs -o "$out/${t}_fuzz"
	"$out/${t}_fuzz" -max_total_time="$per" -max_len=4096 -timeout=5 \
		-print_final_stats=1 "$out/corpus/$t" "$top/tests/fuzz/corpus/$t" \
		2>"$out/$t.log" || { tail -40 "$out/$t.log" >&2; echo "fuzz: $t: crash (log $out/$t.log)" >&2; exit 1; }
	runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$out/$t.log")
	cov=$(grep -o 'cov: [0-9]*' "$out/$t.log" | tail -1 | cut -d' ' -f2)
	echo "fuzz: $t: $runs inputs in ${per}s, coverage $cov edges, no crash, corpus $(ls "$out/corpus/$t" | wc -l) entries"
done
