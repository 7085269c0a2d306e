#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# upstream-series.sh [OUTDIR]
#
# Turns this repository into the patch series for mainline, made with
# git format-patch against Debian's linux-source-7.2 (the tree
# scripts/kernel-trees.sh prepares), and proves it on that tree, patch by
# patch:
#
#   1 dt-bindings: vendor-prefixes: Add ALSEN Technology Inc.
#   2 dt-bindings: iio: imu: Add ALSEN AS9888 (+ MAINTAINERS entry)
#   3.. one patch per stage of upstream/stages/ (the driver in steps, then
#       its documentation; scripts/upstream-stages.sh makes each stage's
#       tree, the last one is this repository's files). A stage directory
#       holding a file named "rfc" is sent as "[RFC PATCH n/m]"; one
#       holding "mainline.patch" (a diff, a/ b/ prefixes, of files of the
#       pristine tree, such as a note on a sysfs-bus-iio entry) has it
#       applied in its patch
#   0   the cover letter: upstream/cover-letter (its subject, a blank line,
#       its text) in git format-patch's cover letter, before the shortlog
#       and the diffstat git writes
#
# The MAINTAINERS entry comes with the binding and grows with what each
# patch adds: the driver directory as one F: line (with the patch that
# makes it), the rst and the ABI file. checkpatch asks every patch that
# adds files to update MAINTAINERS (FILE_PATH_CHANGES); a patch whose new
# files all lie in the driver directory, which the entry covers already,
# is checked with that one warning ignored. What is not sent:
# drivers/iio/imu/as9888/Kbuild and compat/ (the out-of-tree build on
# older kernels), lib/calib/ (userspace-only arithmetic), the top-level
# Kbuild.
#
# Checks, one line each, any problem fails the script:
#   stages      every stage's tree can be made (a change to the repository
#               inside a hunk of a stage's changes.patch names the stage)
#   cover       the cover letter exists, has no placeholder left, and its
#               text names every patch by its subject (on a line of
#               upstream/cover-letter; the shortlog git adds is not
#               counted), and every RFC stage's patch says "[RFC PATCH"
#   am          git am of the series (the cover letter left out, as b4
#               and git am do) onto the pristine 7.2 tree
#   identical   the series applied in full equals the repository's files,
#               byte for byte
#   checkpatch  scripts/checkpatch.pl --strict on every patch (commit
#               message included): 0 errors, warnings and checks
#   build N/M   at every patch that has the driver: in-tree (Kconfig, not
#               M=) make W=1 C=1 drivers/iio/imu/as9888/, incremental from
#               the patch before, 0 compiler and sparse warnings; no
#               as9888_ symbol undefined in the core or missing for the bus
#               and test modules (nm); scripts/kernel-doc -Wall -none on
#               the driver silent
#   sparse      every .c of the driver was checked by sparse
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
	[ "$2" = ok ] || [ "$2" = skipped ] || FAIL=1
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

# 3..: the driver and its documentation, one patch per stage of
# upstream/stages/ (scripts/upstream-stages.sh makes their trees; the last
# is this repository's files)
TREES="$SLOG/trees"
"$(dirname "$0")/upstream-stages.sh" trees "$TREES" >"$SLOG/stages.log" 2>&1 || {
	sed 's/^/    /' "$SLOG/stages.log" >&2
	result stages FAIL "upstream-stages.sh trees failed (log: $SLOG/stages.log)"
	exit 1
}
mapfile -t STAGE_NAMES < <(find "$REPO/upstream/stages" -mindepth 1 -maxdepth 1 -type d -printf '%f\n' | LC_ALL=C sort)

# insert_sorted FILE LINE PATTERN: LINE into FILE among the lines that
# match PATTERN (group 1 the sort key), unless it is there already
insert_sorted() {
	python3 - "$@" <<-'EOF'
		import os, re, sys
		path, new, pattern = sys.argv[1:4]
		lines = open(path).read().split("\n")
		if new in lines:
		    sys.exit(0)
		idx = [i for i, l in enumerate(lines) if re.match(pattern, l)]
		key = lambda l: re.match(pattern, l).group(1)
		pos = next((i for i in idx if key(lines[i]) > key(new)), idx[-1] + 1)
		lines.insert(pos, new)
		tmp = path + ".as9888.tmp"
		open(tmp, "w").write("\n".join(lines))
		os.replace(tmp, path)
	EOF
}
# the docs toctree of Documentation/iio/index.rst, in its order
insert_doc_index() {
	python3 - "$GIT/Documentation/iio/index.rst" <<-'EOF'
		import os, sys
		path = sys.argv[1]
		lines = open(path).read().split("\n")
		if "   as9888" in lines:
		    sys.exit(0)
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
}

for s in "${STAGE_NAMES[@]}"; do
	while IFS= read -r f; do
		put "$TREES/$s/$f" "$f"
	done < <(cd "$TREES/$s" && find . -type f | sed 's|^\./||' | LC_ALL=C sort)
	mfiles=("$BIND_REL")
	if [ -f "$GIT/$DRV_REL/Kconfig" ]; then
		insert_sorted "$GIT/drivers/iio/imu/Kconfig" 'source "drivers/iio/imu/as9888/Kconfig"' \
			'^source "drivers/iio/imu/([^"]*)/Kconfig"'
		insert_sorted "$GIT/drivers/iio/imu/Makefile" "obj-y += as9888/" \
			'^obj-y \+= ([a-z0-9_]+)/$'
		mfiles+=("$DRV_REL/")
	fi
	[ ! -f "$GIT/$ABI_REL" ] || mfiles+=("$ABI_REL")
	if [ -f "$GIT/$DOC_REL" ]; then
		insert_doc_index
		mfiles+=("$DOC_REL")
	fi
	maintainers_entry "${mfiles[@]}"
	if [ -f "$REPO/upstream/stages/$s/mainline.patch" ]; then
		G apply "$REPO/upstream/stages/$s/mainline.patch" ||
			die "stage $s: its mainline.patch does not apply to linux-source-$K"
	fi
	commit "$(msg "$s" <"$REPO/upstream/stages/$s/message")"
done

rm -f "$OUT"/*.patch
G format-patch -q --no-signature --zero-commit --cover-letter -o "$OUT" as9888-base..as9888
COVER="$OUT/0000-cover-letter.patch"
mapfile -t PATCHES < <(find "$OUT" -maxdepth 1 -name '0*.patch' ! -name "${COVER##*/}" | sort)

# --- RFC patches and the cover letter ----------------------------------------
# Patches 1 and 2 are the bindings; stage k (from 0) is patch k + 3
rfc=()
for ((k = 0; k < ${#STAGE_NAMES[@]}; k++)); do
	[ -e "$REPO/upstream/stages/${STAGE_NAMES[$k]}/rfc" ] || continue
	p="${PATCHES[$((k + 2))]}"
	sed -i '0,/^Subject: \[PATCH /s//Subject: [RFC PATCH /' "$p"
	rfc+=("$p")
done
CL_SRC="$REPO/upstream/cover-letter"
python3 - "$COVER" "$CL_SRC" <<-'EOF'
	import os, sys
	path, src = sys.argv[1:3]
	subject, _, body = open(src).read().partition("\n\n")
	text = open(path).read()
	text = text.replace("*** SUBJECT HERE ***", subject.strip(), 1)
	text = text.replace("*** BLURB HERE ***", body.rstrip("\n"), 1)
	open(path + ".as9888.tmp", "w").write(text)
	os.replace(path + ".as9888.tmp", path)
EOF
bad=""
! grep -q '\*\*\* .* HERE \*\*\*' "$COVER" || bad="$bad a placeholder is left;"
while IFS= read -r subj; do
	grep -qF -- "$subj" "$CL_SRC" || bad="$bad it does not name \"$subj\";"
done < <(G log --reverse --format=%s as9888-base..as9888)
for p in "${rfc[@]}"; do
	grep -q '^Subject: \[RFC PATCH ' "$p" || bad="$bad ${p##*/} is not marked RFC;"
done
if [ -z "$bad" ]; then
	result cover ok "${COVER##*/} names the ${#PATCHES[@]} patches; RFC:$(for p in "${rfc[@]}"; do printf ' %s' "${p##*/}"; done)"
else
	result cover FAIL "${COVER##*/}:$bad"
fi

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

# --- the series equals the repository ---------------------------------------
# The last patch's tree is this repository's files, byte for byte
LAST="${STAGE_NAMES[${#STAGE_NAMES[@]} - 1]}"
ndiff=0
nfiles=0
while IFS= read -r f; do
	nfiles=$((nfiles + 1))
	cmp -s "$GIT/$f" "$REPO/$f" || { ndiff=$((ndiff + 1)); echo "    differs: $f" >&2; }
done < <(cd "$TREES/$LAST" && find . -type f | sed 's|^\./||' | LC_ALL=C sort)
if [ "$ndiff" -eq 0 ]; then
	result identical ok "the series applied in full: $nfiles files equal to the repository's"
else
	result identical FAIL "$ndiff of $nfiles files differ from the repository's"
fi

# --- checkpatch -------------------------------------------------------------
# covered_adds PATCH: PATCH adds files, all of them in the driver directory,
# and leaves MAINTAINERS alone: the entry's F: line for the directory came
# with the patch that made it, so checkpatch's "does MAINTAINERS need
# updating?" is answered already
covered_adds() {
	local added
	grep -q '^+++ b/MAINTAINERS$' "$1" && return 1
	grep -qxF "F:	$DRV_REL/" "$GIT/MAINTAINERS" || return 1
	added=$(awk '/^--- \/dev\/null$/ { getline; sub(/^\+\+\+ b\//, ""); print }' "$1")
	[ -n "$added" ] && ! printf '%s\n' "$added" | grep -qv "^$DRV_REL/"
}
total=0
: >"$SLOG/checkpatch.log"
for p in "${PATCHES[@]}"; do
	ignore=()
	if covered_adds "$p"; then
		ignore=(--ignore FILE_PATH_CHANGES)
		printf '== %s: its new files are in %s/, which MAINTAINERS covers: FILE_PATH_CHANGES ignored\n' \
			"$(basename "$p")" "$DRV_REL" >>"$SLOG/checkpatch.log"
	fi
	out=$(cd "$GIT" && perl scripts/checkpatch.pl --strict --show-types ${ignore[@]+"${ignore[@]}"} "$p" 2>&1 || true)
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

# --- in-tree build, sparse, kernel-doc, links: at every patch ---------------
# Bisectable: every patch that has the driver builds (W=1 C=1, in-tree,
# Kconfig), with no compiler or sparse warning and no as9888_ symbol left
# undefined, and its kernel-doc is clean. The builds are incremental: make
# redoes what a patch changed (the first one is from scratch).
if [ ! -f "$BO/.config" ]; then
	log "copying the prepared $K build to $BO (once)"
	rm -rf "$BO" "$BO.new"
	cp -a "$(kobj "$K")" "$BO.new"
	mv "$BO.new" "$BO"
fi
CHECKW="$SER/sparse-check"
write_sparse_wrapper "$CHECKW"
MK=(make -C "$GIT" O="$BO" -j"$JOBS")
rm -rf "$BO/$DRV_REL"
: >"$SLOG/sparse-runs"
: >"$SLOG/build.log"
mapfile -t COMMITS < <(G rev-list --reverse as9888-base..as9888-am)
nbuilt=0
for ((n = 0; n < ${#COMMITS[@]}; n++)); do
	c="${COMMITS[$n]}"
	pn="$(printf '%d/%d' $((n + 1)) ${#COMMITS[@]})"
	# (the patches before the driver are not checked out: their files,
	# such as the binding, keep their mtimes and make keeps its work)
	G cat-file -e "$c:$DRV_REL/Kconfig" 2>/dev/null || continue
	G checkout -q --detach "$c"
	nbuilt=$((nbuilt + 1))
	blog="$SLOG/build-$((n + 1)).log"
	slog="$SLOG/sparse-$((n + 1)).log"
	want=(AS9888 AS9888_I2C AS9888_SPI)
	grep -q '^config AS9888_KUNIT_TEST' "$GIT/$DRV_REL/Kconfig" && want+=(AS9888_KUNIT_TEST)
	for o in "${want[@]:1}"; do
		"$GIT/scripts/config" --file "$BO/.config" -m "$o"
	done
	"${MK[@]}" olddefconfig >"$SLOG/config.log" 2>&1 ||
		die "olddefconfig failed at patch $pn, see $SLOG/config.log"
	bad=""
	for o in "${want[@]}"; do
		grep -q "^CONFIG_$o=m" "$BO/.config" || bad="$bad Kconfig did not enable CONFIG_$o;"
	done
	: >"$slog"
	rc=0
	AS9888_SPARSE_REAL="$SPARSE_BIN" AS9888_SPARSE_LOG="$slog" \
		AS9888_SPARSE_RUNS="$SLOG/sparse-runs" \
		"${MK[@]}" W=1 C=1 CHECK="$CHECKW" "$DRV_REL/" >"$blog" 2>&1 || rc=$?
	cat "$blog" >>"$SLOG/build.log"
	nw=$(grep -Eci 'warning:|error:' "$blog" || true)
	ns=$(grep -Eci 'warning:|error:' "$slog" || true)
	[ "$rc" -eq 0 ] || bad="$bad make exited $rc;"
	[ "$nw" -eq 0 ] || bad="$bad $nw compiler warnings;"
	[ "$ns" -eq 0 ] || bad="$bad $ns sparse warnings;"
	! grep -q 'not available or not up to date' "$blog" || bad="$bad kbuild says sparse is not available;"
	# Links: nothing of ours undefined in the core, and the bus and test
	# modules find theirs in it (a prototype left without its function
	# builds, and fails only at modpost)
	if [ "$rc" -eq 0 ]; then
		core="$BO/$DRV_REL/as9888_core.o"
		undef=$(nm -u "$core" | awk '$2 ~ /^as9888_/ { print $2 }')
		nm --defined-only "$core" | awk '{ print $3 }' >"$SLOG/core-syms"
		for o in "$BO/$DRV_REL"/as9888_{i2c,spi,calib_kunit}.o; do
			[ -f "$o" ] || continue
			for sym in $(nm -u "$o" | awk '$2 ~ /^as9888_/ { print $2 }'); do
				grep -qxF "$sym" "$SLOG/core-syms" ||
					undef="$undef $sym($(basename "$o"))"
			done
		done
		[ -z "$undef" ] || bad="$bad undefined:$(echo $undef);"
	fi
	kd=$(cd "$GIT" && scripts/kernel-doc -Wall -none "$DRV_REL"/*.[ch] 2>&1 || echo "kernel-doc exited $?")
	[ -z "$kd" ] || bad="$bad kernel-doc: $(printf '%s\n' "$kd" | wc -l) lines;"
	# patches 1 and 2 are the bindings; patch 3 on are the stages
	subj="$(G log -1 --format=%s "$c") [stage ${STAGE_NAMES[$((n - 2))]}]"
	if [ -z "$bad" ]; then
		result "build $pn" ok "$subj: W=1 C=1 $(grep -c '^  CC ' "$blog" || true) files compiled, 0 warnings, links, kernel-doc clean"
	else
		grep -Ei 'warning:|error:|\*\*\*' "$blog" "$slog" | head -20 | sed 's/^/    /' >&2 || true
		[ -z "$kd" ] || printf '%s\n' "$kd" | head -10 | sed 's/^/    /' >&2
		result "build $pn" FAIL "$subj:$bad (logs: $blog $slog)"
	fi
done
G checkout -q as9888-am
unchecked=""
for c in "$GIT/$DRV_REL"/*.c; do
	grep -q "$(basename "$c")\$" "$SLOG/sparse-runs" || unchecked="$unchecked $(basename "$c")"
done
if [ "$nbuilt" -eq 0 ]; then
	result sparse FAIL "no patch has the driver"
elif [ -n "$unchecked" ]; then
	result sparse FAIL "sparse did not check:$unchecked"
else
	result sparse ok "$nbuilt patches built; every one of $(ls "$GIT/$DRV_REL"/*.c | wc -l) .c files checked, 0 warnings"
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
