#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# udev-rules-check.sh: every udev rules file the project ships (the systemd
# rule in daemon/udev/ and the eudev/BusyBox hotplug rule in
# contrib/sysvinit/) checked by "udevadm verify", which bookworm's udev
# (systemd 252) does not have. Debian 13's udev and the libraries it needs
# are downloaded with a private apt list (never installed: dpkg-deb -x into
# the cache) and run through their own dynamic loader. Prints
# "udev-rules: N passed, N failed"; exit status 0 only when all pass.
#
# Environment: AS9888_CACHE (default ~/.cache/as9888).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
# shellcheck source-path=SCRIPTDIR source=apt-private.sh
. "$AS9888_REPO/scripts/apt-private.sh"

dir=$AS9888_CACHE/udev-verify
root=$dir/root
# udev and what its udevadm links against (ldd of Debian 13's binary)
debs=(udev libsystemd-shared libc6 libcrypt1 libacl1 libblkid1 libcap2 libkmod2
	libmount1 libseccomp2 libselinux1 libssl3t64 libzstd1 liblzma5 libpcre2-8-0
	libaudit1 libcap-ng0)
mkdir -p "$dir"
cache_lock udev-verify
if [ ! -x "$root/usr/bin/udevadm" ]; then
	ensure_pkgs debian-archive-keyring
	apt_private "$dir/apt" trixie deb scripts/udev-rules-check.sh
	apt-get "${APT_OPTS[@]}" update >"$dir/apt.log" 2>&1 ||
		die "apt-get update of the private trixie list failed (log $dir/apt.log)"
	rm -rf "$dir/debs" "$root.new"
	mkdir -p "$dir/debs" "$root.new"
	(cd "$dir/debs" && apt-get "${APT_OPTS[@]}" download "${debs[@]}") >>"$dir/apt.log" 2>&1 ||
		die "downloading Debian 13's udev failed (log $dir/apt.log)"
	for d in "$dir"/debs/*.deb; do dpkg-deb -x "$d" "$root.new"; done
	rm -rf "$root"
	mv "$root.new" "$root"
fi
udevadm() {
	"$root/usr/lib64/ld-linux-x86-64.so.2" --library-path \
		"$root/usr/lib/x86_64-linux-gnu:$root/usr/lib/x86_64-linux-gnu/systemd" \
		"$root/usr/bin/udevadm" "$@"
}
log "udevadm $(udevadm --version) from Debian 13"

passed=0
failed=0
# the checker must refuse a rule that is wrong, or its "pass" means nothing
printf 'ACTION=="add", NO_SUCH_KEY{x}="1"\n' >"$dir/broken.rules"
if udevadm verify "$dir/broken.rules" >/dev/null 2>&1; then
	echo "not ok - udevadm verify accepts a broken rule: it checks nothing"
	failed=$((failed + 1))
else
	passed=$((passed + 1))
fi
mapfile -t rules < <(cd "$AS9888_REPO" && git ls-files '*.rules' '*.rules.in')
[ "${#rules[@]}" -gt 0 ] || die "no udev rules file found"
for f in "${rules[@]}"; do
	if out=$(udevadm verify "$AS9888_REPO/$f" 2>&1); then
		echo "ok - $f"
		passed=$((passed + 1))
	else
		echo "not ok - $f"
		printf '%s\n' "$out" | sed 's/^/  /'
		failed=$((failed + 1))
	fi
done
echo "udev-rules: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
