#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# kernel-trees.sh [--source-only] [6.1|7.2|all]
#
# Obtains the two kernel trees the AS9888 driver is built against, from
# Debian packages only, and prepares each one for out-of-tree module builds
# (and as a clean source tree for KUnit/QEMU builds with their own O= dirs):
#
#   6.1  linux-source-6.1 from the system's own (bookworm) sources, installed
#        with apt-get; its tarball is unpacked into the cache.
#   7.2  linux-source-7.2 from Debian unstable, fetched with a PRIVATE apt
#        sources list and lists dir (never installed: apt-get download +
#        dpkg-deb), unpacked into the cache.
#   sparse  built from Debian unstable's sparse source (bookworm's 0.6.4 is
#        too old for 7.2); used for both kernels as CHECK=.
#
# Each version is then built once, by scripts/vm-kernel.sh: the VM bench's
# guest kernel (tinyconfig + tests/vm/config/*.config, a debug config that
# also carries MODVERSIONS, OF and KUnit), with bzImage and modules. That
# build directory (kobj) is what the driver's W=1/sparse build and the
# upstream series' in-tree builds use: its complete Module.symvers lets
# modpost check our modules' undefined symbols, namespaces and CRCs for
# real (no KBUILD_MODPOST_WARN), and no second kernel of the same version
# is built for them.
#
# --source-only unpacks the sources and stops there: no sparse, no build,
# no kernels.env (vm-run.sh takes tools/iio from the 7.2 source even when
# it boots only 6.1).
#
# Idempotent: stamp files make a warm run take about a second. Delete
# $AS9888_CACHE/stamps/<name> to redo one step, or the cache dir to start over.
# Changing a tests/vm/config fragment rebuilds the kernels (vm-kernel.sh).
#
# Warm: about a second. Cold: the sources (about 1 min), sparse (about
# 40 s) and the two kernel builds (README, "Measured").
# Disk: about 1.5 GB (6.1) + 1.8 GB (7.2) of source, 0.7 GB of build output.
#
# Environment: AS9888_CACHE (default ~/.cache/as9888), AS9888_JOBS (default 2).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

usage() {
	echo "usage: $0 [--source-only] [6.1|7.2|all]" >&2
	exit 2
}

source_only=0
if [ "${1:-}" = --source-only ]; then
	source_only=1
	shift
fi
case "${1:-all}" in
6.1 | 7.2) WANT=("$1") ;;
all) WANT=("${AS9888_KERNELS[@]}") ;;
-h | --help) usage ;;
*) usage ;;
esac

BUILD_DEPS=(bc flex bison libelf-dev libssl-dev dwarves cpio kmod rsync
	xz-utils build-essential perl python3 curl ca-certificates
	debian-archive-keyring)

APT_PRIV="$AS9888_CACHE/apt-unstable"

# Options every prepared tree must end up with, on top of tinyconfig.
# Enough to build the AS9888 modules (IIO with buffers and triggers, regmap
# I2C/SPI, GPIO, regulators, NVMEM, PM, KUnit) and to boot the bzImage in
# QEMU with a serial console and an initramfs.
# REGMAP_I2C/REGMAP_SPI have no prompt: BMI160_I2C/BMI160_SPI select them
# (and IIO_TRIGGERED_BUFFER), like our own AS9888_I2C/AS9888_SPI would.

T_START=$(now)
mkdir -p "$AS9888_CACHE" "$STAMP_DIR" "$LOG_DIR" "$AS9888_CACHE/bin"

# One run at a time per cache dir.
exec 9>"$AS9888_CACHE/.kernel-trees.lock"
if ! flock -n 9; then
	log "another kernel-trees.sh holds $AS9888_CACHE/.kernel-trees.lock; waiting"
	flock 9
fi

DID=() # what this run actually did

step_done() { [ -f "$STAMP_DIR/$1" ] && [ "$(cat "$STAMP_DIR/$1")" = "$2" ]; }
mark_done() { printf '%s\n' "$2" >"$STAMP_DIR/$1"; }

# --- apt mirror of this machine, and the private unstable apt state --------

# shellcheck source-path=SCRIPTDIR source=apt-private.sh
. "$AS9888_REPO/scripts/apt-private.sh"

apt_priv_setup() {
	[ "${#APT_OPTS[@]}" -gt 0 ] && return 0
	apt_private "$APT_PRIV" unstable "deb deb-src" scripts/kernel-trees.sh
	local mirror=$MIRROR
	# Refresh the unstable indexes at most once a day.
	local today
	today=$(date +%F)
	if ! step_done apt-unstable-update "$mirror $today"; then
		local t
		t=$(now)
		log "apt-get update (private unstable list, mirror $mirror)"
		apt-get "${APT_OPTS[@]}" update
		mark_done apt-unstable-update "$mirror $today"
		DID+=("fetched Debian unstable indexes from $mirror ($(since "$t"))")
	fi
}

# --- sparse ------------------------------------------------------------------

ensure_sparse() {
	if [ -x "$SPARSE_BIN" ] && [ -f "$STAMP_DIR/sparse" ]; then
		log "sparse: $SPARSE_BIN from $(cat "$STAMP_DIR/sparse") (cached)"
		return 0
	fi
	local t
	t=$(now)
	apt_priv_setup
	local dl="$AS9888_CACHE/sparse/download"
	rm -rf "$AS9888_CACHE/sparse"
	mkdir -p "$dl"
	log "sparse: fetching Debian unstable's sparse source"
	if ! (cd "$dl" && apt-get "${APT_OPTS[@]}" source --download-only sparse); then
		# The .dsc may be missing on the mirror while the tarball is there:
		# fetch the upstream tarball alone and check it against the index.
		log "sparse: apt-get source failed; fetching the orig tarball directly"
		local line url name hash
		line=$(cd "$dl" && apt-get "${APT_OPTS[@]}" source --print-uris sparse | grep -E "\.orig\.tar\." | head -n1)
		[ -n "$line" ] || die "sparse: no orig tarball in unstable's Sources index"
		url=$(printf '%s\n' "$line" | awk '{ gsub("\x27", "", $1); print $1 }')
		name=$(printf '%s\n' "$line" | awk '{ print $2 }')
		hash=$(printf '%s\n' "$line" | awk '{ print $4 }')
		curl -fsSL -o "$dl/$name" "$url"
		case "$hash" in
		SHA256:*) echo "${hash#SHA256:}  $dl/$name" | sha256sum -c - ;;
		*) die "sparse: unexpected hash field '$hash' for $name" ;;
		esac
	fi
	local orig
	orig=$(find "$dl" -maxdepth 1 -name 'sparse_*.orig.tar.*' | head -n1)
	[ -n "$orig" ] || die "sparse: no orig tarball downloaded"
	local srcdir="$AS9888_CACHE/sparse/src"
	mkdir -p "$srcdir"
	tar -xf "$orig" -C "$srcdir" --strip-components=1
	log "sparse: building $(basename "$orig") (make CC=gcc sparse)"
	make -C "$srcdir" -j"$JOBS" CC=gcc sparse >"$LOG_DIR/sparse-build.log" 2>&1 ||
		die "sparse build failed, see $LOG_DIR/sparse-build.log"
	install -m 0755 "$srcdir/sparse" "$SPARSE_BIN.new"
	mv "$SPARSE_BIN.new" "$SPARSE_BIN"
	"$SPARSE_BIN" --version >/dev/null || die "the built sparse does not run"
	mark_done sparse "$(basename "$orig")"
	DID+=("built sparse from $(basename "$orig") ($(since "$t"); it calls itself $("$SPARSE_BIN" --version))")
}

# --- kernel sources ------------------------------------------------------------

# Unpack a linux-source tarball (read from stdin) into $(ksrc k).
unpack_tree() {
	local k="$1" src tmp
	src=$(ksrc "$k")
	tmp="$AS9888_CACHE/src/.unpack-$k"
	rm -rf "$tmp" "$src"
	mkdir -p "$tmp"
	tar -xJ -C "$tmp"
	local top
	top=$(find "$tmp" -mindepth 1 -maxdepth 1 -type d | head -n1)
	if [ -z "$top" ] || [ ! -f "$top/Makefile" ]; then
		die "tarball for $k has no kernel tree"
	fi
	mv "$top" "$src"
	rmdir "$tmp"
}

ensure_source_6_1() {
	local tarball=/usr/src/linux-source-6.1.tar.xz
	ensure_pkgs linux-source-6.1
	[ -f "$tarball" ] || die "$tarball missing after installing linux-source-6.1"
	local id
	id="$(dpkg-query -W -f='${Version}' linux-source-6.1) $(stat -c %s "$tarball")"
	if step_done src-6.1 "$id" && [ -f "$(ksrc 6.1)/Makefile" ]; then
		log "6.1: source $(ksrc 6.1) (cached, linux-source-6.1 $id)"
		return 0
	fi
	local t
	t=$(now)
	log "6.1: unpacking $tarball"
	unpack_tree 6.1 <"$tarball"
	mark_done src-6.1 "$id"
	rm -f "$STAMP_DIR/tree-6.1"
	DID+=("6.1: unpacked linux-source-6.1 $id ($(since "$t"))")
}

ensure_source_7_2() {
	local debdir="$AS9888_CACHE/debs" deb
	mkdir -p "$debdir"
	deb=$(find "$debdir" -maxdepth 1 -name 'linux-source-7.2_*_all.deb' | sort -V | tail -n1)
	if [ -z "$deb" ]; then
		local t
		t=$(now)
		apt_priv_setup
		log "7.2: apt-get download linux-source-7.2 (unstable, not installed)"
		(cd "$debdir" && apt-get "${APT_OPTS[@]}" download linux-source-7.2)
		deb=$(find "$debdir" -maxdepth 1 -name 'linux-source-7.2_*_all.deb' | sort -V | tail -n1)
		[ -n "$deb" ] || die "7.2: download produced no linux-source-7.2 .deb"
		DID+=("7.2: downloaded $(basename "$deb") ($(since "$t"))")
	fi
	local id
	id="$(basename "$deb") $(stat -c %s "$deb")"
	if step_done src-7.2 "$id" && [ -f "$(ksrc 7.2)/Makefile" ]; then
		log "7.2: source $(ksrc 7.2) (cached, $(basename "$deb"))"
		return 0
	fi
	local t member
	t=$(now)
	member=$(dpkg-deb --fsys-tarfile "$deb" | tar -t | grep -E '/usr/src/linux-source-7\.2\.tar\.xz$' | head -n1)
	[ -n "$member" ] || die "7.2: no linux-source-7.2.tar.xz inside $deb"
	log "7.2: unpacking $member from $(basename "$deb") (dpkg-deb, no install)"
	dpkg-deb --fsys-tarfile "$deb" | tar -xO "$member" | unpack_tree 7.2
	mark_done src-7.2 "$id"
	rm -f "$STAMP_DIR/tree-7.2"
	DID+=("7.2: unpacked $(basename "$deb") ($(since "$t"))")
}

# --- configure + build -----------------------------------------------------------

# The build of each version is the VM bench's guest kernel
# (scripts/vm-kernel.sh: tinyconfig + tests/vm/config/*.config, which
# carry what the lint and the series need too): one build a version
prepare_tree() {
	local k="$1" obj t klog
	obj=$(kobj "$k")
	klog="$LOG_DIR/kernel-$k.log"
	t=$(now)
	"$AS9888_REPO/scripts/vm-kernel.sh" "$k" >"$klog" 2>&1 ||
		die "$k: scripts/vm-kernel.sh $k failed, see $klog"
	[ -f "$obj/Module.symvers" ] || die "$k: no Module.symvers in $obj"
	grep -q '[[:space:]]vmlinux[[:space:]]' "$obj/Module.symvers" ||
		die "$k: Module.symvers has no vmlinux symbols"
	mark_done "tree-$k" "$(cat "$STAMP_DIR/vm-kernel-$k")"
	if grep -q "built .* in" "$klog"; then
		DID+=("$k: built $(cat "$obj/include/config/kernel.release") in $obj ($(since "$t"))")
	else
		log "$k: build dir $obj ready (cached)"
	fi
}

write_env() {
	local f="$AS9888_CACHE/kernels.env"
	{
		echo "# Written by scripts/kernel-trees.sh; source it to find the prepared trees."
		echo "AS9888_CACHE='$AS9888_CACHE'"
		echo "SPARSE='$SPARSE_BIN'"
		local k v
		for k in "${AS9888_KERNELS[@]}"; do
			v=${k/./_}
			[ -f "$STAMP_DIR/tree-$k" ] || continue
			echo "KSRC_$v='$(ksrc "$k")'"
			echo "KOBJ_$v='$(kobj "$k")'"
			echo "KREL_$v='$(cat "$(kobj "$k")/include/config/kernel.release")'"
		done
	} >"$f.new"
	mv "$f.new" "$f"
}

# --- main -----------------------------------------------------------------------

ensure_pkgs "${BUILD_DEPS[@]}"
[ "$source_only" -eq 1 ] || ensure_sparse
for k in "${WANT[@]}"; do
	case "$k" in
	6.1) ensure_source_6_1 ;;
	7.2) ensure_source_7_2 ;;
	esac
	[ "$source_only" -eq 1 ] || prepare_tree "$k"
done
if [ "$source_only" -eq 1 ]; then
	for k in "${WANT[@]}"; do log "  $k: src $(ksrc "$k")"; done
	log "done in $(since "$T_START") (sources only)"
	exit 0
fi
write_env

log "summary:"
if [ "${#DID[@]}" -eq 0 ]; then
	log "  nothing to do, everything was cached"
else
	for d in "${DID[@]}"; do log "  $d"; done
fi
log "  sparse:  $SPARSE_BIN (from $(cat "$STAMP_DIR/sparse"))"
for k in "${WANT[@]}"; do
	log "  $k: src $(ksrc "$k")"
	log "  $k: obj $(kobj "$k") ($(cat "$(kobj "$k")/include/config/kernel.release"))"
done
log "  env:     $AS9888_CACHE/kernels.env"
log "done in $(since "$T_START")"
