#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Run every test of the project and end with "N passed, N failed, N skipped",
# alone on the last line.
#
#   scripts/test.sh            everything (the same as "all")
#   scripts/test.sh all        everything
#   scripts/test.sh userspace  only the userspace build and tests
#
# Any other argument is an error (exit 2). The final line counts every
# check: a stage that counts its own (the Meson suite, the boot test, the
# VM bench per kernel, KUnit per test case in it) adds its counts, any other stage
# counts as one; a stage that exits non-zero is at least one failure even
# when it counted none; a skipped check (a TAP "# SKIP", a KUnit skip) is
# counted as skipped, never as passed. The exit status is 0 only when
# nothing failed. A full run refuses the variables that narrow a stage
# (AS9888_VM_ONLY, AS9888_SERIES_SKIP_DOCS, AS9888_SPARSE, AS9888_SRC): a
# narrowed run is not "all". In a full run every skipped check must be an
# environment fact listed in tests/skips-allowed (the entries that applied
# are printed); any other skip fails the run.
#
# Kernel: the two kernel trees from Debian's packages (6.1 LTS and the
# newest, 7.2), each built once (the VM bench's guest kernel, which the
# other kernel stages build against), the driver built against both with
# W=1, sparse and checkpatch --strict, the devicetree binding checked with
# dt-schema, the Yocto layer (oelint-adv per release, SRCREV's tree, the
# kernel fragment), the DKMS build on Debian 12's headers, the
# Debian packages (dpkg-buildpackage, lintian), their apt install in a
# throwaway root with the standard and the cloud kernel's headers, the boot test (a debootstrap
# Debian 12 with Debian's own kernel and the packages installed with apt,
# booted three times in QEMU: systemd, BusyBox init, systemd with an
# upgrade and a purge), and the VM bench:
# debug kernels of both versions in QEMU with the driver bound to the
# simulated chip of the test adapter, driven by real clients, and the
# driver's KUnit suite loaded as a module in each (one check a test case;
# scripts/kunit.sh runs it under UML for a developer, not here).
#
# Userspace: the Meson suite under AddressSanitizer and
# UndefinedBehaviorSanitizer (arithmetic accuracy sweep, chip model
# conformance, simulator, factory test engine, record, save failure
# injection), the mutation check of the arithmetic and the factory-test
# engine against that suite (scripts/mutate.sh), the same suite built with
# musl-gcc and run (scripts/musl-check.sh), a bounded libFuzzer run
# of every parser of outside data, the systemd unit check, and a release
# build of the factory-test benchmark.
set -uo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
build=${AS9888_BUILD:-$top/build}
export AS9888_BUILD=$build
usage() {
	echo "usage: scripts/test.sh [all|userspace]" >&2
	exit 2
}
[ $# -le 1 ] || usage
what=${1:-all}
case $what in
all | userspace) ;;
*) usage ;;
esac
# A full run with a narrowing variable would report a smaller bench as
# the whole: refuse it (run the stage's own script to narrow it)
if [ "$what" = all ]; then
	narrow=""
	[ -z "${AS9888_VM_ONLY:-}" ] || narrow="$narrow AS9888_VM_ONLY=\"$AS9888_VM_ONLY\""
	[ "${AS9888_SERIES_SKIP_DOCS:-0}" = 0 ] ||
		narrow="$narrow AS9888_SERIES_SKIP_DOCS=$AS9888_SERIES_SKIP_DOCS"
	# another sparse or another source tree: not this checkout's checks
	[ -z "${AS9888_SPARSE:-}" ] || narrow="$narrow AS9888_SPARSE=$AS9888_SPARSE"
	[ -z "${AS9888_SRC:-}" ] || narrow="$narrow AS9888_SRC=$AS9888_SRC"
	if [ -n "$narrow" ]; then
		echo "scripts/test.sh all: refusing a narrowed full run:$narrow" >&2
		echo "(unset it, or run the stage's own script with it: scripts/vm-run.sh," \
			"upstream-series.sh, kernel-build.sh, dkms-check.sh)" >&2
		exit 2
	fi
fi
passed=0
failed=0
skipped=0
failures=()
run_start=$(date +%s)
detail=$(mktemp)

# A stage counts as one test, unless it counts its own (counted=1). A stage
# that fails without counting a failure of its own counts one more.
stage_times=()
stage() {
	local name=$1 failed0=$failed t0 verdict
	shift
	echo "== $name"
	counted=0
	t0=$(date +%s)
	if "$@"; then
		[ $counted -eq 1 ] || passed=$((passed + 1))
		verdict=pass
	else
		[ "$failed" -gt "$failed0" ] || failed=$((failed + 1))
		failures+=("$name")
		verdict=FAIL
	fi
	echo "-- $name: $verdict"
	stage_times+=("$(printf '%6d s  %-4s  %s' $(($(date +%s) - t0)) "$verdict" "$name")")
}

meson_suite() {
	local dir=$build/asan
	[ -f "$dir/build.ninja" ] ||
		meson setup "$dir" "$top" -Dwerror=true -Db_sanitize=address,undefined \
			-Db_lundef=false >/dev/null || return 1
	ninja -C "$dir" || return 1
	# this run's log only: a log left by an earlier run counts nothing
	rm -f "$dir/meson-logs/testlog.json"
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		meson test -C "$dir" --num-processes 2 --print-errorlogs
	local rc=$?
	# count the suite's own tests into the summary: every result but OK
	# is a failure (a SKIP too: the suite has all it needs, setup.sh
	# installs it, so a skip is a test that did not run)
	local ok=0 fail=0
	if [ -f "$dir/meson-logs/testlog.json" ]; then
		ok=$(grep -c '"result": "OK"' "$dir/meson-logs/testlog.json" || true)
		fail=$(grep -vc '"result": "OK"' "$dir/meson-logs/testlog.json" || true)
	fi
	echo "meson: $ok tests passed, $fail failed"
	passed=$((passed + ok))
	failed=$((failed + fail))
	counted=1
	# no test ran: the stage fails (stage() counts it)
	[ "$ok" -gt 0 ] || [ "$fail" -gt 0 ] || return 1
	return $rc
}

release_build() {
	local dir=$build/release
	[ -f "$dir/build.ninja" ] ||
		meson setup "$dir" "$top" -Dwerror=true --buildtype=release >/dev/null || return 1
	ninja -C "$dir"
}

# counted_run LOG PREFIX CMD...: run CMD, its output also into LOG, and
# count its "PREFIXN passed, N failed[, N skipped]" lines (summed) into the
# summary
counted_run() {
	local log=$1 prefix=$2 rc ok fail skip
	shift 2
	"$@" 2>&1 | tee "$log"
	rc=${PIPESTATUS[0]}
	# what failed, repeated at the end of the run (a log cut to its tail)
	grep -E '(^|\] )not ok |WARNING: |ERROR: ' "$log" | head -n 20 |
		sed "s|^|  $(basename "$log"): |" >>"$detail"
	read -r ok fail skip < <(sed -n "s/^$prefix\([0-9]*\) passed, \([0-9]*\) failed\(, \([0-9]*\) skipped\)\{0,1\}\( .*\)\{0,1\}\$/\1 \2 \4/p" "$log" |
		awk '{ p += $1; f += $2; s += $3 } END { print p + 0, f + 0, s + 0 }')
	# no test ran: the stage fails (stage() counts it)
	[ "$ok" -gt 0 ] || [ "$fail" -gt 0 ] || return 1
	passed=$((passed + ok))
	failed=$((failed + fail))
	skipped=$((skipped + skip))
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

# the packages installed with dkms on two kernels: its checks counted
dkms_install() {
	counted_run "$build/dkms-install.log" 'dkms-install: ' "$top/scripts/dkms-install-check.sh"
}

# contrib/yocto/meta-as9888 (scripts/yocto-check.sh): its checks counted
yocto_check() {
	counted_run "$build/yocto.log" 'yocto: ' "$top/scripts/yocto-check.sh"
}

# every udev rules file through Debian 13's "udevadm verify": its checks counted
udev_rules() {
	counted_run "$build/udev-rules.log" 'udev-rules: ' "$top/scripts/udev-rules-check.sh"
}

# the suite built with musl-gcc (scripts/musl-check.sh): its tests counted
musl_suite() {
	counted_run "$build/musl.log" 'musl: ' "$top/scripts/musl-check.sh"
}

benchmark() {
	"$top/scripts/bench-factory-test.sh" "$build/release/daemon/as9888-calibd"
}

stage "setup" "$top/scripts/setup.sh"
stage "meson test (ASan+UBSan)" meson_suite
stage "mutation check: every mutant of tests/mutate/mutants.txt killed" "$top/scripts/mutate.sh"
stage "fuzz the parsers (60 s shared by the targets)" "$top/scripts/fuzz.sh" 60
stage "release build" release_build
stage "musl: daemon, libas9888magn and the suite built with musl-gcc" musl_suite
stage "gpio.c against libgpiod 2.x" "$top/scripts/libgpiod2-check.sh"
stage "systemd units" "$top/scripts/check-units.sh" "$build/release/daemon/as9888-calibd"
stage "udev rules (udevadm verify, Debian 13's)" udev_rules
stage "factory-test benchmark" benchmark
stage "daemon idle cost and restore latency (release build)" \
	"$top/tests/daemon/daemon.sh" "$build/release/daemon/as9888-calibd"

if [ "$what" = all ]; then
	stage "kernel trees (Debian linux-source 6.1 and 7.2, sparse, one build of each)" \
		"$top/scripts/kernel-trees.sh" all
	stage "driver: W=1, sparse, checkpatch --strict on 6.1 and 7.2" \
		"$top/scripts/kernel-build.sh" all
	stage "upstream series on 7.2: git am, checkpatch and in-tree W=1 C=1 at every patch, kernel-doc, ABI, dt_binding_check, htmldocs" \
		"$top/scripts/upstream-series.sh"
	stage "devicetree binding (dt-schema)" "$top/scripts/dt-check.sh"
	stage "Yocto layer: oelint-adv for each release, the pinned tree takes the recipe's flags, the kernel fragment" \
		yocto_check
	stage "DKMS build against Debian 12's headers" "$top/scripts/dkms-check.sh"
	stage "Debian packages (dpkg-buildpackage, lintian)" "$top/scripts/deb-build.sh"
	stage "DKMS: apt install of the packages on Debian's standard kernel (built) and cloud kernel (skipped, saying why)" \
		dkms_install
	stage "boot test: Debian 12 with Debian's kernel, DKMS and systemd in QEMU" boot_test
	stage "VM bench: driver, adapter, daemon and KUnit in QEMU on 6.1 and 7.2" vm_bench
fi

# each stage's wall time, so a slow stage shows (CI has 90 minutes)
echo
echo "stage times (wall clock, this run started $(date -u -d "@$run_start" '+%F %T') UTC):"
printf '  %s\n' "${stage_times[@]}"
printf '%8d s  total\n' $(($(date +%s) - run_start))
echo
# A full run's skips: each must match an entry of tests/skips-allowed
if [ "$what" = all ] && [ "$skipped" -gt 0 ]; then
	if ! "$top/scripts/skips-allowed.sh" "$top/tests/skips-allowed" "$skipped" \
		"$build/vm.log" "$build/boot-debian.log" "$build/musl.log"; then
		failed=$((failed + 1))
		failures+=("skipped checks outside tests/skips-allowed")
	fi
fi
if [ ${#failures[@]} -gt 0 ] && [ -s "$detail" ]; then
	echo "what failed (the first 20 lines of each counted stage's log):"
	cat "$detail"
fi
rm -f "$detail"
[ ${#failures[@]} -eq 0 ] || printf 'failed: %s\n' "${failures[@]}"
# every failed stage is at least one failure (stage()), so the line and
# the exit status agree with the list above
echo "$passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ] && [ ${#failures[@]} -eq 0 ]
