#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# kernel-build.sh [6.1|7.2|all]
#
# Builds the AS9888 out-of-tree modules (top-level Kbuild ->
# drivers/iio/imu/as9888/Makefile) against each kernel tree prepared by
# scripts/kernel-trees.sh (run automatically; a second run is quick), with
#
#   make -C <build dir> M=<staged copy> W=1 C=1 CHECK=<sparse from unstable>
#        CONFIG_AS9888=m CONFIG_AS9888_I2C=m CONFIG_AS9888_SPI=m
#        CONFIG_AS9888_KUNIT_TEST=m modules
#
# and runs the 7.2 tree's scripts/checkpatch.pl --strict --no-tree -f on every
# driver .c/.h. Fails on ANY compiler, sparse, modpost or checkpatch warning,
# and when sparse did not really run: "sparse is not available" in the log, a
# driver .c that never went through CHECK, or a known-bad probe module that
# sparse does not flag.
#
# The sources are copied to $AS9888_CACHE/modbuild/<k>/ and built there from
# scratch every run (a few seconds), so nothing is written into the
# repository and warnings of unchanged files are never skipped.
#
# Timings (2 cores shared with other jobs): with prepared trees 18-35 s for
# both kernels + checkpatch (each kernel: module build 6-12 s, sparse probe
# 1-2 s; checkpatch 2-4 s). Cold, add kernel-trees.sh's cold time.
#
# Prints one line per check and kernel: "<check> <kernel>: N warnings".
# Exit status: 0 clean, 1 warnings/errors/checker not run (or sources the
# Makefile names are missing), 2 usage,
# 3 no driver sources yet (nothing was built).
#
# Environment: AS9888_CACHE, AS9888_JOBS, AS9888_SRC (source root holding
# Kbuild and drivers/iio/imu/as9888; default: this repository),
# AS9888_SPARSE (another sparse binary, e.g. to see the check fail with
# bookworm's /usr/bin/sparse).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

select_kernels "$@"

SRC_ROOT="$(cd "${AS9888_SRC:-$AS9888_REPO}" && pwd)"
DRV="$SRC_ROOT/$AS9888_DRIVER_REL"
T_START=$(now)
cache_lock kernel-build

mapfile -t CFILES < <(driver_c_files "$SRC_ROOT")
if [ "${#CFILES[@]}" -eq 0 ]; then
	echo "kernel-build: no driver sources (*.c) in $DRV yet; nothing was built"
	exit 3
fi
[ -f "$SRC_ROOT/Kbuild" ] || die "missing $SRC_ROOT/Kbuild"
[ -f "$DRV/Makefile" ] || die "missing $DRV/Makefile"
mapfile -t MISSING < <(driver_missing_sources "$SRC_ROOT")
if [ "${#MISSING[@]}" -gt 0 ]; then
	echo "kernel-build: $AS9888_DRIVER_REL/Makefile needs sources that do not exist (yet): ${MISSING[*]}" >&2
	exit 1
fi

# Prepared trees + our sparse (idempotent; seconds when already done).
"$(dirname "$0")/kernel-trees.sh" "${1:-all}" >"$LOG_DIR/kernel-build-trees.log" 2>&1 ||
	die "kernel-trees.sh failed, see $LOG_DIR/kernel-build-trees.log"
ensure_pkgs perl rsync
SPARSE_BIN="${AS9888_SPARSE:-$SPARSE_BIN}"
[ -x "$SPARSE_BIN" ] || die "no sparse at $SPARSE_BIN"

MODBUILD="$AS9888_CACHE/modbuild"
mkdir -p "$MODBUILD" "$LOG_DIR"
WARN_RE='warning:|error:|not available or not up to date'

# CHECK wrapper: sparse's runs and messages counted apart from gcc's
WRAPPER="$MODBUILD/sparse-check"
write_sparse_wrapper "$WRAPPER"

FAIL=0
SUMMARY=()
fail() {
	printf '[%s] FAIL: %s\n' "$SCRIPT_NAME" "$*" >&2
	FAIL=1
}

# Show warning lines with the staged path mapped back to the source root.
show() { sed -e "s|$2/|$SRC_ROOT/|g" "$1" | grep -Ei "$WARN_RE" | sed 's/^/    /' || true; }

# A module sparse must flag: proves that CHECK runs with this tree's flags.
sparse_probe() {
	local k="$1"
	local dir="$MODBUILD/sparse-probe-$k"
	rm -rf "$dir"
	mkdir -p "$dir"
	cat >"$dir/probe.c" <<-'EOF'
		// SPDX-License-Identifier: GPL-2.0
		#include <linux/module.h>
		#include <linux/uaccess.h>
		int as9888_sparse_probe(int __user *p);
		int as9888_sparse_probe(int __user *p)
		{
			return *p; /* sparse: dereference of noderef expression */
		}
		MODULE_LICENSE("GPL");
	EOF
	echo 'obj-m += probe.o' >"$dir/Kbuild"
	make -C "$(kobj "$k")" M="$dir" C=1 CHECK="$SPARSE_BIN" modules >"$dir/probe.log" 2>&1 || true
	grep -q 'dereference of noderef expression' "$dir/probe.log"
}

build_one() {
	local k="$1" obj stage blog slog runs
	obj=$(kobj "$k")
	stage="$MODBUILD/$k"
	blog="$LOG_DIR/kernel-build-$k.log"
	slog="$LOG_DIR/sparse-$k.log"
	runs="$MODBUILD/sparse-runs-$k"

	# Fresh copy of the sources: Kbuild plus the driver directory.
	rm -rf "$stage"
	mkdir -p "$stage/$AS9888_DRIVER_REL"
	cp "$SRC_ROOT/Kbuild" "$stage/"
	rsync -a --include='*.c' --include='*.h' --include='Makefile' --include='Kbuild' \
		--include='Kconfig' --include='compat/' --exclude='*' "$DRV/" "$stage/$AS9888_DRIVER_REL/"
	: >"$slog"
	: >"$runs"

	local cfg=(CONFIG_AS9888=m CONFIG_AS9888_I2C=m CONFIG_AS9888_SPI=m)
	if grep -q '^CONFIG_KUNIT=[ym]' "$obj/.config"; then
		cfg+=(CONFIG_AS9888_KUNIT_TEST=m)
	fi
	local t rc=0
	t=$(now)
	log "$k: make -C $obj M=$stage W=1 C=1 CHECK=sparse ${cfg[*]} modules"
	AS9888_SPARSE_REAL="$SPARSE_BIN" AS9888_SPARSE_LOG="$slog" AS9888_SPARSE_RUNS="$runs" \
		make -C "$obj" M="$stage" W=1 C=1 CHECK="$WRAPPER" "${cfg[@]}" \
		-j"$JOBS" modules >"$blog" 2>&1 || rc=$?

	local nbuild nsparse
	nbuild=$(grep -Eci "$WARN_RE" "$blog" || true)
	nsparse=$(grep -Eci "$WARN_RE" "$slog" || true)
	if [ "$rc" -ne 0 ]; then
		fail "$k: make exited with $rc (log: $blog)"
		grep -E 'Error [0-9]|\*\*\*' "$blog" | sed -e "s|$stage/|$SRC_ROOT/|g" -e 's/^/    /' || true
		[ "$nbuild" -gt 0 ] || nbuild=1
	fi
	SUMMARY+=("build $k: $nbuild warnings")
	local nruns
	nruns=$(sort -u "$runs" | grep -c . || true)
	if [ "$nruns" -lt "${#CFILES[@]}" ]; then
		SUMMARY+=("sparse $k: $nsparse warnings (but sparse checked only $nruns of ${#CFILES[@]} .c files)")
	else
		SUMMARY+=("sparse $k: $nsparse warnings")
	fi
	if [ "$nbuild" -gt 0 ]; then
		fail "$k: compiler/modpost warnings or errors (log: $blog):"
		show "$blog" "$stage"
	fi
	if [ "$nsparse" -gt 0 ]; then
		fail "$k: sparse warnings (log: $slog):"
		show "$slog" "$stage"
	fi

	# Did sparse really run on every driver source?
	if grep -q 'not available or not up to date' "$blog"; then
		fail "$k: kbuild says sparse is not available or not up to date"
	fi
	local c rel unchecked=0
	for c in "${CFILES[@]}"; do
		rel=${c#"$SRC_ROOT/"}
		if ! grep -qF "$stage/$rel" "$runs" && ! grep -qxF "$rel" "$runs"; then
			fail "$k: sparse did not check $rel (not compiled? not in the Makefile?)"
			unchecked=1
		fi
	done
	if [ "$unchecked" -eq 0 ] && [ "$rc" -eq 0 ]; then
		log "$k: sparse ran $(wc -l <"$runs") times, on every driver .c"
	fi
	if sparse_probe "$k"; then
		log "$k: sparse probe flagged as expected"
	else
		fail "$k: sparse did not flag the known-bad probe (see $MODBUILD/sparse-probe-$k/probe.log)"
	fi

	if [ "$rc" -eq 0 ]; then
		local kos
		kos=$(sed -e 's|.*/||' -e 's|\.o$|.ko|' "$stage/modules.order" | tr '\n' ' ')
		log "$k: built ${kos}against $(cat "$obj/include/config/kernel.release") in $(since "$t")"
	fi
}

checkpatch_all() {
	local cp clog total=0 f out
	cp="$(ksrc 7.2)/scripts/checkpatch.pl"
	clog="$LOG_DIR/checkpatch.log"
	if [ ! -f "$cp" ]; then
		"$(dirname "$0")/kernel-trees.sh" 7.2 >>"$LOG_DIR/kernel-build-trees.log" 2>&1 ||
			die "kernel-trees.sh 7.2 failed, see $LOG_DIR/kernel-build-trees.log"
	fi
	: >"$clog"
	local files=()
	mapfile -t files < <(find "$DRV" -maxdepth 1 -type f \( -name '*.c' -o -name '*.h' \) | sort)
	log "checkpatch (7.2, --strict --no-tree -f) on ${#files[@]} files"
	for f in "${files[@]}"; do
		out=$(perl "$cp" --strict --no-tree --show-types -f "$f" 2>&1 || true)
		printf '== %s\n%s\n' "$f" "$out" >>"$clog"
		local e w c n
		read -r e w c < <(printf '%s\n' "$out" | sed -n 's/^total: \([0-9]*\) errors, \([0-9]*\) warnings, \([0-9]*\) checks.*/\1 \2 \3/p' | tail -n1)
		if [ -z "${e:-}" ]; then
			fail "checkpatch gave no verdict for $f (see $clog)"
			n=1
		else
			n=$((e + w + c))
		fi
		if [ "$n" -gt 0 ]; then
			printf '%s\n' "$out" | grep -E '^(ERROR|WARNING|CHECK)|^#|^\+' | sed 's/^/    /' || true
		fi
		total=$((total + n))
	done
	SUMMARY+=("checkpatch 7.2: $total warnings")
	[ "$total" -eq 0 ] || fail "checkpatch: $total errors/warnings/checks (log: $clog)"
}

log "source root $SRC_ROOT (${#CFILES[@]} .c files), kernels: ${WANT[*]}"
for k in "${WANT[@]}"; do
	build_one "$k"
done
checkpatch_all

log "summary:"
for s in "${SUMMARY[@]}"; do echo "$s"; done
if [ "$FAIL" -ne 0 ]; then
	log "FAILED in $(since "$T_START")"
	exit 1
fi
log "all clean in $(since "$T_START")"
