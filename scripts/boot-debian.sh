#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Boot test on a stock Debian 12: a debootstrap image (minbase, systemd as
# PID 1, udev) with Debian's own kernel (linux-image-$KVER, the version
# linux-headers-amd64 names), booted in QEMU (TCG). Into it go, as a
# user and an integrator would put them:
#  - the Debian packages of the last commit (scripts/deb-build.sh:
#    as9888-calibd and as9888-dkms), installed with `apt install ./*.deb`
#    in the image: dh-dkms builds the driver against the image's kernel
#    headers, the package enables the socket (plus a SocketGroup= drop-in);
#  - the test adapter (tests/vm/adapter) built against the same kernel,
#    with the kernel's interrupt simulator compiled in (tests/boot/
#    irq_sim_compat.c: Debian's kernel has no CONFIG_IRQ_SIM), loaded at
#    boot by modules-load.d;
#  - for the BusyBox boot: busybox-static, tests/boot/busybox/ (inittab,
#    rcS, mdev.conf) and tests/boot/guest-busybox.sh.
# Boot 1, factory (a board fresh from assembly): no record, no failed unit,
# the restore unit skipped with one warning in the journal; the factory
# test through the driver writes the record. Boot 2, busybox: BusyBox init
# as PID 1 (no systemd, no udev; mdev): the package's init script applied
# the record before the first consumer, mdev's hotplug line and the daemon
# after a rebind (tests/boot/guest-busybox.sh). Boot 3, boot: tests/boot/
# guest-test.sh checks the calibration was applied by
# as9888-calibd-restore@ before multi-user.target, again after a rebind and
# after the device is instantiated late, the socket for a user in
# SocketGroup, then an upgrade of the package (the record kept) and a purge
# (no file left behind). Packages and adapter come from the last commit
# (git archive HEAD), not from files being edited.
#
# The root file system (debootstrap + Debian's kernel, and a copy with what
# the packages need: dkms, the kernel's headers, libgpiod2, busybox-static;
# gpiod for the factory-speed rounds' gpioinfo)
# is cached in $AS9888_CACHE/boot (~/.cache/as9888/boot, under cache_lock "boot"), so
# any checkout on this machine reuses it; this checkout's builds, disk image
# and logs are in $AS9888_BUILD/boot (default build/boot). A second run
# rebuilds only what changed and boots three times. Needs root (debootstrap,
# chroot, loop mount); installs the Debian packages it lacks. Each boot is
# bounded (AS9888_BOOT_TIMEOUT, 1500 s): a guest that stalls is stopped and
# reported with its log and the last check it printed. Each phase's guest
# prints its plan ("BOOTTEST plan N", tests/boot/guest-test.sh and
# guest-busybox.sh); a phase that made another number of checks, or printed
# no plan, is one more failure. Prints "boot-debian: N passed, M failed
# (T s in all)".
set -euo pipefail

# shellcheck source=scripts/kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"
top=$AS9888_REPO
cache=$AS9888_CACHE/boot
work=${AS9888_BUILD:-$top/build}/boot
boot_timeout=${AS9888_BOOT_TIMEOUT:-1500}
t0=$(date +%s)
[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, chroot, loop mount): run it as root or with sudo"
mkdir -p "$cache" "$work"
cache_lock boot

ensure_pkgs debootstrap qemu-system-x86 e2fsprogs linux-headers-amd64 \
	build-essential kmod rsync
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

# 1b. a copy with what `apt install ./as9888-*.deb` pulls in (installed
# from the network once, so each run installs the packages offline)
deps="dkms linux-headers-$KVER libgpiod2 busybox-static gpiod"
droot=$cache/rootfs-$KVER-debs
if [ "$(cat "$droot/.as9888-complete" 2>/dev/null)" != "$deps" ]; then
	log "the packages' dependencies into a copy of the root file system: $deps"
	rm -rf "$droot"
	cp -a "$rootfs" "$droot"
	rm -f "$droot/.as9888-complete"
	cp -L /etc/resolv.conf "$droot/etc/resolv.conf"
	cat >"$droot/etc/apt/sources.list" <<-EOF
	deb http://deb.debian.org/debian bookworm main
	deb http://deb.debian.org/debian bookworm-updates main
	deb http://deb.debian.org/debian-security bookworm-security main
	EOF
	mount --bind /proc "$droot/proc"
	mount --bind /dev "$droot/dev"
	{ chroot "$droot" apt-get -q update &&
		DEBIAN_FRONTEND=noninteractive chroot "$droot" apt-get -q install -y $deps; } \
		>"$cache/deps-install.log" 2>&1 || rc=$?
	umount "$droot/dev" "$droot/proc"
	[ "${rc:-0}" -eq 0 ] || die "cannot install $deps in the image (log $cache/deps-install.log; network?)"
	chroot "$droot" apt-get clean
	echo "$deps" >"$droot/.as9888-complete"
fi
log "with the packages' dependencies: $(du -sh "$droot" | cut -f1), $(( $(date +%s) - t0 )) s"

# 2. the sources of the last commit; only files whose content changed get
# a new time (archive times are commit times: an older commit would look
# older than the objects built from a newer one)
src=$work/src
rm -rf "$src.new"
mkdir -p "$src.new" "$src"
git -C "$top" archive HEAD | tar -x -C "$src.new"
rsync -rc --delete "$src.new/" "$src/"
rm -rf "$src.new"

# the Debian packages (scripts/deb-build.sh: built once per commit)
"$top/scripts/deb-build.sh" >"$work/deb-build.log" 2>&1 || {
	tail -20 "$work/deb-build.log"
	die "the Debian packages failed to build or check (log $work/deb-build.log)"
}
debdir=${AS9888_BUILD:-$top/build}/deb
ver=$(sed -n '1s/^as9888 (\([^)]*\)).*/\1/p' "$src/debian/changelog")
debs=("$debdir/as9888-calibd_${ver}_$(dpkg --print-architecture).deb" "$debdir/as9888-dkms_${ver}_all.deb")

# the adapter against the same kernel, with the interrupt simulator
ad=$src/tests/vm/adapter
cp "$top/tests/boot/irq_sim_compat.c" "$ad/"
# (a line of its own: the object list goes on over continuation lines)
echo 'as9888_sim-y += irq_sim_compat.o' >>"$ad/Kbuild"
make -C "/lib/modules/$KVER/build" M="$ad" modules >"$work/adapter.log" 2>&1 ||
	die "adapter build failed (log $work/adapter.log)"

log "packages and adapter built ($(( $(date +%s) - t0 )) s)"

# 3. the disk image: the cached root file system plus this run's files
img=$work/disk.img
mnt=$work/mnt
rm -f "$img"
truncate -s 3G "$img"
mkfs.ext4 -q -d "$droot" "$img"
mkdir -p "$mnt"
mount -o loop "$img" "$mnt"
trap 'umount "$mnt/proc" "$mnt/dev" "$mnt" 2>/dev/null || true' EXIT
rm -f "$mnt/.as9888-complete"
mkdir -p "$mnt/lib/modules/$KVER/extra"
cp "$ad/as9888_sim.ko" "$mnt/lib/modules/$KVER/extra/"
depmod -b "$mnt" "$KVER"
echo as9888_sim >"$mnt/etc/modules-load.d/as9888-sim.conf"
chroot "$mnt" groupadd -f as9888
chroot "$mnt" usermod -a -G as9888 tester
mkdir -p "$mnt/etc/systemd/system/as9888-calibd.socket.d"
printf '[Socket]\nSocketGroup=as9888\n' >"$mnt/etc/systemd/system/as9888-calibd.socket.d/group.conf"
install -D -m 0644 "$top/tests/boot/lib.sh" "$mnt/usr/local/lib/as9888-boottest/lib.sh"
install -m 0755 "$top/tests/boot/guest-test.sh" "$mnt/usr/local/bin/as9888-boottest"
install -m 0644 "$top/tests/boot/as9888-boottest.service" "$mnt/etc/systemd/system/"
# the BusyBox boot: init=/usr/local/lib/as9888-bb/init (BusyBox's init)
install -m 0755 "$top/tests/boot/guest-busybox.sh" "$mnt/usr/local/bin/as9888-boottest-busybox"
install -D -m 0755 "$top/tests/boot/busybox/rcS" "$mnt/usr/local/lib/as9888-bb/rcS"
ln -sf /bin/busybox "$mnt/usr/local/lib/as9888-bb/init"
install -m 0644 "$top/tests/boot/busybox/inittab" "$mnt/etc/inittab"
install -m 0644 "$top/tests/boot/busybox/mdev.conf" "$mnt/etc/mdev.conf"
chroot "$mnt" systemctl enable as9888-boottest.service >/dev/null 2>&1
chroot "$mnt" systemctl mask serial-getty@ttyS0.service getty@tty1.service >/dev/null 2>&1

# the packages, as a user installs them; the image's file list before, for
# the purge check of the last boot
chroot "$mnt" bash -c '. /usr/local/lib/as9888-boottest/lib.sh && snapshot' >"$work/files-before"
mkdir -p "$mnt/root/debs" "$mnt/root/debs-upgrade"
cp "${debs[@]}" "$mnt/root/debs/"
cp "$work/files-before" "$mnt/root/files-before"
# (no service starts in the chroot: policy-rc.d, as in any chroot)
printf '#!/bin/sh\nexit 101\n' >"$mnt/usr/sbin/policy-rc.d"
chmod 0755 "$mnt/usr/sbin/policy-rc.d"
mount --bind /proc "$mnt/proc"
mount --bind /dev "$mnt/dev"
rc=0
DEBIAN_FRONTEND=noninteractive chroot "$mnt" sh -c \
	"cd /root/debs && apt install -y $(printf './%s ' "${debs[@]##*/}")" >"$work/apt-install.log" 2>&1 || rc=$?
umount "$mnt/dev" "$mnt/proc"
rm -f "$mnt/usr/sbin/policy-rc.d"
[ "$rc" -eq 0 ] || { tail -20 "$work/apt-install.log"; die "apt install of the packages failed (log $work/apt-install.log)"; }
ls "$mnt/lib/modules/$KVER/updates/dkms/"as9888_i2c.ko* >/dev/null 2>&1 ||
	die "dkms did not install as9888_i2c for $KVER (log $work/apt-install.log)"
log "installed: $(chroot "$mnt" dpkg-query -W -f='${Package} ${Version}, ' as9888-calibd as9888-dkms)driver built by dkms for $KVER"
# the upgrade of the last boot: the same package with a higher version
x=$work/upgrade
rm -rf "$x"
dpkg-deb -R "${debs[0]}" "$x"
sed -i "s/^Version: .*/Version: ${ver}+boottest1/" "$x/DEBIAN/control"
dpkg-deb --root-owner-group -b "$x" "$mnt/root/debs-upgrade/as9888-calibd_${ver}+boottest1_$(dpkg --print-architecture).deb" >/dev/null
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
	# (a second argument: more kernel parameters)
	timeout -k 10 "$boot_timeout" qemu-system-x86_64 -accel tcg -m 1024 -nographic -no-reboot \
		-kernel "$work/vmlinuz-$KVER" -initrd "$work/initrd.img-$KVER" \
		-drive file="$img",format=raw,if=virtio \
		-append "root=/dev/vda rw console=ttyS0 quiet loglevel=4 panic=10 as9888.phase=$1 systemd.show_status=0${2:+ $2}" \
		-nic none </dev/null >"$work/$1.log" 2>&1 || rc=$?
	log "boot $1: $(( $(date +%s) - t )) s"
	grep -a '^BOOTTEST' "$work/$1.log" | tr -d '\r' || true
	if grep -aq '^BOOTTEST done' "$work/$1.log"; then
		local plan made
		# (the plan is the guest's first line: under systemd the console's
		# reset sequences stand before it on the line)
		plan=$(tr -d '\r' <"$work/$1.log" | sed -n 's/^.*BOOTTEST plan \([0-9]*\)$/\1/p' | head -n1)
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
{ boot factory; boot busybox init=/usr/local/lib/as9888-bb/init; boot boot; } | tee "$work/results"
passed=$(grep -c '^BOOTTEST ok' "$work/results" || true)
failed=$(grep -c '^BOOTTEST not ok' "$work/results" || true)
echo "boot-debian: $passed passed, $failed failed ($(( $(date +%s) - t0 )) s in all)"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
