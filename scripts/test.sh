#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Run every test of the project and end with "N passed, N failed".
#
#   scripts/test.sh            everything
#   scripts/test.sh userspace  only the userspace build and tests
#
# Kernel: the two kernel trees from Debian's packages (6.1 LTS and the
# newest, 7.2), the driver built against both with W=1, sparse and
# checkpatch --strict, the devicetree binding checked with dt-schema, the
# KUnit suite on both under UML, the DKMS build on Debian 12's headers, the
# boot test (a debootstrap Debian 12 with Debian's own kernel, the driver
# from DKMS and systemd as PID 1, booted twice in QEMU), and the VM bench:
# debug kernels of both versions in QEMU with the driver bound to the
# simulated chip of the test adapter, driven by real clients.
#
# Userspace: the Meson suite under AddressSanitizer and
# UndefinedBehaviorSanitizer (arithmetic accuracy sweep, chip model
# conformance, simulator, factory test engine, record, save failure
# injection), a bounded libFuzzer run of every parser of outside data, the systemd
# unit check, and a release build of the factory-test benchmark.
set -uo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
build=${AS9888_BUILD:-$top/build}
export AS9888_BUILD=$build
what=${1:-all}
passed=0
failed=0
failures=()

# A stage counts as one test, unless it counts its own (counted=1)
stage() {
	local name=$1
	shift
	echo "== $name"
	counted=0
	if "$@"; then
		[ $counted -eq 1 ] || passed=$((passed + 1))
		echo "-- $name: pass"
	else
		[ $counted -eq 1 ] || failed=$((failed + 1))
		failures+=("$name")
		echo "-- $name: FAIL"
	fi
}

meson_suite() {
	local dir=$build/asan
	[ -f "$dir/build.ninja" ] ||
		meson setup "$dir" "$top" -Dwerror=true -Db_sanitize=address,undefined \
			-Db_lundef=false >/dev/null || return 1
	ninja -C "$dir" || return 1
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		meson test -C "$dir" --num-processes 2 --print-errorlogs
	local rc=$?
	# count the suite's own tests into the summary
	local ok fail
	ok=$(grep -c '"result": "OK"' "$dir/meson-logs/testlog.json" || true)
	fail=$(grep -vc '"result": "OK"' "$dir/meson-logs/testlog.json" || true)
	echo "meson: $ok tests passed, $fail failed"
	passed=$((passed + ok))
	failed=$((failed + fail))
	counted=1
	return $rc
}

release_build() {
	local dir=$build/release
	[ -f "$dir/build.ninja" ] ||
		meson setup "$dir" "$top" -Dwerror=true --buildtype=release >/dev/null || return 1
	ninja -C "$dir"
}

# KUnit's own test counts go into the summary
kunit_suite() {
	local log=$build/kunit.log rc ok fail
	"$top/scripts/kunit.sh" all 2>&1 | tee "$log"
	rc=${PIPESTATUS[0]}
	ok=$(sed -n 's/^kunit [0-9.]*: \([0-9]*\) tests, \([0-9]*\) failed$/\1 \2/p' "$log" |
		awk '{ s += $1 - $2 } END { print s + 0 }')
	fail=$(sed -n 's/^kunit [0-9.]*: \([0-9]*\) tests, \([0-9]*\) failed$/\2/p' "$log" |
		awk '{ s += $1 } END { print s + 0 }')
	if [ "$ok" -eq 0 ]; then
		return 1	# no test ran: the stage fails and counts as one
	fi
	passed=$((passed + ok))
	failed=$((failed + fail + (rc != 0 && fail == 0)))
	counted=1
	return $rc
}

# counted_run LOG PREFIX CMD...: run CMD, its output also into LOG, and
# count its "PREFIX N passed, M failed" lines (summed) into the summary
counted_run() {
	local log=$1 prefix=$2 rc ok fail
	shift 2
	"$@" 2>&1 | tee "$log"
	rc=${PIPESTATUS[0]}
	ok=$(sed -n "s/^$prefix\([0-9]*\) passed, \([0-9]*\) failed.*\$/\1/p" "$log" |
		awk '{ s += $1 } END { print s + 0 }')
	fail=$(sed -n "s/^$prefix\([0-9]*\) passed, \([0-9]*\) failed.*\$/\2/p" "$log" |
		awk '{ s += $1 } END { print s + 0 }')
	# no test ran: the stage fails and counts as one
	[ "$ok" -gt 0 ] || [ "$fail" -gt 0 ] || return 1
	passed=$((passed + ok))
	failed=$((failed + fail + (rc != 0 && fail == 0)))
	counted=1
	return $rc
}

# The VM bench's test counts (per kernel) go into the summary
vm_bench() {
	counted_run "$build/vm.log" '[0-9.]*: ' "$top/scripts/vm-run.sh" all
}

# and the Debian boot test's checks
boot_test() {
	counted_run "$build/boot-debian.log" 'boot-debian: ' "$top/scripts/boot-debian.sh"
}

benchmark() {
	"$top/scripts/bench-factory-test.sh" "$build/release/daemon/as9888-calibd"
}

stage "setup" "$top/scripts/setup.sh"
stage "meson test (ASan+UBSan)" meson_suite
stage "fuzz the parsers (60 s shared by the targets)" "$top/scripts/fuzz.sh" 60
stage "release build" release_build
stage "gpio.c against libgpiod 2.x" "$top/scripts/libgpiod2-check.sh"
stage "systemd units" "$top/scripts/check-units.sh" "$build/release/daemon/as9888-calibd"
stage "factory-test benchmark" benchmark
stage "daemon idle cost and restore latency (release build)" \
	"$top/tests/daemon/daemon.sh" "$build/release/daemon/as9888-calibd"

if [ "$what" = all ]; then
	stage "kernel trees (Debian linux-source 6.1 and 7.2, sparse)" \
		"$top/scripts/kernel-trees.sh" all
	stage "driver: W=1, sparse, checkpatch --strict on 6.1 and 7.2" \
		"$top/scripts/kernel-build.sh" all
	stage "upstream series on 7.2: git am, checkpatch, in-tree W=1 C=1, kernel-doc, ABI, dt_binding_check, htmldocs" \
		"$top/scripts/upstream-series.sh"
	stage "devicetree binding (dt-schema)" "$top/scripts/dt-check.sh"
	stage "KUnit on 6.1 and 7.2 (UML)" kunit_suite
	stage "DKMS build against Debian 12's headers" "$top/scripts/dkms-check.sh"
	stage "Debian packages (dpkg-buildpackage, lintian)" "$top/scripts/deb-build.sh"
	stage "boot test: Debian 12 with Debian's kernel, DKMS and systemd in QEMU" boot_test
	stage "VM bench: driver, adapter and daemon in QEMU on 6.1 and 7.2" vm_bench
fi

echo
[ ${#failures[@]} -eq 0 ] || printf 'failed: %s\n' "${failures[@]}"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
