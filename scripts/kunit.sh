#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# kunit.sh [6.1|7.2|all]
#
# Runs the AS9888 KUnit suite (drivers/iio/imu/as9888/as9888_calib_kunit.c)
# under UML with each cached kernel's tools/testing/kunit/kunit.py.
#
# kunit.py builds only tests inside the kernel tree, so each kernel gets a
# tree of its own in the cache: a hard-link copy of the pristine source
# prepared by scripts/kernel-trees.sh ($AS9888_CACHE/kunit/linux-<k>), whose
# drivers/iio/imu/{Kconfig,Makefile} are replaced by edited copies that hook
# in as9888/ (idempotent; the pristine tree and the repository are never
# written to), and into which the driver directory is synchronised on every
# run. The build directory is $AS9888_CACHE/kunit/build-<k>; the kunitconfig
# is drivers/iio/imu/as9888/.kunitconfig.
#
# Fails when a test fails, when the run crashes, and when no test ran.
# Prints "kunit <k>: N tests, F failed" per kernel.
#
# Environment: AS9888_CACHE, AS9888_JOBS, AS9888_SRC (source root holding
# drivers/iio/imu/as9888; default: this repository).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

select_kernels "$@"
# One run at a time per cache: two runs in the same UML build directories
# break each other (one's kunit.py rebuilds what the other is running)
cache_lock kunit

SRC_ROOT="$(cd "${AS9888_SRC:-$AS9888_REPO}" && pwd)"
DRV="$SRC_ROOT/$AS9888_DRIVER_REL"
KUNITCONFIG="$DRV/.kunitconfig"
KUNIT_DIR="$AS9888_CACHE/kunit"

[ -f "$DRV/as9888_calib_kunit.c" ] || die "no KUnit suite in $DRV"
[ -f "$KUNITCONFIG" ] || die "no $KUNITCONFIG"
mkdir -p "$KUNIT_DIR" "$LOG_DIR"
ensure_pkgs rsync

# Replace a hard-linked file of the tree copy by a private copy (so that
# editing it leaves the pristine tree alone) and append a line once.
hook_line() {
	local file="$1" line="$2"
	if ! grep -qxF "$line" "$file"; then
		cp "$file" "$file.as9888.tmp"
		printf '%s\n' "$line" >>"$file.as9888.tmp"
		mv "$file.as9888.tmp" "$file"
	fi
}

prepare_tree() {
	local k="$1" src tree
	src=$(ksrc "$k")
	tree="$KUNIT_DIR/linux-$k"

	if [ ! -f "$src/Makefile" ]; then
		"$(dirname "$0")/kernel-trees.sh" "$k" >"$LOG_DIR/kunit-trees-$k.log" 2>&1 ||
			die "kernel-trees.sh $k failed, see $LOG_DIR/kunit-trees-$k.log"
	fi
	if [ ! -f "$tree/Makefile" ]; then
		log "$k: hard-link copy of $src"
		rm -rf "$tree.new"
		cp -al "$src" "$tree.new"
		mv "$tree.new" "$tree"
	fi

	hook_line "$tree/drivers/iio/imu/Kconfig" 'source "drivers/iio/imu/as9888/Kconfig"'
	hook_line "$tree/drivers/iio/imu/Makefile" 'obj-y += as9888/'

	# The driver sources (a copy, never the repository itself): files whose
	# content changed get a new mtime, so make rebuilds exactly those, also
	# when the copy goes back to older sources.
	mkdir -p "$tree/$AS9888_DRIVER_REL"
	rsync -r --checksum --no-times --delete "$DRV"/ "$tree/$AS9888_DRIVER_REL/"
}

FAIL=0
SUMMARY=()

run_one() {
	local k="$1" tree build klog rc=0 total failed
	tree="$KUNIT_DIR/linux-$k"
	build="$KUNIT_DIR/build-$k"
	klog="$LOG_DIR/kunit-$k.log"

	prepare_tree "$k"
	log "$k: kunit.py run (log: $klog)"
	(cd "$tree" && python3 tools/testing/kunit/kunit.py run --arch=um \
		--jobs="$JOBS" --build_dir="$build" \
		--kunitconfig="$KUNITCONFIG") >"$klog" 2>&1 || rc=$?

	total=$(sed -n 's/.*Ran \([0-9]\+\) tests.*/\1/p' "$klog" | tail -n1)
	failed=$(sed -n 's/.*failed: \([0-9]\+\).*/\1/p' "$klog" | tail -n1)
	total=${total:-0}
	failed=${failed:-0}
	SUMMARY+=("kunit $k: $total tests, $failed failed")

	if [ "$rc" -ne 0 ] || [ "$failed" -ne 0 ]; then
		printf '[%s] FAIL: %s: kunit.py exited with %s, %s failed (log: %s)\n' \
			"$SCRIPT_NAME" "$k" "$rc" "$failed" "$klog" >&2
		grep -E '\[FAILED\]|# .*: (EXPECTATION|ASSERTION) FAILED|Expected ' "$klog" |
			head -n 40 | sed 's/^/    /' >&2 || true
		FAIL=1
	elif [ "$total" -eq 0 ]; then
		printf '[%s] FAIL: %s: no test ran (log: %s)\n' "$SCRIPT_NAME" "$k" "$klog" >&2
		FAIL=1
	fi
}

for k in "${WANT[@]}"; do
	run_one "$k"
done

printf '%s\n' "${SUMMARY[@]}"
exit "$FAIL"
