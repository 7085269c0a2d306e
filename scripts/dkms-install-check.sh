#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
# (the checks are eval'd strings, expanded when they run)
# shellcheck disable=SC2016
#
# dkms-install-check.sh
#
# Installs the Debian packages of the last commit (scripts/deb-build.sh:
# as9888-dkms and as9888-calibd) with apt, as a user would, into a
# throwaway Debian 12 root (debootstrap minbase, chroot; nothing is
# installed on this machine but debootstrap) that has the headers of two
# of Debian's kernels of the same release:
#  - linux-headers-<abi>-amd64, the standard kernel (IIO, buffers,
#    triggered buffer, regmap I2C/SPI as modules): dh-dkms must build and
#    install as9888_core, as9888_i2c and as9888_spi for it;
#  - linux-headers-<abi>-cloud-amd64, Debian's cloud kernel (no IIO):
#    dkms.conf's BUILD_EXCLUSIVE_CONFIG must keep dkms from building there,
#    "apt install" must still succeed, and the output must say which
#    options the kernel lacks.
# Also checks that as9888-dkms's boot-time check (as9888-dkms-check, a
# systemd oneshot) warns on a board whose devicetree names the chip while
# no driver is bound, and says nothing where none is named or one is bound
# (run in the root against a made-up sysfs).
#
# The root with dkms and both headers is cached in
# $AS9888_CACHE/dkms-install/root-<abi> (first run: debootstrap and the
# headers, a few minutes); each run installs into a fresh copy of it.
# Needs root. Prints "dkms-install: N passed, N failed".
set -euo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
top=$AS9888_REPO
cache=$AS9888_CACHE/dkms-install
work=${AS9888_BUILD:-$top/build}/dkms-install
[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot)"
mkdir -p "$cache" "$work"
cache_lock dkms-install
ensure_pkgs debootstrap rsync

# the kernels of Debian 12's two metapackages (same ABI)
kver_of() {
	apt-cache depends "$1" 2>/dev/null | sed -n 's/^ *Depends: linux-headers-\([0-9][^ ]*\)$/\1/p' | head -n1
}
KSTD=$(kver_of linux-headers-amd64)
KCLOUD=$(kver_of linux-headers-cloud-amd64)
{ [ -n "$KSTD" ] && [ -n "$KCLOUD" ]; } ||
	die "cannot tell the kernels of linux-headers-amd64 and linux-headers-cloud-amd64 (apt-get update?)"

root=$cache/root-$KSTD
if [ ! -e "$root/.as9888-complete" ]; then
	log "debootstrap bookworm (minbase) with dkms, linux-headers-$KSTD and linux-headers-$KCLOUD"
	# --one-file-system: a /proc left bound by a run that died is not descended into
	rm -rf --one-file-system "$cache"/root-*
	timeout 1800 debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian \
		>"$cache/debootstrap.log" 2>&1 ||
		die "debootstrap failed (log $cache/debootstrap.log)"
	cat >"$root/etc/apt/sources.list" <<-EOT
		deb http://deb.debian.org/debian bookworm main
		deb http://deb.debian.org/debian bookworm-updates main
		deb http://deb.debian.org/debian-security bookworm-security main
	EOT
	# no service is started in the root
	printf '#!/bin/sh\nexit 101\n' >"$root/usr/sbin/policy-rc.d"
	chmod 0755 "$root/usr/sbin/policy-rc.d"
	mount --bind /proc "$root/proc"
	rc=0
	{ chroot "$root" apt-get -q update &&
		DEBIAN_FRONTEND=noninteractive chroot "$root" apt-get -q install -y \
			--no-install-recommends dkms build-essential kmod libgpiod2 \
			"linux-headers-$KSTD" "linux-headers-$KCLOUD"; } >"$cache/root-install.log" 2>&1 || rc=$?
	umount "$root/proc"
	[ "$rc" -eq 0 ] || die "installing dkms and the headers in the root failed (log $cache/root-install.log)"
	chroot "$root" apt-get clean
	touch "$root/.as9888-complete"
	log "root ready ($(du -sh "$root" | cut -f1))"
fi

# the packages of the last commit
"$top/scripts/deb-build.sh" >"$work/deb-build.log" 2>&1 ||
	{ tail -n 20 "$work/deb-build.log"; die "scripts/deb-build.sh failed (log $work/deb-build.log)"; }
debdir=${AS9888_BUILD:-$top/build}/deb
ver=$(git -C "$top" show HEAD:debian/changelog | sed -n '1s/^as9888 (\([^)]*\)).*/\1/p')
debs=("$debdir/as9888-calibd_${ver}_$(dpkg --print-architecture).deb" "$debdir/as9888-dkms_${ver}_all.deb")
for f in "${debs[@]}"; do
	[ -f "$f" ] || die "scripts/deb-build.sh made no $f"
done

# a fresh copy of the root for this run
t0=$(date +%s)
troot=$work/root
umount "$troot/proc" 2>/dev/null || true
rm -rf --one-file-system "$troot"
cp -a --reflink=auto "$root" "$troot"
mkdir -p "$troot/root/debs"
cp "${debs[@]}" "$troot/root/debs/"
mount --bind /proc "$troot/proc"
trap 'umount "$troot/proc" 2>/dev/null || true' EXIT
rc=0
DEBIAN_FRONTEND=noninteractive chroot "$troot" sh -c \
	"cd /root/debs && apt-get install -y --no-install-recommends $(printf './%s ' "${debs[@]##*/}")" \
	>"$work/apt-install.log" 2>&1 || rc=$?
log "apt install of $(printf '%s ' "${debs[@]##*/}")took $(($(date +%s) - t0)) s (log $work/apt-install.log)"

passed=0
failed=0
check() {
	local what=$1
	shift
	if "$@"; then
		echo "ok - $what"
		passed=$((passed + 1))
	else
		echo "not ok - $what"
		failed=$((failed + 1))
	fi
}
mods() { ls "$troot/lib/modules/$1/updates/dkms/" 2>/dev/null; }

check "apt install succeeds with the cloud kernel's headers installed (exit $rc)" [ "$rc" -eq 0 ]
has_mods() { # KVER MODULE...
	local k=$1 m x
	shift
	m=$(mods "$k")
	for x; do
		echo "$m" | grep -q "^$x\.ko" || return 1
	done
}
check "standard kernel $KSTD: as9888_core, as9888_i2c and as9888_spi built and installed" \
	has_mods "$KSTD" as9888_core as9888_i2c as9888_spi
check "cloud kernel $KCLOUD: no module built or installed" \
	eval '[ -z "$(mods "$KCLOUD" | grep as9888)" ]'
check "cloud kernel: the output says which options $KCLOUD lacks" \
	grep -q "as9888-dkms: kernel $KCLOUD lacks CONFIG_IIO .*skipped" "$work/apt-install.log"
check "cloud kernel: dkms says the module is not for that kernel (BUILD_EXCLUSIVE)" \
	grep -qi "BUILD_EXCLUSIVE" "$work/apt-install.log"
check "as9888-dkms-check.service enabled (multi-user.target wants it)" \
	[ -L "$troot/etc/systemd/system/multi-user.target.wants/as9888-dkms-check.service" ]

# the boot-time check on made-up sysfs trees: an AS9888 named by the
# devicetree with no driver, one with its driver, and another chip
fake=$troot/tmp/sys
mkdir -p "$fake/bus/i2c/devices/1-000f/of_node" "$fake/bus/i2c/devices/2-000f/of_node" \
	"$fake/bus/i2c/devices/2-000f/driver" "$fake/bus/i2c/devices/3-0068/of_node" "$fake/bus/spi/devices"
printf 'alsen,as9888\0' >"$fake/bus/i2c/devices/1-000f/of_node/compatible"
printf 'alsen,as9888\0' >"$fake/bus/i2c/devices/2-000f/of_node/compatible"
printf 'invensense,mpu6050\0' >"$fake/bus/i2c/devices/3-0068/of_node/compatible"
rc=0
chroot "$troot" env AS9888_SYSFS_ROOT=/tmp/sys /usr/libexec/as9888-dkms/as9888-dkms-check \
	>"$work/dkms-check.out" 2>&1 || rc=$?
check "boot check: exit 0, one warning (priority 4) for the AS9888 with no driver" \
	eval '[ $rc -eq 0 ] && [ "$(grep -c "^<4>as9888-dkms-check: 1-000f is an AS9888" "$work/dkms-check.out")" = 1 ] && [ "$(wc -l <"$work/dkms-check.out")" = 1 ]'
sed 's/^/  /' "$work/dkms-check.out"
rm -rf "$fake/bus/i2c/devices/1-000f"
rc=0
chroot "$troot" env AS9888_SYSFS_ROOT=/tmp/sys /usr/libexec/as9888-dkms/as9888-dkms-check \
	>"$work/dkms-check.out" 2>&1 || rc=$?
check "boot check: silent when every AS9888 has its driver" \
	eval '[ $rc -eq 0 ] && [ ! -s "$work/dkms-check.out" ]'

echo "the cloud kernel's lines:"
grep -i "as9888-dkms: kernel $KCLOUD\|BUILD_EXCLUSIVE" "$work/apt-install.log" | sort -u | sed 's/^/  /'
umount "$troot/proc"
trap - EXIT
rm -rf --one-file-system "$troot"
echo "dkms-install: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
