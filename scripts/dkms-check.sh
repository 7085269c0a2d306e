#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# dkms-check.sh
#
# Checks that the repository's dkms.conf builds the AS9888 modules the way a
# user's machine would: Debian 12's dkms against Debian 12's distro kernel
# headers (linux-headers-amd64, 6.1). Both packages are installed with apt
# when missing (they are ordinary bookworm packages).
#
# Nothing in the system's DKMS state is touched: the sources are staged in
# $AS9888_CACHE/dkms/source/as9888-<version>/ and "dkms add" + "dkms build"
# run with --dkmstree/--sourcetree pointing into the cache; module signing
# uses a throwaway key in the cache instead of /var/lib/dkms/mok.key. There
# is no "dkms install" (that would write to /lib/modules).
#
# Fails when dkms fails, when a module listed in dkms.conf is missing, when
# a module's vermagic does not match the headers, or on any warning in
# dkms's make.log.
#
# Exit status: 0 built cleanly, 1 failure, 3 no driver sources yet (not run).
#
# Timings (2 cores, shared): warm 7-17 s; cold (apt-get install dkms) 33 s,
# more if linux-headers-amd64 has to be installed too.
# Environment: AS9888_CACHE; AS9888_SRC (source root; default this repo).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

SRC_ROOT="$(cd "${AS9888_SRC:-$AS9888_REPO}" && pwd)"
if [ -z "$(driver_c_files "$SRC_ROOT")" ]; then
	echo "dkms-check: no driver sources yet"
	exit 3
fi
# (the KUnit module is not part of the DKMS build, so its source may be absent)
mapfile -t MISSING < <(driver_missing_sources "$SRC_ROOT" | grep -v '_kunit' || true)
if [ "${#MISSING[@]}" -gt 0 ]; then
	echo "dkms-check: $AS9888_DRIVER_REL/Makefile needs sources that do not exist (yet): ${MISSING[*]}" >&2
	exit 1
fi
CONF="$SRC_ROOT/dkms.conf"
[ -f "$CONF" ] || CONF="$AS9888_REPO/dkms.conf"
[ -f "$CONF" ] || die "no dkms.conf"

T_START=$(now)
cache_lock dkms-check
ensure_pkgs dkms linux-headers-amd64 build-essential kmod openssl rsync

# The distro kernel the metapackage points at, e.g. 6.1.0-56-amd64.
KVER=$(dpkg-query -W -f='${Depends}' linux-headers-amd64 |
	grep -o 'linux-headers-[0-9][^ ,]*-amd64' | head -n1 | sed 's/^linux-headers-//')
[ -n "$KVER" ] || die "cannot tell which kernel linux-headers-amd64 is for"
[ -e "/lib/modules/$KVER/build" ] || die "/lib/modules/$KVER/build missing (linux-headers-$KVER broken?)"

NAME=$(sed -n 's/^PACKAGE_NAME="\{0,1\}\([^"]*\)"\{0,1\}$/\1/p' "$CONF")
VER=$(sed -n 's/^PACKAGE_VERSION="\{0,1\}\([^"]*\)"\{0,1\}$/\1/p' "$CONF")
mapfile -t MODS < <(sed -n 's/^[[:space:]]*BUILT_MODULE_NAME\[[0-9]*\]="\{0,1\}\([^"]*\)"\{0,1\}$/\1/p' "$CONF")
if [ -z "$NAME" ] || [ -z "$VER" ] || [ "${#MODS[@]}" -eq 0 ]; then
	die "dkms.conf lacks PACKAGE_NAME, PACKAGE_VERSION or BUILT_MODULE_NAME"
fi

D="$AS9888_CACHE/dkms"
STAGE="$D/source/$NAME-$VER"
rm -rf "$D/tree" "$D/source"
mkdir -p "$STAGE/$AS9888_DRIVER_REL" "$D/tree" "$LOG_DIR"
cp "$CONF" "$STAGE/dkms.conf"
cp "$SRC_ROOT/Kbuild" "$STAGE/"
rsync -a --include='*.c' --include='*.h' --include='Makefile' --include='Kbuild' \
	--include='Kconfig' --include='compat/' --exclude='*' "$SRC_ROOT/$AS9888_DRIVER_REL/" "$STAGE/$AS9888_DRIVER_REL/"

DKMS=(dkms --dkmstree "$D/tree" --sourcetree "$D/source")
DLOG="$LOG_DIR/dkms-check.log"
log "dkms $(dkms --version | sed 's/^dkms-//'): add + build $NAME/$VER for $KVER (trees in $D)"
dkms_fail() {
	sed 's/^/    /' "$DLOG" >&2
	local mlog
	mlog=$(find "$D/tree" -name make.log -print -quit)
	if [ -n "$mlog" ]; then
		grep -Ei 'warning:|error:|\*\*\*' "$mlog" | sed 's/^/    make.log: /' >&2 || true
		echo "    (full make.log: $mlog)" >&2
	fi
	die "dkms $1 failed (log: $DLOG)"
}
: >"$DLOG"
"${DKMS[@]}" add -m "$NAME" -v "$VER" >>"$DLOG" 2>&1 || dkms_fail add
env mok_signing_key="$D/mok.key" mok_certificate="$D/mok.pub" \
	"${DKMS[@]}" build -m "$NAME" -v "$VER" -k "$KVER" >>"$DLOG" 2>&1 || dkms_fail build
"${DKMS[@]}" status -m "$NAME" >>"$DLOG" 2>&1 || dkms_fail status

BASE="$D/tree/$NAME/$VER/$KVER/$(uname -m)"
MLOG="$BASE/log/make.log"
FAIL=0
for m in "${MODS[@]}"; do
	ko=$(find "$BASE/module" -name "$m.ko*" -print -quit 2>/dev/null || true)
	if [ -z "$ko" ]; then
		echo "dkms-check: module $m.ko was not built" >&2
		FAIL=1
		continue
	fi
	vm=$(modinfo -F vermagic "$ko")
	case "$vm" in
	"$KVER "*) log "built $(basename "$ko") (vermagic $vm)" ;;
	*)
		echo "dkms-check: $m vermagic '$vm' does not match $KVER" >&2
		FAIL=1
		;;
	esac
done
NW=$(grep -Eci 'warning:|error:' "$MLOG" || true)
echo "dkms $KVER: $NW warnings"
if [ "$NW" -gt 0 ]; then
	grep -Ei 'warning:|error:' "$MLOG" | sed "s|$D/tree/$NAME/$VER/build/|$SRC_ROOT/|g; s/^/    /" >&2
	FAIL=1
fi
if [ "$FAIL" -ne 0 ]; then
	log "FAILED in $(since "$T_START") (logs: $DLOG, $MLOG)"
	exit 1
fi
log "dkms build OK in $(since "$T_START") (logs: $DLOG, $MLOG)"
