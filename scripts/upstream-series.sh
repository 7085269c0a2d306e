#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# upstream-series.sh [OUTDIR]
#
# Turns this repository into the patch series for mainline, made with
# git format-patch against Debian's linux-source-7.2 (the tree
# scripts/kernel-trees.sh prepares), and proves it on that tree:
#
#   1/4 dt-bindings: vendor-prefixes: Add ALSEN Technology Inc.
#   2/4 dt-bindings: iio: imu: Add ALSEN AS9888 (+ MAINTAINERS entry)
#   3/4 iio: imu: Add ALSEN AS9888 driver (core, I2C, SPI, arithmetic, KUnit)
#   4/4 docs: iio: Add AS9888 sysfs ABI and driver documentation
#
# The MAINTAINERS entry grows with the files of each patch (checkpatch asks
# every patch that adds files to update MAINTAINERS). What is not sent:
# drivers/iio/imu/as9888/Kbuild and compat/ (the out-of-tree build on older
# kernels), lib/calib/ (userspace-only arithmetic), the top-level Kbuild.
#
# Checks, one line each, any problem fails the script:
#   am          git am of the series onto the pristine 7.2 tree
#   checkpatch  scripts/checkpatch.pl --strict on every patch (commit
#               message included): 0 errors, warnings and checks
#   build       the driver in-tree (Kconfig, not M=): make W=1 C=1
#               drivers/iio/imu/as9888/ on top of the prepared 7.2 build,
#               0 compiler warnings
#   sparse      CHECK= sparse from the cache ran on every .c, 0 warnings
#   kernel-doc  scripts/kernel-doc -Wall -none on the driver: no output
#   abi         tools/docs/get_abi.py validate: nothing new against the
#               pristine tree's own report
#   dt          make dt_binding_check DT_SCHEMA_FILES=<ours>: clean
#   htmldocs    make SPHINXDIRS=iio htmldocs: no warning about our files
#
# Cache ($AS9888_CACHE/series): linux-7.2/ a git repository of the 7.2
# source (made once, then reset to its base commit every run) and build-7.2/
# its O= directory, a copy of the prepared 7.2 build made once. dtschema
# (2023.9 or newer, which dt_binding_check needs; Debian 12 has 2022.08)
# comes from PyPI, at the versions pinned in scripts/dtschema-requirements.txt,
# into the venv scripts/dt-check.sh uses (dtschema_venv in kernel-common.sh).
#
# Environment: AS9888_CACHE, AS9888_JOBS, AS9888_SERIES_FROM (the From: and
# Signed-off-by: identity), AS9888_SERIES_SKIP_DOCS=1 (no htmldocs).
# Exit status: 0 all checks passed, 1 a check failed.
set -euo pipefail

# shellcheck source-path=SCRIPTDIR source=kernel-common.sh
. "$(dirname "$0")/kernel-common.sh"

T_START=$(now)
cache_lock upstream-series

K=7.2
SER="$AS9888_CACHE/series"
GIT="$SER/linux-$K"
BO="$SER/build-$K"
OUT="$(mkdir -p "${1:-$SER/patches}" && cd "${1:-$SER/patches}" && pwd)"
SLOG="$LOG_DIR/upstream-series"
FROM="${AS9888_SERIES_FROM:-AS9888 Linux support team <linux-as9888@lists.alsen.example>}"
DATE="2026-11-23T12:00:00+00:00"
REPO="$AS9888_REPO"
DRV_REL="$AS9888_DRIVER_REL"
mkdir -p "$SER" "$SLOG"

FAIL=0
T_STEP=$(now)
result() { # result NAME OK|FAIL DETAIL (and the time since the last result)
	printf '%-11s %s: %s (%s)\n' "$1" "$2" "$3" "$(since "$T_STEP")"
	T_STEP=$(now)
	[ "$2" = ok ] || FAIL=1
}

"$(dirname "$0")/kernel-trees.sh" "$K" >"$SLOG/trees.log" 2>&1 ||
	die "kernel-trees.sh $K failed, see $SLOG/trees.log"
ensure_pkgs git perl rsync yamllint python3-venv device-tree-compiler \
	libyaml-dev pkg-config
[ "${AS9888_SERIES_SKIP_DOCS:-0}" = 1 ] ||
	ensure_pkgs python3-sphinx python3-sphinx-rtd-theme python3-yaml

# --- the 7.2 tree as a git repository (once), reset every run ---------------
G() { git -C "$GIT" -c user.name="${FROM% <*}" -c user.email="$(echo "$FROM" | sed 's/.*<\(.*\)>.*/\1/')" \
	-c advice.detachedHead=false -c core.autocrlf=false "$@"; }
if ! G rev-parse -q --verify as9888-base >/dev/null 2>&1; then
	log "creating the git repository of linux-$K in $GIT (once)"
	rm -rf "$GIT" "$GIT.new"
	cp -a "$(ksrc "$K")" "$GIT.new"
	git -C "$GIT.new" init -q
	git -C "$GIT.new" add -A -f
	git -C "$GIT.new" -c user.name=Debian -c user.email=debian@localhost \
		commit -q -m "linux-source-$K ($(make -s -C "$GIT.new" kernelversion))"
	git -C "$GIT.new" tag as9888-base
	mv "$GIT.new" "$GIT"
fi
G checkout -q -f -B as9888 as9888-base
G clean -q -fdx

# --- the series -------------------------------------------------------------
# Files are written through new files + mv (the repository is a plain copy,
# but keep the habit: never write through a file in place).
put() { # put SRC DEST(relative to the tree)
	mkdir -p "$(dirname "$GIT/$2")"
	cp "$1" "$GIT/$2.as9888.tmp"
	mv "$GIT/$2.as9888.tmp" "$GIT/$2"
}
commit() { # commit MESSAGE-FILE
	G add -A -f
	GIT_AUTHOR_DATE="$DATE" GIT_COMMITTER_DATE="$DATE" G commit -q -F "$1"
}
msg() { # msg NAME < text: the commit message with the sign-off
	{
		cat
		printf '\nSigned-off-by: %s\n' "$FROM"
	} >"$SLOG/msg-$1"
	printf '%s\n' "$SLOG/msg-$1"
}
# maintainers_entry F-LINE...: the MAINTAINERS entry with these F: lines,
# inserted in alphabetical order of the entry titles
maintainers_entry() {
	python3 - "$GIT/MAINTAINERS" "$FROM" "$@" <<-'EOF'
		import re, sys, os
		path, who, files = sys.argv[1], sys.argv[2], sys.argv[3:]
		title = "ALSEN AS9888 IMU DRIVER"
		text = open(path).read()
		lines = text.split("\n")
		# drop an entry of ours from an earlier patch
		if title in lines:
		    i = lines.index(title)
		    j = i
		    while j < len(lines) and lines[j] != "":
		        j += 1
		    del lines[i:j + 1]
		entry = [title, "M:\t" + who, "L:\tlinux-iio@vger.kernel.org", "S:\tMaintained"]
		entry += ["F:\t" + f for f in sorted(files)]
		# entries start after the first blank line following "Maintainers List"
		start = lines.index("Maintainers List")
		for k in range(start, len(lines)):
		    if (lines[k] and re.match(r"^[A-Z0-9]", lines[k]) and lines[k - 1] == ""
		            and k + 1 < len(lines) and re.match(r"^[A-Z]:\t", lines[k + 1])
		            and lines[k] > title):
		        lines[k:k] = entry + [""]
		        break
		tmp = path + ".as9888.tmp"
		open(tmp, "w").write("\n".join(lines))
		os.replace(tmp, path)
	EOF
}

BIND_REL="Documentation/devicetree/bindings/iio/imu/alsen,as9888.yaml"
ABI_REL="Documentation/ABI/testing/sysfs-bus-iio-as9888"
DOC_REL="Documentation/iio/as9888.rst"

# 1: vendor prefix
G apply "$REPO/dt-bindings/0001-dt-bindings-vendor-prefixes-Add-ALSEN-Technology-Inc.patch"
commit "$(msg 1 <<'EOF'
dt-bindings: vendor-prefixes: Add ALSEN Technology Inc.

ALSEN Technology Inc. makes the AS9888 6-axis accelerometer and
magnetometer, whose binding follows in this series. Add its prefix,
"alsen".
EOF
)"

# 2: binding (+ MAINTAINERS)
put "$REPO/dt-bindings/iio/imu/alsen,as9888.yaml" "$BIND_REL"
maintainers_entry "$BIND_REL"
commit "$(msg 2 <<'EOF'
dt-bindings: iio: imu: Add ALSEN AS9888

The ALSEN AS9888 combines a 3-axis magnetometer (13 bit), a 3-axis
accelerometer (12 bit) with an offset DAC, and a die temperature sensor.
Its factory trim lives in an on-chip EEPROM.

Facts from the datasheet the binding describes:
- I2C up to 400 kHz at 7-bit address 0x0c to 0x0f (pins CAD1/CAD0), or
  4-wire SPI in mode 3 (spi-cpol and spi-cpha) up to 5 MHz.
- Two push-pull, active-high outputs, INT1 and INT2, either of which
  can signal data ready; they are named so that a board may wire one or
  both.
- RSTN, an active-low reset input.
- Two supplies, both needed for the chip to run: VDD (analog, 2.4 V to
  3.6 V) and VID (digital interface, 1.65 V to VDD).

Add the binding, and a MAINTAINERS entry for it.
EOF
)"

# 3: driver
DRV_FILES=(Kconfig Makefile as9888.h as9888_core.h as9888_regs.h
	as9888_calib.h as9888_calib.c as9888_probe.c as9888_chip.c
	as9888_accel.c as9888_magn.c as9888_trigger.c as9888_i2c.c
	as9888_spi.c as9888_calib_kunit.c .kunitconfig)
for f in "${DRV_FILES[@]}"; do
	[ -f "$REPO/$DRV_REL/$f" ] || die "missing $DRV_REL/$f"
	put "$REPO/$DRV_REL/$f" "$DRV_REL/$f"
done
python3 - "$GIT/drivers/iio/imu" <<'EOF'
import os, re, sys
d = sys.argv[1]
def insert_sorted(path, new, pattern):
    lines = open(path).read().split("\n")
    idx = [i for i, l in enumerate(lines) if re.match(pattern, l)]
    key = lambda l: re.match(pattern, l).group(1)
    pos = next((i for i in idx if key(lines[i]) > key(new)), idx[-1] + 1)
    lines.insert(pos, new)
    tmp = path + ".as9888.tmp"
    open(tmp, "w").write("\n".join(lines))
    os.replace(tmp, path)
insert_sorted(d + "/Kconfig", 'source "drivers/iio/imu/as9888/Kconfig"',
              r'^source "drivers/iio/imu/([^"]*)/Kconfig"')
insert_sorted(d + "/Makefile", "obj-y += as9888/", r"^obj-y \+= ([a-z0-9_]+)/$")
EOF
maintainers_entry "$BIND_REL" "$DRV_REL/"
commit "$(msg 3 <<'EOF'
iio: imu: Add ALSEN AS9888 driver

The ALSEN AS9888 is a 6-axis sensor: a 3-axis magnetometer (13 bit,
0.3 uT/LSB before the EEPROM's sensitivity adjustment), a 3-axis
accelerometer (12 bit, about 256 LSB/g) with a per-axis offset DAC, and
a die temperature sensor, on I2C or SPI.

The chip has no continuous mode. Every sample is one single measurement
(MS = 0x01) that ends with ST1.DRDY and, when enabled, a data-ready
pulse on INT1, after which the chip is back in power-down. A sample takes
1.2 ms with the magnetometer off (4.8 ms with the accelerometer's
low-pass filter) and 7.3 ms with it on, and is read in one burst of
0x10..0x1f. Factory trim is read from an EEPROM at 0x40..0x54 in EEPROM
access mode (MS = 0x04, then 300 us); the REF/OSC/gain/DAC trim registers
0x30..0x39 are written from it in power-down only.

The accelerometer's offset and sensitivity drift with temperature by
the EEPROM's coefficients (datasheet section 6): St(t) from St_RT and
Kste, Ot(t) from a level-test offset and Kote, and one offset DAC code
moves the output by 2048 / (gain + 16) LSB. The driver compensates every
reading with the die temperature of the same burst, T = (176 - TMPS) /
1.6 degC, and returns it on a constant scale of 1024 LSB per g, so that
consumers need raw and scale only. The level-test calibration is
in_accel_X_calibbias, in output units (1/1024 g) as sysfs-bus-iio
defines it: the driver realises it as the offset DAC code the datasheet's
optimisation chooses plus a digital residual, and a chip reading at its
rail is not compensated (-ERANGE on sysfs, the output limit in the
buffer). The arithmetic is integer only, in its own unit linked into
the core module, with a KUnit suite.

Each sensor is an IIO device of its own, as in inv_icm42600 and
st_lsm6dsx: "as9888-accel" (accelerometer and temperature) and
"as9888-magn" (magnetometer). Measuring the magnetometer makes a sample
take 7.3 ms instead of 1.2 ms, so a client of the accelerometer alone,
even one that enables every scan element of its device, must never make
the chip measure it. Both devices share the chip's lock and one
data-ready trigger: its sample is read once, each device takes its
channels from it, and the next measurement starts, with the magnetometer
on only while the magnetometer's buffer runs on the trigger. The
trigger's reenable op only re-arms it; the next measurement is paced by
an hrtimer, at the union of the two devices' own sampling frequencies
(the accelerometer alone up to 400 Hz). Both devices on the shared
trigger need CONFIG_IIO_CONSUMERS_PER_TRIGGER >= 2, as for kmx61 and
st_lsm9ds0. A raw read, the self-test or a calibbias write waits for
the gap between two samples, so a client of one sensor neither stops
nor waits for the other's buffer.

The driver provides:
- accelerometer, magnetometer (with the EEPROM sensitivity adjustment
  in the scale) and temperature channels, and mount matrices;
- triggered buffers with the chip's data-ready trigger when INT1 or
  INT2 is wired, any other trigger otherwise;
- oversampling_ratio for the accelerometer filter (1 or 4);
- the magnetometer self-test (MS = 0x08) and its judgment;
- the EEPROM as a read-only NVMEM device;
- runtime PM: VDD and VID are off while the device is unused, and the
  trim and state are restored at power-up; RSTN is held low while the
  supplies are off (a high input would feed the unpowered chip), so
  every power-up is also a reset pulse;
- system sleep: the data-ready trigger is stopped and INT1 disabled
  before the supplies go off, and no measurement starts until resume;
- INT1, or INT2 when only INT2 is named, rising edge or level high (a
  level interrupt is cleared by reading INTxST); a named interrupt that
  cannot be got fails probe;
- a watchdog that restarts a sample whose data-ready edge never came
  (1 s) and retries a sample that could not be started.
EOF
)"

# 4: ABI and documentation
put "$REPO/$ABI_REL" "$ABI_REL"
put "$REPO/$DOC_REL" "$DOC_REL"
python3 - "$GIT/Documentation/iio/index.rst" <<'EOF'
import os, sys
path = sys.argv[1]
lines = open(path).read().split("\n")
start = lines.index("Industrial I/O Kernel Drivers")
i = lines.index(".. toctree::", start) + 1
while lines[i].strip().startswith(":") or not lines[i].strip():
    i += 1
while i < len(lines) and lines[i].startswith("   ") and lines[i].strip() < "as9888":
    i += 1
lines.insert(i, "   as9888")
tmp = path + ".as9888.tmp"
open(tmp, "w").write("\n".join(lines))
os.replace(tmp, path)
EOF
maintainers_entry "$BIND_REL" "$DRV_REL/" "$ABI_REL" "$DOC_REL"
commit "$(msg 4 <<'EOF'
docs: iio: Add AS9888 sysfs ABI and driver documentation

Document the one attribute the AS9888 driver adds to the IIO ABI,
selftest (the magnetometer self-test of the datasheet, with its
judgment), and describe the driver: how the accelerometer reading is
compensated from the EEPROM trim at the die temperature of each
sample, the attributes and the buffer, the data-ready trigger and its
rates, the EEPROM as NVMEM and power management.
EOF
)"

rm -f "$OUT"/*.patch
G format-patch -q --no-signature --zero-commit -o "$OUT" as9888-base..as9888
mapfile -t PATCHES < <(find "$OUT" -maxdepth 1 -name '0*.patch' | sort)

# --- am ---------------------------------------------------------------------
G checkout -q -f -B as9888-am as9888-base
if G am -q "${PATCHES[@]}" >"$SLOG/am.log" 2>&1; then
	result am ok "${#PATCHES[@]} patches applied to linux-source-$K"
else
	result am FAIL "see $SLOG/am.log"
	G am --abort >/dev/null 2>&1 || true
	exit 1
fi

# Files of the series whose content is what the last run had keep that run's
# mtime, so that make does not redo what depends on them (Kconfig, the
# processed dt schema of all bindings: 1-2 minutes). What is checked is
# redone anyway: the driver's objects, the binding's stamps and example are
# deleted below, and the rst files are left new for Sphinx to read again.
MT="$SER/mtimes"
while IFS= read -r f; do
	case "$f" in Documentation/iio/*) continue ;; esac
	if [ -f "$MT/$f" ] && cmp -s "$MT/$f" "$GIT/$f"; then
		touch -r "$MT/$f" "$GIT/$f"
	else
		mkdir -p "$(dirname "$MT/$f")"
		cp -p "$GIT/$f" "$MT/$f"
	fi
done < <(G diff --name-only as9888-base HEAD)

# --- checkpatch -------------------------------------------------------------
total=0
: >"$SLOG/checkpatch.log"
for p in "${PATCHES[@]}"; do
	out=$(cd "$GIT" && perl scripts/checkpatch.pl --strict --show-types "$p" 2>&1 || true)
	printf '== %s\n%s\n' "$(basename "$p")" "$out" >>"$SLOG/checkpatch.log"
	read -r e w c < <(printf '%s\n' "$out" |
		sed -n 's/^total: \([0-9]*\) errors, \([0-9]*\) warnings, \([0-9]*\) checks.*/\1 \2 \3/p' | tail -n1) || true
	if [ -z "${e:-}" ]; then
		n=1
	else
		n=$((e + w + c))
	fi
	if [ "$n" -gt 0 ]; then
		printf '%s\n' "$out" | grep -E '^(ERROR|WARNING|CHECK)|^#' | sed "s|^|    $(basename "$p"): |" >&2 || true
	fi
	total=$((total + n))
done
if [ "$total" -eq 0 ]; then
	result checkpatch ok "--strict, ${#PATCHES[@]} patches, 0 errors/warnings/checks"
else
	result checkpatch FAIL "$total errors/warnings/checks (log: $SLOG/checkpatch.log)"
fi

# --- in-tree build ----------------------------------------------------------
if [ ! -f "$BO/.config" ]; then
	log "copying the prepared $K build to $BO (once)"
	rm -rf "$BO" "$BO.new"
	cp -a "$(kobj "$K")" "$BO.new"
	mv "$BO.new" "$BO"
fi
CHECKW="$SER/sparse-check"
write_sparse_wrapper "$CHECKW"
MK=(make -C "$GIT" O="$BO" -j"$JOBS")
"$GIT/scripts/config" --file "$BO/.config" -m AS9888_I2C -m AS9888_SPI \
	-m AS9888_KUNIT_TEST
"${MK[@]}" olddefconfig >"$SLOG/config.log" 2>&1 || die "olddefconfig failed, see $SLOG/config.log"
miss=""
for o in AS9888 AS9888_I2C AS9888_SPI AS9888_KUNIT_TEST; do
	grep -q "^CONFIG_$o=m" "$BO/.config" || miss="$miss CONFIG_$o"
done
[ -z "$miss" ] || result build FAIL "Kconfig did not enable$miss"
rm -rf "$BO/$DRV_REL"
: >"$SLOG/sparse.log"
: >"$SLOG/sparse-runs"
rc=0
AS9888_SPARSE_REAL="$SPARSE_BIN" AS9888_SPARSE_LOG="$SLOG/sparse.log" \
	AS9888_SPARSE_RUNS="$SLOG/sparse-runs" \
	"${MK[@]}" W=1 C=1 CHECK="$CHECKW" "$DRV_REL/" >"$SLOG/build.log" 2>&1 || rc=$?
nw=$(grep -Eci 'warning:|error:' "$SLOG/build.log" || true)
nobj=$(find "$BO/$DRV_REL" -name '*.o' 2>/dev/null | wc -l)
if [ "$rc" -eq 0 ] && [ "$nw" -eq 0 ]; then
	result build ok "in-tree make W=1 C=1 $DRV_REL/: $nobj objects, 0 warnings"
else
	grep -Ei 'warning:|error:|\*\*\*' "$SLOG/build.log" | head -20 | sed 's/^/    /' >&2 || true
	result build FAIL "make exited $rc, $nw warnings (log: $SLOG/build.log)"
fi
ns=$(grep -Eci 'warning:|error:' "$SLOG/sparse.log" || true)
unchecked=""
for c in "$GIT/$DRV_REL"/*.c; do
	grep -q "$(basename "$c")\$" "$SLOG/sparse-runs" || unchecked="$unchecked $(basename "$c")"
done
if grep -q 'not available or not up to date' "$SLOG/build.log"; then
	result sparse FAIL "kbuild says sparse is not available or not up to date"
elif [ -n "$unchecked" ]; then
	result sparse FAIL "sparse did not check:$unchecked"
elif [ "$ns" -ne 0 ]; then
	sed 's/^/    /' "$SLOG/sparse.log" >&2
	result sparse FAIL "$ns warnings (log: $SLOG/sparse.log)"
else
	result sparse ok "$(sort -u "$SLOG/sparse-runs" | wc -l) files checked, 0 warnings"
fi

# --- kernel-doc -------------------------------------------------------------
kd=$(cd "$GIT" && scripts/kernel-doc -Wall -none "$DRV_REL"/*.[ch] 2>&1 || echo "kernel-doc exited $?")
if [ -z "$kd" ]; then
	result kernel-doc ok "-Wall -none on $(ls "$GIT/$DRV_REL"/*.[ch] | wc -l) files: nothing reported"
else
	printf '%s\n' "$kd" | sed 's/^/    /' >&2
	result kernel-doc FAIL "$(printf '%s\n' "$kd" | wc -l) lines reported"
fi

# --- ABI --------------------------------------------------------------------
abi() { (cd "$GIT" && python3 tools/docs/get_abi.py --dir Documentation/ABI validate 2>&1 | sort); }
abi >"$SLOG/abi-series.txt"
mv "$GIT/$ABI_REL" "$SLOG/abi-file.tmp"
abi >"$SLOG/abi-base.txt"
mv "$SLOG/abi-file.tmp" "$GIT/$ABI_REL"
new=$(comm -13 "$SLOG/abi-base.txt" "$SLOG/abi-series.txt")
ours=$(grep -c "sysfs-bus-iio-as9888" "$SLOG/abi-series.txt" || true)
nwhat=$(grep -c '^What:' "$GIT/$ABI_REL")
if [ -z "$new" ] && [ "$ours" -eq 0 ] && [ -f "$GIT/$ABI_REL" ]; then
	result abi ok "get_abi.py validate: $nwhat entries, nothing new against the tree's own $(wc -l <"$SLOG/abi-base.txt") lines"
else
	printf '%s\n' "$new" | sed 's/^/    /' >&2
	result abi FAIL "get_abi.py validate reports new problems (logs: $SLOG/abi-*.txt)"
fi

# --- dt_binding_check -------------------------------------------------------
VENV="$AS9888_CACHE/dtschema-venv"
dtschema_venv "$VENV"
DTB="$BO/Documentation/devicetree/bindings"
rm -f "$DTB"/.yamllint.checked "$DTB"/.dt-binding.checked "$DTB"/.dt-style.checked \
	"$DTB"/iio/imu/alsen,as9888.example.dt*
rc=0
PATH="$VENV/bin:$PATH" "${MK[@]}" dt_binding_check \
	DT_SCHEMA_FILES="iio/imu/alsen,as9888.yaml" >"$SLOG/dt.log" 2>&1 || rc=$?
# Anything but make's and kbuild's progress lines is a finding: dt-validate
# says "Unevaluated properties are not allowed" with no "warning" in it.
# (dtschema's tools cannot use make's jobserver from here; harmless.)
dtbad=$(grep -Ev '^make(\[[0-9]+\])?: (Entering|Leaving) directory|^  [A-Z]+( \[C\])? |Unable to reopen jobserver' "$SLOG/dt.log" || true)
if [ "$rc" -eq 0 ] && [ -z "$dtbad" ] && grep -q 'alsen,as9888' "$SLOG/dt.log"; then
	result dt ok "make dt_binding_check DT_SCHEMA_FILES=iio/imu/alsen,as9888.yaml (dtschema $("$VENV/bin/dt-doc-validate" --version)): clean"
else
	printf '%s\n' "$dtbad" | head -20 | sed 's/^/    /' >&2
	result dt FAIL "make exited $rc (log: $SLOG/dt.log)"
fi

# --- htmldocs ---------------------------------------------------------------
if [ "${AS9888_SERIES_SKIP_DOCS:-0}" = 1 ]; then
	result htmldocs skipped "AS9888_SERIES_SKIP_DOCS=1"
else
	rc=0
	rm -f "$BO/Documentation/output/iio/as9888.html"
	"${MK[@]}" SPHINXDIRS=iio htmldocs >"$SLOG/htmldocs.log" 2>&1 || rc=$?
	# our files by name (the cache's own path also holds "as9888")
	ours_re='as9888\.rst|sysfs-bus-iio-as9888|alsen,as9888|imu/as9888/'
	hw=$(grep -E "$ours_re" "$SLOG/htmldocs.log" | grep -Eci 'warning|error' || true)
	html="$BO/Documentation/output/iio/as9888.html"
	if [ "$rc" -eq 0 ] && [ "$hw" -eq 0 ] && [ -s "$html" ]; then
		result htmldocs ok "make SPHINXDIRS=iio htmldocs (Sphinx $(sphinx-build --version 2>/dev/null | awk '{print $NF}')): as9888.html, 0 warnings about our files"
	else
		grep -E "$ours_re" "$SLOG/htmldocs.log" | head -20 | sed 's/^/    /' >&2 || true
		result htmldocs FAIL "make exited $rc, $hw warnings (log: $SLOG/htmldocs.log)"
	fi
fi

log "series in $OUT ($(ls "$OUT" | tr '\n' ' '))"
if [ "$FAIL" -ne 0 ]; then
	log "FAILED in $(since "$T_START")"
	exit 1
fi
log "all checks passed in $(since "$T_START")"
