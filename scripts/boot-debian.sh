#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Boot test on a stock Debian 12: a debootstrap image (minbase, systemd as
# PID 1, udev) with Debian's own kernel (linux-image-$KVER, the version
# linux-headers-amd64 names), booted in QEMU (TCG). Into it go, as a
# package and an integrator would put them:
#  - the driver, built by dkms from dkms.conf against that kernel's headers
#    (own dkms trees, nothing written to the host's /lib/modules);
#  - the test adapter (tests/vm/adapter) built against the same kernel,
#    with the kernel's interrupt simulator compiled in (tests/boot/
#    irq_sim_compat.c: Debian's kernel has no CONFIG_IRQ_SIM), loaded at
#    boot by modules-load.d;
#  - the product build of as9888-calibd (-Dsimulator=false -Dlibgpiod=
#    disabled -Dtests=disabled, prefix /usr) installed by meson install:
#    units, udev rule, tmpfiles entry as installed; the socket enabled with
#    a SocketGroup= drop-in.
# Boot 1 (a board fresh from assembly): no record, no failed unit, the
# restore unit skipped; the factory test through the driver writes the
# record. Boot 2: tests/boot/guest-test.sh checks the calibration was
# applied by as9888-calibd-restore@ before multi-user.target, again after a
# rebind and after the device is instantiated late, and the socket for a
# user in SocketGroup. Driver and adapter come from the last commit (git
# archive HEAD), not from files being edited.
#
# The root file system (debootstrap + Debian's kernel) is cached in
# $AS9888_CACHE/boot (~/.cache/as9888/boot, under cache_lock "boot"), so
# any checkout on this machine reuses it; this checkout's builds, disk image
# and logs are in $AS9888_BUILD/boot (default build/boot). A second run
# rebuilds only what changed and boots twice. Needs root (debootstrap,
# chroot, loop mount); installs the Debian packages it lacks. Each boot is
# bounded (AS9888_BOOT_TIMEOUT, 600 s): a guest that stalls is stopped and
# reported with its log and the last check it printed. Each phase's guest
# prints its plan ("BOOTTEST plan N", tests/boot/guest-test.sh); a phase
# that made another number of checks, or printed no plan, is one more
# failure. Prints "boot-debian: N passed, M failed (T s in all)".
set -euo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
top=$AS9888_REPO
cache=$AS9888_CACHE/boot
work=${AS9888_BUILD:-$top/build}/boot
boot_timeout=${AS9888_BOOT_TIMEOUT:-600}
t0=$(date +%s)
[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot, loop mount): run it as root or with sudo"
mkdir -p "$cache" "$work"
cache_lock boot

ensure_pkgs debootstrap qemu-system-x86 e2fsprogs dkms linux-headers-amd64 \
	build-essential meson ninja-build kmod rsync
KVER=$(dpkg-query -W -f='${Depends}' linux-headers-amd64 |
	grep -o 'linux-headers-[0-9][^ ,]*-amd64' | head -n1 | sed 's/^linux-headers-//')
[ -e "/lib/modules/$KVER/build" ] || die "no headers for $KVER: apt-get install linux-headers-$KVER"

# 1. the root file system, cached: Debian 12 minbase + systemd + kernel
rootfs=$cache/rootfs-$KVER
if [ ! -e "$rootfs/.as9888-complete" ]; then
	log "debootstrap bookworm (minbase, systemd, udev) and linux-image-$KVER"
	rm -rf "$rootfs" "$cache"/linux-image-*.deb
	timeout 1800 debootstrap --variant=minbase \
		--include=systemd,systemd-sysv,udev,kmod,initramfs-tools,linux-base,procps \
		bookworm "$rootfs" http://deb.debian.org/debian >"$cache/debootstrap.log" 2>&1 ||
		die "debootstrap failed or took over 30 min (log $cache/debootstrap.log; network? a mirror in http_proxy?)"
	# the image's version may be in bookworm-security only
	(cd "$cache" && timeout 900 apt-get download "linux-image-$KVER" >"$cache/download.log" 2>&1) ||
		die "cannot download linux-image-$KVER (log $cache/download.log; apt-get update? is it still in bookworm or bookworm-security?)"
	cp "$cache"/linux-image-"$KVER"_*.deb "$rootfs/tmp/kernel.deb"
	mount --bind /proc "$rootfs/proc"
	chroot "$rootfs" dpkg -i /tmp/kernel.deb >"$cache/kernel-install.log" 2>&1 ||
		{ umount "$rootfs/proc"; die "kernel install failed (log $cache/kernel-install.log)"; }
	umount "$rootfs/proc"
	rm -f "$rootfs/tmp/kernel.deb"
	rm -rf "$rootfs"/usr/share/doc/* "$rootfs"/usr/share/man/* "$rootfs"/var/cache/apt/*.bin \
		"$rootfs"/var/lib/apt/lists/*
	echo as9888-boot >"$rootfs/etc/hostname"
	echo "/dev/vda / ext4 rw,relatime 0 1" >"$rootfs/etc/fstab"
	chroot "$rootfs" passwd -d root >/dev/null
	chroot "$rootfs" useradd -m tester
	touch "$rootfs/.as9888-complete"
fi
log "root file system ready ($(du -sh "$rootfs" | cut -f1), $(( $(date +%s) - t0 )) s)"

# 2. the sources of the last commit; only files whose content changed get
# a new time (archive times are commit times: an older commit would look
# older than the objects built from a newer one)
src=$work/src
rm -rf "$src.new"
mkdir -p "$src.new" "$src"
git -C "$top" archive HEAD | tar -x -C "$src.new"
rsync -rc --delete "$src.new/" "$src/"
rm -rf "$src.new"

# the driver through dkms.conf, in our own dkms trees
dk=$work/dkms
rm -rf "$dk"
mkdir -p "$dk/tree" "$dk/source/as9888-0.1.0"
cp -a "$src/dkms.conf" "$src/Kbuild" "$src/drivers" "$dk/source/as9888-0.1.0/"
DKMS=(dkms --dkmstree "$dk/tree" --sourcetree "$dk/source")
"${DKMS[@]}" add -m as9888 -v 0.1.0 >"$dk/dkms.log" 2>&1 &&
	env mok_signing_key="$dk/mok.key" mok_certificate="$dk/mok.pub" \
	"${DKMS[@]}" build -m as9888 -v 0.1.0 -k "$KVER" >>"$dk/dkms.log" 2>&1 ||
	die "dkms build failed (log $dk/dkms.log)"
kos=$dk/tree/as9888/0.1.0/$KVER/$(uname -m)/module

# the adapter against the same kernel, with the interrupt simulator
ad=$src/tests/vm/adapter
cp "$top/tests/boot/irq_sim_compat.c" "$ad/"
sed -i 's/^as9888_sim-y := .*/& irq_sim_compat.o/' "$ad/Kbuild"
make -C "/lib/modules/$KVER/build" M="$ad" modules >"$work/adapter.log" 2>&1 ||
	die "adapter build failed (log $work/adapter.log)"

# the daemon: the product build, installed as a package installs it
b=$work/calibd
[ -f "$b/build.ninja" ] ||
	meson setup "$b" "$src" --prefix=/usr --sysconfdir=/etc --buildtype=release \
		-Dsimulator=false -Dlibgpiod=disabled -Dtests=disabled >"$work/meson.log" 2>&1 ||
	die "meson setup failed (log $work/meson.log)"
meson setup --reconfigure "$b" "$src" >/dev/null 2>&1 || true
ninja -C "$b" >"$work/ninja.log" 2>&1 || die "build failed (log $work/ninja.log)"
log "driver (dkms), adapter and daemon built ($(( $(date +%s) - t0 )) s)"

# 3. the disk image: the cached root file system plus this run's files
img=$work/disk.img
mnt=$work/mnt
rm -f "$img"
truncate -s 2G "$img"
mkfs.ext4 -q -d "$rootfs" "$img"
mkdir -p "$mnt"
mount -o loop "$img" "$mnt"
trap 'umount "$mnt" 2>/dev/null || true' EXIT
DESTDIR=$mnt meson install -C "$b" --no-rebuild --quiet >/dev/null
mkdir -p "$mnt/lib/modules/$KVER/updates/dkms" "$mnt/lib/modules/$KVER/extra"
cp "$kos"/*.ko* "$mnt/lib/modules/$KVER/updates/dkms/"
cp "$ad/as9888_sim.ko" "$mnt/lib/modules/$KVER/extra/"
depmod -b "$mnt" "$KVER"
echo as9888_sim >"$mnt/etc/modules-load.d/as9888-sim.conf"
chroot "$mnt" groupadd -f as9888
chroot "$mnt" usermod -a -G as9888 tester
mkdir -p "$mnt/etc/systemd/system/as9888-calibd.socket.d"
printf '[Socket]\nSocketGroup=as9888\n' >"$mnt/etc/systemd/system/as9888-calibd.socket.d/group.conf"
install -m 0755 "$top/tests/boot/guest-test.sh" "$mnt/usr/local/bin/as9888-boottest"
install -m 0644 "$top/tests/boot/as9888-boottest.service" "$mnt/etc/systemd/system/"
chroot "$mnt" systemctl enable as9888-calibd.socket as9888-boottest.service >/dev/null 2>&1
chroot "$mnt" systemctl mask serial-getty@ttyS0.service getty@tty1.service >/dev/null 2>&1
cp "$mnt/boot/vmlinuz-$KVER" "$mnt/boot/initrd.img-$KVER" "$work/"
umount "$mnt"
trap - EXIT

# PHASE: boot the image once, the serial console into $work/PHASE.log. A
# guest that does not finish within $boot_timeout s is stopped; its log and
# the last check it printed are named. (The kernel reboots 10 s after a
# panic, which -no-reboot turns into QEMU's exit; the test unit in the
# guest has its own TimeoutStartSec=.)
boot() {
	local t rc=0 last
	t=$(date +%s)
	timeout -k 10 "$boot_timeout" qemu-system-x86_64 -accel tcg -m 1024 -nographic -no-reboot \
		-kernel "$work/vmlinuz-$KVER" -initrd "$work/initrd.img-$KVER" \
		-drive file="$img",format=raw,if=virtio \
		-append "root=/dev/vda rw console=ttyS0 quiet loglevel=4 panic=10 as9888.phase=$1 systemd.show_status=0" \
		-nic none </dev/null >"$work/$1.log" 2>&1 || rc=$?
	log "boot $1: $(( $(date +%s) - t )) s"
	grep -a '^BOOTTEST' "$work/$1.log" | tr -d '\r' || true
	if grep -aq '^BOOTTEST done' "$work/$1.log"; then
		local plan made
		plan=$(tr -d '\r' <"$work/$1.log" | sed -n 's/^BOOTTEST plan \([0-9]*\)$/\1/p' | head -n1)
		made=$(grep -acE '^BOOTTEST (not )?ok - ' "$work/$1.log" || true)
		[ -n "$plan" ] && [ "$plan" -eq "$made" ] ||
			echo "BOOTTEST not ok - $1: $made checks made, the guest's plan says ${plan:-nothing}"
		return 0
	fi
	last=$(grep -a '^BOOTTEST' "$work/$1.log" | tr -d '\r' | tail -n1 || true)
	if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
		echo "BOOTTEST not ok - $1: the guest stalled and was stopped after $boot_timeout s; last line: ${last:-none} (log $work/$1.log)"
	else
		echo "BOOTTEST not ok - $1: the guest stopped before the end (QEMU exit $rc); last line: ${last:-none} (log $work/$1.log)"
	fi
}
{ boot factory; boot boot; } | tee "$work/results"
passed=$(grep -c '^BOOTTEST ok' "$work/results" || true)
failed=$(grep -c '^BOOTTEST not ok' "$work/results" || true)
echo "boot-debian: $passed passed, $failed failed ($(( $(date +%s) - t0 )) s in all)"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
