#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# scripts/layering-check.py: the tree keeps its layers, and the check
# refuses each kind of break when one is made in a copy of the tree.
# Usage: check.sh SOURCE_ROOT
set -u
top=${1:?usage: check.sh SOURCE_ROOT}
checker=$top/scripts/layering-check.py
n=0
fail=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
not_ok() { n=$((n + 1)); fail=1; echo "not ok $n - $1"; }
echo "1..10"

out=$(python3 "$checker" "$top" 2>&1)
if [ $? -eq 0 ]; then ok "the tree keeps its layers and has no include circle"
else not_ok "the tree keeps its layers and has no include circle"; echo "$out" | sed 's/^/# /'; fi

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
fresh() {
	rm -rf "$scratch/t"
	mkdir -p "$scratch/t/drivers/iio/imu"
	cp -r "$top/daemon" "$top/hal" "$top/lib" "$scratch/t/"
	cp -r "$top/drivers/iio/imu/as9888" "$scratch/t/drivers/iio/imu/"
}
# expect_refusal NAME PATTERN: the check exits 1 and says PATTERN
expect_refusal() {
	local out rc
	out=$(python3 "$checker" "$scratch/t" 2>&1)
	rc=$?
	if [ $rc -eq 1 ] && grep -q -- "$2" <<<"$out"; then ok "$1"
	else not_ok "$1 (exit $rc)"; echo "$out" | sed 's/^/# /'; fi
}
add_include() { sed -i "0,/^#include/s||#include \"$2\"\n#include|" "$scratch/t/daemon/src/$1"; }

fresh
add_include common/record.c store/record_pair.h
expect_refusal "an include from a lower layer up is refused" \
	'common/record.c:[0-9]*: "store/record_pair.h" is above'
fresh
add_include service/uevent.c commands/cli.h
# the include is there, and the checker takes it
grep -q '^#include "commands/cli.h"' "$scratch/t/daemon/src/service/uevent.c" &&
	python3 "$checker" "$scratch/t" >/dev/null 2>&1 &&
	ok "an include down (service to commands) is allowed" ||
	not_ok "an include down (service to commands) is allowed"
fresh
add_include store/atomic_file.c record_pair.h
expect_refusal "a daemon header included without its folder is refused" \
	'"record_pair.h" is a daemon header: name its folder'
fresh
add_include common/json.c common/remedy.h
add_include common/remedy.c common/json.h
expect_refusal "an include circle inside one layer is refused" \
	'include circle: daemon/src/common/json <-> daemon/src/common/remedy'
fresh
add_include main.c commands/nonexistent.h
expect_refusal "an include of a file that is not there is refused" '"commands/nonexistent.h" is no file'
fresh
add_include common/fd_close.c ../service/uevent.h
expect_refusal "an include through .. is refused" '"../service/uevent.h": no ".." in an include'
fresh
sed -i '0,/^#include/s||#include <service/uevent.h>\n#include|' "$scratch/t/daemon/src/common/json.c"
expect_refusal "an angle include up is refused as a quoted one is" \
	'common/json.c:[0-9]*: "service/uevent.h" is above'
fresh
add_include store/lock_file.c chip/iio.h
expect_refusal "store/ including chip/ (beside each other) is refused" \
	'"chip/iio.h": store/ and chip/ are beside each other'
fresh
touch "$scratch/t/daemon/src/helpers.c"
expect_refusal "a file in no layer is refused" 'daemon/src/helpers.c: in no layer'
exit $fail
