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
# The root file system (debootstrap + kernel) is cached in
# $AS9888_BUILD/boot (default build/boot); a second run rebuilds only the
# modules and the daemon and boots twice. Needs root (debootstrap, loop
# mount). Prints "boot-debian: N passed, M failed" and the times.
set -euo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
cache=${AS9888_BUILD:-$top/build}/boot
mkdir -p "$cache"
t0=$(date +%s)
log() { echo "boot-debian: $*"; }
die() { echo "boot-debian: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot, loop mount)"

need=()
for p in debootstrap qemu-system-x86 e2fsprogs dkms linux-headers-amd64 \
	 build-essential meson ninja-build kmod; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
		need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
	log "installing ${need[*]}"
	apt-get update -q >/dev/null
	DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${need[@]}" >/dev/null
fi
KVER=$(dpkg-query -W -f='${Depends}' linux-headers-amd64 |
	grep -o 'linux-headers-[0-9][^ ,]*-amd64' | head -n1 | sed 's/^linux-headers-//')
[ -e "/lib/modules/$KVER/build" ] || die "no headers for $KVER"

# 1. the root file system, cached: Debian 12 minbase + systemd + kernel
rootfs=$cache/rootfs-$KVER
if [ ! -e "$rootfs/.as9888-complete" ]; then
	log "debootstrap bookworm (minbase, systemd, udev) and linux-image-$KVER"
	rm -rf "$rootfs" "$cache"/linux-image-*.deb
	debootstrap --variant=minbase \
		--include=systemd,systemd-sysv,udev,kmod,initramfs-tools,linux-base,procps \
		bookworm "$rootfs" http://deb.debian.org/debian >"$cache/debootstrap.log" 2>&1 ||
		die "debootstrap failed (log $cache/debootstrap.log)"
	# the image's version may be in bookworm-security only
	(cd "$cache" && apt-get download "linux-image-$KVER" >/dev/null)
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

# 2. the sources of the last commit
src=$cache/src
rm -rf "$src"
mkdir -p "$src"
git -C "$top" archive HEAD | tar -x -C "$src"

# the driver through dkms.conf, in our own dkms trees
dk=$cache/dkms
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
make -C "/lib/modules/$KVER/build" M="$ad" modules >"$cache/adapter.log" 2>&1 ||
	die "adapter build failed (log $cache/adapter.log)"

# the daemon: the product build, installed as a package installs it
b=$cache/calibd
[ -f "$b/build.ninja" ] ||
	meson setup "$b" "$src" --prefix=/usr --sysconfdir=/etc --buildtype=release \
		-Dsimulator=false -Dlibgpiod=disabled -Dtests=disabled >"$cache/meson.log" 2>&1 ||
	die "meson setup failed (log $cache/meson.log)"
meson setup --reconfigure "$b" "$src" >/dev/null 2>&1 || true
ninja -C "$b" >"$cache/ninja.log" 2>&1 || die "build failed (log $cache/ninja.log)"
log "driver (dkms), adapter and daemon built ($(( $(date +%s) - t0 )) s)"

# 3. the disk image: the cached root file system plus this run's files
img=$cache/disk.img
mnt=$cache/mnt
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
cp "$mnt/boot/vmlinuz-$KVER" "$mnt/boot/initrd.img-$KVER" "$cache/"
umount "$mnt"
trap - EXIT

boot() {	# PHASE: boot the image once, the serial console into $cache/PHASE.log
	local t=$(date +%s)
	timeout 600 qemu-system-x86_64 -accel tcg -m 1024 -nographic -no-reboot \
		-kernel "$cache/vmlinuz-$KVER" -initrd "$cache/initrd.img-$KVER" \
		-drive file="$img",format=raw,if=virtio \
		-append "root=/dev/vda rw console=ttyS0 quiet loglevel=4 as9888.phase=$1 systemd.show_status=0" \
		-nic none </dev/null >"$cache/$1.log" 2>&1 || true
	log "boot $1: $(( $(date +%s) - t )) s"
	grep -a '^BOOTTEST' "$cache/$1.log" | tr -d '\r'
	grep -aq '^BOOTTEST done' "$cache/$1.log" || { echo "BOOTTEST not ok - $1: the guest did not finish (log $cache/$1.log)"; }
}
{ boot factory; boot boot; } | tee "$cache/results"
passed=$(grep -c '^BOOTTEST ok' "$cache/results" || true)
failed=$(grep -c '^BOOTTEST not ok' "$cache/results" || true)
log "$passed passed, $failed failed, $(( $(date +%s) - t0 )) s in all"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
