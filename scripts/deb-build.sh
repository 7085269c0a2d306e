#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The Debian packages of the last commit (git archive HEAD), as a
# distribution builds them: `dpkg-buildpackage -us -uc -b` on debian/,
# giving as9888-calibd_<v>_<arch>.deb and as9888-dkms_<v>_all.deb in
# $AS9888_BUILD/deb (default build/deb), then
#  - lintian on the .changes, failing on any error, warning or info tag not
#    overridden (the overrides in debian/*.lintian-overrides say why);
#  - one version everywhere: debian/changelog, meson.build, dkms.conf and
#    the /usr/src/as9888-<v> paths of debian/as9888-dkms.install;
#  - the packages' contents: the program, units, udev rule, tmpfiles entry
#    and man page in as9888-calibd, the sources and dkms.conf in
#    as9888-dkms; the maintainer scripts enable the socket only (never the
#    daemon's service), register the init script with update-rc.d, hand the
#    module to dkms, and purge alone deletes the state directory.
# The boot test (scripts/boot-debian.sh) installs these .debs. A second run
# of the same commit reuses them (the tree's hash is in build/deb/.tree).
# Installs the Debian packages it lacks (debhelper, dh-dkms, lintian, ...).
# Prints "deb-build: ..." lines and exits non-zero on any failure.
set -euo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
top=$AS9888_REPO
out=${AS9888_BUILD:-$top/build}/deb
t0=$(date +%s)
mkdir -p "$out"

ensure_pkgs dpkg-dev debhelper dh-dkms lintian meson ninja-build pkgconf libgpiod-dev gcc systemd udev

tree=$(git -C "$top" rev-parse 'HEAD^{tree}')
ver=$(git -C "$top" show HEAD:debian/changelog | sed -n '1s/^as9888 (\([^)]*\)).*/\1/p')
[ -n "$ver" ] || die "debian/changelog: no version on its first line"
arch=$(dpkg --print-architecture)
calibd_deb=$out/as9888-calibd_${ver}_$arch.deb
dkms_deb=$out/as9888-dkms_${ver}_all.deb

status=0
fail() { echo "deb-build: $*: FAIL"; status=1; }
ok() { echo "deb-build: $*: ok"; }

if [ "$(cat "$out/.tree" 2>/dev/null)" = "$tree" ] && [ -f "$calibd_deb" ] && [ -f "$dkms_deb" ]; then
	log "packages of tree $tree already built: $(basename "$calibd_deb"), $(basename "$dkms_deb")"
else
	rm -rf "$out"
	mkdir -p "$out/src"
	git -C "$top" archive HEAD | tar -x -C "$out/src"
	log "dpkg-buildpackage -us -uc -b ($ver)"
	(cd "$out/src" && dpkg-buildpackage -us -uc -b) >"$out/build.log" 2>&1 || {
		tail -30 "$out/build.log"
		die "dpkg-buildpackage failed (log $out/build.log)"
	}
	echo "$tree" >"$out/.tree"
	log "built in $(( $(date +%s) - t0 )) s (log $out/build.log)"
fi
changes=$out/as9888_${ver}_$arch.changes
for f in "$calibd_deb" "$dkms_deb" "$changes"; do
	[ -f "$f" ] || die "dpkg-buildpackage made no $(basename "$f") (log $out/build.log)"
done

# lintian: errors, warnings and infos all fail; pedantic tags are shown.
# (lintian 2.116 counts an overridden tag it is asked to show as a
# failure: the overrides are listed by a second run)
lint=(lintian --display-level '>=pedantic')
if "${lint[@]}" --fail-on error,warning,info "$changes" >"$out/lintian.log" 2>&1; then
	"${lint[@]}" --show-overrides "$changes" 2>/dev/null | grep '^O: ' >"$out/lintian-overrides.log" || true
	ok "lintian $(lintian --version | awk '{ print $2 }') clean, $(wc -l <"$out/lintian-overrides.log") justified override(s)"
	sed 's/^/  lintian /' "$out/lintian-overrides.log"
else
	cat "$out/lintian.log"
	fail "lintian"
fi
grep '^P: ' "$out/lintian.log" | sed 's/^/  lintian /' || true

# one version everywhere
mver=$(sed -n "s/^[[:space:]]*version: '\([^']*\)'.*/\1/p" "$out/src/meson.build" | head -n1)
dver=$(sed -n 's/^PACKAGE_VERSION="\{0,1\}\([^"]*\)"\{0,1\}$/\1/p' "$out/src/dkms.conf")
if [ "$mver" = "$ver" ] && [ "$dver" = "$ver" ] &&
	! grep -v -e " usr/src/as9888-$ver/" -e " usr/libexec/as9888-dkms/\$" \
		"$out/src/debian/as9888-dkms.install" | grep -q .; then
	ok "one version: changelog, meson.build, dkms.conf, /usr/src/as9888-$ver"
else
	fail "versions differ: changelog $ver, meson.build $mver, dkms.conf $dver (and debian/as9888-dkms.install)"
fi

# contents
contents() { dpkg-deb -c "$1" | awk '{ print $6 }' | sed 's|^\./|/|'; }
want_calibd=(/usr/sbin/as9888-calibd /usr/share/man/man8/as9888-calibd.8.gz
	/lib/systemd/system/as9888-calibd.socket /lib/systemd/system/as9888-calibd.service
	/lib/systemd/system/as9888-calibd-restore@.service /lib/udev/rules.d/60-as9888-calibd.rules
	/usr/lib/tmpfiles.d/as9888-calibd.conf /usr/share/doc/as9888-calibd/RECORD.md.gz
	/usr/share/doc/as9888-calibd/report.schema.json
	/usr/share/doc/as9888-calibd/copyright /etc/init.d/as9888-calibd)
want_dkms=("/usr/src/as9888-$ver/dkms.conf" "/usr/src/as9888-$ver/Kbuild"
	"/usr/src/as9888-$ver/drivers/iio/imu/as9888/Makefile"
	"/usr/src/as9888-$ver/drivers/iio/imu/as9888/as9888_i2c.c"
	"/usr/src/as9888-$ver/drivers/iio/imu/as9888/compat/as9888_compat.h")
check_files() {
	local deb=$1 f missing=()
	shift
	for f in "$@"; do
		contents "$deb" | grep -qx "$f" || missing+=("$f")
	done
	if [ "${#missing[@]}" -eq 0 ]; then
		ok "$(basename "$deb"): $# expected files in it ($(contents "$deb" | grep -vc '/$') files)"
	else
		fail "$(basename "$deb") lacks ${missing[*]}"
	fi
}
check_files "$calibd_deb" "${want_calibd[@]}"
check_files "$dkms_deb" "${want_dkms[@]}"
# every driver source of the tree is in the DKMS package
n_src=$(cd "$out/src" && find drivers -name '*.[ch]' -o -name Makefile -o -name Kbuild -o -name Kconfig | wc -l)
n_pkg=$(contents "$dkms_deb" | grep -c "^/usr/src/as9888-$ver/drivers/.*[^/]$")
[ "$n_src" -eq "$n_pkg" ] && ok "as9888-dkms: all $n_src driver files of the tree" ||
	fail "as9888-dkms has $n_pkg driver files, the tree $n_src"

# maintainer scripts
ctl=$out/control
rm -rf "$ctl"
mkdir -p "$ctl"
dpkg-deb -e "$calibd_deb" "$ctl/calibd"
dpkg-deb -e "$dkms_deb" "$ctl/dkms"
if grep -q 'deb-systemd-helper.* enable .*as9888-calibd.socket' "$ctl/calibd/postinst" &&
	! grep -Eq "(enable|start|restart)[^\n]*'?as9888-calibd\.service" "$ctl/calibd/postinst" &&
	! grep -q 'as9888-calibd.service' "$ctl/calibd/postinst"; then
	ok "as9888-calibd postinst enables the socket, never the daemon's service"
else
	fail "as9888-calibd postinst: not the socket alone"
fi
grep -q 'systemd-tmpfiles .*--create .*as9888-calibd.conf' "$ctl/calibd/postinst" &&
	ok "as9888-calibd postinst creates the state directory (tmpfiles.d)" ||
	fail "as9888-calibd postinst: no systemd-tmpfiles --create"
if awk '/"\$1" = purge/ { p = 1 } p && /rm -rf \/var\/lib\/as9888$/ { f = 1 } END { exit !f }' "$ctl/calibd/postrm"; then
	ok "as9888-calibd postrm: purge alone deletes /var/lib/as9888"
else
	fail "as9888-calibd postrm: purge does not delete the state directory"
fi
grep -q 'update-rc.d as9888-calibd defaults' "$ctl/calibd/postinst" &&
	grep -q 'invoke-rc.d --skip-systemd-native as9888-calibd' "$ctl/calibd/postinst" &&
	grep -q 'update-rc.d as9888-calibd remove' "$ctl/calibd/postrm" &&
	ok "as9888-calibd: the init script registered with update-rc.d (skipped under systemd), removed on purge" ||
	fail "as9888-calibd: the init script is not registered with update-rc.d"
grep -q "/usr/lib/dkms/common.postinst" "$ctl/dkms/postinst" &&
	grep -q "dkms remove -m \$DKMS_NAME -v \$DKMS_VERSION --all" "$ctl/dkms/prerm" &&
	grep -q '^DKMS_NAME=as9888$' "$ctl/dkms/postinst" &&
	ok "as9888-dkms: dh-dkms postinst adds and builds, prerm removes as9888/$ver" ||
	fail "as9888-dkms: no dh-dkms maintainer scripts"
dpkg-deb -f "$dkms_deb" Depends | grep -q dkms &&
	ok "as9888-dkms depends on dkms" || fail "as9888-dkms does not depend on dkms"

echo "deb-build: $(basename "$calibd_deb") $(du -k "$calibd_deb" | cut -f1) KiB, $(basename "$dkms_deb") $(du -k "$dkms_deb" | cut -f1) KiB in $out, $(( $(date +%s) - t0 )) s"
exit $status
