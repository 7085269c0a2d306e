#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# libgpiod2-check.sh
#
# Checks that the daemon's GPIO unit (daemon/src/chip/gpio.c, with
# -DAS9888_GPIOD_V2) and the raw backend build against libgpiod 2.x, which
# Debian 12 does not have (bookworm ships 1.6.3, the default build).
#
#  1. libgpiod 2.x source comes from Debian trixie through a PRIVATE apt
#     configuration in $AS9888_CACHE/apt-trixie/ (its own sources.list with a
#     deb-src line, its own lists and package cache). The mirror is the one
#     the system's /etc/apt/sources.list(.d) uses for the running release
#     (read through "apt-get indextargets"). The upstream (orig) tarball is
#     checked against the SHA256 in trixie's Sources index, unpacked and built
#     as a static library into $AS9888_CACHE/libgpiod2/. Nothing from trixie
#     is ever installed into the system.
#  2. gpio.c and backend_raw.c are compiled with the project's warning flags
#     and -Werror against that library's headers; tests/gpio/gpio_v2_smoke.c
#     is linked with gpio.c and the static libgpiod and run: it prints the
#     library version and checks that opening a line on a chip that does not
#     exist fails with -errno and a message naming the chip.
#  3. Prints "libgpiod2-check: gpio.c builds against libgpiod <version>: ok".
#
# A stamp file ($AS9888_CACHE/stamps/libgpiod2) makes later runs skip step 1:
# a warm run only recompiles the three files (about a second).
#
# Exit status: 0 ok, non-zero on any failure.
# Environment: AS9888_CACHE (default ~/.cache/as9888); AS9888_JOBS (make -j,
#   default 2); LIBGPIOD2_REBUILD=1 forces step 1 again.
set -euo pipefail

NAME=libgpiod2-check
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CACHE="${AS9888_CACHE:-$HOME/.cache/as9888}"
JOBS="${AS9888_JOBS:-2}"
SUITE=trixie
PREFIX="$CACHE/libgpiod2"
APT_PRIV="$CACHE/apt-$SUITE"
WORK="$CACHE/libgpiod2-work"
STAMP="$CACHE/stamps/libgpiod2"
LOG_DIR="$CACHE/logs"
BUILD_LOG="$LOG_DIR/libgpiod2-build.log"
OUT="$CACHE/libgpiod2-check"

log() { printf '[%s] %s\n' "$NAME" "$*"; }
die() {
	printf '[%s] ERROR: %s\n' "$NAME" "$*" >&2
	exit 1
}
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f s", b - a }'; }

for tool in apt-get apt-cache curl sha256sum tar make gcc awk flock; do
	command -v "$tool" >/dev/null 2>&1 || die "'$tool' is needed but not installed"
done

T0=$(now)
mkdir -p "$CACHE/stamps" "$LOG_DIR" "$OUT"
# One run at a time per cache (the build directory and prefix are shared).
exec 9>"$CACHE/libgpiod2.lock"
flock 9

# --- step 1: libgpiod 2.x from Debian trixie -----------------------------------

# shellcheck source-path=SCRIPTDIR source=apt-private.sh
. "$REPO/scripts/apt-private.sh"

apt_priv_setup() {
	apt_private "$APT_PRIV" "$SUITE" deb-src scripts/libgpiod2-check.sh
	log "apt-get update (private $SUITE deb-src list, mirror $MIRROR)"
	apt-get "${APT_OPTS[@]}" update >"$LOG_DIR/libgpiod2-apt-update.log" 2>&1 ||
		{ cat "$LOG_DIR/libgpiod2-apt-update.log" >&2; die "apt-get update of the private $SUITE list failed"; }
}

# Field of the libgpiod stanza in the private Sources index.
src_field() {
	apt-cache "${APT_OPTS[@]}" showsrc --only-source libgpiod 2>/dev/null |
		awk -v f="$1" '
			/^$/ { stop = 1 }
			stop { next }
			$0 ~ "^" f ":" { sub("^" f ":[[:space:]]*", ""); print; found = 1; next }
			found && /^[[:space:]]/ { print; next }
			{ found = 0 }'
}

fetch_and_build() {
	local t dsc_version upstream dir orig hash size dl
	t=$(now)
	apt_priv_setup
	dsc_version=$(src_field Version | head -n1)
	[ -n "$dsc_version" ] || die "no libgpiod in $SUITE's Sources index"
	upstream=${dsc_version#*:}
	upstream=${upstream%-*}
	case "$upstream" in
	2.*) ;;
	*) die "$SUITE's libgpiod is $dsc_version, not 2.x" ;;
	esac
	dir=$(src_field Directory | head -n1)
	read -r hash size orig < <(src_field Checksums-Sha256 |
		awk '$3 ~ /\.orig\.tar\.[a-z0-9]+$/ { print $1, $2, $3; exit }') || true
	{ [ -n "${orig:-}" ] && [ -n "$dir" ]; } ||
		die "no orig tarball for libgpiod $dsc_version in $SUITE's Sources index"
	log "libgpiod $dsc_version in $SUITE: $orig ($size bytes, sha256 $hash)"

	dl="$WORK/download"
	mkdir -p "$dl"
	if [ -f "$dl/$orig" ] && echo "$hash  $dl/$orig" | sha256sum -c --status -; then
		log "$orig already downloaded"
	else
		rm -f "$dl/$orig"
		# apt-get source fetches .dsc, orig and debian tarballs; the .dsc
		# may 404 on the mirror while the tarball is there, so a failure
		# only matters when the orig tarball is missing or wrong: then
		# fetch it alone from the pool directory the index names.
		(cd "$dl" && apt-get "${APT_OPTS[@]}" source --download-only \
			"libgpiod=$dsc_version" >"$LOG_DIR/libgpiod2-apt-source.log" 2>&1) ||
			log "apt-get source failed (the .dsc may be missing; see $LOG_DIR/libgpiod2-apt-source.log)"
		if ! { [ -f "$dl/$orig" ] && echo "$hash  $dl/$orig" | sha256sum -c --status -; }; then
			log "fetching $MIRROR/$dir/$orig directly"
			curl -fsSL --retry 2 -o "$dl/$orig.part" "$MIRROR/$dir/$orig" ||
				die "download of $MIRROR/$dir/$orig failed"
			mv "$dl/$orig.part" "$dl/$orig"
		fi
	fi
	echo "$hash  $dl/$orig" | sha256sum -c --status - ||
		die "$orig: sha256 $(sha256sum "$dl/$orig" | cut -d' ' -f1) does not match the Sources index ($hash)"
	log "$orig: sha256 matches $SUITE's Sources index"

	local src="$WORK/src"
	rm -rf "$src"
	mkdir -p "$src"
	tar -xf "$dl/$orig" -C "$src" --strip-components=1
	[ -x "$src/configure" ] || die "$orig has no configure script"
	log "building libgpiod $upstream (static) into $PREFIX (log: $BUILD_LOG)"
	rm -rf "$PREFIX"
	if ! (cd "$src" &&
		./configure --prefix="$PREFIX" --enable-static --disable-shared \
			--disable-tools --disable-tests --disable-examples \
			--disable-bindings-cxx --disable-bindings-python \
			--disable-bindings-rust --disable-bindings-glib \
			--disable-dbus --disable-systemd &&
		make -j"$JOBS" && make install) >"$BUILD_LOG" 2>&1; then
		tail -n 30 "$BUILD_LOG" >&2
		die "libgpiod $upstream build failed, see $BUILD_LOG"
	fi
	{ [ -f "$PREFIX/include/gpiod.h" ] && [ -f "$PREFIX/lib/libgpiod.a" ]; } ||
		die "libgpiod install into $PREFIX lacks include/gpiod.h or lib/libgpiod.a"
	printf '%s\n' "$upstream" "$dsc_version" "$orig" "$hash" >"$STAMP"
	log "libgpiod $upstream ready ($(since "$t"))"
}

if [ "${LIBGPIOD2_REBUILD:-0}" != 1 ] && [ -f "$STAMP" ] &&
	[ -f "$PREFIX/include/gpiod.h" ] && [ -f "$PREFIX/lib/libgpiod.a" ]; then
	log "libgpiod $(head -n1 "$STAMP") in $PREFIX (cached; LIBGPIOD2_REBUILD=1 rebuilds)"
else
	rm -f "$STAMP"
	fetch_and_build
fi
VERSION=$(head -n1 "$STAMP")

# --- step 2: gpio.c (+ backend_raw.c) against it ----------------------------------

CFLAGS=(-DAS9888_GPIOD_V2 -std=gnu11 -Wall -Wextra -Werror -Wshadow
	-Wstrict-prototypes -Wmissing-prototypes -D_GNU_SOURCE
	-I "$PREFIX/include"
	-I "$REPO/tools/include" -I "$REPO/drivers/iio/imu/as9888" -I "$REPO/daemon/src")
# The headers must be libgpiod 2's, not the system's 1.6 ones.
grep -q 'gpiod_line_request' "$PREFIX/include/gpiod.h" ||
	die "$PREFIX/include/gpiod.h is not libgpiod 2.x's"

# gpio.c and the smoke test get exactly the flags above. backend_raw.c's
# transport callbacks ignore some parameters by design: like meson.build (the
# project's arguments), it gets -Wno-unused-parameter.
compile() {
	local unit=$1
	shift
	gcc "${CFLAGS[@]}" "$@" -c "$REPO/$unit" -o "$OUT/$(basename "$unit" .c).o" ||
		die "$unit does not compile against libgpiod $VERSION (flags: ${CFLAGS[*]} $*)"
	log "compiled $unit${*:+ ($*)}"
}
compile daemon/src/chip/gpio.c
compile daemon/src/chip/backend_raw.c -Wno-unused-parameter
compile tests/gpio/gpio_v2_smoke.c
gcc -o "$OUT/gpio_v2_smoke" "$OUT/gpio_v2_smoke.o" "$OUT/gpio.o" \
	"$PREFIX/lib/libgpiod.a" ||
	die "linking tests/gpio/gpio_v2_smoke.c with gpio.c and libgpiod $VERSION failed"
log "linked $OUT/gpio_v2_smoke (static libgpiod $VERSION)"

if ! smoke=$("$OUT/gpio_v2_smoke"); then
	printf '%s\n' "$smoke"
	die "gpio_v2_smoke failed"
fi
printf '%s\n' "$smoke" | sed "s/^/[$NAME] smoke: /"
got=$(printf '%s\n' "$smoke" | awk '$1 == "version" { print $2; exit }')
[ "$got" = "$VERSION" ] ||
	die "gpio_library_version() says '$got', expected '$VERSION'"

log "done ($(since "$T0"))"
echo "$NAME: gpio.c builds against libgpiod $VERSION: ok"
