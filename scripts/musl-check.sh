#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# musl-check.sh
#
# Builds the daemon, libas9888magn and the userspace tests with Debian's
# musl-gcc (package musl-tools, musl 1.2.3 on Debian 12) and runs the
# Meson suite on that build: what Buildroot and Yocto's musl toolchains
# and Alpine link against. The C library is the point, so the build is a
# plain one (-Dwerror=true, no sanitizers: ASan and UBSan's runtimes are
# glibc's).
#
#  1. apt installs musl-tools if missing (and cmake for step 2).
#  2. cmocka for musl: Debian's libcmocka-dev is built against glibc and
#     cannot be linked into a musl program, so its source package (the
#     same version, bookworm's cmocka) comes through a private apt deb-src
#     list (scripts/apt-private.sh; apt checks the files against the
#     signed Sources index) and is built with musl-gcc as a static library
#     into $AS9888_CACHE/musl/cmocka. A stamp makes later runs skip this.
#  3. musl-gcc's specs see musl's headers only: the kernel's UAPI headers
#     (linux/, asm/, asm-generic/ from linux-libc-dev) are added through a
#     directory of links, as a musl toolchain ships them. pkg-config looks
#     in the musl prefix only (meson native file: pkg_config_libdir), so
#     no glibc library (libgpiod) is picked up: the daemon is built
#     without libgpiod (its stub), as on a musl board without it.
#  4. meson setup + ninja in $AS9888_BUILD/musl; checks that the daemon's
#     interpreter is musl's and that close_range() was not found (the
#     /proc/self/fd fallback of daemon/src/common/fd_close.c is what runs).
#  5. meson test on that build: every test of the suite runs there (none
#     needs glibc). Prints "musl: N passed, N failed" from the suite's own
#     log; exit 1 when any test failed or none ran.
#
# Environment: AS9888_CACHE (default ~/.cache/as9888), AS9888_BUILD
#   (default <repo>/build), MUSL_CMOCKA_REBUILD=1 forces step 2 again.
set -euo pipefail

NAME=musl-check
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CACHE="${AS9888_CACHE:-$HOME/.cache/as9888}"
BUILD="${AS9888_BUILD:-$REPO/build}/musl"
MUSL="$CACHE/musl"
PREFIX="$MUSL/cmocka"
KINC="$MUSL/kernel-headers"
STAMP="$CACHE/stamps/musl-cmocka"
LOG_DIR="$CACHE/logs"
MUSL_INTERP=/lib/ld-musl-x86_64.so.1

log() { printf '[%s] %s\n' "$NAME" "$*"; }
die() {
	printf '[%s] ERROR: %s\n' "$NAME" "$*" >&2
	exit 1
}

mkdir -p "$CACHE/stamps" "$LOG_DIR" "$MUSL"
exec 9>"$MUSL/lock"
flock 9

# --- step 1: musl-gcc ------------------------------------------------------------
need=()
for p in musl-tools cmake dpkg-dev; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
		need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
	log "installing ${need[*]}"
	sudo=""
	[ "$(id -u)" -eq 0 ] || sudo=sudo
	$sudo apt-get update -q >"$LOG_DIR/musl-apt.log" 2>&1 || true
	DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends \
		"${need[@]}" >>"$LOG_DIR/musl-apt.log" 2>&1 ||
		{ tail -n 20 "$LOG_DIR/musl-apt.log" >&2; die "apt-get install ${need[*]} failed"; }
fi
command -v musl-gcc >/dev/null || die "musl-gcc is missing after installing musl-tools"
musl_version=$(dpkg-query -W -f='${Version}' musl-dev 2>/dev/null || echo unknown)

# --- step 2: cmocka built with musl-gcc ------------------------------------------
build_cmocka() {
	# shellcheck source-path=SCRIPTDIR source=apt-private.sh
	. "$REPO/scripts/apt-private.sh"
	local codename version dl src b
	# shellcheck disable=SC1091
	codename=$(. /etc/os-release && printf '%s' "${VERSION_CODENAME:-}")
	[ -n "$codename" ] || die "no VERSION_CODENAME in /etc/os-release"
	apt_private "$MUSL/apt" "$codename" deb-src scripts/musl-check.sh
	apt-get "${APT_OPTS[@]}" update >"$LOG_DIR/musl-apt-update.log" 2>&1 ||
		{ tail -n 20 "$LOG_DIR/musl-apt-update.log" >&2; die "apt-get update of the private $codename deb-src list failed"; }
	version=$(apt-cache "${APT_OPTS[@]}" showsrc --only-source cmocka 2>/dev/null |
		sed -n 's/^Version: //p' | head -n1)
	[ -n "$version" ] || die "no cmocka source package in $codename's Sources index"
	dl="$MUSL/download"
	src="$MUSL/cmocka-src"
	b="$MUSL/cmocka-build"
	rm -rf "$dl" "$src" "$b" "$PREFIX"
	mkdir -p "$dl" "$b"
	log "cmocka $version ($codename source package): fetching"
	(cd "$dl" && apt-get "${APT_OPTS[@]}" source --download-only "cmocka=$version") \
		>"$LOG_DIR/musl-cmocka-source.log" 2>&1 ||
		{ tail -n 20 "$LOG_DIR/musl-cmocka-source.log" >&2; die "apt-get source cmocka=$version failed"; }
	dpkg-source --no-check -x "$dl"/cmocka_*.dsc "$src" >>"$LOG_DIR/musl-cmocka-source.log" 2>&1 ||
		die "dpkg-source -x of cmocka $version failed (see $LOG_DIR/musl-cmocka-source.log)"
	log "cmocka $version: building with musl-gcc (static) into $PREFIX"
	(cd "$b" && CC=musl-gcc cmake "$src" -DCMAKE_INSTALL_PREFIX="$PREFIX" \
		-DCMAKE_BUILD_TYPE=Release -DWITH_STATIC_LIB=ON -DWITH_EXAMPLES=OFF \
		-DUNIT_TESTING=OFF && make -j2 install) >"$LOG_DIR/musl-cmocka-build.log" 2>&1 ||
		{ tail -n 20 "$LOG_DIR/musl-cmocka-build.log" >&2; die "building cmocka $version with musl-gcc failed"; }
	# -lcmocka must find the static archive: no shared one beside it
	rm -f "$PREFIX"/lib/libcmocka.so*
	cp "$PREFIX/lib/libcmocka-static.a" "$PREFIX/lib/libcmocka.a"
	[ -f "$PREFIX/lib/pkgconfig/cmocka.pc" ] || die "cmocka's build installed no cmocka.pc"
	echo "$version" >"$STAMP"
}
if [ "${MUSL_CMOCKA_REBUILD:-0}" = 1 ] || [ ! -f "$STAMP" ] || [ ! -f "$PREFIX/lib/libcmocka.a" ]; then
	build_cmocka
fi
log "cmocka $(cat "$STAMP") for musl in $PREFIX"

# --- step 3: kernel UAPI headers and the native file -----------------------------
multiarch=$(gcc -print-multiarch)
mkdir -p "$KINC"
for d in linux:/usr/include/linux asm:/usr/include/$multiarch/asm \
	asm-generic:/usr/include/asm-generic; do
	[ -d "${d#*:}" ] || die "${d#*:} is missing (package linux-libc-dev)"
	ln -sfn "${d#*:}" "$KINC/${d%%:*}"
done
native="$MUSL/native.ini"
cat >"$native" <<EOT
# written by scripts/musl-check.sh
[binaries]
c = 'musl-gcc'

[built-in options]
c_args = ['-isystem', '$KINC']

[properties]
pkg_config_libdir = ['$PREFIX/lib/pkgconfig']
EOT

# --- step 4: the build ------------------------------------------------------------
if [ ! -f "$BUILD/build.ninja" ] || ! cmp -s "$native" "$BUILD/native.ini"; then
	rm -rf "$BUILD"
	meson setup "$BUILD" "$REPO" --native-file "$native" -Dwerror=true \
		-Dtests=enabled >"$LOG_DIR/musl-setup.log" 2>&1 ||
		{ tail -n 30 "$LOG_DIR/musl-setup.log" >&2; die "meson setup with musl-gcc failed"; }
	cp "$native" "$BUILD/native.ini"
fi
ninja -C "$BUILD" || die "the build with musl-gcc failed"
calibd="$BUILD/daemon/as9888-calibd"
interp=$(readelf -l "$calibd" | sed -n 's/.*Requesting program interpreter: \(.*\)]/\1/p')
[ "$interp" = "$MUSL_INTERP" ] || die "$calibd asks for ${interp:-no interpreter}, not musl's $MUSL_INTERP"
if grep -q -- '-DHAVE_CLOSE_RANGE' "$BUILD/build.ninja"; then
	die "meson found close_range() in musl $musl_version: the fallback is not what this build runs"
fi
log "built with musl $musl_version ($interp); close_range() not found: the /proc/self/fd fallback is built"

# --- step 5: the suite -----------------------------------------------------------
rm -f "$BUILD/meson-logs/testlog.json"
rc=0
meson test -C "$BUILD" --no-rebuild --num-processes 2 --print-errorlogs || rc=$?
ok=0
fail=0
if [ -f "$BUILD/meson-logs/testlog.json" ]; then
	ok=$(grep -c '"result": "OK"' "$BUILD/meson-logs/testlog.json" || true)
	fail=$(grep -vc '"result": "OK"' "$BUILD/meson-logs/testlog.json" || true)
fi
echo "musl: $ok passed, $fail failed"
[ "$ok" -gt 0 ] || [ "$fail" -gt 0 ] || die "no test ran"
[ "$fail" -eq 0 ] && [ "$rc" -eq 0 ]
