#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The package: a product build as a distribution or BSP makes it
# (-Dsimulator=false -Dlibgpiod=disabled -Dtests=disabled, prefix /usr,
# no werror), `meson install --destdir`, and the installed file list
# compared with the expected one exactly; the paths substituted in the
# units; the binary without the simulator and libgpiod (not linked, not
# compiled in, and saying so when asked for them); then the full build's
# own install list (the build dir the suite runs in). Output is TAP.
#
# Usage: install.sh SOURCE-DIR BUILD-DIR
set -u

src=$(realpath "${1:?usage: install.sh SOURCE-DIR BUILD-DIR}")
full=$(realpath "${2:?usage: install.sh SOURCE-DIR BUILD-DIR}")
work=$(mktemp -d /tmp/as9888-install-XXXXXX)
trap 'rm -rf "$work"' EXIT
# shellcheck source=../lib/tap.sh
. "$src/tests/lib/tap.sh"
tap_plan 17
TAP_SHOW="$work/log"

expected_files() {	# PREFIX
	sed "s|^|$1|" <<'EOF_LIST'
/lib/systemd/system/as9888-calibd-restore@.service
/lib/systemd/system/as9888-calibd.service
/lib/systemd/system/as9888-calibd.socket
/lib/tmpfiles.d/as9888-calibd.conf
/lib/udev/rules.d/60-as9888-calibd.rules
/sbin/as9888-calibd
/share/doc/as9888-calibd/RECORD.md
/share/doc/as9888-calibd/report.schema.json
/share/man/man8/as9888-calibd.8
EOF_LIST
}
installed_files() { (cd "$1" && find . -type f -o -type l | sed 's|^\.||' | LC_ALL=C sort); }

# the product build: the options the Yocto recipe and Buildroot package use
product_flags="-Dsimulator=false -Dlibgpiod=disabled -Dtests=disabled"
b=$work/build
check "product build configures (no simulator, no libgpiod, no tests)" \
	eval 'meson setup "$b" "$src" --prefix=/usr --sysconfdir=/etc --buildtype=release \
		$product_flags >"$work/log" 2>&1'
check "and builds" eval 'ninja -C "$b" >"$work/log" 2>&1'
check "no cmocka, no test program, no simulator in it" \
	eval '! grep -qi "dependency cmocka found: YES" "$b/meson-logs/meson-log.txt" &&
	      [ -z "$(find "$b" -name "test_*" -type f)" ] &&
	      [ ! -e "$b/daemon/sim" ]'
check "meson install --destdir" \
	eval 'DESTDIR="$work/root" meson install -C "$b" --no-rebuild >"$work/log" 2>&1'
expected_files /usr | LC_ALL=C sort >"$work/expected"
installed_files "$work/root" >"$work/installed"
check "installed files are exactly the expected list" \
	eval 'diff -u "$work/expected" "$work/installed" >"$work/log"'

root=$work/root
restore="$root/usr/lib/systemd/system/as9888-calibd-restore@.service"
daemon="$root/usr/lib/systemd/system/as9888-calibd.service"
check "units: configured paths, none left unsubstituted" \
	eval 'grep -q "^ExecStart=/usr/sbin/as9888-calibd restore --backend iio --device %f --record /var/lib/as9888/calibration \$AS9888_CALIBD_RESTORE_OPTS$" "$restore" &&
	      grep -q "^ExecStart=/usr/sbin/as9888-calibd daemon --backend iio" "$daemon" &&
	      grep -q "^EnvironmentFile=-/etc/default/as9888-calibd$" "$daemon" &&
	      ! grep -rq "@[a-z]*@" "$root/usr/lib"'
check "tmpfiles.d: the state directory, root's own" \
	grep -q "^d /var/lib/as9888 0755 root root -$" "$root/usr/lib/tmpfiles.d/as9888-calibd.conf"

calibd=$root/usr/sbin/as9888-calibd
check "the binary runs" eval '"$calibd" --help >"$work/log" 2>&1'
check "not linked with libgpiod" eval '! ldd "$calibd" | grep -q gpiod'
check "no simulator or libgpiod code in it" \
	eval '! nm "$b/daemon/as9888-calibd" | grep -Eq " (as9888_sim_|as9888_model_|gpiod_)"'
"$calibd" factory-test --backend sim --record "$work/rec" >"$work/out" 2>"$work/err"
rc=$?
check "--backend sim: fails and says it is built without the simulator" \
	eval '[ $rc -ne 0 ] && grep -q "built without the simulator" "$work/err" && [ ! -e "$work/rec" ]'
check "the raw backend's pins say they need libgpiod" \
	grep -q "built without libgpiod" <(strings "$calibd")

# the examples build with exactly these flags and sources
check "Yocto recipe and Buildroot package: the product flags of this test" \
	python3 - "$src/contrib" $product_flags <<'PY'
import re, sys
top, want = sys.argv[1], set(sys.argv[2:])
bb = open(top + "/yocto/meta-as9888/recipes-sensors/as9888-calibd/as9888-calibd_git.bb").read()
flags = set(re.search(r'^EXTRA_OEMESON = "([^"]*)"', bb, re.M).group(1).split())
pc = re.search(r'^PACKAGECONFIG \?\?= "([^"]*)"', bb, re.M).group(1).split()
for name, on, off in re.findall(r'^PACKAGECONFIG\[(\w+)\] = "([^,]*),([^,]*),', bb, re.M):
    flags.add(on if name in pc else off)
assert flags == want, ("yocto", flags ^ want)
mk = open(top + "/buildroot/package/as9888-calibd/as9888-calibd.mk").read()
flags = set(re.search(r"^AS9888_CALIBD_CONF_OPTS = (.*)$", mk, re.M).group(1).split())
# without BR2_PACKAGE_LIBGPIOD: the else branch
flags.add(re.search(r"^else\nAS9888_CALIBD_CONF_OPTS \+= (-Dlibgpiod=\S+)", mk, re.M).group(1))
assert flags == want, ("buildroot", flags ^ want)
PY
check "Android.bp: the sources of the product build, no more, no less" \
	python3 - "$src" "$b" <<'PY'
import json, os, re, subprocess, sys
src, b = sys.argv[1:]
targets = json.loads(subprocess.run(["meson", "introspect", "--targets", b],
    capture_output=True, check=True).stdout)
built = set()
for t in targets:
    if t["name"] in ("as9888-calibd", "calibd", "as9888_calib", "as9888iio", "magcal", "as9888magn", "as9888hal"):
        for s in t["target_sources"]:
            built |= {os.path.relpath(f, src) for f in s["sources"]}
bp = open(src + "/contrib/android/Android.bp").read()
listed = set(re.findall(r'"([\w/.-]+\.c)"', bp))
assert built == listed, sorted(built ^ listed)
PY
check "Android init .rc (init's grammar), SELinux file_contexts and the daemon: one socket name" \
	python3 - "$src" <<'PY'
import re, sys
src = sys.argv[1]
name = re.search(r'#define ANDROID_SOCKET_NAME\s+"(\w+)"',
                 open(src + "/daemon/src/service/service_socket.h").read()).group(1)
# init's sections ("on", "service", "import" at the start of a line) and
# the service options used here, indented below a service
options = {"class", "socket", "user", "group", "capabilities", "task_profiles",
           "oneshot", "disabled", "seclabel", "writepid", "file", "critical",
           "ioprio", "priority", "setenv", "onrestart", "rlimit", "stdio_to_kmsg"}
services, section = {}, None
for line in open(src + "/contrib/android/as9888-calibd.rc").read().splitlines():
    if not line.strip() or line.lstrip().startswith("#"):
        continue
    words = line.split()
    if not line[0].isspace():
        assert words[0] in ("on", "service", "import"), line
        section = words[0]
        if section == "service":
            assert len(words) >= 3 and words[2].startswith("/"), line
            svc = services.setdefault(words[1], {"args": words[2:], "opts": []})
        continue
    assert section, line
    if section == "service":
        assert words[0] in options, line
        svc["opts"].append(words)
(daemon,) = [s for s in services.values() if "daemon" in s["args"]]
sockets = [o for o in daemon["opts"] if o[0] == "socket"]
assert len(sockets) == 1 and sockets[0][1:3] == [name, "stream"], sockets
args = daemon["args"]
assert args[args.index("--socket") + 1] == "/dev/socket/" + name, args
fc = open(src + "/contrib/android/sepolicy/file_contexts").read()
assert re.search(r"^/dev/socket/%s\s" % name, fc, re.M), "file_contexts"
PY

# the full build the suite runs in (simulator, libgpiod, tests): same list
# under its own prefix
prefix=$(meson introspect --buildoptions "$full" |
	python3 -c 'import json, sys; print(next(o["value"] for o in json.load(sys.stdin) if o["name"] == "prefix"))')
check "full build: meson install --destdir" \
	eval 'DESTDIR="$work/root2" meson install -C "$full" --no-rebuild >"$work/log" 2>&1'
expected_files "$prefix" | LC_ALL=C sort >"$work/expected2"
installed_files "$work/root2" >"$work/installed2"
check "full build: installed files are exactly the expected list (no test program)" \
	eval 'diff -u "$work/expected2" "$work/installed2" >"$work/log"'

tap_end
