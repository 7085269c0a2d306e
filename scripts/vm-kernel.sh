#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-kernel.sh [6.1|7.2|all]
#
# Builds the guest kernel of the real-kernel test bench for each version:
# a small x86_64 debug kernel (tinyconfig + tests/vm/config/{base,devices,
# debug,checks,<version>}.config: serial console, initramfs, modules, I2C/
# SPI/GPIO/IIO/NVMEM, KASAN, PROVE_LOCKING, DEBUG_ATOMIC_SLEEP, kmemleak,
# MODVERSIONS, OF, KUnit), then the AS9888 driver modules (the KUnit suite
# as a module too) and the test adapter (tests/vm/adapter) against it.
#
# This is the only kernel build of each version: scripts/kernel-trees.sh
# runs it, and the driver's W=1/sparse build (kernel-build.sh) and the
# upstream series' in-tree builds use its build directory (kobj).
#
# Uses the pristine sources unpacked by scripts/kernel-trees.sh and builds
# into its own O= directory:
#   $AS9888_CACHE/vm/build-<k>/            kernel build (bzImage, .config)
#   $AS9888_CACHE/vm/mod-<k>/              staged module sources + objects
#   $AS9888_CACHE/vm/mod-<k>/ko/           the .ko files for the initramfs
# Every option asked for is checked in the final .config; a missing one is
# an error. The kernel is only rebuilt when the fragments or the source
# change (stamp), so a warm run takes seconds.
#
# Environment: AS9888_CACHE, AS9888_JOBS (default 2).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

select_kernels "$@"
# the lock of vm-run.sh, unless it runs us
[ -n "${AS9888_VM_LOCKED:-}" ] || cache_lock vm

VM_DIR="$AS9888_CACHE/vm"
CFG_DIR="$AS9888_REPO/tests/vm/config"
mkdir -p "$VM_DIR" "$LOG_DIR" "$STAMP_DIR"
T_START=$(now)

ensure_pkgs bc flex bison libelf-dev libssl-dev cpio kmod rsync build-essential

# The unpacked sources come from kernel-trees.sh.
need_src() {
	local k="$1"
	if [ ! -f "$(ksrc "$k")/Makefile" ]; then
		# the sources only: kernel-trees.sh's build step runs this script
		log "$k: no unpacked source yet, running scripts/kernel-trees.sh --source-only $k"
		"$AS9888_REPO/scripts/kernel-trees.sh" --source-only "$k" \
			>"$LOG_DIR/vm-kernel-trees-$k.log" 2>&1 ||
			die "kernel-trees.sh --source-only $k failed, see $LOG_DIR/vm-kernel-trees-$k.log"
	fi
}

fragments() {
	local k="$1" f
	for f in base devices debug checks "$k"; do
		[ -f "$CFG_DIR/$f.config" ] && printf '%s\n' "$CFG_DIR/$f.config"
	done
}

check_config() {
	local k="$1" obj="$2" bad=() line name val f
	while IFS= read -r f; do
		while IFS= read -r line; do
			case "$line" in CONFIG_*=*) ;; *) continue ;; esac
			name=${line%%=*}
			val=${line#*=}
			if [ "$val" = n ]; then
				grep -qE "^$name=[ym]$" "$obj/.config" && bad+=("$name (wanted n)")
			else
				grep -qx "$name=$val" "$obj/.config" || bad+=("$line")
			fi
		done <"$f"
	done < <(fragments "$k")
	if [ "${#bad[@]}" -gt 0 ]; then
		die "$k: options missing from the final .config ($obj/.config): ${bad[*]}"
	fi
}

build_kernel() {
	local k="$1" src obj klog id t
	src=$(ksrc "$k")
	obj="$VM_DIR/build-$k"
	klog="$LOG_DIR/vm-kernel-$k.log"
	mkdir -p "$obj"
	id=$( { cat "$src/Makefile"; fragments "$k" | xargs cat; } | sha256sum | cut -c1-16)
	if [ -f "$obj/arch/x86/boot/bzImage" ] && [ -f "$STAMP_DIR/vm-kernel-$k" ] &&
		[ "$(cat "$STAMP_DIR/vm-kernel-$k")" = "$id" ]; then
		check_config "$k" "$obj"
		log "$k: kernel up to date ($obj)"
		return 0
	fi
	t=$(now)
	log "$k: configuring $obj (tinyconfig + $(fragments "$k" | xargs -n1 basename | tr '\n' ' '))"
	{
		make -C "$src" O="$obj" tinyconfig
		# shellcheck disable=SC2046
		"$src/scripts/kconfig/merge_config.sh" -m -O "$obj" "$obj/.config" $(fragments "$k")
		make -C "$src" O="$obj" olddefconfig
	} >"$klog" 2>&1 || die "$k: configuration failed, see $klog"
	check_config "$k" "$obj"
	log "$k: building bzImage and modules with -j$JOBS (log: $klog)"
	make -C "$src" O="$obj" -j"$JOBS" bzImage modules >>"$klog" 2>&1 ||
		die "$k: kernel build failed, see $klog"
	[ -f "$obj/Module.symvers" ] || die "$k: no Module.symvers"
	printf '%s\n' "$id" >"$STAMP_DIR/vm-kernel-$k"
	log "$k: built $(cat "$obj/include/config/kernel.release") in $(since "$t")"
}

# Out-of-tree modules: the driver (top-level Kbuild) and the adapter, from a
# staged copy of the sources so that no object lands in the repository.
build_modules() {
	local k="$1" obj stage mlog t
	obj="$VM_DIR/build-$k"
	stage="$VM_DIR/mod-$k"
	mlog="$LOG_DIR/vm-modules-$k.log"
	t=$(now)
	# objects of a kernel built with another configuration are stale even
	# where kbuild's dependencies miss it (a struct that grew a field)
	if [ "$(cat "$stage/.kernel-id" 2>/dev/null)" != "$(cat "$STAMP_DIR/vm-kernel-$k")" ]; then
		rm -rf "$stage"
	fi
	mkdir -p "$stage"
	cp "$STAMP_DIR/vm-kernel-$k" "$stage/.kernel-id"
	# by content, and a copied file gets the time of the copy: a checkout
	# whose file is older than the staged object (another branch, another
	# clone) must still rebuild it
	rsync -rlpD --checksum --delete --exclude='*.o' --exclude='*.ko' --exclude='*.cmd' \
		--exclude='*.mod*' --exclude='modules.order' --exclude='Module.symvers' \
		--exclude='ko/' \
		--include='/Kbuild' \
		--include='/drivers/' --include='/drivers/iio/' --include='/drivers/iio/imu/' \
		--include='/drivers/iio/imu/as9888/***' \
		--include='/tests/' --include='/tests/model/***' \
		--include='/tests/vm/' --include='/tests/vm/adapter/***' \
		--exclude='*' "$AS9888_REPO/" "$stage/"
	{
		make -C "$obj" M="$stage" -j"$JOBS" \
			CONFIG_AS9888=m CONFIG_AS9888_I2C=m CONFIG_AS9888_SPI=m \
			CONFIG_AS9888_KUNIT_TEST=m modules
		make -C "$obj" M="$stage/tests/vm/adapter" -j"$JOBS" \
			KBUILD_EXTRA_SYMBOLS="$stage/Module.symvers" modules
	} >"$mlog" 2>&1 || {
		grep -E 'error|warning' "$mlog" | head -40 >&2 || true
		die "$k: module build failed, see $mlog"
	}
	if grep -E 'warning:' "$mlog" >&2; then
		die "$k: module build warnings, see $mlog"
	fi
	rm -rf "$stage/ko"
	mkdir -p "$stage/ko"
	# the modules this build made (modules.order: paths or objects, by
	# kernel version), not a .ko an older tree left in the stage
	local order m
	for order in "$stage/modules.order" "$stage/tests/vm/adapter/modules.order"; do
		while read -r m; do
			m=${m%.o}
			m=${m%.ko}.ko
			case $m in /*) ;; *) m=$(dirname "$order")/$m ;; esac
			cp "$m" "$stage/ko/" || die "$k: $m is in modules.order but was not built"
		done <"$order"
	done
	log "$k: modules $(cd "$stage/ko" && ls | tr '\n' ' ')in $(since "$t")"
}

for k in "${WANT[@]}"; do
	need_src "$k"
	build_kernel "$k"
	build_modules "$k"
done
log "done in $(since "$T_START")"
