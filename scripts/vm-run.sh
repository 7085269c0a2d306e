#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# vm-run.sh [6.1|7.2|all]
#
# The real-kernel test bench: for each kernel version, builds (cached) the
# debug kernel, the driver and the test adapter (scripts/vm-kernel.sh) and
# as9888-calibd linked statically, packs an initramfs (busybox-static, the
# modules, the daemon, tests/vm/guest/) and boots it in QEMU (TCG) under a
# stall watchdog. The guest prints TAP and an end marker, then reboots.
#
# No total time budget: a busy machine makes every test slower. Instead a
# guest that prints no TAP line (ok, not ok, or a "# " diagnostic) for
# AS9888_VM_STALL seconds is stopped, and the test it stalled in is named.
# AS9888_VM_TIMEOUT is only a last resort against a runaway guest.
#
# A kernel fails when a test fails, when the guest stalls, when the end
# marker is missing (hang, panic) or on any kernel splat in the serial log
# (BUG, WARNING, KASAN, lockdep, Oops, panic, kmemleak leak, hung task).
# Expected totals: every test file declares the checks it makes ("plan N",
# tests/vm/guest/lib.sh); the guest prints "# AS9888-PLAN <file>
# planned=P made=M" after each file, and each file that was to run (all,
# or AS9888_VM_ONLY's) but has no such line, or made another number of
# checks than its plan, is one more failure. Prints "<k>: N passed, N
# failed" per kernel (", N skipped" when a test printed a TAP "# SKIP":
# not counted as passed); exit status 0 only when none failed.
#
# "all" builds both kernels one after the other, then runs the two guests
# side by side (a TCG guest keeps one core busy): each with its own serial
# log, stall watchdog and summary line.
#
# Everything goes to $AS9888_CACHE/vm/ (logs: $AS9888_CACHE/logs/vm-run-<k>.log).
# One run at a time per cache (lock $AS9888_CACHE/.vm.lock: a second run
# waits). Environment: AS9888_CACHE, AS9888_JOBS, AS9888_VM_STALL (s without
# a TAP line, default 300), AS9888_VM_TIMEOUT (s in all, default 7200),
# AS9888_VM_ONLY (test files to run, e.g. "10-probe 90-spi"; default all),
# AS9888_VM_TSC_KHZ (the guest's TSC rate; default measured on the host,
# "0": the guest calibrates it itself, see guest_clock).
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

select_kernels "$@"
# One bench at a time per cache: the kernels, modules, initramfs and logs
# under $AS9888_CACHE/vm are shared (vm-kernel.sh below runs under this
# lock; AS9888_VM_LOCKED=1 says that the caller holds it)
[ -n "${AS9888_VM_LOCKED:-}" ] || cache_lock vm
export AS9888_VM_LOCKED=1

VM_DIR="$AS9888_CACHE/vm"
GUEST="$AS9888_REPO/tests/vm/guest"
TIMEOUT="${AS9888_VM_TIMEOUT:-7200}"
STALL="${AS9888_VM_STALL:-300}"
mkdir -p "$VM_DIR" "$LOG_DIR"
T_START=$(now)

ensure_pkgs busybox-static qemu-system-x86 cpio gzip meson ninja-build \
	pkg-config libgpiod-dev libcmocka-dev gcc gpiod file libiio-utils \
	dbus-daemon dbus-system-bus-common libglib2.0-0

# as9888-calibd, statically linked (glibc + libgpiod 1.6 static libs)
build_daemon() {
	local b="$VM_DIR/daemon-static" t
	t=$(now)
	# The cache is shared by every checkout: a build directory set up from
	# another checkout would build that checkout's daemon. Start afresh.
	if [ -f "$b/build.ninja" ] &&
		[ "$(cat "$b/.as9888-source" 2>/dev/null)" != "$AS9888_REPO" ]; then
		log "as9888-calibd (static): build directory set up from another checkout, set up again"
		rm -rf "$b"
	fi
	if [ ! -f "$b/build.ninja" ]; then
		meson setup "$b" "$AS9888_REPO" -Dprefer_static=true \
			-Dc_link_args=-static -Dbuildtype=release \
			>"$LOG_DIR/vm-daemon.log" 2>&1 ||
			die "meson setup failed, see $LOG_DIR/vm-daemon.log"
		echo "$AS9888_REPO" >"$b/.as9888-source"
	fi
	# and the sensors HAL's core behind its command line (87-hal)
	ninja -C "$b" daemon/as9888-calibd hal/as9888-hal-cat >>"$LOG_DIR/vm-daemon.log" 2>&1 ||
		die "static as9888-calibd build failed, see $LOG_DIR/vm-daemon.log"
	for p in daemon/as9888-calibd hal/as9888-hal-cat; do
		file -L "$b/$p" | grep -q 'statically linked' ||
			die "$b/$p is not statically linked"
	done
	DAEMON="$b/daemon/as9888-calibd"
	HAL_CAT="$b/hal/as9888-hal-cat"
	log "as9888-calibd and as9888-hal-cat (static) ready in $(since "$t")"
}

# The kernel's tools/iio (lsiio, iio_generic_buffer), linked statically
build_tools_iio() {
	local o="$VM_DIR/tools-iio/"
	mkdir -p "$o"
	# A fresh cache has no 7.2 source yet (vm-kernel.sh unpacks the
	# kernels it boots, later, and maybe not 7.2): unpack it first
	if [ ! -f "$(ksrc 7.2)/Makefile" ]; then
		log "tools/iio: no 7.2 source yet, running scripts/kernel-trees.sh --source-only 7.2"
		"$AS9888_REPO/scripts/kernel-trees.sh" --source-only 7.2 \
			>"$LOG_DIR/vm-kernel-trees-src-7.2.log" 2>&1 ||
			die "kernel-trees.sh --source-only 7.2 failed, see $LOG_DIR/vm-kernel-trees-src-7.2.log"
	fi
	make -C "$(ksrc 7.2)/tools/iio" OUTPUT="$o" LDFLAGS=-static \
		>"$LOG_DIR/vm-tools-iio.log" 2>&1 ||
		die "tools/iio build failed, see $LOG_DIR/vm-tools-iio.log"
	TOOLS_IIO="$o"
}

# The real consumer (issue 12): Debian 12's iio-sensor-proxy with its udev
# rule, systemd-udevd and the system bus. The packages that are not the
# host's own (iio-sensor-proxy, libgudev, udev) are taken with apt-get
# download into $VM_DIR/debs (kept: a second run downloads nothing) and
# unpacked into $VM_DIR/proxy-root; dbus-daemon, GLib and the libraries
# they share are the host's (ensure_pkgs above). Sets PROXY_ROOT and
# PROXY_VERSIONS (package=version, one a line).
PROXY_DEBS="iio-sensor-proxy libgudev-1.0-0 udev"
stage_sensor_proxy() {
	local debs="$VM_DIR/debs" r="$VM_DIR/proxy-root" p f t
	t=$(now)
	mkdir -p "$debs"
	for p in $PROXY_DEBS; do
		compgen -G "$debs/${p}_*.deb" >/dev/null && continue
		(cd "$debs" && apt-get download -q "$p") >>"$LOG_DIR/vm-debs.log" 2>&1 ||
			die "apt-get download $p failed, see $LOG_DIR/vm-debs.log"
	done
	rm -rf "$r"
	mkdir -p "$r"
	PROXY_VERSIONS=""
	for p in $PROXY_DEBS; do
		f=$(ls "$debs/${p}"_*.deb | tail -n 1)
		dpkg-deb -x "$f" "$r" || die "cannot unpack $f"
		PROXY_VERSIONS="$PROXY_VERSIONS$p=$(dpkg-deb -f "$f" Version)
"
	done
	for p in dbus-daemon libglib2.0-0; do
		PROXY_VERSIONS="$PROXY_VERSIONS$p=$(dpkg-query -W -f='${Version}' "$p")
"
	done
	PROXY_ROOT="$r"
	log "iio-sensor-proxy, udev and the system bus staged in $(since "$t")"
}

# iio-sensor-proxy 3.7 (issue 12), the version phones ship, from Debian 13
# (trixie): its buffer driver, and the polkit check of every claim that
# came with 3.4, so trixie's polkitd as well. The packages come through a
# private apt configuration in $AS9888_CACHE/apt-trixie-bin (see
# apt-private.sh; nothing from trixie is installed into the host): the two
# programs' packages and, following Depends and Pre-Depends, every package
# of section "libs" they need (libc6, GLib, libgudev, libudev, libpolkit,
# ...), into $VM_DIR/debs-trixie with the list of names (a warm run reads
# the list and downloads nothing). They are unpacked into $VM_DIR/trixie-root
# and checked: trixie's own loader must resolve every library of every
# program in TRIXIE_PROGS there. Sets TRIXIE_ROOT and TRIXIE_VERSIONS.
TRIXIE_ROOTS="iio-sensor-proxy polkitd"
TRIXIE_PROGS="usr/libexec/iio-sensor-proxy usr/bin/monitor-sensor usr/lib/polkit-1/polkitd usr/bin/pkcheck"
TRIXIE_LIB=usr/lib/x86_64-linux-gnu
# shellcheck source-path=SCRIPTDIR source=apt-private.sh
. "$AS9888_REPO/scripts/apt-private.sh"
# trixie_closure PACKAGE...: the packages and their "libs" dependencies,
# one a line
trixie_closure() {
	local want=("$@") seen=" " next p
	while [ "${#want[@]}" -gt 0 ]; do
		for p in "${want[@]}"; do seen="$seen$p "; done
		next=$(apt-cache "${APT_OPTS[@]}" depends --no-recommends --no-suggests \
			--no-conflicts --no-breaks --no-replaces --no-enhances "${want[@]}" |
			awk '$1 ~ /^\|?(Pre)?Depends:$/ && $2 !~ /^</ { print $2 }' | sort -u)
		want=()
		for p in $next; do
			case "$seen" in *" $p "*) continue ;; esac
			[ "$(apt-cache "${APT_OPTS[@]}" show --no-all-versions "$p" |
				sed -n 's/^Section: //p')" = libs ] && want+=("$p")
		done
	done
	# shellcheck disable=SC2086 # one word a package
	printf '%s\n' $seen
}
# trixie_libs ROOT PROGRAM: the files of the libraries (and the loader)
# that trixie's loader in ROOT loads for PROGRAM, one a line; fails if one
# is not found or is not under ROOT
trixie_libs() {
	"$1/$TRIXIE_LIB/ld-linux-x86-64.so.2" --library-path "$1/$TRIXIE_LIB" --list "$2" |
		awk -v r="$1/" '$2 == "=>" { if (index($3, r) != 1) bad = 1; else print $3 }
			END { exit bad }'
}
stage_trixie() {
	local debs="$VM_DIR/debs-trixie" r="$VM_DIR/trixie-root" p f t prog n=0 bytes=0
	local list="$VM_DIR/debs-trixie/packages" need=all pkgs=() d
	t=$(now)
	mkdir -p "$debs"
	if [ "$(head -n1 "$list" 2>/dev/null)" = "roots: $TRIXIE_ROOTS" ]; then
		need=""
		for p in $(tail -n +2 "$list"); do
			compgen -G "$debs/${p}_*.deb" >/dev/null || need="$need $p"
		done
	fi
	if [ -n "$need" ]; then
		apt_private "$AS9888_CACHE/apt-trixie-bin" trixie deb scripts/vm-run.sh
		log "trixie packages: apt-get update (private list, mirror $MIRROR)"
		apt-get "${APT_OPTS[@]}" update >"$LOG_DIR/vm-debs-trixie.log" 2>&1 ||
			die "apt-get update of the private trixie list failed, see $LOG_DIR/vm-debs-trixie.log"
		# shellcheck disable=SC2086 # one word a package
		mapfile -t pkgs < <(trixie_closure $TRIXIE_ROOTS)
		rm -f "$debs"/*.deb
		(cd "$debs" && apt-get "${APT_OPTS[@]}" download "${pkgs[@]}") \
			>>"$LOG_DIR/vm-debs-trixie.log" 2>&1 ||
			die "apt-get download of trixie's ${pkgs[*]} failed, see $LOG_DIR/vm-debs-trixie.log"
		{ echo "roots: $TRIXIE_ROOTS"; printf '%s\n' "${pkgs[@]}"; } >"$list"
	fi
	rm -rf "$r"
	mkdir -p "$r"
	TRIXIE_VERSIONS=""
	mapfile -t pkgs < <(tail -n +2 "$list")
	for p in "${pkgs[@]}"; do
		d=("$debs/${p}"_*.deb)
		f=${d[-1]}
		dpkg-deb -x "$f" "$r" || die "cannot unpack $f"
		TRIXIE_VERSIONS="$TRIXIE_VERSIONS$p=$(dpkg-deb -f "$f" Version)
"
		n=$((n + 1))
		bytes=$((bytes + $(stat -c %s "$f")))
	done
	for prog in $TRIXIE_PROGS; do
		[ -x "$r/$prog" ] || die "no $prog in trixie's packages"
		trixie_libs "$r" "$r/$prog" >/dev/null ||
			die "trixie's loader does not find every library of $prog in $r"
	done
	TRIXIE_ROOT="$r"
	log "trixie: $(printf '%s' "$TRIXIE_VERSIONS" | grep -E '^(iio-sensor-proxy|polkitd)=' | tr '\n' ' ')staged from $n packages ($((bytes / 1024)) KiB of .deb) in $(since "$t")"
}

# The guest's clock. Under TCG the guest's TSC is the host's (QEMU reads
# the host's TSC for the guest's RDTSC). The guest calibrates it against
# the emulated PIT, which fails when the host is busy ("tsc: Unable to
# calibrate against PIT"); the guest then keeps time with jiffies, in 4 ms
# steps, and nothing shorter can be timed: the driver's 5 us reset pulse
# disappears, the adapter's 1.2 ms measurements last a tick. So the guest
# is told the rate, measured here against CLOCK_MONOTONIC_RAW over 200 ms,
# and that its TSC is reliable (one CPU, constant rate). Sets GUEST_CLOCK.
guest_clock() {
	local src="$VM_DIR/tsc-khz.c" bin="$VM_DIR/tsc-khz" khz="${AS9888_VM_TSC_KHZ:-}"
	GUEST_CLOCK=""
	if [ -z "$khz" ]; then
		if [ "$(uname -m)" != x86_64 ] || ! grep -qw constant_tsc /proc/cpuinfo; then
			warn "no constant TSC on this host: the guest calibrates its own"
			return 0
		fi
		cat >"$src" <<'EOF_C'
#include <stdio.h>
#include <time.h>
#include <x86intrin.h>

int main(void)
{
	struct timespec a, b, d = { 0, 200000000 };
	unsigned long long t0, t1;
	double ns;

	clock_gettime(CLOCK_MONOTONIC_RAW, &a);
	t0 = __rdtsc();
	nanosleep(&d, NULL);
	clock_gettime(CLOCK_MONOTONIC_RAW, &b);
	t1 = __rdtsc();
	ns = (b.tv_sec - a.tv_sec) * 1e9 + (b.tv_nsec - a.tv_nsec);
	printf("%.0f\n", (t1 - t0) / ns * 1e6);
	return 0;
}
EOF_C
		gcc -O2 -o "$bin" "$src" || die "cannot build $src"
		khz=$("$bin")
	fi
	if [ "$khz" != 0 ]; then
		GUEST_CLOCK="tsc_early_khz=$khz tsc=reliable"
		log "guest clock: TSC at $khz kHz (the host's)"
	fi
}

# copy_with_libs ROOT BINARY [DEST [STAGE]]: a dynamic program (into
# DEST, default /usr/bin) and the libraries it needs; STAGE is an unpacked
# package tree searched for libraries before the host's
copy_with_libs() {
	local root="$1" bin="$2" dest="${3:-/usr/bin}" stage="${4:-}" lib path=""
	mkdir -p "$root$dest"
	cp "$bin" "$root$dest/"
	[ -z "$stage" ] || path="$stage/usr/lib/x86_64-linux-gnu:$stage/lib/x86_64-linux-gnu"
	for lib in $(LD_LIBRARY_PATH="$path" ldd "$bin" | grep -o '/[^ ]*'); do
		local to="${lib#"$stage"}"
		mkdir -p "$root$(dirname "$to")"
		cp -L "$lib" "$root$to"
	done
}

# The staged iio-sensor-proxy, udevd and dbus-daemon in the initramfs
install_sensor_proxy() {
	local root="$1" r="$PROXY_ROOT"
	copy_with_libs "$root" "$r/usr/sbin/iio-sensor-proxy" /usr/sbin "$r"
	copy_with_libs "$root" "$r/usr/bin/monitor-sensor" /usr/bin "$r"
	copy_with_libs "$root" "$r/bin/udevadm" /usr/bin "$r"
	mkdir -p "$root/lib/systemd" "$root/lib/udev/rules.d" "$root/etc/udev" \
		"$root/etc/dbus-1/system.d" "$root/usr/share/dbus-1" "$root/run"
	ln -sf /usr/bin/udevadm "$root/lib/systemd/systemd-udevd"
	cp "$r/lib/udev/rules.d/80-iio-sensor-proxy.rules" "$root/lib/udev/rules.d/"
	cp "$r/etc/udev/udev.conf" "$root/etc/udev/"
	copy_with_libs "$root" /usr/bin/dbus-daemon /usr/bin
	cp /usr/share/dbus-1/system.conf "$root/usr/share/dbus-1/"
	cp "$r/etc/dbus-1/system.d/net.hadess.SensorProxy.conf" "$root/etc/dbus-1/system.d/"
	# polkitd (trixie's, 76-sensor-proxy-37) runs as polkitd
	printf '%s\n' root:x:0:0:root:/root:/bin/sh messagebus:x:100:101::/nonexistent:/bin/false \
		polkitd:x:996:996::/nonexistent:/bin/false >"$root/etc/passwd"
	printf '%s\n' root:x:0: messagebus:x:101: polkitd:x:996: >"$root/etc/group"
	echo 4f0b1a3c9e7d4b2a8c6e5f1d2a3b4c5d >"$root/etc/machine-id"
	# GLib's default system bus address is under /var/run, as on Debian
	mkdir -p "$root/var"
	ln -sfn /run "$root/var/run"
	printf '%s' "$PROXY_VERSIONS" >"$root/tests/clients.txt"
}

# The trixie programs in /opt/trixie of the initramfs, each with the
# libraries that trixie's loader resolves for it (in /opt/trixie/usr/lib/
# x86_64-linux-gnu; the loader also as /opt/trixie/lib64/ld-linux-x86-64.so.2,
# merged /usr as in trixie), so that nothing of bookworm's is loaded and
# nothing of bookworm's is replaced. Also trixie's udev rule, its D-Bus
# policies with a system bus configuration that includes only them (the
# host's system.conf without /etc/dbus-1/system.d, where 3.0's policy is),
# and polkit's actions and rules (polkitd reads /usr/share/polkit-1 and
# /etc/polkit-1, links to the ones under /opt/trixie).
install_trixie() {
	local root="$1" r="$TRIXIE_ROOT" o="$1/opt/trixie" prog lib f
	mkdir -p "$o/$TRIXIE_LIB" "$o/usr/lib64" "$o/etc/polkit-1/rules.d" "$root/etc"
	for prog in $TRIXIE_PROGS; do
		mkdir -p "$o/$(dirname "$prog")"
		cp "$r/$prog" "$o/$prog"
		for lib in $(trixie_libs "$r" "$r/$prog"); do
			cp -L "$lib" "$o/$TRIXIE_LIB/${lib##*/}"
		done
	done
	ln -sf "../lib/x86_64-linux-gnu/ld-linux-x86-64.so.2" "$o/usr/lib64/ld-linux-x86-64.so.2"
	ln -sfn usr/lib64 "$o/lib64"
	for f in usr/lib/udev/rules.d/80-iio-sensor-proxy.rules \
		usr/share/dbus-1/system.d/net.hadess.SensorProxy.conf \
		usr/share/dbus-1/system.d/org.freedesktop.PolicyKit1.conf \
		usr/share/polkit-1/actions/net.hadess.SensorProxy.policy \
		usr/share/polkit-1/rules.d/50-default.rules; do
		mkdir -p "$o/$(dirname "$f")"
		cp "$r/$f" "$o/$f"
	done
	grep -v '<includedir>/etc/dbus-1/system.d</includedir>' /usr/share/dbus-1/system.conf \
		>"$o/usr/share/dbus-1/system.conf"
	mkdir -p "$root/usr/share"
	ln -sfn /opt/trixie/usr/share/polkit-1 "$root/usr/share/polkit-1"
	ln -sfn /opt/trixie/etc/polkit-1 "$root/etc/polkit-1"
	printf '%s' "$TRIXIE_VERSIONS" >"$root/tests/clients-trixie.txt"
}

pack_initramfs() {
	local k="$1"
	local root="$VM_DIR/initramfs-$k" out="$VM_DIR/initramfs-$k.cpio.gz" a
	rm -rf "$root"
	mkdir -p "$root"/{bin,sbin,usr/bin,usr/sbin,proc,sys,dev,tmp,run,var/lib/as9888} \
		"$root/lib/modules/as9888" "$root/tests"
	cp /bin/busybox "$root/bin/busybox"
	for a in $("$root/bin/busybox" --list); do
		[ "$a" = busybox ] || ln -sf busybox "$root/bin/$a"
	done
	cp "$DAEMON" "$root/bin/as9888-calibd"
	cp "$HAL_CAT" "$root/bin/as9888-hal-cat"
	cp "$TOOLS_IIO/lsiio" "$TOOLS_IIO/iio_generic_buffer" "$root/usr/bin/"
	for a in gpiodetect gpioinfo gpioget iio_info iio_attr iio_readdev; do
		copy_with_libs "$root" "/usr/bin/$a"
	done
	install_sensor_proxy "$root"
	install_trixie "$root"
	cp "$VM_DIR/mod-$k/ko/"*.ko "$root/lib/modules/as9888/"
	cp "$GUEST/init" "$root/init"
	cp "$GUEST/lib.sh" "$GUEST/run-all.sh" "$root/tests/"
	# the record helpers the host's tests use (lib.sh sources them)
	cp "$AS9888_REPO/tests/lib/record.sh" "$root/tests/record.sh"
	cp -r "$GUEST/tests" "$root/tests/tests"
	# AS9888_VM_ONLY="10-probe 90-spi": run only these test files
	printf '%s\n' "${FILES[@]}" >"$root/tests/only"
	# AS9888_VM_SOAK=1 (scripts/vm-soak.sh): the repeated tests at their
	# soak depth (62-bind-50: 50 cycles of each kind, not 10)
	[ "${AS9888_VM_SOAK:-0}" = 0 ] || echo 1 >"$root/tests/soak"
	# 11-kunit's plan: the test cases of the driver's KUnit suite
	grep -c 'KUNIT_CASE' "$AS9888_REPO/$AS9888_DRIVER_REL/as9888_calib_kunit.c" \
		>"$root/tests/kunit-cases" || true
	chmod +x "$root/init" "$root/tests/run-all.sh"
	(cd "$root" && find . -print0 | cpio --null -o -H newc --quiet | gzip -1) >"$out"
	INITRD="$out"
}

SPLAT_RE='BUG:|WARNING:|KASAN|UBSAN|general protection|Oops|Kernel panic|possible recursive locking|possible circular locking|possible irq lock inversion|inconsistent lock state|suspicious RCU usage|unreferenced object|blocked for more than|scheduling while atomic|sleeping function called from invalid context|Call Trace'

# run_one K: boot kernel K's guest (initramfs packed) under the stall
# watchdog and judge its log; writes the summary line to $VM_DIR/result-K
# and returns non-zero when K failed
run_one() {
	local k="$1"
	local log="$LOG_DIR/vm-run-$k.log" t rc=0 pass fail skip splat qpid
	local lines=0 n quiet=0 stalled="" initrd="$VM_DIR/initramfs-$k.cpio.gz"
	rm -f "$VM_DIR/result-$k"
	t=$(now)
	log "$k: booting $VM_DIR/build-$k/arch/x86/boot/bzImage (log: $log)"
	timeout -k 10 "$TIMEOUT" qemu-system-x86_64 -accel tcg -m 1G \
		-nographic -no-reboot -monitor none -serial stdio \
		-kernel "$VM_DIR/build-$k/arch/x86/boot/bzImage" -initrd "$initrd" \
		-append "console=ttyS0 loglevel=5 oops=panic panic_on_warn=1 panic=-1 kmemleak=on $GUEST_CLOCK" \
		</dev/null >"$log" 2>&1 &
	qpid=$!
	# a bench stopped from outside (timeout, ^C) takes its guest with it
	# shellcheck disable=SC2064 # the pid of this guest, now
	trap "kill $qpid 2>/dev/null || true" EXIT
	trap "kill $qpid 2>/dev/null || true; exit 143" TERM INT
	# the stall watchdog: TAP lines (and diagnostics) must keep coming
	while kill -0 "$qpid" 2>/dev/null; do
		sleep 5
		n=$(grep -cE '^(ok |not ok |# )' "$log" || true)
		if [ "$n" -ne "$lines" ]; then
			lines=$n
			quiet=0
			continue
		fi
		quiet=$((quiet + 5))
		if [ "$quiet" -ge "$STALL" ]; then
			stalled=$(grep -E '^# --- ' "$log" | tail -n 1 | tr -d '\r' | sed 's/^# --- //')
			stalled=${stalled:-the boot, before the first test}
			kill "$qpid" 2>/dev/null || true
			break
		fi
	done
	wait "$qpid" || rc=$?
	trap - EXIT TERM INT
	tr -d '\r' <"$log" >"$log.tmp" && mv "$log.tmp" "$log"
	# a TAP "# SKIP" is not a pass: counted apart
	skip=$(grep -c '^ok .*# SKIP' "$log" || true)
	pass=$(($(grep -c '^ok ' "$log" || true) - skip))
	fail=$(grep -c '^not ok ' "$log" || true)
	grep -E '^(not ok|# )|^ok .*# SKIP' "$log" | grep -v '^# dmesg' | sed "s/^/[$k] /" || true
	# the TAP plan must match the results (nothing silently skipped)
	local plan
	plan=$(sed -n 's/^1\.\.\([0-9]*\)$/\1/p' "$log" | tail -n1)
	if [ -z "$plan" ] || [ "$plan" -ne $((pass + fail + skip)) ] || [ "$plan" -eq 0 ]; then
		fail=$((fail + 1))
		warn "$k: TAP plan '${plan:-none}' does not match $pass passed + $fail failed + $skip skipped"
	fi
	# each test file that was to run made the checks its plan says
	local f p made
	for f in "${FILES[@]}"; do
		p=$(sed -n "s/^# AS9888-PLAN $f planned=\([0-9a-z]*\) made=[0-9]*\$/\1/p" "$log" | tail -n1)
		made=$(sed -n "s/^# AS9888-PLAN $f planned=[0-9a-z]* made=\([0-9]*\)\$/\1/p" "$log" | tail -n1)
		if [ -z "$made" ]; then
			fail=$((fail + 1))
			warn "$k: $f: did not run to its end (no AS9888-PLAN line)"
		elif [ "$p" != "$made" ]; then
			fail=$((fail + 1))
			warn "$k: $f: made $made checks, its plan says $p"
		fi
	done
	if [ -n "$stalled" ]; then
		fail=$((fail + 1))
		warn "$k: stalled in $stalled: no TAP line for $STALL s (stopped at $(since "$t")); last lines of $log:"
		grep -E '^(ok |not ok |# )' "$log" | tail -n 5 >&2
	elif ! grep -q '^AS9888-VM-END' "$log"; then
		fail=$((fail + 1))
		warn "$k: no end marker (qemu exit $rc; last-resort timeout $TIMEOUT s): see $log"
		tail -n 30 "$log" >&2
	fi
	splat=$(grep -E "$SPLAT_RE" "$log" || true)
	if [ -n "$splat" ]; then
		fail=$((fail + 1))
		warn "$k: kernel splat in the serial log ($log):"
		printf '%s\n' "$splat" | head -n 20 >&2
	fi
	local skipped=""
	[ "$skip" -eq 0 ] || skipped=", $skip skipped"
	echo "$k: $pass passed, $fail failed$skipped ($(since "$t") in QEMU)" >"$VM_DIR/result-$k"
	[ "$fail" -eq 0 ]
}

# The test files that are to run: every tests/*.sh, or AS9888_VM_ONLY's
FILES=()
for f in "$GUEST"/tests/*.sh; do
	f=$(basename "$f" .sh)
	if [ -n "${AS9888_VM_ONLY:-}" ]; then
		case " $(echo $AS9888_VM_ONLY) " in *" $f "*) ;; *) continue ;; esac
	fi
	FILES+=("$f")
done
for f in ${AS9888_VM_ONLY:-}; do
	[ -f "$GUEST/tests/$f.sh" ] || die "AS9888_VM_ONLY: no test file $GUEST/tests/$f.sh"
done
[ ${#FILES[@]} -gt 0 ] || die "AS9888_VM_ONLY='${AS9888_VM_ONLY:-}' names no test file of $GUEST/tests"

build_daemon
build_tools_iio
stage_sensor_proxy
stage_trixie
guest_clock
# the builds one after the other (each uses both cores) ...
for k in "${WANT[@]}"; do
	"$AS9888_REPO/scripts/vm-kernel.sh" "$k"
	pack_initramfs "$k"
done
# ... the guests side by side, each judged on its own; their reports
# (the failures and diagnostics of each kernel) one after the other
PIDS=()
for k in "${WANT[@]}"; do
	run_one "$k" >"$VM_DIR/report-$k" 2>&1 &
	PIDS+=("$!")
done
log "guests of ${WANT[*]} started (serial logs: $LOG_DIR/vm-run-<k>.log)"
# a bench stopped from outside stops both guests (each run_one kills its own)
trap 'kill "${PIDS[@]}" 2>/dev/null; wait; exit 143' TERM INT
FAILED=0
for i in "${!WANT[@]}"; do
	wait "${PIDS[$i]}" || FAILED=1
done
trap - TERM INT
for k in "${WANT[@]}"; do
	cat "$VM_DIR/report-$k"
done
for k in "${WANT[@]}"; do
	if [ -s "$VM_DIR/result-$k" ]; then
		cat "$VM_DIR/result-$k"
	else
		echo "$k: 0 passed, 1 failed (the bench of $k ended without a result)"
		FAILED=1
	fi
done
# the failures again, last, where a log cut to its tail still shows them
for k in "${WANT[@]}"; do
	if grep -qE '^\[[0-9.]+\] not ok |WARNING: ' "$VM_DIR/report-$k" 2>/dev/null; then
		echo "failures of $k:"
		grep -E '^\[[0-9.]+\] not ok |WARNING: ' "$VM_DIR/report-$k" | head -n 20
	fi
done
log "done in $(since "$T_START")"
exit "$FAILED"
